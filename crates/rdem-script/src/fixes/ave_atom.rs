//! `fix ID group ave/atom Nevery Nrepeat Nfreq value ...`: per-atom time averages of
//! attributes (`x y z vx vy vz fx fy fz`), per-atom computes (`c_ID`, `c_ID[i]`), per-atom
//! fixes (`f_ID`, `f_ID[i]`) and atom-style variables (`v_name`), over `Nrepeat` samples
//! `Nevery` steps apart ending on each multiple of `Nfreq`; the result is a per-atom
//! vector (one value) or array (`f_ID[i]`) for dumps, 0 outside the group.
//!
//! The sums live in a per-particle property (`fix ave/atom ID`), so they follow the
//! particles through sorting and migration. As in LIGGGHTS, the same array holds the
//! running sum during a window and the average after it, and the steps follow LAMMPS'
//! `nextvalid` (with `Nrepeat` 1 a multiple of `Nfreq` at a run's set-up is sampled).

use super::sampling::Schedule;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{id_help, Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo::split_reference;
use crate::variables::Variable;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "ave/atom",
    parse,
    Stages::END_OF_STEP,
    "`x y z vx vy vz fx fy fz`, `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`; per-atom `f_ID[i]` in dumps",
)
.notes("the sums stay in the particles (a per-particle property) after `unfix`");

/// The attributes LIGGGHTS' ave/atom reads.
const ATTRIBUTES: [&str; 9] = ["x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"];

/// One input.
#[derive(Debug, Clone, PartialEq)]
enum Input {
    /// A particle attribute.
    Field(String),
    /// `c_ID` / `c_ID[i]`.
    Compute(String, Option<usize>),
    /// `f_ID` / `f_ID[i]`.
    Fix(String, Option<usize>),
    /// `v_name`.
    Variable(String),
}

/// `fix ave/atom`.
pub struct AveAtom {
    schedule: Schedule,
    inputs: Vec<Input>,
    /// Name of the per-particle property holding the values.
    prop: String,
}

impl AveAtom {
    /// The values of input `k` for the owned particles.
    fn input(&self, sim: &Sim, k: usize) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no simulation box")?;
        match &self.inputs[k] {
            Input::Field(f) => crate::computes::kernels::field_values(w, f)
                .ok_or_else(|| Error::invalid(format!("bad attribute {f}"))),
            Input::Compute(id, col) => crate::context::compute_peratom(sim, id, *col),
            Input::Fix(id, col) => super::fix_peratom(sim, id, *col),
            Input::Variable(v) => match sim.script.vars.get(v) {
                Some(Variable::Atom(f)) => crate::context::eval_atom(sim, f),
                _ => Err(format!("variable '{v}' is not atom-style").into()),
            },
        }
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut schedule = Schedule::parse(a)?;
    let nevery = schedule.nevery;
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        let k = a.pos();
        let input = if ATTRIBUTES.contains(&w) {
            Input::Field(w.to_string())
        } else {
            match split_reference(w) {
                Some(('c', id, col)) => {
                    let Some(c) = sim.defs.computes.iter().find(|c| c.id() == id) else {
                        let ids: Vec<&str> = sim.defs.computes.iter().map(|c| c.id()).collect();
                        return Err(a.error_at(
                            k,
                            format!("no compute '{id}'"),
                            Some(id_help("compute", id, &ids)),
                        ));
                    };
                    let n = c.peratom_cols();
                    let fits = match col {
                        None => n == 0,
                        Some(j) => j >= 1 && j <= n,
                    };
                    if !c.is_peratom() || !fits {
                        return Err(a.error_at(
                            k,
                            format!("'{w}' is not a per-atom vector or column of compute {id}"),
                            None,
                        ));
                    }
                    Input::Compute(id.to_string(), col)
                }
                Some(('f', id, col)) => {
                    let Some(f) = sim.defs.fixes.iter().find(|f| f.id() == id) else {
                        let ids: Vec<&str> = sim.defs.fixes.iter().map(|f| f.id()).collect();
                        return Err(a.error_at(
                            k,
                            format!("no fix '{id}'"),
                            Some(id_help("fix", id, &ids)),
                        ));
                    };
                    let Some((n, freq)) = f.imp.peratom_shape() else {
                        return Err(a.error_at(
                            k,
                            format!("fix {id} computes no per-atom values"),
                            None,
                        ));
                    };
                    let fits = match col {
                        None => n == 0,
                        Some(j) => j >= 1 && j <= n,
                    };
                    if !fits {
                        return Err(a.error_at(
                            k,
                            format!("'{w}' does not match fix {id}'s columns"),
                            None,
                        ));
                    }
                    if nevery % freq != 0 {
                        return Err(a.error_at(
                            k,
                            format!("fix {id} is not computed at compatible times (every {freq} steps; Nevery is {nevery})"),
                            None,
                        ));
                    }
                    Input::Fix(id.to_string(), col)
                }
                Some(('v', v, None))
                    if matches!(sim.script.vars.get(v), Some(Variable::Atom(_))) =>
                {
                    Input::Variable(v.to_string())
                }
                Some(('v', v, None)) => {
                    return Err(a.error_at(
                        k,
                        format!("variable '{v}' is not an atom-style variable"),
                        None,
                    ))
                }
                _ => {
                    return Err(a.error_at(
                        k,
                        format!("unknown ave/atom value '{w}'"),
                        Some(format!(
                            "{}, c_ID, c_ID[i], f_ID, f_ID[i] or v_name",
                            ATTRIBUTES.join(" ")
                        )),
                    ))
                }
            }
        };
        inputs.push(input);
        a.seek(k + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(a.pos(), "ave/atom needs at least one value", None));
    }
    let step = sim.world_ref(a)?.step;
    schedule.begin(step);
    let prop = format!("fix ave/atom {} ({} values)", head.id, inputs.len());
    Ok(Box::new(AveAtom {
        schedule,
        inputs,
        prop,
    }))
}

