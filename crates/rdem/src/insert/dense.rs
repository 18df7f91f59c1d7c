//! `fix insert/pack/dense` (LIGGGHTS-PFM): a dense random packing of a distribution's
//! particles that fills a region once, grown by an advancing front.
//!
//! The algorithm, as LIGGGHTS-PFM's manual and fix describe it (written anew here):
//!
//! 1. The particles are packed with radii enlarged by f = ∛(0.57 / φ), φ the requested
//!    volume fraction (at most 0.57, the densest packing the front reaches); they are
//!    inserted with their own radii, so the packing of enlarged spheres, about 0.57 of
//!    the region, leaves the real spheres at about φ, with gaps of at least
//!    (f − 1)(rᵢ + rⱼ) between new neighbours. Near walls the front packs looser, so when
//!    the count misses φ V / v̄ by more than 1 %, rdem packs again from the same random
//!    numbers with f corrected by the cube root of the ratio (never below 1); this second
//!    packing is rdem's (LIGGGHTS-PFM inserts its first).
//! 2. Three touching spheres start the packing at the centre of the region's box (or a
//!    random point of the region where 2.155 enlarged radii fit), turned at random.
//! 3. Every placed sphere joins the front, a first-in first-out queue. For the sphere at
//!    the head of the queue, the next particle of the distribution is placed touching it
//!    and two of its neighbours (the points at the right distances from the three
//!    centres), at the valid point nearest the start: inside the insertion box, the whole
//!    enlarged sphere in the region, overlapping no sphere. This repeats while more than
//!    one valid point was found; a particle with no valid point waits for the next front
//!    sphere, and the head leaves the queue. The packing ends when the queue is empty.
//!
//! Particles already there (on any rank) take part with their own radii. Every rank packs
//! the same particles from the same random numbers and keeps those in its subdomain, so
//! the result does not depend on the number of ranks (LIGGGHTS-PFM packs each subdomain
//! on its own rank). Nothing here is drawn per step: the fix acts once (or every N steps).

use std::collections::VecDeque;

use glam::DVec3;
use rand::Rng;

use super::place::{add_placed, draw_velocity, random_rotation, Placed, TagCursor};
use super::{Distribution, InsertRng, VelocityLaw};
use crate::error::{Error, Result};
use crate::region::Region;
use crate::world::World;

/// The densest volume fraction the front reaches with the enlarged spheres (and the
/// largest volume fraction the fix accepts; LIGGGHTS-PFM's `max_volfrac`).
pub const MAX_VOLUME_FRACTION: f64 = 0.57;

/// Radius of the sphere around the start point that the three first spheres need, in
/// largest enlarged radii: the circumscribed sphere of three touching spheres,
/// (1 + 2/√3) r ≈ 2.155 r.
const START_REACH: f64 = 2.155;

/// Settings and state of one `fix insert/pack/dense`.
#[derive(Debug, Clone)]
pub struct DensePack {
    /// Fix ID.
    pub id: String,
    /// Group bits given to inserted particles (besides `all`).
    pub groupbit: u32,
    /// Insertion region (bounded).
    pub region: Region,
    /// Particle mix.
    pub dist: Distribution,
    /// The volume fraction asked for (at most [`MAX_VOLUME_FRACTION`]).
    pub volume_fraction: f64,
    /// `insert_every N` (insertion at the steps that are multiples of N), or `None`: once.
    pub every: Option<u64>,
    /// Velocity law of the inserted particles.
    pub velocity: VelocityLaw,
    /// Angular velocity of the inserted particles.
    pub omega: DVec3,
    rng: InsertRng,
    done: bool,
}

/// What one dense insertion did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DenseReport {
    /// Particles the volume fraction asks for: ⌊(φ V − V_present) / v̄⌋.
    pub estimate: u64,
    /// Particles inserted.
    pub inserted: u64,
    /// Their mass.
    pub mass: f64,
    /// Their volume over the region's volume.
    pub volume_fraction: f64,
    /// Region volume used for the estimate.
    pub region_volume: f64,
    /// The factor the radii were enlarged by for the packing that was inserted.
    pub radius_factor: f64,
}

/// A sphere of the packing: centre and (enlarged, for new ones) radius.
#[derive(Debug, Clone, Copy)]
struct Sphere {
    x: DVec3,
    r: f64,
}

