//! `fix mesh/surface/stress/servo`: a `mesh/surface/stress` mesh that a PID controller
//! translates along an axis until the particles push on it with `target_val`
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
    "as `mesh/surface/stress`, and `com x y z`, `ctrlPV force`, `axis ax ay az`, `target_val F`, `vel_max v`, `kp`, `ki`, `kd`; `fix_modify ID integrate start\\|stop` (or `servo/integrate`), `servo/target_val`, `servo/vel_max`, `servo/ctrlParam kp ki kd`",
)
.notes("PID law measured on LIGGGHTS 3.8 and matched to 1e-9 (see `rdem::mesh_servo`): moves in the step after the force it reacts to; `f_ID[1..9]` total force, torque about the centre of mass, the centre of mass; `ctrlPV torque`, `mode auto`, `ratio` and variable axes stop with an error (not supported yet); a stopped servo does not move but its vertices keep their last velocity for the contacts (as LIGGGHTS 3.8)");

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
    ctrl: bool,
    axis: Option<DVec3>,
    target: Option<f64>,
    vmax: Option<f64>,
    gains: [Option<f64>; 3],
}

impl ServoWords {
    /// Reads the servo keyword `w` (at the current word) and its values.
    pub(super) fn read(&mut self, a: &mut Args, w: &str) -> CmdResult<()> {
        a.seek(a.pos() + 1);
        match w {
            "com" => self.com = Some(a.vec3("centre of mass")?),
            "ctrlPV" => {
                if a.peek() == Some("torque") {
                    a.seek(a.pos() + 1);
                    return Err(a.error_prev(
                        "ctrlPV torque is not supported by this rdem release yet",
                        Some("supported: ctrlPV force".into()),
                    ));
                }
                a.keyword("ctrlPV", &["force"])?;
                self.ctrl = true;
            }
            "axis" => {
                let at = a.pos();
                if a.peek().is_some_and(|s| s.starts_with("v_")) {
                    return Err(a.error_at(
                        at,
                        "a variable axis is not supported by this rdem release yet",
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
                let v = a.f64("target force")?;
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
            _ => {
                return Err(a.error_prev(
                    format!("servo keyword '{w}' is not supported by this rdem release yet"),
                    Some("the PID controller (kp, ki, kd) is; mode auto is not".into()),
                ))
            }
        }
        Ok(())
    }

    /// The servo once every keyword is read: `com`, `ctrlPV`, `axis`, `target_val` and
    /// `vel_max` are obligatory; gains default to kp 0.01, ki 0, kd 0 (the manual);
    /// `vel_max` must stay below skin / (2 dt) (the manual's condition).
    pub(super) fn finish(self, sim: &Sim, a: &Args) -> CmdResult<Servo> {
        let missing = |what: &str| {
            a.error_at(
                STYLE_WORD,
                format!("mesh/surface/stress/servo needs '{what}'"),
                Some("obligatory: com, ctrlPV, axis, target_val, vel_max".into()),
            )
        };
        let com = self.com.ok_or_else(|| missing("com x y z"))?;
        if !self.ctrl {
            return Err(missing("ctrlPV force"));
        }
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
        let [kp, ki, kd] = self.gains;
        Ok(Servo::new(
            axis,
            com,
            target,
            vmax,
            [kp.unwrap_or(0.01), ki.unwrap_or(0.0), kd.unwrap_or(0.0)],
        ))
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
