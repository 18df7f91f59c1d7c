//! `fix ID group store/state N input ... [com yes|no]` (LIGGGHTS 3.8, from LAMMPS): per
//! particle of the group, copies of attributes (`x`, `xu`, `vx`, `radius`, ... the names
//! `dump custom` knows), per-atom compute or fix values (`c_ID`, `c_ID[i]`, `f_ID`,
//! `f_ID[i]`) and atom-style variables (`v_name`), kept for later use (`f_ID`,
//! `f_ID[i]`) in variables, dumps and reductions.
//!
//! Attributes are stored when the fix is defined; computes, fixes and variables at the
//! set-up of the first run after it. With N > 0 every value is stored again at the end
//! of every step that is a multiple of N; with N = 0 never again. `com yes` takes the
//! group's centre of mass (unwrapped, mass-weighted, at that moment) from `xu yu zu`.
//! Particles outside the group, and those added later until the next store, hold 0. The
//! values are a per-particle property: they move with their particles between ranks and
//! come back from restart files.

use rdem_io::Field;

use crate::error::Error;

use super::peratom_ref::PerAtomRef;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "store/state",
    parse,
    Stages::END_OF_STEP,
    "`N input ... [com yes|no]`: per particle, copies of attributes (the `dump custom` names), `c_ID[i]`, `f_ID[i]`, `v_name`, stored at the definition (computes, fixes, variables: at the next run's set-up) and every N steps (N = 0: once); `f_ID[i]` reads them",
);

enum Input {
    Field(Field, String),
    Ref(PerAtomRef),
}

struct StoreState {
    every: u64,
    inputs: Vec<Input>,
    com: bool,
    /// The particle property holding the values.
    prop: String,
    /// The computes, fixes and variables were stored once.
    stored_all: bool,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.u64("N (0: store once)")?;
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        if w == "com" {
            break;
        }
        let input = if let Some(f) = Field::parse(w) {
            Input::Field(f, w.to_string())
        } else if let Some(r) = PerAtomRef::parse(sim, a, a.pos(), w)? {
            Input::Ref(r)
        } else {
            return Err(a.error_at(
                a.pos(),
                format!("fix store/state: unknown input '{w}'"),
                Some(format!(
                    "an attribute ({}), c_ID, c_ID[i], f_ID, f_ID[i] or v_name",
                    Field::NAMES.join(" ")
                )),
            ));
        };
        inputs.push(input);
        a.seek(a.pos() + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(a.pos(), "fix store/state needs at least one input", None));
    }
    let mut com = false;
    while !a.is_done() {
        a.keyword("fix store/state keyword", &["com"])?;
        com = a.yes_no("com")?;
    }
    sim.world_ref(a)?;
    Ok(Box::new(StoreState {
        every,
        inputs,
        com,
        prop: format!("store/state:{}", head.id),
        stored_all: false,
    }))
}

impl StoreState {
    /// The values to store: the attributes (and with `all`, the computes, fixes and
    /// variables) of the owned particles; `None` for an input not stored now.
    fn columns(&self, sim: &Sim, groupbit: u32, all: bool) -> Result<Vec<Option<Vec<f64>>>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let n = w.particles.nlocal();
        let com = if self.com {
            crate::computes::kernels::group_com(w, groupbit).1
        } else {
            glam::DVec3::ZERO
        };
        let mut columns: Vec<Option<Vec<f64>>> = Vec::new();
        for input in &self.inputs {
            columns.push(match input {
                Input::Field(f, name) => {
                    let p = &w.particles;
                    let shift = match name.as_str() {
                        "xu" => com[0],
                        "yu" => com[1],
                        "zu" => com[2],
                        _ => 0.0,
                    };
                    Some((0..n).map(|i| f.value(p, &w.domain, i) - shift).collect())
                }
                _ if !all => None,
                Input::Ref(r) => Some(r.values(sim)?),
            });
        }
        Ok(columns)
    }

    /// Writes `columns` into the group's owned particles.
    fn write(
        &self,
        w: &mut rdem::World,
        groupbit: u32,
        columns: &[Option<Vec<f64>>],
    ) -> Result<(), Error> {
        let n = w.particles.nlocal();
        let p = &mut w.particles;
        let id = p
            .property(&self.prop)
            .ok_or("fix store/state: its values are gone")?;
        for i in (0..n).filter(|&i| p.mask[i] & groupbit != 0) {
            let row = p.props[id.0].get_mut(i);
            for (k, c) in columns.iter().enumerate() {
                if let Some(c) = c {
                    row[k] = c[i];
                }
            }
        }
        Ok(())
    }
}

impl ScriptFix for StoreState {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        if super::property_atom::fix_values(sim, a, &self.prop, self.inputs.len())? {
            // The values come back from the restart file (as LIGGGHTS keeps them).
            self.stored_all = true;
            return Ok(());
        }
        let columns = self
            .columns(sim, head.groupbit, false)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
        self.write(sim.world_mut(a)?, head.groupbit, &columns)
            .map_err(|e| a.error_cmd(e.to_string(), None))
    }

    fn peratom_shape(&self) -> Option<(usize, u64)> {
        let n = self.inputs.len();
        Some((if n == 1 { 0 } else { n }, 1))
    }

    fn peratom(&self, sim: &Sim, head: &FixHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let p = &w.particles;
        let id = p
            .property(&self.prop)
            .ok_or_else(|| format!("fix {}: its values are gone", head.id))?;
        let k = col.map_or(0, |c| c - 1);
        Ok((0..p.nlocal()).map(|i| p.props[id.0].get(i)[k]).collect())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let due = if ctx.setup {
            !self.stored_all
        } else {
            self.every > 0 && ctx.step % self.every == 0
        };
        if !due {
            return Ok(());
        }
        self.stored_all = true;
        let columns = self.columns(ctx.view(), head.groupbit, true)?;
        self.write(ctx.world(), head.groupbit, &columns)
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&self.prop);
        }
    }
}
