//! `compute ID group property/atom field ...`: per-atom fields (one: a per-atom vector,
//! several: an array).

use super::kernels::field_values;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{suggest, Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs("property/atom", parse, "per-atom properties");

/// The fields.
#[derive(Debug)]
pub struct PropertyAtom(Vec<String>);

impl ScriptCompute for PropertyAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(if self.0.len() > 1 { self.0.len() } else { 0 })
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let k = super::pick_index(&c.id, col, self.0.len())?;
        field_values(super::world(sim)?, &self.0[k])
            .ok_or_else(|| Error::invalid(format!("bad field {}", self.0[k])))
    }
}

/// `compute ID group property/atom field ...`.
fn parse(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let mut f = Vec::new();
    while let Some(w) = a.peek() {
        if !crate::atom_fields::is_field(w) {
            return Err(a.error_at(
                a.pos(),
                format!("unknown per-atom property '{w}'"),
                Some(suggest(w, &crate::atom_fields::NAMES)),
            ));
        }
        f.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if f.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "compute property/atom needs at least one property",
            Some(format!(
                "e.g. radius; valid: {}",
                crate::atom_fields::NAMES.join(" ")
            )),
        ));
    }
    Ok(Box::new(PropertyAtom(f)))
}
