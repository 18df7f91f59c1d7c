//! Heat radiation between particles by Monte Carlo ray tracing (LIGGGHTS-PFM's `fix
//! heat/gran/radiation`): grey, diffuse particles of uniform temperature that exchange
//! Stefan–Boltzmann radiation with each other and with a background at `T_B`.
//!
//! Each step every owned particle i emits its power `P_i = ε_i σ A_i T_i⁴` (`A_i = 4π r_i²`,
//! `ε` the `thermalEmissivity` of its type, σ = 5.670373e-8 W m⁻² K⁻⁴) as one ray: its heat
//! flow loses `P_i`, and the ray leaves a uniformly random point of its surface in a
//! direction uniformly random over the outward hemisphere. The ray hits the first sphere
//! along it whose entry point lies within `cutoff` of the ray's origin (a sphere holding
//! the origin, where two overlap, is hit where the ray enters it, behind the origin):
//!
//! - when it hits j, j absorbs `ε_j` of the ray's power and the rest is reflected from the
//!   hit point, in a direction uniformly random over the hemisphere of j's outward normal
//!   there; the reflected ray goes on the same way, its power each time the remaining
//!   fraction `a = Π(1 − ε)` of `P_i`;
//! - a ray that hits nothing takes the background's radiation back to its emitter: i gains
//!   `a ε_i σ A_i T_B⁴` (for the emitted ray a = 1: a lone particle follows
//!   `m c dT/dt = ε σ A (T_B⁴ − T⁴)`);
//! - after `max_bounces` reflections, or once `a` < 0.001, the power left, `a P_i`, goes
//!   back to i.
//!
//! These are the fork's rules (LIGGGHTS-PFM, measured and read from its documentation),
//! with two differences, both where the fork's bin walk is not a rule a user could state:
//! its search reaches up to one neighbor-bin stencil beyond `cutoff`, and it lets ghost
//! particles emit too (periodic images and other ranks' particles would radiate twice);
//! here only owned particles emit, and ghosts (kept out to `cutoff` plus the largest
//! radius) absorb, their shares added to their owners.
//!
//! Directions are uniform over the hemisphere (as the fork draws them), not
//! cosine-weighted. The random numbers come from one generator per rank seeded with
//! `seed + rank`, drawn in the order of the owned particles, so a run does not depend on
//! the thread count; with MPI it depends on the decomposition, as the fork's does.
//!
//! The search is a uniform grid of cells at least one diameter wide over all particles,
//! walked cell by cell along the ray (Amanatides & Woo 1987) with each cell's 27-cell
//! block tested; the buffers are kept between steps.

use glam::DVec3;
use rand::{Rng, SeedableRng};

use crate::comm::Comm;
use crate::error::{Error, Result};
use crate::heat::HeatProps;
use crate::particles::Particles;

/// The Stefan–Boltzmann constant σ as LIGGGHTS-PFM takes it (W m⁻² K⁻⁴).
pub const STEFAN_BOLTZMANN: f64 = 5.670373e-8;

/// Below this remaining fraction a reflected ray stops and gives its power back to the
/// emitter (the fork's threshold).
const MIN_FRACTION: f64 = 0.001;

/// The radiation model and its state.
#[derive(Debug, Clone)]
pub struct HeatRadiation {
    /// Thermal emissivity of each type (index type − 1), each in [0, 1].
    pub emissivity: Vec<f64>,
    /// Background temperature T_B.
    pub background: f64,
    /// Largest number of reflections of a ray.
    pub max_bounces: u32,
    /// Reach of a ray from its origin.
    pub cutoff: f64,
    rng: rand_pcg::Pcg64,
    grid: Grid,
    flow: Vec<f64>,
}

impl HeatRadiation {
    /// Radiation with background `background`, at most `max_bounces` reflections, rays
    /// reaching `cutoff`, random numbers from `seed + rank`; the emissivities are set
    /// by [`HeatRadiation::set_emissivity`].
    pub fn new(
        background: f64,
        max_bounces: u32,
        cutoff: f64,
        seed: u64,
        rank: usize,
    ) -> Result<Self> {
        if !(cutoff > 0.0 && cutoff.is_finite()) {
            return Err(Error::Invalid {
                what: "heat/gran/radiation cutoff",
                reason: format!("{cutoff} must be > 0"),
            });
        }
        if !(background >= 0.0 && background.is_finite()) {
            return Err(Error::Invalid {
                what: "heat/gran/radiation background_temperature",
                reason: format!("{background} must be >= 0 K"),
            });
        }
        Ok(Self {
            emissivity: Vec::new(),
            background,
            max_bounces,
            cutoff,
            rng: rand_pcg::Pcg64::seed_from_u64(seed.wrapping_add(rank as u64)),
            grid: Grid::default(),
            flow: Vec::new(),
        })
    }