/// The spheres of the packing on a grid of cubic cells (a linked list per cell), for the
/// neighbour and overlap queries.
#[derive(Clone)]
struct Cells {
    lo: DVec3,
    size: f64,
    dims: [usize; 3],
    head: Vec<u32>,
    next: Vec<u32>,
    spheres: Vec<Sphere>,
}

const NONE: u32 = u32::MAX;

impl Cells {
    /// A grid over the box `lo..hi` with cells of `size` (at least the largest reach of a
    /// query), or an error when it would be unreasonably large.
    fn new(lo: DVec3, hi: DVec3, size: f64) -> Result<Self> {
        let ext = (hi - lo).max(DVec3::splat(size));
        let dims = [0, 1, 2].map(|a| ((ext[a] / size).ceil() as usize).max(1));
        let n = dims[0] as u128 * dims[1] as u128 * dims[2] as u128;
        if n > 200_000_000 {
            return Err(Error::Invalid {
                what: "insert/pack/dense",
                reason: format!(
                    "the region holds too many particles for the packing grid ({n} cells of {size})"
                ),
            });
        }
        Ok(Self {
            lo,
            size,
            dims,
            head: vec![NONE; n as usize],
            next: Vec::new(),
            spheres: Vec::new(),
        })
    }

    fn cell_of(&self, x: DVec3) -> [usize; 3] {
        [0, 1, 2].map(|a| {
            let c = ((x[a] - self.lo[a]) / self.size).floor();
            c.clamp(0.0, (self.dims[a] - 1) as f64) as usize
        })
    }

    fn index(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// Adds a sphere; returns its index.
    fn push(&mut self, s: Sphere) -> usize {
        let k = self.spheres.len();
        let cell = self.index(self.cell_of(s.x));
        self.spheres.push(s);
        self.next.push(self.head[cell]);
        self.head[cell] = k as u32;
        k
    }

    /// Calls `f` with every sphere index in the 27 cells around `x`.
    fn around(&self, x: DVec3, mut f: impl FnMut(usize) -> bool) -> bool {
        let c = self.cell_of(x);
        let range = |a: usize| c[a].saturating_sub(1)..=(c[a] + 1).min(self.dims[a] - 1);
        for z in range(2) {
            for y in range(1) {
                for xx in range(0) {
                    let mut k = self.head[self.index([xx, y, z])];
                    while k != NONE {
                        if f(k as usize) {
                            return true;
                        }
                        k = self.next[k as usize];
                    }
                }
            }
        }
        false
    }

    /// True if a sphere at `x` of radius `r` overlaps (or touches) one of the grid's.
    fn overlaps(&self, x: DVec3, r: f64) -> bool {
        self.around(x, |k| {
            let s = self.spheres[k];
            (s.x - x).length_squared() <= (s.r + r) * (s.r + r)
        })
    }
}

/// The points at distances `h1`, `h2`, `h3` from `p1`, `p2`, `p3` (none, one or two).
fn trilaterate(p1: DVec3, h1: f64, p2: DVec3, h2: f64, p3: DVec3, h3: f64) -> [Option<DVec3>; 2] {
    let none = [None, None];
    let d12 = p2 - p1;
    let d = d12.length();
    if d <= 1e-12 * h1
        || d > h1 + h2
        || (p3 - p1).length() > h1 + h3
        || (p3 - p2).length() > h2 + h3
    {
        return none;
    }
    let ex = d12 / d;
    let d13 = p3 - p1;
    let i = ex.dot(d13);
    let perp = d13 - i * ex;
    let j = perp.length();
    if j <= 1e-12 * h1 {
        return none;
    }
    let ey = perp / j;
    let ez = ex.cross(ey);
    let x = (h1 * h1 - h2 * h2 + d * d) / (2.0 * d);
    let y = (h1 * h1 - h3 * h3 + i * i + j * j) / (2.0 * j) - i / j * x;
    let z2 = h1 * h1 - x * x - y * y;
    if z2 < 0.0 {
        return none;
    }
    let base = p1 + x * ex + y * ey;
    let z = z2.sqrt();
    if z <= 1e-12 * h1 {
        return [Some(base), None];
    }
    [Some(base + z * ez), Some(base - z * ez)]
}

impl DensePack {
    /// A dense insertion after checking its numbers; `seed` seeds its generator. A volume
    /// fraction above [`MAX_VOLUME_FRACTION`] is the caller's to clamp (with a warning).
    pub fn new(
        id: &str,
        seed: u64,
        groupbit: u32,
        region: Region,
        dist: Distribution,
        volume_fraction: f64,
        every: Option<u64>,
    ) -> Result<Self> {
        if !(volume_fraction > 0.0 && volume_fraction <= MAX_VOLUME_FRACTION) {
            return Err(Error::Invalid {
                what: "volumefraction_region",
                reason: format!("must be in (0, {MAX_VOLUME_FRACTION}], got {volume_fraction}"),
            });
        }
        if every == Some(0) {
            return Err(Error::Invalid {
                what: "insert_every",
                reason: "must be >= 1".into(),
            });
        }
        if region.bounding_box().is_none() {
            return Err(Error::Invalid {
                what: "insert/pack/dense region",
                reason: "must be bounded (a block, sphere, cylinder, cone or their union or intersection)".into(),
            });
        }
        Ok(Self {
            id: id.to_string(),
            groupbit,
            region,
            dist,
            volume_fraction,
            every,
            velocity: VelocityLaw::Constant(DVec3::ZERO),
            omega: DVec3::ZERO,
            rng: super::rng(seed),
            done: false,
        })
    }

