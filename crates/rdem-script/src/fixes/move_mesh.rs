//! `fix move/mesh mesh ID style args`: a prescribed motion of a mesh (linear, wiggle,
//! rotate, riggle, viblin, vibrot). The motion lives in the engine's mesh, which moves it
//! at every step; several motions of one mesh superpose and are removed in reverse order.

use super::{mesh_ref, style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "move/mesh",
    parse,
    Stages::NONE,
    "`mesh ID` then `linear`, `wiggle`, `rotate`, `riggle`, `viblin`, `vibrot`",
)
.notes("positions and vertex velocities evaluated analytically each step; several on one mesh superpose in LIGGGHTS' order (a later motion moves with the earlier ones) and are removed in reverse order, the mesh staying where it is; `viblin`/`vibrot` follow LIGGGHTS' cosine series (the mesh jumps by Σ Cₖ cos pₖ when they start); `linear/variable`, `rotate/variable` stop with an error");

/// A motion of the world's mesh of index `mesh`.
pub struct MoveMesh {
    mesh: usize,
    /// The motion and the word its errors point at, until installed.
    parsed: Option<(rdem::mesh_motion::Motion, usize)>,
}

impl ScriptFix for MoveMesh {
    /// Starts the motion at the current time.
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        let Some((motion, style_at)) = self.parsed.take() else {
            return Ok(());
        };
        let w = sim.world_mut(a)?;
        let t = w.step as f64 * w.dt;
        let m = &mut w.meshes[self.mesh];
        let verts = m.mesh.verts.clone();
        let points: Vec<_> = m.stress.iter().map(|s| s.reference_point).collect();
        m.motion
            .add(&head.id, motion, t, &verts, &points)
            .map_err(|e| a.error_at(style_at, e.to_string(), None))
    }

    /// The motion's start time, and the vertex positions (and carried points) the mesh's
    /// motions start from.
    fn save_state(&self, sim: &Sim, head: &FixHead) -> Option<Vec<u8>> {
        let m = &sim.world.as_ref()?.meshes[self.mesh].motion;
        let t0 = m.movers.iter().find(|x| x.0 == head.id)?.2;
        let base: Vec<[f64; 3]> = m.base.iter().map(|v| v.to_array()).collect();
        let carried: Vec<[f64; 3]> = m.carried.iter().map(|v| v.to_array()).collect();
        postcard::to_stdvec(&(t0, base, carried)).ok()
    }

    fn restore_state(&mut self, sim: &mut Sim, head: &FixHead, state: &[u8]) -> Result<(), Error> {
        // Restart files written before the carried points hold (t0, base).
        let (t0, base, carried): (f64, Vec<[f64; 3]>, Vec<[f64; 3]>) =
            match super::decode_state(state) {
                Ok(s) => s,
                Err(_) => {
                    let (t0, base): (f64, Vec<[f64; 3]>) = super::decode_state(state)?;
                    (t0, base, Vec::new())
                }
            };
        let w = sim.world.as_mut().ok_or("no simulation box")?;
        let m = &mut w.meshes[self.mesh].motion;
        if base.len() != m.base.len() {
            return Err(format!(
                "it moves {} vertices, the mesh has {}",
                base.len(),
                m.base.len()
            )
            .into());
        }
        if let Some(x) = m.movers.iter_mut().find(|x| x.0 == head.id) {
            x.2 = t0;
        }
        m.base = base.into_iter().map(rdem::DVec3::from_array).collect();
        m.carried = carried.into_iter().map(rdem::DVec3::from_array).collect();
        Ok(())
    }

    /// Refuses to remove a motion that is not the last one of its mesh (LIGGGHTS' rule:
    /// superposed motions go in reverse order).
    fn check_unfix(&self, sim: &Sim, head: &FixHead) -> Result<(), Error> {
        let Some(w) = &sim.world else { return Ok(()) };
        let movers = &w.meshes[self.mesh].motion.movers;
        if let Some(last) = movers.last() {
            if last.0 != head.id && movers.iter().any(|x| x.0 == head.id) {
                return Err(format!(
                    "move/mesh fixes of mesh {} must be removed in reverse order: unfix {} first",
                    w.meshes[self.mesh].id, last.0
                )
                .into());
            }
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        if let Some(w) = &mut sim.world {
            let t = w.step as f64 * w.dt;
            // The order was checked (check_unfix); a redefinition removes the last.
            let _ = w.meshes[self.mesh].motion.remove(&head.id, t);
        }
    }
}