    /// The emissivity of each type (index type − 1); each must lie in [0, 1].
    pub fn set_emissivity(&mut self, emissivity: Vec<f64>) -> Result<()> {
        if let Some(e) = emissivity.iter().find(|e| !(0.0..=1.0).contains(*e)) {
            return Err(Error::Invalid {
                what: "thermalEmissivity",
                reason: format!("{e} must not be < 0 or > 1"),
            });
        }
        self.emissivity = emissivity;
        Ok(())
    }

    fn eps(&self, ty: u32) -> f64 {
        self.emissivity
            .get((ty as usize).wrapping_sub(1))
            .copied()
            .unwrap_or(0.0)
    }

    /// How far beyond a subdomain ghosts must reach: `cutoff` plus the largest radius.
    pub fn ghost_reach(&self, rmax: f64) -> f64 {
        self.cutoff + rmax
    }

    /// One step of radiation: every owned particle emits one ray; the heat flows it
    /// causes are added to the particles' `heatFlux` (ghosts' shares to their owners).
    /// `props` are the heat properties, which the heat integration
    /// ([`crate::heat::HeatConduction`]) holds.
    pub fn radiate(&mut self, p: &mut Particles, props: &HeatProps, comm: &dyn Comm) {
        let n = p.nlocal();
        let len = p.len();
        let mut flow = std::mem::take(&mut self.flow);
        flow.clear();
        flow.resize(len, 0.0);
        self.grid.build(&p.x[..len], &p.radius[..len]);
        let temp = &p.props[props.temp.0].data;
        let tb4 = self.background.powi(4);
        for i in 0..n {
            let r = p.radius[i];
            let area = 4.0 * std::f64::consts::PI * r * r;
            let eps_i = self.eps(p.ty[i]);
            let t = temp[i];
            let power = area * eps_i * STEFAN_BOLTZMANN * t * t * t * t;
            let back = area * eps_i * STEFAN_BOLTZMANN * tb4;
            flow[i] -= power;
            let normal = unit_vector(&mut self.rng);
            let mut origin = p.x[i] + r * normal;
            let mut dir = hemisphere(&mut self.rng, normal);
            let mut from = i;
            let mut fraction = 1.0;
            let mut bounces = 0;
            loop {
                let Some((j, t_hit)) = self.grid.trace(
                    &p.x[..len],
                    &p.radius[..len],
                    origin,
                    dir,
                    from,
                    self.cutoff,
                ) else {
                    flow[i] += fraction * back;
                    break;
                };
                let eps_j = self.eps(p.ty[j]);
                flow[j] += eps_j * fraction * power;
                fraction *= 1.0 - eps_j;
                if bounces == self.max_bounces || fraction < MIN_FRACTION {
                    flow[i] += fraction * power;
                    break;
                }
                bounces += 1;
                origin += t_hit * dir;
                let nj = (origin - p.x[j]).normalize_or_zero();
                dir = hemisphere(&mut self.rng, nj);
                from = j;
            }
        }
        comm.reverse_scalar(p, &mut flow);
        let fl = &mut p.props[props.flux.0].data;
        for (f, q) in fl[..n].iter_mut().zip(&flow) {
            *f += q;
        }
        self.flow = flow;
    }
}

/// A uniformly random unit vector (Marsaglia 1972).
fn unit_vector(rng: &mut impl Rng) -> DVec3 {
    loop {
        let u = 2.0 * rng.gen::<f64>() - 1.0;
        let v = 2.0 * rng.gen::<f64>() - 1.0;
        let s = u * u + v * v;
        if s <= 1.0 {
            let a = 2.0 * (1.0 - s).sqrt();
            return DVec3::new(a * u, a * v, 2.0 * s - 1.0);
        }
    }
}

/// A uniformly random unit vector on the hemisphere around `n`.
fn hemisphere(rng: &mut impl Rng, n: DVec3) -> DVec3 {
    let d = unit_vector(rng);
    if d.dot(n) < 0.0 {
        -d
    } else {
        d
    }
}