impl ScriptFix for AveAtom {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let n = self.inputs.len();
        let p = &mut sim.world_mut(a)?.particles;
        let id = p
            .add_property(&self.prop, n, &vec![0.0; n])
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
        // A redefinition with the same ID starts from zero.
        p.props[id.0].data.iter_mut().for_each(|v| *v = 0.0);
        Ok(())
    }

    fn peratom_shape(&self) -> Option<(usize, u64)> {
        let n = self.inputs.len();
        Some((if n == 1 { 0 } else { n }, self.schedule.nfreq))
    }

    fn peratom(&self, sim: &Sim, head: &FixHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let n = self.inputs.len();
        let k = match (col, n) {
            (None, 1) => 0,
            (Some(j), n) if j >= 1 && j <= n && n > 1 => j - 1,
            _ => {
                return Err(
                    format!("f_{}: fix {} gives {n} per-atom value(s)", head.id, head.id).into(),
                )
            }
        };
        let p = &sim.world.as_ref().ok_or("no simulation box")?.particles;
        let id = p.property(&self.prop).ok_or("its values are gone")?;
        let prop = &p.props[id.0];
        Ok((0..p.nlocal()).map(|i| prop.get(i)[k]).collect())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let Some(first) = self.schedule.due(step) else {
            return Ok(());
        };
        let values: Vec<Vec<f64>> = (0..self.inputs.len())
            .map(|k| self.input(ctx.view(), k))
            .collect::<Result<_, _>>()?;
        let p = &mut ctx.world().particles;
        let id = p.property(&self.prop).ok_or("its values are gone")?;
        let n = p.nlocal();
        let width = self.inputs.len();
        let (mask, prop) = (&p.mask, &mut p.props[id.0]);
        if first {
            prop.data[..n * width].iter_mut().for_each(|v| *v = 0.0);
        }
        for i in 0..n {
            if mask[i] & head.groupbit != 0 {
                let row = prop.get_mut(i);
                for (k, v) in values.iter().enumerate() {
                    row[k] += v[i];
                }
            }
        }
        if !self.schedule.sampled(step) {
            return Ok(());
        }
        let scale = 1.0 / self.schedule.nrepeat as f64;
        prop.data[..n * width].iter_mut().for_each(|v| *v *= scale);
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
