//! `fix wall/sph xplane|yplane|zplane lo hi r0 D`: a repulsive plane wall for SPH
//! particles (Monaghan 1992's boundary force in the form LIGGGHTS 3.8 uses): a particle
//! at distance r < r0 from a plane is pushed away from it, on either side, by
//! F = D ((r0/r)⁴ − (r0/r)²) (measured: the force does not depend on the particle's mass,
//! velocity or pressure). `lo` and `hi` are the planes' positions, each may be absent
//! (`NULL`). It acts in the post-force stage, also at a run's set-up.

use glam::DVec3;

use super::kernel::KernelKind;
use crate::region::Region;

/// A `wall/sph` fix.
#[derive(Debug, Clone, PartialEq)]
pub struct SphWall {
    /// Axis normal to the planes (0 = x).
    pub axis: usize,
    /// Positions of the planes (`NULL` = none).
    pub planes: [Option<f64>; 2],
    /// Reach r0.
    pub r0: f64,
    /// Strength D (force).
    pub d: f64,
    /// Kernel (set by `set sphkernel`; LIGGGHTS' wall holds one, the force above does not
    /// use it).
    pub kernel: Option<KernelKind>,
}

impl SphWall {
    /// The wall force on a particle at `x`.
    #[inline]
    pub fn force(&self, x: DVec3) -> DVec3 {
        let mut f = DVec3::ZERO;
        for plane in self.planes.iter().flatten() {
            let s = x[self.axis] - plane;
            let r = s.abs();
            if r < self.r0 && r > 0.0 {
                let q = self.r0 / r;
                let q2 = q * q;
                f[self.axis] += self.d * (q2 * q2 - q2) * s.signum();
            }
        }
        f
    }
}

/// `fix wall/region/sph region r0 D`: each part of the region's surface within r0 of a
/// particle in it ([`Region::surface`]) pushes it away from the surface with
/// the force of [`SphWall`], plus the pressure force of a copy of the particle at the
/// wall, −m² (2P/ρ²) dW/dr(r, sl) (measured on LIGGGHTS 3.8: no viscous or
/// tensile-correction term, only within r0; the manual: "they can see a clone of
/// theirself at the wall"; a sphere region's force points to its centre, measured).
#[derive(Debug, Clone, PartialEq)]
pub struct SphRegionWall {
    /// The region (one that [`Region::max_surface_contacts`] knows).
    pub region: Region,
    /// Reach r0.
    pub r0: f64,
    /// Strength D.
    pub d: f64,
    /// Kernel (set by `set sphkernel`).
    pub kernel: Option<KernelKind>,
    /// Smoothing length per type (`sl`, from the pair style at set-up).
    pub sl: Vec<f64>,
}

impl SphRegionWall {
    /// The forces on the owned particles of `groupbit`.
    pub fn apply(&self, p: &mut crate::Particles, groupbit: u32) {
        let Some(k) = self.kernel else { return };
        let Some(props) = super::SphProps::find(p) else {
            return;
        };
        super::kernel::with_kernel!(k, K, self.apply_with::<K>(p, props, groupbit))
    }

    fn apply_with<K: super::Kernel>(
        &self,
        p: &mut crate::Particles,
        props: super::SphProps,
        bit: u32,
    ) {
        let n = p.nlocal();
        let rho = &p.props[props.rho.0].data;
        let pr = &p.props[props.p.0].data;
        let mut found = [(0.0, DVec3::ZERO); crate::region::MAX_SURFACE_CONTACTS];
        for i in 0..n {
            if p.mask[i] & bit == 0 {
                continue;
            }
            let n = self.region.surface(p.x[i], self.r0, &mut found);
            if n == 0 {
                continue;
            }
            let h = self.sl.get(p.ty[i] as usize).copied().unwrap_or(0.0);
            let m = p.rmass[i];
            let clone = 2.0 * pr[i] / (rho[i] * rho[i]) * m * m;
            for &(r, normal) in &found[..n] {
                let q = self.r0 / r;
                let q2 = q * q;
                let fw = self.d * (q2 * q2 - q2) - clone * K::dw(r, h);
                p.f[i] += fw * normal;
            }
        }
    }
}
