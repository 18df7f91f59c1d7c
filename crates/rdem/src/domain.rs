//! The simulation box, its boundaries, periodic remapping and the subdomain predicates of
//! seed 000. Serially the single subdomain is the whole box and the processor grid is
//! 1×1×1; with MPI each rank owns one brick of a Px×Py×Pz grid.

use glam::DVec3;

use crate::error::{Error, Result};
use crate::particles::Tag;

/// Distance by which a subdomain face that coincides with the global box is padded
/// outward in [`Domain::is_in_subdomain`] (LIGGGHTS' SMALL_DMBRDR).
pub const SUBDOMAIN_PAD: f64 = 1.0e-8;
/// Absolute tolerance used to decide that a subdomain face coincides with the box face.
pub const FACE_MATCH_TOL: f64 = 1.0e-13;
/// Shrink-wrapped faces are placed this fraction of the box length beyond the particles.
pub const SHRINK_MARGIN: f64 = 1.0e-4;

/// Boundary condition of one box face (LIGGGHTS `boundary` letters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// `p`: periodic.
    Periodic,
    /// `f`: fixed; particles beyond it are lost.
    Fixed,
    /// `s`: shrink-wrapped to the particles.
    Shrink,
    /// `m`: shrink-wrapped, but never smaller than the initial box.
    ShrinkMin,
}

impl Boundary {
    /// Parses one LIGGGHTS boundary letter.
    pub fn from_letter(c: char) -> Option<Self> {
        match c {
            'p' => Some(Self::Periodic),
            'f' => Some(Self::Fixed),
            's' => Some(Self::Shrink),
            'm' => Some(Self::ShrinkMin),
            _ => None,
        }
    }
    /// True for `s` and `m`.
    pub fn is_shrink(self) -> bool {
        matches!(self, Self::Shrink | Self::ShrinkMin)
    }
}

const AXES: [char; 3] = ['x', 'y', 'z'];

/// Box, boundaries and this process's subdomain.
#[derive(Debug, Clone, PartialEq)]
pub struct Domain {
    /// Lower box corner.
    pub boxlo: DVec3,
    /// Upper box corner.
    pub boxhi: DVec3,
    /// Box as first created (lower bound for `m` faces).
    pub initial_lo: DVec3,
    /// Box as first created.
    pub initial_hi: DVec3,
    /// `[axis][0 = lo face, 1 = hi face]`.
    pub boundary: [[Boundary; 2]; 3],
    /// Lower corner of this process's subdomain.
    pub sublo: DVec3,
    /// Upper corner of this process's subdomain.
    pub subhi: DVec3,
    /// Processor grid (Px, Py, Pz).
    pub procgrid: [usize; 3],
    /// This process's position in the grid.
    pub myloc: [usize; 3],
    /// Lees–Edwards shear of the periodic images (`fix lebc`), if any.
    pub shear: Option<crate::shear::Shear>,
}

impl Domain {
    /// A box from `lo` to `hi` with the same boundary on both faces of each axis.
    pub fn new(lo: DVec3, hi: DVec3, boundary: [Boundary; 3]) -> Result<Self> {
        Self::with_faces(lo, hi, boundary.map(|b| [b, b]))
    }

    /// A box with per-face boundaries (a periodic axis must be periodic on both faces).
    pub fn with_faces(lo: DVec3, hi: DVec3, boundary: [[Boundary; 2]; 3]) -> Result<Self> {
        for a in 0..3 {
            if !(lo[a].is_finite() && hi[a].is_finite() && lo[a] < hi[a]) {
                return Err(Error::Invalid {
                    what: "box",
                    reason: format!(
                        "along {} the lower bound {} must be finite and below the upper bound {}",
                        AXES[a], lo[a], hi[a]
                    ),
                });
            }
            let [l, h] = boundary[a];
            if (l == Boundary::Periodic) != (h == Boundary::Periodic) {
                return Err(Error::Invalid {
                    what: "boundary",
                    reason: format!("along {} both faces must be periodic, or neither", AXES[a]),
                });
            }
        }
        Ok(Self {
            boxlo: lo,
            boxhi: hi,
            initial_lo: lo,
            initial_hi: hi,
            boundary,
            sublo: lo,
            subhi: hi,
            procgrid: [1, 1, 1],
            myloc: [0, 0, 0],
            shear: None,
        })
    }

