//! `compute ID group erotate/sphere`: Σ ½ I ω² over the free spheres of the group (a
//! clump's spheres count nothing, as in LIGGGHTS 3.8): a global scalar; and `compute ID
//! group erotate`, LIGGGHTS' sum over every particle shape: those spheres plus every
//! clump's ½ ω·L (LIGGGHTS 3.8 printed erotate/multisphere's value for it on the tutorial
//! multisphere_stone_restitution, with erotate/sphere 0).

use super::kernels::{erotate, erotate_clumps};
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "erotate/sphere",
    parse,
    "rotational kinetic energy of the group",
);

/// The registry row of `erotate` (LIGGGHTS sums spheres, superquadrics and multispheres;
/// rdem has spheres and clumps).
pub(super) const ROW_ALL: ComputeRow = ComputeRow::runs(
    "erotate",
    parse_all,
    "rotational kinetic energy of the group's free spheres and of every clump",
);

fn parse(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(ERotateSphere { clumps: false }))
}

fn parse_all(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(ERotateSphere { clumps: true }))
}

/// `compute erotate/sphere` (or, with the clumps, `compute erotate`).
#[derive(Debug)]
pub struct ERotateSphere {
    /// Adds every clump's rotational energy (`erotate`).
    clumps: bool,
}

impl ScriptCompute for ERotateSphere {
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
        let w = super::world(sim)?;
        let clumps = if self.clumps { erotate_clumps(w) } else { 0.0 };
        Ok(erotate(w, c.groupbit) + clumps)
    }
}
