//! `compute ID group displace/atom`: each particle's displacement since the compute was
//! defined, 4 columns dx dy dz |d|, unwrapped through periodic boundaries with the image
//! flags (positions are compared as x + image · box length).

use crate::error::Error;
use std::collections::HashMap;

use glam::DVec3;
use rdem::World;

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "displace/atom",
    parse,
    "dx dy dz \\|d\\| since the definition, unwrapped through periodic boundaries",
)
.notes("a particle created after the compute has origin (0,0,0), as LIGGGHTS 3.8 reports");

/// The unwrapped positions at definition, by tag (every rank holds all of them, so a
/// particle that migrates keeps its origin).
#[derive(Debug)]
pub struct DisplaceAtom {
    origin: HashMap<rdem::particles::Tag, DVec3>,
}

/// x + image · box length of owned particle `i`.
fn unwrapped(w: &World, i: usize) -> DVec3 {
    let p = &w.particles;
    let size = w.domain.boxhi - w.domain.boxlo;
    p.x[i] + DVec3::from_array(p.image[i].get().map(f64::from)) * size
}

impl ScriptCompute for DisplaceAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(4)
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let k = super::pick_index(&c.id, col, 4)?;
        let w = super::world(sim)?;
        let p = &w.particles;
        Ok((0..p.nlocal())
            .map(|i| {
                if p.mask[i] & c.groupbit == 0 {
                    return 0.0;
                }
                // LIGGGHTS 3.8: a particle created after the compute was defined has
                // origin 0 (its displacement is its unwrapped position; checked with
                // create_atoms after the compute).
                let o = self.origin.get(&p.tag[i]).copied().unwrap_or(DVec3::ZERO);
                let d = unwrapped(w, i) - o;
                if k < 3 {
                    d[k]
                } else {
                    d.length()
                }
            })
            .collect())
    }
}

fn parse(sim: &Sim, _a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let mut origin = HashMap::new();
    if let Some(w) = &sim.world {
        let p = &w.particles;
        let mut mine = Vec::with_capacity(4 * p.nlocal());
        for i in 0..p.nlocal() {
            let u = unwrapped(w, i);
            mine.extend_from_slice(&[p.tag[i] as f64, u.x, u.y, u.z]);
        }
        // Untagged particles (none after create_atoms or a run) have no origin yet.
        for r in w
            .comm
            .all_gather(&mine)
            .chunks_exact(4)
            .filter(|r| r[0] > 0.0)
        {
            origin.insert(r[0] as rdem::particles::Tag, DVec3::new(r[1], r[2], r[3]));
        }
    }
    Ok(Box::new(DisplaceAtom { origin }))
}