    /// Box lengths.
    pub fn prd(&self) -> DVec3 {
        self.boxhi - self.boxlo
    }
    /// True if `axis` is periodic.
    pub fn periodic(&self, axis: usize) -> bool {
        self.boundary[axis][0] == Boundary::Periodic
    }
    /// Per-axis periodicity.
    pub fn periodicity(&self) -> [bool; 3] {
        [self.periodic(0), self.periodic(1), self.periodic(2)]
    }
    /// Box volume.
    pub fn volume(&self) -> f64 {
        let p = self.prd();
        p.x * p.y * p.z
    }

    /// Seed 000 eq. (1): closed-box membership.
    pub fn is_in_domain(&self, x: DVec3) -> bool {
        (0..3).all(|a| self.boxlo[a] <= x[a] && x[a] <= self.boxhi[a])
    }

    /// Seed 000 eqs. (2)–(3): half-open subdomain membership `lo <= x < hi`, with faces that
    /// coincide with the global box (within [`FACE_MATCH_TOL`]) padded outward by
    /// [`SUBDOMAIN_PAD`].
    pub fn is_in_subdomain(&self, x: DVec3) -> bool {
        (0..3).all(|a| {
            let mut lo = self.sublo[a];
            let mut hi = self.subhi[a];
            if (lo - self.boxlo[a]).abs() < FACE_MATCH_TOL {
                lo -= SUBDOMAIN_PAD;
            }
            if (hi - self.boxhi[a]).abs() < FACE_MATCH_TOL {
                hi += SUBDOMAIN_PAD;
            }
            lo <= x[a] && x[a] < hi
        })
    }

    /// Seed 000 eqs. (4)–(5): membership of the extended subdomain used by insertion. Per
    /// axis: no constraint with one process along it; the last process only needs
    /// `x >= lo`, the first only `x <= hi`; the others `lo <= x < hi`.
    pub fn is_in_extended_subdomain(&self, x: DVec3) -> bool {
        (0..3).all(|a| {
            let p = self.procgrid[a];
            let m = self.myloc[a];
            if p == 1 {
                true
            } else if m == p - 1 {
                x[a] >= self.sublo[a]
            } else if m == 0 {
                x[a] <= self.subhi[a]
            } else {
                self.sublo[a] <= x[a] && x[a] < self.subhi[a]
            }
        })
    }

    /// Seed 000 eq. (6): true when `x` is at least `d[a]` away from both subdomain faces
    /// along every axis `a`.
    pub fn check_dist_subbox_borders(&self, x: DVec3, d: DVec3) -> bool {
        (0..3).all(|a| (x[a] - self.sublo[a]).abs() >= d[a] && (x[a] - self.subhi[a]).abs() >= d[a])
    }