/// Where the ray `o + t d` (d a unit vector) enters the sphere (c, r): the smaller root
/// t0, also when it is negative (the origin inside the sphere); `None` when the ray
/// misses it or the sphere lies wholly behind the origin.
pub fn ray_sphere(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let oc = o - c;
    let b = oc.dot(d);
    let cc = oc.length_squared() - r * r;
    let disc = b * b - cc;
    if disc < 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    // The far root from the cancellation-free form when b > 0.
    let (t0, t1) = if b > 0.0 {
        let q = -b - sq;
        (q, if q != 0.0 { cc / q } else { 0.0 })
    } else {
        let q = -b + sq;
        (if q != 0.0 { cc / q } else { 0.0 }, q)
    };
    if t1 <= 0.0 {
        return None;
    }
    Some(t0)
}

/// A uniform grid of cells over the particle centres, each cell's particles contiguous.
#[derive(Debug, Clone, Default)]
struct Grid {
    lo: DVec3,
    h: f64,
    dims: [i64; 3],
    /// Start of each cell's particles in `items` (cells + 1 entries).
    start: Vec<u32>,
    items: Vec<u32>,
    cell_of: Vec<u32>,
    fill: Vec<u32>,
}

impl Grid {
    fn build(&mut self, x: &[DVec3], radius: &[f64]) {
        let n = x.len();
        let rmax = radius.iter().copied().fold(0.0, f64::max);
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &xi in x {
            lo = lo.min(xi);
            hi = hi.max(xi);
        }
        if n == 0 {
            lo = DVec3::ZERO;
            hi = DVec3::ZERO;
        }
        let mut h = (2.0 * rmax).max(1e-300);
        let pad = |h: f64| rmax + h;
        let cells = |h: f64| {
            let ext = hi - lo + 2.0 * DVec3::splat(pad(h));
            let d = (ext / h).ceil().max(DVec3::ONE);
            d.x * d.y * d.z
        };
        // At most about 8 cells per particle: wider cells for sparse particles.
        let limit = (8 * n + 64) as f64;
        while cells(h) > limit {
            h *= 1.5;
        }
        let p = pad(h);
        self.lo = lo - DVec3::splat(p);
        let ext = hi - lo + 2.0 * DVec3::splat(p);
        let d = (ext / h).ceil().max(DVec3::ONE);
        self.dims = [d.x as i64, d.y as i64, d.z as i64];
        self.h = h;
        let ncell = (self.dims[0] * self.dims[1] * self.dims[2]) as usize;
        self.start.clear();
        self.start.resize(ncell + 1, 0);
        self.cell_of.clear();
        for &xi in x {
            let c = self.index(self.cell(xi));
            self.cell_of.push(c as u32);
            self.start[c + 1] += 1;
        }
        for c in 0..ncell {
            self.start[c + 1] += self.start[c];
        }
        self.items.clear();
        self.items.resize(n, 0);
        self.fill.clone_from(&self.start);
        for (i, &c) in self.cell_of.iter().enumerate() {
            let c = c as usize;
            self.items[self.fill[c] as usize] = i as u32;
            self.fill[c] += 1;
        }
    }

    fn cell(&self, x: DVec3) -> [i64; 3] {
        let c = ((x - self.lo) / self.h).floor();
        [
            (c.x as i64).clamp(0, self.dims[0] - 1),
            (c.y as i64).clamp(0, self.dims[1] - 1),
            (c.z as i64).clamp(0, self.dims[2] - 1),
        ]
    }

    fn index(&self, c: [i64; 3]) -> usize {
        ((c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]) as usize
    }

