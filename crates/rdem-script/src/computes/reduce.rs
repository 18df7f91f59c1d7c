//! `compute ID group reduce mode input ...`: sums, extremes and means over the group of
//! per-atom properties, per-atom computes (`c_ID`, `c_ID[i]`), per-atom fix values (`f_ID`,
//! `f_ID[i]`) and atom-style variables, and over every row (the group aside, as in LAMMPS)
//! of a local compute's column (`compute pair/gran/local`, ...: the largest overlap, say).
//! With no value at all, `min` is 1e20 and `max` −1e20, as LIGGGHTS 3.8 prints them.

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
    "`sum\\|min\\|max\\|ave\\|sumsq\\|avesq` of per-atom properties, `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, `v_name`, and of the columns `c_ID[i]` of local computes (every contact, the group aside)",
);

/// One input.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    /// A per-atom field (`x`, `vx`, `radius`, ...).
    Field(String),
    /// `c_ID` or `c_ID[i]` of a per-atom compute.
    Compute(String, Option<usize>),
    /// `c_ID` or `c_ID[i]` (0-based column here) of a local compute: every row.
    Local(String, usize),
    /// `v_name` of an atom-style variable.
    Variable(String),
    /// `f_ID` or `f_ID[i]` of a fix with per-atom values (`property/atom`).
    Fix(String, Option<usize>),
}

/// The registry row of `reduce/region`.
pub(super) const ROW_REGION: ComputeRow = ComputeRow::runs(
    "reduce/region",
    parse_region,
    "`REGION` then as `reduce`, over the group's particles inside the region (its surface included, as LIGGGHTS 3.8 counts it); per-atom inputs only",
);

/// The mode and the inputs.
#[derive(Debug)]
pub struct Reduce {
    /// `reduce/region`: the region the particles must be in.
    region: Option<String>,
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
            Input::Local(cid, col) => {
                let lc = sim
                    .defs
                    .computes
                    .iter()
                    .find(|c| c.id() == cid)
                    .ok_or_else(|| Error::undefined("compute", cid))?;
                let width = lc.imp.local_cols().unwrap_or(1).max(1);
                let rows = lc.imp.local(sim, &lc.head)?;
                let column = rows.chunks_exact(width).map(|r| r[*col]);
                return Ok(super::kernels::reduce_over(w, &self.mode, column));
            }
            Input::Fix(fid, col) => crate::fixes::fix_peratom(sim, fid, *col)?,
            Input::Variable(v) => match sim.script.vars.get(v) {
                Some(Variable::Atom(f)) => crate::context::eval_atom(sim, f)?,
                _ => return Err(format!("variable '{v}' is not atom-style").into()),
            },
        };
        match &self.region {
            None => Ok(reduce(w, &self.mode, c.groupbit, &values)),
            Some(r) => {
                let region = crate::regions::region_now(sim, r)?;
                let p = &w.particles;
                let inside = (0..p.nlocal())
                    .filter(|&i| p.mask[i] & c.groupbit != 0 && region.contains(p.x[i]))
                    .map(|i| values[i]);
                Ok(super::kernels::reduce_over(w, &self.mode, inside))
            }
        }
    }
}

/// `compute ID group reduce/region REGION mode input ...`.
fn parse_region(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let region = sim.region_id(a)?;
    let at = a.pos();
    let mut r = parse_reduce(sim, a)?;
    if let Some(k) = r.inputs.iter().position(|i| matches!(i, Input::Local(..))) {
        return Err(a.error_at(
            at + 1 + k,
            "compute reduce/region takes per-atom inputs (a local compute's rows have no position)",
            None,
        ));
    }
    r.region = Some(region);
    Ok(Box::new(r))
}

/// `compute ID group reduce mode input ...`.
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(parse_reduce(sim, a)?))
}

/// The mode and inputs of `reduce` and `reduce/region`.
fn parse_reduce(sim: &Sim, a: &mut Args) -> CmdResult<Reduce> {
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
                    Some(c) if c.imp.local_cols().is_some() => {
                        let n = c.imp.local_cols().unwrap_or(0);
                        match col {
                            Some(k) if k >= 1 && k <= n => Input::Local(cid.to_string(), k - 1),
                            None if n == 1 => Input::Local(cid.to_string(), 0),
                            _ => {
                                return Err(a.error_at(
                                    a.pos(),
                                    format!("compute {cid} gives {n} local column(s)"),
                                    Some(format!("use c_{cid}[1..{n}]")),
                                ))
                            }
                        }
                    }
                    Some(_) => {
                        return Err(a.error_at(
                            a.pos(),
                            format!("compute {cid} is neither per-atom nor local"),
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
    Ok(Reduce {
        region: None,
        mode,
        inputs,
    })
}