    /// Smallest distance from `x` to the six subdomain faces.
    pub fn dist_subbox_borders(&self, x: DVec3) -> f64 {
        (0..3)
            .map(|a| {
                (x[a] - self.sublo[a])
                    .abs()
                    .min((x[a] - self.subhi[a]).abs())
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Seed 000 eqs. (7)–(8): the smallest subdomain extent and its axis; ties go to the
    /// higher axis.
    pub fn min_subbox_extent(&self) -> (f64, usize) {
        let ext = self.subhi - self.sublo;
        let mut best = (ext[0], 0);
        for a in 1..3 {
            if ext[a] <= best.0 {
                best = (ext[a], a);
            }
        }
        best
    }

    /// Seed 000 eq. (9): particle `i` (with `nlocal` owned particles) is a ghost lying
    /// within `cutneighmax` of a periodic face.
    pub fn is_periodic_ghost(&self, i: usize, nlocal: usize, x: DVec3, cutneighmax: f64) -> bool {
        i >= nlocal
            && (0..3).any(|a| {
                self.periodic(a)
                    && (x[a] < self.boxlo[a] + cutneighmax || x[a] > self.boxhi[a] - cutneighmax)
            })
    }

    /// Seed 000 eq. (10): `i == map(tag_i)`, i.e. `i` is the owned particle or the first
    /// ghost image of its tag. `map` returns the index the tag map holds for a tag.
    pub fn is_owned_or_first_ghost(i: usize, tag: Tag, map: impl Fn(Tag) -> Option<usize>) -> bool {
        map(tag) == Some(i)
    }

    /// Wraps `x` into the box along periodic axes, updating the image counts. Non-periodic
    /// axes are left alone. Image counts saturate at the `i32` range (a particle that far
    /// away means the run has blown up; it must not overflow), and a NaN coordinate is
    /// left as it is.
    pub fn remap(&self, x: &mut DVec3, image: &mut [i32; 3]) {
        let prd = self.prd();
        for a in 0..3 {
            if !self.periodic(a) {
                continue;
            }
            if x[a] < self.boxlo[a] || x[a] >= self.boxhi[a] {
                let n = ((x[a] - self.boxlo[a]) / prd[a]).floor();
                x[a] -= n * prd[a];
                // `as` saturates, and so does the addition.
                image[a] = image[a].saturating_add(n as i32);
                // Round-off can leave x exactly on the upper face.
                if x[a] >= self.boxhi[a] {
                    x[a] = self.boxlo[a];
                    image[a] = image[a].saturating_add(1);
                }
                if x[a] < self.boxlo[a] {
                    x[a] = self.boxlo[a];
                }
            }
        }
    }

    /// The order in which ghosts are made along the axes: x, y, z; under Lees–Edwards
    /// shear y first, so that the x images of the shifted y images follow.
    pub fn ghost_axes(&self) -> [usize; 3] {
        if self.shear.is_some() {
            [1, 0, 2]
        } else {
            [0, 1, 2]
        }
    }

    /// Advances the Lees–Edwards offset by one step of `dt` (no-op without shear);
    /// returns the box lengths the offset wrapped by ([`crate::shear::Shear::advance`]).
    pub fn advance_shear(&mut self, dt: f64) -> i32 {
        let prd = self.prd();
        match &mut self.shear {
            Some(s) => s.advance(dt, prd.x, prd.y),
            None => 0,
        }
    }

    /// Seed 002 eq. (4): the unwrapped position `x + n ⊙ L`.
    pub fn unmap(&self, x: DVec3, image: [i32; 3]) -> DVec3 {
        x + DVec3::new(image[0] as f64, image[1] as f64, image[2] as f64) * self.prd()
    }

    /// Checks that a new particle at `x` lies in the box along every axis that is neither
    /// periodic nor shrink-wrapped.
    pub fn check_inside_fixed(&self, x: DVec3) -> Result<()> {
        for a in 0..3 {
            let fixed_lo = self.boundary[a][0] == Boundary::Fixed;
            let fixed_hi = self.boundary[a][1] == Boundary::Fixed;
            if (fixed_lo && x[a] < self.boxlo[a]) || (fixed_hi && x[a] > self.boxhi[a]) {
                return Err(Error::OutsideBox {
                    x: x.x,
                    y: x.y,
                    z: x.z,
                    axis: AXES[a],
                    lo: self.boxlo[a],
                    hi: self.boxhi[a],
                });
            }
        }
        Ok(())
    }

    /// True when some face of the box is fixed (`f`), so that particles can be lost.
    pub fn has_fixed_face(&self) -> bool {
        self.boundary
            .iter()
            .flatten()
            .any(|&b| b == Boundary::Fixed)
    }

    /// True when a particle at `x` has left a fixed face and must be dropped.
    pub fn is_lost(&self, x: DVec3) -> bool {
        (0..3).any(|a| {
            (self.boundary[a][0] == Boundary::Fixed && x[a] < self.boxlo[a])
                || (self.boundary[a][1] == Boundary::Fixed && x[a] > self.boxhi[a])
        })
    }

    /// Shrink-wraps `s` and `m` faces around the particle extent `[lo, hi]` (global, over
    /// all ranks), with a margin of [`SHRINK_MARGIN`] × the *initial* box length (LAMMPS'
    /// `small`, fixed when the box is created, so the wrapped box depends only on the
    /// current particles, not on how often it was wrapped before); `m` faces never move
    /// inside the initial box. Serially the subdomain follows the box.
    pub fn shrink_wrap(&mut self, lo: DVec3, hi: DVec3) {
        let prd = self.initial_hi - self.initial_lo;
        for a in 0..3 {
            let small = SHRINK_MARGIN * prd[a];
            match self.boundary[a][0] {
                Boundary::Shrink if lo[a].is_finite() => self.boxlo[a] = lo[a] - small,
                Boundary::ShrinkMin if lo[a].is_finite() => {
                    self.boxlo[a] = (lo[a] - small).min(self.initial_lo[a])
                }
                _ => {}
            }
            match self.boundary[a][1] {
                Boundary::Shrink if hi[a].is_finite() => self.boxhi[a] = hi[a] + small,
                Boundary::ShrinkMin if hi[a].is_finite() => {
                    self.boxhi[a] = (hi[a] + small).max(self.initial_hi[a])
                }
                _ => {}
            }
        }
        self.update_subdomain();
    }

    /// Places this process at `rank` of the grid `procgrid` (x fastest, then y, then z,
    /// as LAMMPS' default map) and sets its subdomain: an equal share of the box per axis.
    pub fn set_grid(&mut self, procgrid: [usize; 3], rank: usize) {
        self.procgrid = procgrid;
        self.myloc = [
            rank % procgrid[0],
            (rank / procgrid[0]) % procgrid[1],
            rank / (procgrid[0] * procgrid[1]),
        ];
        self.update_subdomain();
    }

    /// Recomputes the subdomain from the box (after the box changed: shrink-wrap).
    pub fn update_subdomain(&mut self) {
        for a in 0..3 {
            let m = self.myloc[a];
            self.sublo[a] = self.cut(a, m);
            self.subhi[a] = self.cut(a, m + 1);
        }
    }

    /// The `m`-th cut of the processor grid along axis `a` (0 ..= Pa): the box faces at
    /// the ends, an equal share of the box between.
    pub fn cut(&self, a: usize, m: usize) -> f64 {
        let p = self.procgrid[a];
        if m == 0 {
            self.boxlo[a]
        } else if m == p {
            self.boxhi[a]
        } else {
            self.boxlo[a] + (self.boxhi[a] - self.boxlo[a]) * m as f64 / p as f64
        }
    }

    /// Grid position (per axis) of the subdomain that owns `x` under the half-open rule of
    /// [`Domain::is_in_subdomain`]; points outside the box go to the nearest edge brick.
    pub fn owner_loc(&self, x: DVec3) -> [usize; 3] {
        let prd = self.prd();
        let mut loc = [0; 3];
        for a in 0..3 {
            let p = self.procgrid[a];
            if p == 1 {
                continue;
            }
            // The same boundaries `update_subdomain` computes, searched from the estimate.
            let bound = |m: usize| self.cut(a, m);
            let est = ((x[a] - self.boxlo[a]) / prd[a] * p as f64).floor();
            let mut m = if est.is_nan() {
                0
            } else {
                est.clamp(0.0, (p - 1) as f64) as usize
            };
            while m > 0 && x[a] < bound(m) {
                m -= 1;
            }
            while m + 1 < p && x[a] >= bound(m + 1) {
                m += 1;
            }
            loc[a] = m;
        }
        loc
    }

    /// Rank of the grid position `loc` (x fastest).
    pub fn rank_of(&self, loc: [usize; 3]) -> usize {
        loc[0] + self.procgrid[0] * (loc[1] + self.procgrid[1] * loc[2])
    }

    /// Checks that the ghost cutoff fits in one neighbouring subdomain along every axis
    /// split between several ranks (ghosts come from the adjacent ranks only).
    pub fn check_subdomain_cutoff(&self, cutoff: f64) -> Result<()> {
        let ext = self.sub_extent();
        for a in 0..3 {
            if self.procgrid[a] > 1 && ext[a] < cutoff {
                return Err(Error::Invalid {
                    what: "processors",
                    reason: format!(
                        "the subdomains are {} long along {}, less than the neighbor cutoff \
                         {cutoff} (twice the largest radius plus the skin); use fewer \
                         processors along {} ('processors' command)",
                        ext[a], AXES[a], AXES[a]
                    ),
                });
            }
        }
        Ok(())
    }

    /// Extent of the subdomain along each axis.
    pub fn sub_extent(&self) -> DVec3 {
        self.subhi - self.sublo
    }

    /// True if any face is shrink-wrapped.
    pub fn has_shrink(&self) -> bool {
        self.boundary.iter().flatten().any(|b| b.is_shrink())
    }

    /// Checks that every periodic length is at least twice `contact`, the largest
    /// distance at which two particles interact (the neighbor cutoff without the skin):
    /// then a particle interacts with at most one periodic image of each partner, and
    /// never with its own image. Boxes shorter than twice the neighbor cutoff are allowed
    /// (the ghosts then hold several images of a particle, and the neighbor list may hold
    /// two images of one partner, one of which can touch); see
    /// [`Domain::short_periodic_half`].
    pub fn check_periodic_contact(&self, contact: f64) -> Result<()> {
        let prd = self.prd();
        for a in 0..3 {
            if self.periodic(a) && prd[a] < 2.0 * contact {
                return Err(Error::PeriodicBoxTooSmall {
                    axis: AXES[a],
                    len: prd[a],
                    contact,
                });
            }
        }
        Ok(())
    }

    /// Half the shortest periodic length that is less than twice `cutoff`, if any: the
    /// neighbor list can then hold more than one image of a partner (LAMMPS and
    /// LIGGGHTS run such boxes too; their ghost exchange makes as many image layers as
    /// the cutoff needs).
    pub fn short_periodic_half(&self, cutoff: f64) -> Option<f64> {
        let prd = self.prd();
        (0..3)
            .filter(|&a| self.periodic(a) && prd[a] < 2.0 * cutoff)
            .map(|a| 0.5 * prd[a])
            .reduce(f64::min)
    }
}

/// The processor grid for `nprocs` ranks: among the factorizations Px·Py·Pz = nprocs that
/// agree with `fixed` (0 = free), the one with the least total subdomain surface for a box
/// of lengths `prd` (LAMMPS' default rule; ties go to the first found, Px varying slowest).
/// `None` when no factorization agrees with `fixed`.
pub fn least_surface_grid(nprocs: usize, prd: DVec3, fixed: [usize; 3]) -> Option<[usize; 3]> {
    let mut best: Option<([usize; 3], f64)> = None;
    for px in 1..=nprocs {
        if nprocs % px != 0 || (fixed[0] != 0 && fixed[0] != px) {
            continue;
        }
        for py in 1..=nprocs / px {
            if (nprocs / px) % py != 0 || (fixed[1] != 0 && fixed[1] != py) {
                continue;
            }
            let pz = nprocs / px / py;
            if fixed[2] != 0 && fixed[2] != pz {
                continue;
            }
            let (a, b, c) = (prd.x / px as f64, prd.y / py as f64, prd.z / pz as f64);
            let surf = a * b + b * c + a * c;
            if best.is_none_or(|(_, s)| surf < s) {
                best = Some(([px, py, pz], surf));
            }
        }
    }
    best.map(|(g, _)| g)
}

#[cfg(test)]
mod grid_tests {
    use super::*;

    #[test]
    fn least_surface_grid_splits_the_long_axis() {
        let prd = DVec3::new(1.0, 1.0, 4.0);
        assert_eq!(least_surface_grid(2, prd, [0; 3]), Some([1, 1, 2]));
        assert_eq!(least_surface_grid(4, prd, [0; 3]), Some([1, 1, 4]));
        assert_eq!(least_surface_grid(4, DVec3::ONE, [0; 3]), Some([1, 2, 2]));
        assert_eq!(least_surface_grid(4, prd, [2, 0, 0]), Some([2, 1, 2]));
        assert_eq!(least_surface_grid(4, prd, [3, 0, 0]), None);
        assert_eq!(least_surface_grid(1, prd, [0; 3]), Some([1, 1, 1]));
    }

    #[test]
    fn every_point_has_exactly_one_owner() {
        let mut d = Domain::new(
            DVec3::new(-0.3, 0.0, 0.1),
            DVec3::new(0.7, 1.0, 0.4),
            [Boundary::Periodic, Boundary::Fixed, Boundary::Fixed],
        )
        .unwrap();
        let grid = [3, 1, 2];
        let pts = [
            DVec3::new(-0.3, 0.5, 0.1),
            DVec3::new(0.7, 0.5, 0.4),
            DVec3::new(-0.3 + 1.0 / 3.0, 0.2, 0.25),
            DVec3::new(0.0333, 0.9, 0.2499999),
            DVec3::new(0.366666, 0.0, 0.25),
        ];
        for x in pts {
            let mut owners = vec![];
            for r in 0..6 {
                d.set_grid(grid, r);
                if d.is_in_subdomain(x) {
                    owners.push(r);
                }
            }
            assert_eq!(owners.len(), 1, "{x:?}: {owners:?}");
            assert_eq!(d.rank_of(d.owner_loc(x)), owners[0], "{x:?}");
        }
    }
}
