//! `compute ID group ke`: Σ ½ m v² over the group: a global scalar.

use super::kernels::kinetic;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow =
    ComputeRow::runs("ke", parse, "translational kinetic energy of the group");

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(Ke))
}

/// `compute ke`.
#[derive(Debug)]
pub struct Ke;

impl ScriptCompute for Ke {
    fn shape(&self) -> Shape {
        Shape::scalar()
    }

    fn extensive(&self) -> bool {
        true
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        if let Some(k) = idx {
            let id = &c.id;
            return Err(format!("c_{id}[{k}]: compute {id} has no global vector").into());
        }
        Ok(kinetic(super::world(sim)?, c.groupbit))
    }
}
