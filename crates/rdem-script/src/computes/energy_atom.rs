//! Per-atom energies: `compute ID group ke/atom` (½ m v²) and
//! `compute ID group erotate/sphere/atom` (½ I ω², I = 2/5 m r²); 0 outside the group
//! and for a clump's spheres (as LIGGGHTS 3.8).

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row of `ke/atom`.
pub(super) const ROW_KE: ComputeRow = ComputeRow::runs(
    "ke/atom",
    parse_ke,
    "per-atom translational kinetic energy ½ m v²",
);

/// The registry row of `erotate/sphere/atom`.
pub(super) const ROW_EROTATE: ComputeRow = ComputeRow::runs(
    "erotate/sphere/atom",
    parse_erotate,
    "per-atom rotational kinetic energy ½ I ω²",
);

/// Which energy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// ½ m v².
    Translation,
    /// ½ I ω².
    Rotation,
}

/// `compute ke/atom` or `compute erotate/sphere/atom`.
#[derive(Debug)]
pub struct EnergyAtom {
    kind: Kind,
}

impl ScriptCompute for EnergyAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(0)
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        super::pick_index(&c.id, col, 1)?;
        let w = super::world(sim)?;
        let p = &w.particles;
        let clump = super::kernels::clump_spheres(w);
        Ok((0..p.nlocal())
            .map(|i| {
                if p.mask[i] & c.groupbit == 0 {
                    0.0
                } else if self.kind == Kind::Translation {
                    0.5 * p.rmass[i] * p.v[i].length_squared()
                } else if clump(i) {
                    // A clump's sphere: 0, as LIGGGHTS 3.8 prints (see kernels::erotate).
                    0.0
                } else {
                    0.5 * p.inertia(i) * p.omega[i].length_squared()
                }
            })
            .collect())
    }
}

fn parse_ke(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(EnergyAtom {
        kind: Kind::Translation,
    }))
}

fn parse_erotate(_sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    Ok(Box::new(EnergyAtom {
        kind: Kind::Rotation,
    }))
}
