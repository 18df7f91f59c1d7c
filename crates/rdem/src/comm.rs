//! Communication seam. The engine talks to other subdomains only through [`Comm`]; the
//! serial case is the one-rank implementation [`Serial`], whose only ghosts are periodic
//! images. An MPI implementation (feature `mpi`, a later issue) implements the same trait.

use glam::DVec3;

use crate::domain::Domain;
use crate::particles::Particles;

/// Exchange of particles and ghost data between subdomains, and global reductions.
pub trait Comm: std::fmt::Debug + Send {
    /// This process's rank.
    fn rank(&self) -> usize;
    /// Number of ranks.
    fn size(&self) -> usize;
    /// Moves owned particles that left this subdomain to their new owners. Ghosts must
    /// have been cleared.
    fn exchange(&mut self, p: &mut Particles, domain: &Domain);
    /// Creates ghosts of every particle within `cutoff` of a subdomain face (including
    /// periodic images), after the locals.
    fn borders(&mut self, p: &mut Particles, domain: &Domain, cutoff: f64);
    /// Refreshes ghost positions, velocities, angular velocities, radii and masses from
    /// their owners (radii and masses change between re-neighborings under `fix adapt`).
    fn forward(&mut self, p: &mut Particles);
    /// Adds ghost forces and torques onto their owners.
    fn reverse(&mut self, p: &mut Particles);
    /// Adds the per-particle virial of ghosts (`virial[g]`, 6 components) onto their
    /// owners, as [`Comm::reverse`] does for forces.
    fn reverse_virial(&mut self, p: &Particles, virial: &mut [[f64; 6]]);
    /// Global sum.
    fn sum(&self, x: f64) -> f64;
    /// Global sum of a count.
    fn sum_count(&self, x: u64) -> u64;
    /// Global minimum.
    fn min(&self, x: f64) -> f64;
    /// Global maximum.
    fn max(&self, x: f64) -> f64;
    /// Global maximum of a count or tag.
    fn max_count(&self, x: u64) -> u64;
    /// Sum of `x` over the ranks below this one (exclusive prefix sum), for tag extension.
    fn exclusive_prefix_count(&self, x: u64) -> u64;
}

/// One process owning the whole box. Ghosts are the periodic images within the cutoff,
/// made axis by axis so that edge and corner images exist too.
#[derive(Debug, Clone, Default)]
pub struct Serial {
    /// Shift of each ghost relative to its owner (index `g - nlocal`).
    shift: Vec<DVec3>,
}

impl Serial {
    /// The serial communicator.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Comm for Serial {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn exchange(&mut self, _p: &mut Particles, _domain: &Domain) {}

    fn borders(&mut self, p: &mut Particles, domain: &Domain, cutoff: f64) {
        p.clear_ghosts();
        self.shift.clear();
        let prd = domain.prd();
        let nlocal = p.nlocal();
        for a in 0..3 {
            if !domain.periodic(a) {
                continue;
            }
            let n = p.len();
            let mut l = DVec3::ZERO;
            l[a] = prd[a];
            for i in 0..n {
                let base = if i < nlocal {
                    DVec3::ZERO
                } else {
                    self.shift[i - nlocal]
                };
                let xa = p.x[i][a];
                if xa < domain.boxlo[a] + cutoff {
                    p.push_ghost(i, l);
                    self.shift.push(base + l);
                }
                if xa >= domain.boxhi[a] - cutoff {
                    p.push_ghost(i, -l);
                    self.shift.push(base - l);
                }
            }
        }
    }

    fn forward(&mut self, p: &mut Particles) {
        let nlocal = p.nlocal();
        for (k, &s) in self.shift.iter().enumerate() {
            let g = nlocal + k;
            let o = p.origin[g];
            p.x[g] = p.x[o] + s;
            p.v[g] = p.v[o];
            p.omega[g] = p.omega[o];
            p.radius[g] = p.radius[o];
            p.rmass[g] = p.rmass[o];
        }
    }

    fn reverse(&mut self, p: &mut Particles) {
        let nlocal = p.nlocal();
        for g in nlocal..p.len() {
            let o = p.origin[g];
            let (f, t) = (p.f[g], p.torque[g]);
            p.f[o] += f;
            p.torque[o] += t;
        }
    }

    fn reverse_virial(&mut self, p: &Particles, virial: &mut [[f64; 6]]) {
        let nlocal = p.nlocal();
        for g in nlocal..p.len() {
            let o = p.origin[g];
            let w = virial[g];
            for (a, b) in virial[o].iter_mut().zip(&w) {
                *a += b;
            }
        }
    }

    fn sum(&self, x: f64) -> f64 {
        x
    }
    fn sum_count(&self, x: u64) -> u64 {
        x
    }
    fn min(&self, x: f64) -> f64 {
        x
    }
    fn max(&self, x: f64) -> f64 {
        x
    }
    fn max_count(&self, x: u64) -> u64 {
        x
    }
    fn exclusive_prefix_count(&self, _x: u64) -> u64 {
        0
    }
}