    /// The factor f = ∛(0.57 / φ) the radii are enlarged by for the packing.
    pub fn radius_factor(&self) -> f64 {
        (MAX_VOLUME_FRACTION / self.volume_fraction).cbrt()
    }

    /// The generators' states and whether the one insertion of `insert_every once` is
    /// done, for a restart file.
    pub fn progress(&self) -> (super::InsertProgress, bool) {
        let p = super::InsertProgress {
            rng: self.rng.clone(),
            dist: self.dist.rngs(),
            last: None,
            start: None,
            inserted: 0,
        };
        (p, self.done)
    }

    /// Takes back what [`DensePack::progress`] gave; false if it belongs to another
    /// distribution.
    pub fn set_progress(&mut self, p: &super::InsertProgress, done: bool) -> bool {
        if !self.dist.set_rngs(&p.dist) {
            return false;
        }
        self.rng = p.rng.clone();
        self.done = done;
        true
    }

    /// True if an insertion is due at `step`: once (the first step asked), or at the
    /// multiples of `insert_every`.
    pub fn due(&self, step: u64) -> bool {
        match self.every {
            None => !self.done,
            Some(n) => step % n == 0,
        }
    }

    /// Packs the region and inserts the particles this rank owns (call when
    /// [`DensePack::due`]).
    pub fn insert(&mut self, world: &mut World) -> Result<DenseReport> {
        self.done = true;
        let f = self.radius_factor();
        let boxlo = world.domain.boxlo;
        let boxhi = world.domain.boxhi;
        let (rlo, rhi) = self.region.bounding_box().expect("checked in new");
        // The second packing's factor stays within [1, 1.1 f]; the grid is sized for it.
        let fmax = 1.1 * f;
        let rmax = self.dist.max_radius() * fmax;
        // Particles already there, from every rank, in tag order (the packing is then the
        // same on any number of ranks).
        let p = &world.particles;
        let n = p.nlocal();
        let present_max = world
            .comm
            .max(p.radius[..n].iter().copied().fold(0.0, f64::max));
        let cell = (4.0 * rmax).max(present_max + 3.0 * rmax);
        let (glo, ghi) = (rlo - DVec3::splat(cell), rhi + DVec3::splat(cell));
        let mut mine = Vec::new();
        let mut present_volume = 0.0;
        for i in 0..n {
            let x = p.x[i];
            if x.cmpge(glo).all() && x.cmple(ghi).all() {
                mine.extend_from_slice(&[p.tag[i] as f64, x.x, x.y, x.z, p.radius[i]]);
            }
            if self.region.contains(x) {
                present_volume += p.rmass[i] / p.density[i];
            }
        }
        let present_volume = world.comm.sum(present_volume);
        let mut near: Vec<[f64; 5]> = world
            .comm
            .all_gather(&mine)
            .chunks_exact(5)
            .map(|c| [c[0], c[1], c[2], c[3], c[4]])
            .collect();
        near.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let mut cells = Cells::new(glo, ghi, cell)?;
        for s in &near {
            cells.push(Sphere {
                x: DVec3::new(s[1], s[2], s[3]),
                r: s[4],
            });
        }
        let rng = &mut self.rng;
        let volume = self.region.volume((boxlo, boxhi), 1_000_000, || rng.gen());
        let wanted = ((self.volume_fraction * volume - present_volume)
            / self.dist.mean_particle_volume())
        .max(0.0);
        let estimate = wanted.floor() as u64;
        // The first packing, and a second one with the factor corrected by the cube root
        // of the count's ratio when the first misses by more than 1 % (the front packs
        // looser than 0.57 near walls); the second draws the same random numbers.
        let (rng0, dist0) = (self.rng.clone(), self.dist.clone());
        let mut placed = self.pack(&mut cells.clone(), (boxlo, boxhi), f)?;
        let mut factor = f;
        let got = placed.len() as f64;
        if wanted > 0.0 && got > 0.0 && (got / wanted - 1.0).abs() > 0.01 {
            let f1 = (f * (got / wanted).cbrt()).clamp(1.0, fmax);
            if f1 != f {
                (self.rng, self.dist) = (rng0, dist0);
                placed = self.pack(&mut cells, (boxlo, boxhi), f1)?;
                factor = f1;
            }
        }
        let (mut inserted, mut mass, mut vol) = (0u64, 0.0, 0.0);
        let mut tags = TagCursor::new(world);
        for pl in &placed {
            mass += add_placed(world, &self.dist, pl, self.omega, self.groupbit, &mut tags)?.0;
            vol += 4.0 / 3.0 * std::f64::consts::PI * pl.radius.powi(3);
            inserted += 1;
        }
        world.extend_tags();
        Ok(DenseReport {
            estimate,
            inserted,
            mass,
            volume_fraction: if volume > 0.0 { vol / volume } else { 0.0 },
            region_volume: volume,
            radius_factor: factor,
        })
    }

