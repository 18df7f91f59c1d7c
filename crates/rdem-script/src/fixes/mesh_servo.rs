//! `fix mesh/surface/stress/servo`: a `mesh/surface/stress` mesh that a PID controller
//! (or the gain-scheduled law of `mode auto`) translates along an axis until the
//! particles push on it with `target_val` (`ctrlPV force`), or turns about the axis
//! through `com` until their torque about it is `target_val` (`ctrlPV torque`)
//! (LIGGGHTS 3.8's mesh module servo; the law is in [`rdem::mesh_servo`]). This file
//! holds the servo keywords, their checks and `fix_modify ID integrate start|stop`
//! (with `servo/integrate`, `servo/target_val`, `servo/vel_max`, `servo/ctrlParam`).

use rdem::mesh_servo::Servo;
use rdem::DVec3;

use super::{style, FixHead, FixRow, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "mesh/surface/stress/servo",
    super::mesh_surface::parse,
    Stages::VALUES,
    "as `mesh/surface/stress`, and `com x y z`, `ctrlPV force\\|torque`, `axis ax ay az`, `target_val F`, `vel_max v`, `kp`, `ki`, `kd`, `mode auto`, `ratio dr`; `fix_modify ID integrate start\\|stop` (or `servo/integrate`), `servo/target_val`, `servo/vel_max`, `servo/ctrlParam kp ki kd`",
)
.notes("PID law measured on LIGGGHTS 3.8 and matched to 1e-9 (see `rdem::mesh_servo`): moves in the step after the force it reacts to; `ctrlPV torque` turns the mesh about the axis through `com` at most `vel_max` at its farthest vertex; `mode auto` switches from `vel_max` to `ratio` · min radius / dt when a particle is within radius + skin of the mesh at a neighbor build (LIGGGHTS 3.8 switched 8 steps later in a measured case: its candidate rule differs); `f_ID[1..9]` total force, torque about the centre of mass, the centre of mass; variable axes stop with an error (not supported yet; LIGGGHTS 3.8 rejects them too); a stopped servo does not move but its vertices keep their last velocity for the contacts (as LIGGGHTS 3.8)");

/// Servo keywords of `mesh/surface/stress/servo`.
pub(super) const KEYS: [&str; 10] = [
    "com",
    "ctrlPV",
    "axis",
    "target_val",
    "vel_max",
    "kp",
    "ki",
    "kd",
    "mode",
    "ratio",
];

/// The servo keywords read so far.
#[derive(Default)]
pub(super) struct ServoWords {
    com: Option<DVec3>,
    /// `ctrlPV`: Some(true) for torque, with the word's position.
    ctrl: Option<(bool, usize)>,
    axis: Option<DVec3>,
    target: Option<f64>,
    vmax: Option<f64>,
    gains: [Option<f64>; 3],
    /// `mode auto`, with the word's position.
    auto: Option<usize>,
    ratio: Option<f64>,
}

impl ServoWords {
    /// Reads the servo keyword `w` (at the current word) and its values.
    pub(super) fn read(&mut self, a: &mut Args, w: &str) -> CmdResult<()> {
        a.seek(a.pos() + 1);
        match w {
            "com" => self.com = Some(a.vec3("centre of mass")?),
            "ctrlPV" => {
                let at = a.pos();
                self.ctrl = Some((a.keyword("ctrlPV", &["force", "torque"])? == "torque", at));
            }
            "axis" => {
                let at = a.pos();
                // The manual allows variables here, but LIGGGHTS 3.8 reads three numbers
                // ("Expected floating point parameter" for `axis 0 0 v_a`).
                let words = a.words();
                let var = |k: usize| words.get(at + k).is_some_and(|w| w.text.starts_with("v_"));
                if let Some(k) = (0..3).find(|&k| var(k)) {
                    return Err(a.error_at(
                        at + k,
                        "a variable axis is not supported by this rdem release yet (LIGGGHTS 3.8 does not take one either)",
                        Some("give three numbers".into()),
                    ));
                }
                let v = a.vec3("axis")?;
                if !v.is_finite() || v.length() <= 0.0 {
                    return Err(a.error_at(at, "the axis has no direction", None));
                }
                self.axis = Some(v);
            }
            "target_val" => {
                let v = a.f64("target force or torque")?;
                if v == 0.0 {
                    return Err(a.error_prev(
                        "target_val must not be 0 (the controller divides the error by it)",
                        None,
                    ));
                }
                self.target = Some(v);
            }
            "vel_max" => self.vmax = Some(a.positive("maximum wall speed")?),
            "kp" => self.gains[0] = Some(a.non_negative("kp")?),
            "ki" => self.gains[1] = Some(a.non_negative("ki")?),
            "kd" => self.gains[2] = Some(a.non_negative("kd")?),
            "mode" => {
                self.auto = Some(a.pos() - 1);
                a.keyword("mode", &["auto"])?;
            }
            "ratio" => self.ratio = Some(a.positive("ratio")?),
            _ => {
                return Err(a.error_prev(
                    format!("servo keyword '{w}' is not supported by this rdem release yet"),
                    Some(format!("servo keywords: {}", KEYS.join(", "))),
                ))
            }
        }
        Ok(())
    }

