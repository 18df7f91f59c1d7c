//! `compute ID group erotate/multisphere` and `compute ID group ke/multisphere`: the
//! rotational (Σ ½ ω·I ω, in each body's principal frame) and translational (Σ ½ M V²)
//! kinetic energy of the rigid clumps of `fix multisphere`, global scalars. As in
//! LIGGGHTS, the group is ignored: every clump counts.

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row of `erotate/multisphere`.
pub(super) const ROW_EROTATE: ComputeRow = ComputeRow::runs(
    "erotate/multisphere",
    parse_erotate,
    "rotational kinetic energy of every clump (the group is ignored, as in LIGGGHTS)",
);

/// The registry row of `ke/multisphere`.
pub(super) const ROW_KE: ComputeRow = ComputeRow::runs(
    "ke/multisphere",
    parse_ke,
    "translational kinetic energy of every clump (the group is ignored, as in LIGGGHTS)",
);

fn parse_erotate(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    a.done()?;
    Ok(Box::new(ClumpEnergy { rotational: true }))
}

fn parse_ke(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    a.done()?;
    Ok(Box::new(ClumpEnergy { rotational: false }))
}

/// One of the two clump energies.
#[derive(Debug)]
pub struct ClumpEnergy {
    rotational: bool,
}

impl ScriptCompute for ClumpEnergy {
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
        // Every rank holds every clump: the sum is the same on every rank.
        let all = if self.rotational {
            super::kernels::erotate_clumps(w)
        } else {
            w.multisphere.as_ref().map_or(0.0, |ms| {
                ms.bodies.iter().map(|b| b.kinetic_energy().0).sum()
            })
        };
        Ok(all)
    }
}