    /// A valid centre for an enlarged sphere of radius `r`: inside the insertion box
    /// `lo..hi`, the whole sphere in the region, no overlap.
    fn valid(&self, cells: &Cells, lo: DVec3, hi: DVec3, x: DVec3, r: f64) -> bool {
        x.cmpge(lo).all()
            && x.cmple(hi).all()
            && self.region.contains_sphere(x, r)
            && !cells.overlaps(x, r)
    }

    /// The next particle: one that found no place before, else a new draw of the
    /// distribution (template, real radius).
    fn next_particle(&mut self, waiting: &mut VecDeque<(usize, f64)>) -> (usize, f64) {
        waiting.pop_front().unwrap_or_else(|| {
            let k = self.dist.pick();
            (k, self.dist.templates[k].draw_radius())
        })
    }

    /// The packing with radii enlarged by `f` in the box `bx` (`cells` holds the particles
    /// already there): positions of the new particles (real radii) in insertion order.
    fn pack(&mut self, cells: &mut Cells, bx: (DVec3, DVec3), f: f64) -> Result<Vec<Placed>> {
        let rmax = self.dist.max_radius() * f;
        let (rlo, rhi) = self.region.bounding_box().expect("checked in new");
        // Centres stay one largest enlarged radius inside the box (as LIGGGHTS-PFM keeps
        // them inside its subdomain).
        let lo = rlo.max(bx.0 + DVec3::splat(rmax));
        let hi = rhi.min(bx.1 - DVec3::splat(rmax));
        if !lo.cmplt(hi).all() {
            return Ok(Vec::new());
        }
        let start_reach = START_REACH * rmax;
        let domain = (lo, hi);
        let mut start = (lo + hi) * 0.5;
        let fits = |s: &Self, c: &Cells, x: DVec3| {
            s.region.contains_sphere(x, start_reach) && !c.overlaps(x, start_reach)
        };
        if !fits(self, cells, start) {
            let mut found = None;
            for _ in 0..10_000 {
                let rng = &mut self.rng;
                let Some(x) = self.region.sample(domain, || rng.gen(), 1000) else {
                    break;
                };
                if fits(self, cells, x) {
                    found = Some(x);
                    break;
                }
            }
            start = found.ok_or_else(|| Error::Invalid {
                what: "insert/pack/dense",
                reason: format!(
                    "found no free point of the region {start_reach} away from its boundary and \
                     from the particles there, to start the packing"
                ),
            })?;
        }
        let mut placed: Vec<Placed> = Vec::new();
        let mut front: VecDeque<usize> = VecDeque::new();
        let mut waiting: VecDeque<(usize, f64)> = VecDeque::new();
        // The first three: touching, their centroid at the start, turned at random.
        let first: Vec<(usize, f64)> = (0..3).map(|_| self.next_particle(&mut waiting)).collect();
        let r: Vec<f64> = first.iter().map(|&(_, r)| r * f).collect();
        let (a, b, c) = (r[1] + r[2], r[0] + r[2], r[0] + r[1]);
        let cos = ((b * b + c * c - a * a) / (2.0 * b * c)).clamp(-1.0, 1.0);
        let tri = [
            DVec3::ZERO,
            DVec3::new(c, 0.0, 0.0),
            DVec3::new(b * cos, b * (1.0 - cos * cos).sqrt(), 0.0),
        ];
        let centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
        let rot = random_rotation(&mut self.rng);
        for (k, &(t, real)) in first.iter().enumerate() {
            let x = start + rot * (tri[k] - centroid);
            self.place(cells, &mut front, &mut placed, t, real, r[k], x);
        }
        let mut near: Vec<usize> = Vec::new();
        while let Some(&cur) = front.front() {
            let c = cells.spheres[cur];
            loop {
                let (t, real) = self.next_particle(&mut waiting);
                let rs = real * f;
                near.clear();
                cells.around(c.x, |k| {
                    let s = cells.spheres[k];
                    let reach = c.r + 2.0 * rs + s.r;
                    if k != cur && (s.x - c.x).length_squared() <= reach * reach {
                        near.push(k);
                    }
                    false
                });
                // Halos a hair wider than contact, so a new sphere never touches.
                let eps = 1e-9 * rmax;
                let h = |s: Sphere| s.r + rs + eps;
                let (mut best, mut best_d2, mut nvalid) = (None, f64::INFINITY, 0usize);
                for (u, &i) in near.iter().enumerate() {
                    for &j in &near[u + 1..] {
                        let (si, sj) = (cells.spheres[i], cells.spheres[j]);
                        for x in trilaterate(c.x, h(c), si.x, h(si), sj.x, h(sj))
                            .into_iter()
                            .flatten()
                        {
                            if self.valid(cells, lo, hi, x, rs) {
                                nvalid += 1;
                                let d2 = (x - start).length_squared();
                                if d2 < best_d2 {
                                    (best, best_d2) = (Some(x), d2);
                                }
                            }
                        }
                    }
                }
                let Some(x) = best else {
                    waiting.push_back((t, real));
                    break;
                };
                self.place(cells, &mut front, &mut placed, t, real, rs, x);
                if nvalid <= 1 {
                    break;
                }
            }
            front.pop_front();
        }
        Ok(placed)
    }