    /// The servo of a mesh with vertices `verts` once every keyword is read: `com`,
    /// `ctrlPV`, `axis`, `target_val` and `vel_max` are obligatory; gains default to kp
    /// 0.01, ki 0, kd 0 (the manual); `vel_max` must stay below skin / (2 dt) (the
    /// manual's condition); `mode auto` needs `ratio`; a torque servo needs a vertex off
    /// its axis.
    pub(super) fn finish(self, sim: &Sim, a: &Args, verts: &[DVec3]) -> CmdResult<Servo> {
        let missing = |what: &str| {
            a.error_at(
                STYLE_WORD,
                format!("mesh/surface/stress/servo needs '{what}'"),
                Some("obligatory: com, ctrlPV, axis, target_val, vel_max".into()),
            )
        };
        let com = self.com.ok_or_else(|| missing("com x y z"))?;
        let (torque, ctrl_at) = self.ctrl.ok_or_else(|| missing("ctrlPV force|torque"))?;
        let axis = self.axis.ok_or_else(|| missing("axis ax ay az"))?;
        let target = self.target.ok_or_else(|| missing("target_val F"))?;
        let vmax = self.vmax.ok_or_else(|| missing("vel_max v"))?;
        if let Some(w) = &sim.world {
            let (skin, dt) = (w.neighbor.settings.skin, w.dt);
            if dt > 0.0 && vmax >= skin / (2.0 * dt) {
                let at = a
                    .words()
                    .iter()
                    .position(|x| x.text == "vel_max")
                    .unwrap_or(STYLE_WORD);
                return Err(a.error_at(
                    at + 1,
                    format!(
                        "vel_max {vmax} must be below skin / (2 timestep) = {}",
                        skin / (2.0 * dt)
                    ),
                    Some("a faster wall could pass particles between neighbor list builds".into()),
                ));
            }
        }
        if let (Some(at), None) = (self.auto, self.ratio) {
            // LIGGGHTS 3.8: "please define 'ratio' for the mesh, since you use the auto mode".
            return Err(a.error_at(
                at,
                "mode auto needs 'ratio dr' (the speed near particles, dr · min radius / timestep)",
                None,
            ));
        }
        let [kp, ki, kd] = self.gains;
        let gains = [kp.unwrap_or(0.01), ki.unwrap_or(0.0), kd.unwrap_or(0.0)];
        let mut servo = if torque {
            Servo::new_torque(axis, com, target, vmax, gains, verts).ok_or_else(|| {
                a.error_at(
                    ctrl_at,
                    "ctrlPV torque: every vertex of the mesh lies on the rotation axis",
                    Some("the axis passes through com".into()),
                )
            })?
        } else {
            Servo::new(axis, com, target, vmax, gains)
        };
        servo.auto = self.auto.is_some();
        // Without mode auto LIGGGHTS 3.8 takes 'ratio' and does not use it.
        servo.ratio = self.ratio.unwrap_or(0.0);
        Ok(servo)
    }
}

/// `fix_modify ID keyword ...` of a servo mesh: `integrate start|stop` (and
/// `servo/integrate`), `servo/target_val F`, `servo/vel_max v`, `servo/ctrlParam kp ki
/// kd`. LIGGGHTS 3.8 takes the bare `integrate` with a warning that it is deprecated.
pub(super) fn modify(sim: &mut Sim, head: &FixHead, kw: &str, a: &mut Args) -> CmdResult<bool> {
    const OWN: [&str; 5] = [
        "integrate",
        "servo/integrate",
        "servo/target_val",
        "servo/vel_max",
        "servo/ctrlParam",
    ];
    if !OWN.contains(&kw) {
        return Ok(false);
    }
    let kw_at = a.pos() - 1;
    let value = match kw {
        "integrate" | "servo/integrate" => {
            Some(a.keyword("integrate", &["start", "stop"])? == "start")
        }
        _ => None,
    };
    let mut numbers = [0.0; 3];
    match kw {
        "servo/target_val" => {
            numbers[0] = a.f64("target force")?;
            if numbers[0] == 0.0 {
                return Err(a.error_prev("target_val must not be 0", None));
            }
        }
        "servo/vel_max" => numbers[0] = a.positive("maximum wall speed")?,
        "servo/ctrlParam" => {
            for (k, what) in ["kp", "ki", "kd"].iter().enumerate() {
                numbers[k] = a.non_negative(what)?;
            }
        }
        _ => {}
    }
    if kw == "integrate" {
        a.warn_at(
            kw_at,
            "fix_modify integrate: LIGGGHTS 3.8 calls this keyword deprecated; servo/integrate names the servo",
        );
    }
    let w = sim.world_mut(a)?;
    let servo = w
        .mesh_index(&head.id)
        .and_then(|k| w.meshes[k].servo.as_mut())
        .ok_or_else(|| a.error_at(kw_at, format!("fix {} has no servo", head.id), None))?;
    match kw {
        "servo/target_val" => servo.target = numbers[0],
        "servo/vel_max" => servo.vmax = numbers[0],
        "servo/ctrlParam" => [servo.kp, servo.ki, servo.kd] = numbers,
        _ => servo.active = value.unwrap_or(servo.active),
    }
    Ok(true)
}
