//! `compute ID group erotate/sphere`: Σ ½ I ω² over the group: a global scalar; and
//! `compute ID group erotate`, LIGGGHTS' sum over every particle shape, which for rdem's
//! spheres is the same value.

use super::kernels::erotate;
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "erotate/sphere",
    parse,
    "rotational kinetic energy of the group",
);

/// The registry row of `erotate` (LIGGGHTS sums spheres, superquadrics and multispheres;
/// rdem has spheres only).
pub(super) const ROW_ALL: ComputeRow = ComputeRow::runs(
    "erotate",
    parse,
    "rotational kinetic energy of the group (spheres)",
);

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(ERotateSphere))
}

/// `compute erotate/sphere`.
#[derive(Debug)]
pub struct ERotateSphere;

impl ScriptCompute for ERotateSphere {
    fn shape(&self) -> Shape {
        Shape::scalar()
    }

    fn extensive(&self) -> bool {
        true
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, String> {
        if let Some(k) = idx {
            let id = &c.id;
            return Err(format!("c_{id}[{k}]: compute {id} has no global vector"));
        }
        Ok(erotate(super::world(sim)?, c.groupbit))
    }
}