    /// Places particle (template `t`, real radius `real`, enlarged `rs`) at `x`.
    #[allow(clippy::too_many_arguments)]
    fn place(
        &mut self,
        cells: &mut Cells,
        front: &mut VecDeque<usize>,
        placed: &mut Vec<Placed>,
        t: usize,
        real: f64,
        rs: f64,
        x: DVec3,
    ) {
        front.push_back(cells.push(Sphere { x, r: rs }));
        placed.push(Placed {
            template: t,
            x,
            radius: real,
            v: draw_velocity(self.velocity, &mut self.rng),
            q: glam::DQuat::IDENTITY,
            about_bound: false,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two points at distance 1 from three unit-spaced centres are the apexes of the
    /// regular tetrahedra on the triangle, ±√(2/3) off its plane.
    #[test]
    fn trilateration_finds_the_tetrahedron_apexes() {
        let p1 = DVec3::ZERO;
        let p2 = DVec3::X;
        let p3 = DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0);
        let [a, b] = trilaterate(p1, 1.0, p2, 1.0, p3, 1.0);
        let (a, b) = (a.unwrap(), b.unwrap());
        for x in [a, b] {
            for p in [p1, p2, p3] {
                assert!(((x - p).length() - 1.0).abs() < 1e-14);
            }
        }
        assert!((a.z.abs() - (2.0f64 / 3.0).sqrt()).abs() < 1e-14);
        assert!((a.z + b.z).abs() < 1e-14);
        // Too far apart: none.
        assert_eq!(trilaterate(p1, 0.4, p2, 0.4, p3, 0.4), [None, None]);
    }

    #[test]
    fn random_rotations_are_rotations() {
        let mut rng = crate::insert::rng(7);
        for _ in 0..100 {
            let q = random_rotation(&mut rng);
            let v = q * DVec3::new(1.0, 2.0, 3.0);
            assert!((v.length() - 14f64.sqrt()).abs() < 1e-12);
        }
    }
}
