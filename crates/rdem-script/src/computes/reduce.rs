//! `compute ID group reduce mode input ...`: sums, extremes and means over the group of
//! per-atom properties, per-atom computes (`c_ID`, `c_ID[i]`), per-atom fix values (`f_ID`,
//! `f_ID[i]`) and atom-style variables.

use super::kernels::{field_values, reduce, REDUCE_MODES};
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::id_help;
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use crate::thermo;
use crate::variables::Variable;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "reduce",
    parse,
    "`sum\\|min\\|max\\|ave\\|sumsq\\|avesq` of per-atom properties, `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`",
);

/// One input.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    /// A per-atom field (`x`, `vx`, `radius`, ...).
    Field(String),
    /// `c_ID` or `c_ID[i]` of a per-atom compute.
    Compute(String, Option<usize>),
    /// `v_name` of an atom-style variable.
    Variable(String),
    /// `f_ID` or `f_ID[i]` of a fix with per-atom values (`property/atom`).
    Fix(String, Option<usize>),
}

/// The mode and the inputs.
#[derive(Debug)]
pub struct Reduce {
    /// `sum`, `min`, `max`, `ave`, `sumsq`, `avesq`.
    mode: String,
    /// Inputs (one gives a scalar, several a vector).
    inputs: Vec<Input>,
}

impl ScriptCompute for Reduce {
    fn shape(&self) -> Shape {
        if self.inputs.len() == 1 {
            Shape::scalar()
        } else {
            Shape::vector(self.inputs.len())
        }
    }

    /// LIGGGHTS: reduce sum is extensive, min/max/ave are not; sumsq follows sum, avesq
    /// follows ave.
    fn extensive(&self) -> bool {
        matches!(self.mode.as_str(), "sum" | "sumsq")
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let w = super::world(sim)?;
        let k = super::pick_index(&c.id, idx, self.inputs.len())?;
        let values = match &self.inputs[k] {
            Input::Field(f) => field_values(w, f).ok_or_else(|| format!("bad field {f}"))?,
            Input::Compute(cid, col) => crate::context::compute_peratom(sim, cid, *col)?,
            Input::Fix(fid, col) => crate::fixes::fix_peratom(sim, fid, *col)?,
            Input::Variable(v) => match sim.script.vars.get(v) {
                Some(Variable::Atom(f)) => crate::context::eval_atom(sim, f)?,
                _ => return Err(format!("variable '{v}' is not atom-style").into()),
            },
        };
        Ok(reduce(w, &self.mode, c.groupbit, &values))
    }
}

/// `compute ID group reduce mode input ...`.
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let mode = a.keyword("reduce mode", &REDUCE_MODES)?.to_string();
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        if w == "replace" {
            return Err(a.error_at(a.pos(), "compute reduce replace is not supported", None));
        }
        let input = if crate::atom_fields::is_field(w) {
            Input::Field(w.to_string())
        } else {
            match thermo::split_reference(w) {
                Some(('c', cid, col)) => match sim.defs.computes.iter().find(|c| c.id() == cid) {
                    Some(c) if c.is_peratom() => Input::Compute(cid.to_string(), col),
                    Some(_) => {
                        return Err(a.error_at(
                            a.pos(),
                            format!("compute {cid} is not per-atom"),
                            None,
                        ))
                    }
                    None => {
                        let ids: Vec<&str> = sim.defs.computes.iter().map(|c| c.id()).collect();
                        return Err(a.error_at(
                            a.pos(),
                            format!("no compute '{cid}'"),
                            Some(id_help("compute", cid, &ids)),
                        ));
                    }
                },
                Some(('v', v, None)) => Input::Variable(v.to_string()),
                Some(('f', fid, col)) => {
                    crate::fixes::check_fix_peratom(sim, fid, col)
                        .map_err(|m| a.error_at(a.pos(), m, None))?;
                    Input::Fix(fid.to_string(), col)
                }
                _ => {
                    return Err(a.error_at(
                        a.pos(),
                        format!("unknown reduce input '{w}'"),
                        Some(format!(
                            "a per-atom property ({}), c_ID, c_ID[N], f_ID, f_ID[N] or v_name",
                            crate::atom_fields::NAMES.join(" ")
                        )),
                    ))
                }
            }
        };
        inputs.push(input);
        a.seek(a.pos() + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(a.pos(), "compute reduce needs at least one input", None));
    }
    Ok(Box::new(Reduce { mode, inputs }))
}