/// `fix ID group move/mesh mesh MESH style args`: linear, wiggle, rotate, riggle,
/// viblin, vibrot ([`rdem::mesh_motion::Motion`]), from the current time on.
fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    use rdem::mesh_motion::Motion;
    a.keyword("move/mesh keyword", &["mesh"])?;
    let mesh = mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?;
    if sim
        .world
        .as_ref()
        .is_some_and(|w| w.meshes[mesh].servo.is_some())
    {
        return Err(a.error_prev(
            "a servo mesh (mesh/surface/stress/servo) cannot also be moved by move/mesh",
            Some("LIGGGHTS 3.8's manual forbids it: the servo sets the motion".into()),
        ));
    }
    const STYLES: [&str; 6] = ["linear", "wiggle", "rotate", "riggle", "viblin", "vibrot"];
    const LATER_STYLES: [&str; 3] = ["linear/variable", "rotate/variable", "file"];
    if let Some(w) = a.peek() {
        if LATER_STYLES.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("move/mesh style '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", STYLES.join(", "))),
            ));
        }
    }
    let style_at = a.pos();
    let style = a.keyword("move/mesh style", &STYLES)?;
    let axis = |a: &mut Args| -> CmdResult<rdem::DVec3> {
        a.keyword(&format!("{style} keyword"), &["axis"])?;
        let at = a.pos();
        let v = a.vec3("axis")?;
        if !v.is_finite() || v.length() <= 0.0 {
            return Err(a.error_at(at, "the axis has no direction", None));
        }
        Ok(v.normalize())
    };
    let origin = |a: &mut Args| -> CmdResult<rdem::DVec3> {
        a.keyword(&format!("{style} keyword"), &["origin"])?;
        a.vec3("origin")
    };
    let period = |a: &mut Args| -> CmdResult<f64> {
        a.keyword(&format!("{style} keyword"), &["period"])?;
        a.positive("period")
    };
    // order n amplitude C1..Cn phase p1..pn period T1..Tn
    let series = |a: &mut Args| -> CmdResult<Vec<[f64; 3]>> {
        a.keyword(&format!("{style} keyword"), &["order"])?;
        let n = a.count("order (1 to 30)")? as usize;
        if n > 30 {
            return Err(a.error_prev("order must be 1 to 30", None));
        }
        let mut terms = vec![[0.0; 3]; n];
        for (k, what) in ["amplitude", "phase", "period"].iter().enumerate() {
            a.keyword(&format!("{style} keyword"), &[what])?;
            for t in terms.iter_mut() {
                t[k] = if k == 2 {
                    a.positive("period")?
                } else {
                    a.f64(what)?
                };
            }
        }
        Ok(terms)
    };
    let motion = match style {
        "linear" => Motion::Linear(a.vec3("velocity")?),
        "wiggle" => {
            a.keyword("wiggle keyword", &["amplitude"])?;
            let amplitude = a.vec3("amplitude")?;
            Motion::Wiggle {
                amplitude,
                period: period(a)?,
            }
        }
        "rotate" => Motion::Rotate {
            origin: origin(a)?,
            axis: axis(a)?,
            period: period(a)?,
        },
        "riggle" => {
            let (origin, axis, period) = (origin(a)?, axis(a)?, period(a)?);
            a.keyword("riggle keyword", &["amplitude"])?;
            let deg = a.f64("amplitude (degrees)")?;
            Motion::Riggle {
                origin,
                axis,
                period,
                amplitude: deg.to_radians(),
            }
        }
        "viblin" => {
            let axis = axis(a)?;
            Motion::Viblin {
                axis,
                terms: series(a)?,
            }
        }
        _ => {
            let (origin, axis) = (origin(a)?, axis(a)?);
            Motion::Vibrot {
                origin,
                axis,
                terms: series(a)?,
            }
        }
    };
    a.done()?;
    Ok(Box::new(MoveMesh {
        mesh,
        parsed: Some((motion, style_at)),
    }))
}