    /// The first sphere other than `skip` along the ray `o + t d` whose entry point lies
    /// within `reach` of `o`, and its entry parameter t.
    fn trace(
        &self,
        x: &[DVec3],
        radius: &[f64],
        o: DVec3,
        d: DVec3,
        skip: usize,
        reach: f64,
    ) -> Option<(usize, f64)> {
        let mut cell = self.cell(o);
        let mut step = [0i64; 3];
        let mut t_max = [f64::INFINITY; 3];
        let mut t_delta = [f64::INFINITY; 3];
        for a in 0..3 {
            if d[a] > 0.0 {
                step[a] = 1;
                let edge = self.lo[a] + (cell[a] + 1) as f64 * self.h;
                t_max[a] = (edge - o[a]) / d[a];
                t_delta[a] = self.h / d[a];
            } else if d[a] < 0.0 {
                step[a] = -1;
                let edge = self.lo[a] + cell[a] as f64 * self.h;
                t_max[a] = (edge - o[a]) / d[a];
                t_delta[a] = -self.h / d[a];
            }
        }
        let mut best: Option<(usize, f64)> = None;
        loop {
            for dz in -1..=1 {
                let cz = cell[2] + dz;
                if cz < 0 || cz >= self.dims[2] {
                    continue;
                }
                for dy in -1..=1 {
                    let cy = cell[1] + dy;
                    if cy < 0 || cy >= self.dims[1] {
                        continue;
                    }
                    for dx in -1..=1 {
                        let cx = cell[0] + dx;
                        if cx < 0 || cx >= self.dims[0] {
                            continue;
                        }
                        let c = self.index([cx, cy, cz]);
                        for &j in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                            let j = j as usize;
                            if j == skip {
                                continue;
                            }
                            if let Some(t) = ray_sphere(o, d, x[j], radius[j]) {
                                if t <= reach && best.is_none_or(|(_, b)| t < b) {
                                    best = Some((j, t));
                                }
                            }
                        }
                    }
                }
            }
            // The next cell along the ray, where the ray leaves this one.
            let a = if t_max[0] <= t_max[1] && t_max[0] <= t_max[2] {
                0
            } else if t_max[1] <= t_max[2] {
                1
            } else {
                2
            };
            let t_exit = t_max[a];
            if best.is_some_and(|(_, b)| b <= t_exit) || t_exit > reach || !t_exit.is_finite() {
                return best;
            }
            cell[a] += step[a];
            if cell[a] < 0 || cell[a] >= self.dims[a] {
                return best;
            }
            t_max[a] += t_delta[a];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn a_ray_enters_a_sphere_at_the_near_root() {
        let o = DVec3::ZERO;
        let d = DVec3::X;
        assert_eq!(ray_sphere(o, d, DVec3::new(3.0, 0.0, 0.0), 1.0), Some(2.0));
        // Behind the origin: missed.
        assert_eq!(ray_sphere(o, d, DVec3::new(-3.0, 0.0, 0.0), 1.0), None);
        // Beside the ray: missed.
        assert_eq!(ray_sphere(o, d, DVec3::new(3.0, 1.5, 0.0), 1.0), None);
        // Holding the origin: entered behind it.
        let t = ray_sphere(o, d, DVec3::new(0.5, 0.0, 0.0), 1.0).unwrap();
        assert!((t + 0.5).abs() < 1e-15, "{t}");
    }

    #[test]
    fn hemisphere_directions_are_uniform() {
        // Over the hemisphere around z, uniform directions have <d_z> = 1/2 and
        // <d_z²> = 1/3 (a cosine-weighted draw would give 2/3 and 1/2).
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let n = 200_000;
        let (mut m1, mut m2) = (0.0, 0.0);
        for _ in 0..n {
            let d = hemisphere(&mut rng, DVec3::Z);
            assert!(d.z >= 0.0 && (d.length() - 1.0).abs() < 1e-12);
            m1 += d.z;
            m2 += d.z * d.z;
        }
        m1 /= n as f64;
        m2 /= n as f64;
        // Standard errors about 6.5e-4 and 6.7e-4: 5 sigma.
        assert!((m1 - 0.5).abs() < 3.3e-3, "{m1}");
        assert!((m2 - 1.0 / 3.0).abs() < 3.4e-3, "{m2}");
    }

    #[test]
    fn the_grid_walk_finds_the_nearest_sphere_as_a_brute_force_search_does() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let n = 400;
        let x: Vec<DVec3> = (0..n)
            .map(|_| DVec3::new(rng.gen(), rng.gen(), rng.gen()) * 0.5)
            .collect();
        let radius: Vec<f64> = (0..n).map(|_| 0.01 + 0.02 * rng.gen::<f64>()).collect();
        let mut grid = Grid::default();
        grid.build(&x, &radius);
        for k in 0..2000 {
            let i = k % n;
            let normal = unit_vector(&mut rng);
            let o = x[i] + radius[i] * normal;
            let d = hemisphere(&mut rng, normal);
            let reach = 0.02 + 0.3 * rng.gen::<f64>();
            let got = grid.trace(&x, &radius, o, d, i, reach);
            let want = (0..n)
                .filter(|&j| j != i)
                .filter_map(|j| ray_sphere(o, d, x[j], radius[j]).map(|t| (j, t)))
                .filter(|&(_, t)| t <= reach)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            assert_eq!(got, want, "ray {k}");
        }
    }
}
