//! `compute ID group contact/atom`: the number of particles each particle touches: a per-atom vector.

use super::kernels::contact_counts;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "contact/atom",
    parse,
    "number of particle contacts per particle",
);

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(ContactAtom))
}

/// `compute contact/atom`.
#[derive(Debug)]
pub struct ContactAtom;

impl ScriptCompute for ContactAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(0)
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        if col.is_some() {
            let id = &c.id;
            return Err(format!("compute {id} is a per-atom vector: use c_{id}").into());
        }
        Ok(contact_counts(super::world(sim)?))
    }
}
