//! `fix massflow/mesh`: counts the particles (and their mass) that cross a mesh face
//! towards `vec_side`, optionally deleting them; `f_ID[1..6]` gives totals and rates.

use super::{mesh_ref, style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "massflow/mesh",
    parse,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "`mesh ID vec_side vx vy vz`, `count once\\|multiple`, `delete_atoms yes\\|no`; `screen`, `writeTime` accepted",
)
.notes("`f_ID[1..6]`: mass and count through the face, mass and number rates since the previous evaluation (thermo output), deleted mass and count; a particle counts when its centre crosses the face's plane inside a triangle; `delete_atoms yes` removes it at the next re-neighboring, as LIGGGHTS does; `point_at_outlet`, `inside_out`, `file`, `append` stop with an error");

/// `fix massflow/mesh`: the engine's counter and the output rates.
pub struct MassFlowFix {
    /// Totals and settings.
    pub flow: rdem::massflow::MassFlow,
    /// (step, mass, count) when the rates were last evaluated (`None`: the run start).
    pub last: std::cell::Cell<Option<(u64, f64, u64)>>,
    /// (step, mass rate, number rate) of the last evaluation.
    pub rates: std::cell::Cell<(u64, f64, f64)>,
}

impl MassFlowFix {
    /// `f_ID[1..6]`: mass, count, mass rate and number rate since the last evaluation
    /// at an earlier step (the previous thermo output), deleted mass and count.
    fn rates(&self, step: u64, dt: f64) -> [f64; 6] {
        let f = &self.flow;
        let (s, mr, nr) = self.rates.get();
        let (mr, nr) = if s == step {
            (mr, nr)
        } else {
            let (s0, m0, c0) = self.last.get().unwrap_or((0, 0.0, 0));
            let t = step.saturating_sub(s0) as f64 * dt;
            let r = if t > 0.0 {
                ((f.mass - m0) / t, (f.count - c0) as f64 / t)
            } else {
                (0.0, 0.0)
            };
            self.last.set(Some((step, f.mass, f.count)));
            self.rates.set((step, r.0, r.1));
            r
        };
        [
            f.mass,
            f.count as f64,
            mr,
            nr,
            f.deleted_mass,
            f.deleted as f64,
        ]
    }
}

/// `fix ID group massflow/mesh mesh MESH vec_side x y z [count once|multiple]
/// [delete_atoms yes|no] [screen yes|no]`.
fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (id, groupbit) = (head.id.as_str(), head.groupbit);
    a.keyword("massflow/mesh keyword", &["mesh"])?;
    let mesh_at = a.pos();
    let mesh = mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?;
    const KEYS: [&str; 5] = ["vec_side", "count", "delete_atoms", "screen", "writeTime"];
    const LATER_KEYS: [&str; 5] = ["point_at_outlet", "inside_out", "file", "append", "lambda"];
    let (mut side, mut once, mut delete) = (None, false, false);
    while let Some(w) = a.peek() {
        if LATER_KEYS.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("massflow/mesh keyword '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", KEYS.join(", "))),
            ));
        }
        match a.keyword("massflow/mesh keyword", &KEYS)? {
            "vec_side" => side = Some(a.vec3("vec_side")?),
            "count" => once = a.keyword("count", &["once", "multiple"])? == "once",
            "delete_atoms" => delete = a.yes_no("delete_atoms")?,
            "screen" => {
                a.yes_no("screen")?;
            }
            _ => {}
        }
    }
    let Some(side) = side else {
        return Err(a.error_at(
            STYLE_WORD,
            "massflow/mesh needs 'vec_side vx vy vz' (the outer side of the face)",
            None,
        ));
    };
    let w = sim.world_ref(a)?;
    let mut mf = rdem::massflow::MassFlow::new(id, mesh, &w.meshes[mesh].mesh, groupbit, side)
        .map_err(|e| a.error_at(mesh_at, e.to_string(), None))?;
    mf.once = once;
    mf.delete = delete;
    Ok(Box::new(MassFlowFix {
        flow: mf,
        last: std::cell::Cell::new(None),
        rates: std::cell::Cell::new((u64::MAX, 0.0, 0.0)),
    }))
}

impl ScriptFix for MassFlowFix {
    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, String> {
        let w = sim.world.as_ref().ok_or("needs a simulation box")?;
        Ok(self.rates(w.step, w.dt).to_vec())
    }

    fn end_of_step(
        &mut self,
        sim: &mut Sim,
        _head: &FixHead,
        _step: u64,
        setup: bool,
    ) -> Result<(), String> {
        if setup {
            return Ok(());
        }
        let w = sim.world.as_mut().ok_or("needs a simulation box")?;
        self.flow.update(w).map_err(|e| e.to_string())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
