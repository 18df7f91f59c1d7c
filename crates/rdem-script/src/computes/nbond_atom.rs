//! `compute ID group nbond/atom`: intact bonds per particle (an rdem addition): a per-atom vector.

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow =
    ComputeRow::runs("nbond/atom", parse, "intact bonds per particle").notes("an rdem addition");

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(NBondAtom))
}

/// `compute nbond/atom`.
#[derive(Debug)]
pub struct NBondAtom;

impl ScriptCompute for NBondAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(0)
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        if col.is_some() {
            let id = &c.id;
            return Err(format!("compute {id} is a per-atom vector: use c_{id}").into());
        }
        Ok(super::world(sim)?.bonds_per_particle())
    }
}
