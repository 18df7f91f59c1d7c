//! Euler-grid averages, as LIGGGHTS' `fix ave/euler` computes them (SPEC §4, seed 001).
//!
//! The box is cut into a regular grid: the wanted cell size is `c` × the largest particle
//! diameter, each axis gets `floor(extent / size)` cells (at least one) and the cells of an
//! axis share its extent equally, so the actual cell is usually a little larger than
//! asked. Cells are numbered x fastest, then y, then z. A particle belongs to the cell that
//! holds its centre (indices clamped to the grid). Per cell, over the particles of the
//! group:
//!
//! * `v_avg` = Σ m v / Σ m (mass-weighted, Favre average);
//! * `radius` = Σ r / n (arithmetic mean);
//! * `volume_fraction` = Σ (4/3 π r³) / V (a sphere counts whole in the cell of its
//!   centre);
//! * `pressure` = −(σ_xx + σ_yy + σ_zz) / (3 V) with the per-particle stress × volume
//!   σ_i = −m_i (v_i − v_avg) ⊗ (v_i − v_avg) − W_i, where W_i is the particle's contact
//!   virial ([`crate::World::virial`]: ½ r_ij ⊗ F_ij over its pair contacts). The kinetic
//!   part is the fluctuation about the cell's average velocity (LIGGGHTS' "convective"
//!   correction of `compute stress/atom`).
//!
//! V is the cell volume, or with a base-volume region the part of the cell inside that
//! region, estimated once per grid from sample points ([`EulerGrid::base_volumes`]). An
//! empty cell has zero velocity, radius and volume fraction, and a pressure of −0 (LIGGGHTS
//! prints `-0.000000`); a cell with no base volume reports volume fraction and pressure 0.

use glam::DVec3;

use crate::comm::Comm;
use crate::particles::Particles;
use crate::region::Region;

/// Sample points per axis and cell used to estimate a cell's volume inside a region.
pub const BASE_VOLUME_SAMPLES: usize = 20;

/// The regular grid over a box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerGrid {
    /// Lower corner of the box.
    pub lo: DVec3,
    /// Cells per axis.
    pub n: [usize; 3],
    /// Actual cell edge lengths (extent / n per axis).
    pub cell: DVec3,
}

impl EulerGrid {
    /// The grid over `lo..hi` for wanted cell edges `size` per axis (cells per axis
    /// `floor(extent / size)`, at least 1; a size that is not positive gives one cell).
    pub fn new(lo: DVec3, hi: DVec3, size: DVec3) -> Self {
        let ext = hi - lo;
        let mut n = [1usize; 3];
        for (a, na) in n.iter_mut().enumerate() {
            if size[a] > 0.0 && ext[a].is_finite() {
                *na = ((ext[a] / size[a]).floor() as usize).max(1);
            }
        }
        let cell = DVec3::new(
            ext.x / n[0] as f64,
            ext.y / n[1] as f64,
            ext.z / n[2] as f64,
        );
        Self { lo, n, cell }
    }

    /// Number of cells.
    pub fn ncells(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// The cell of point `x` (x fastest, indices clamped to the grid).
    pub fn cell_of(&self, x: DVec3) -> usize {
        let mut k = [0usize; 3];
        for a in 0..3 {
            let f = ((x[a] - self.lo[a]) / self.cell[a]).floor();
            // NaN and negative values go to 0 (the `as` cast saturates).
            k[a] = (f.max(0.0) as usize).min(self.n[a] - 1);
        }
        k[0] + self.n[0] * (k[1] + self.n[1] * k[2])
    }

    /// Centre of cell `c`.
    pub fn centre(&self, c: usize) -> DVec3 {
        let (i, j, k) = (
            c % self.n[0],
            (c / self.n[0]) % self.n[1],
            c / (self.n[0] * self.n[1]),
        );
        self.lo + DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5) * self.cell
    }

    /// Volume of one cell.
    pub fn cell_volume(&self) -> f64 {
        self.cell.x * self.cell.y * self.cell.z
    }

    /// Volume of each cell inside `region`: the cell volume times the fraction of
    /// [`BASE_VOLUME_SAMPLES`]³ sample points inside the region (the points are the centres
    /// of a regular sub-grid of the cell, a deterministic stand-in for LIGGGHTS' Monte
    /// Carlo estimate).
    pub fn base_volumes(&self, region: &Region) -> Vec<f64> {
        let s = BASE_VOLUME_SAMPLES;
        let total = (s * s * s) as f64;
        (0..self.ncells())
            .map(|c| {
                let corner = self.centre(c) - 0.5 * self.cell;
                let mut inside = 0usize;
                for a in 0..s {
                    for b in 0..s {
                        for d in 0..s {
                            let f = DVec3::new(a as f64 + 0.5, b as f64 + 0.5, d as f64 + 0.5)
                                / s as f64;
                            if region.contains(corner + f * self.cell) {
                                inside += 1;
                            }
                        }
                    }
                }
                self.cell_volume() * inside as f64 / total
            })
            .collect()
    }
}

/// Per-cell results of one evaluation, in cell order (x fastest).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EulerCells {
    /// Cell centres.
    pub centre: Vec<DVec3>,
    /// Mass-weighted average velocity.
    pub v_avg: Vec<DVec3>,
    /// Solid volume fraction.
    pub volume_fraction: Vec<f64>,
    /// Mean particle radius.
    pub radius: Vec<f64>,
    /// Pressure (−trace/3 of the cell stress).
    pub pressure: Vec<f64>,
}

impl EulerCells {
    /// Number of cells.
    pub fn len(&self) -> usize {
        self.centre.len()
    }

    /// True without cells.
    pub fn is_empty(&self) -> bool {
        self.centre.is_empty()
    }
}

/// Cell averages of the particles in `groupbit` on `grid` over every rank of `comm` (see
/// the module documentation): each rank adds up its owned particles, the per-cell sums
/// are summed over the ranks before the averages are formed, so every rank gets the same
/// global result. `virial` holds the contact virial of each owned particle
/// (xx yy zz xy xz yz); `base_volume`, when given, the volume of each cell to divide by.
/// This is a collective call: every rank must make it.
pub fn average(
    grid: &EulerGrid,
    p: &Particles,
    groupbit: u32,
    virial: &[[f64; 6]],
    base_volume: Option<&[f64]>,
    comm: &dyn Comm,
) -> EulerCells {
    let nc = grid.ncells();
    let nlocal = p.nlocal();
    let cell_of: Vec<usize> = (0..nlocal).map(|i| grid.cell_of(p.x[i])).collect();
    let selected = |i: usize| p.mask[i] & groupbit != 0;
    // Per cell: count, mass, momentum (3), radius sum, solid volume.
    const W: usize = 7;
    let mut sums = vec![0.0; nc * W];
    for i in (0..nlocal).filter(|&i| selected(i)) {
        let s = &mut sums[cell_of[i] * W..(cell_of[i] + 1) * W];
        let r = p.radius[i];
        let mv = p.rmass[i] * p.v[i];
        s[0] += 1.0;
        s[1] += p.rmass[i];
        s[2] += mv.x;
        s[3] += mv.y;
        s[4] += mv.z;
        s[5] += r;
        s[6] += 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    }
    comm.sum_slice(&mut sums);
    let cell = |c: usize| &sums[c * W..(c + 1) * W];
    let count: Vec<f64> = (0..nc).map(|c| cell(c)[0]).collect();
    let mass: Vec<f64> = (0..nc).map(|c| cell(c)[1]).collect();
    let mv: Vec<DVec3> = (0..nc)
        .map(|c| DVec3::new(cell(c)[2], cell(c)[3], cell(c)[4]))
        .collect();
    let rsum: Vec<f64> = (0..nc).map(|c| cell(c)[5]).collect();
    let vsolid: Vec<f64> = (0..nc).map(|c| cell(c)[6]).collect();
    let v_avg: Vec<DVec3> = (0..nc)
        .map(|c| {
            if mass[c] > 0.0 {
                mv[c] / mass[c]
            } else {
                DVec3::ZERO
            }
        })
        .collect();
    // Trace of the stress × volume of each cell: Σ −(m |v − v_avg|² + W_xx + W_yy + W_zz).
    let mut trace = vec![0.0; nc];
    for i in (0..nlocal).filter(|&i| selected(i)) {
        let c = cell_of[i];
        let dv = p.v[i] - v_avg[c];
        let w = &virial[i];
        let m = p.rmass[i];
        trace[c] += -(m * dv.x * dv.x + w[0]) - (m * dv.y * dv.y + w[1]) - (m * dv.z * dv.z + w[2]);
    }
    comm.sum_slice(&mut trace);
    let mut out = EulerCells::default();
    for c in 0..nc {
        let vol = base_volume.map_or(grid.cell_volume(), |b| b[c]);
        out.centre.push(grid.centre(c));
        out.v_avg.push(v_avg[c]);
        out.radius.push(if count[c] > 0.0 {
            rsum[c] / count[c]
        } else {
            0.0
        });
        if vol > 0.0 {
            out.volume_fraction.push(vsolid[c] / vol);
            out.pressure.push(-trace[c] / (3.0 * vol));
        } else {
            out.volume_fraction.push(0.0);
            out.pressure.push(0.0);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_counts_centres_and_order() {
        let g = EulerGrid::new(
            DVec3::new(-0.01, -0.01, -0.01),
            DVec3::new(0.014, 0.01, 0.01),
            DVec3::splat(0.008),
        );
        assert_eq!(g.n, [3, 2, 2]);
        assert_eq!(g.ncells(), 12);
        let c = g.centre(10);
        assert!((c - DVec3::new(0.002, 0.005, 0.005)).length() < 1e-15);
        assert_eq!(g.cell_of(DVec3::new(0.0, 0.0, 0.0)), 10);
        assert_eq!(g.cell_of(DVec3::new(1.0, 1.0, 1.0)), 11);
        assert_eq!(g.cell_of(DVec3::new(-1.0, -1.0, -1.0)), 0);
        // A size larger than the box gives one cell per axis.
        assert_eq!(
            EulerGrid::new(DVec3::ZERO, DVec3::ONE, DVec3::splat(5.0)).n,
            [1, 1, 1]
        );
        // Edges per axis (LIGGGHTS-PFM's `cell_size_relative cx cy cz`).
        let g = EulerGrid::new(DVec3::ZERO, DVec3::ONE, DVec3::new(0.5, 0.25, 0.1));
        assert_eq!(g.n, [2, 4, 10]);
        assert!((g.cell - DVec3::new(0.5, 0.25, 0.1)).length() < 1e-15);
    }

    /// Three spheres in one cell, two contacts, at a run's set-up (no tangential spring
    /// yet and tangential damping off, so the contact forces are Hertz normal forces with
    /// normal damping): the cell pressure against the closed forms, and the per-particle
    /// virial against ½ r ⊗ F.
    #[test]
    fn pressure_of_three_overlapping_spheres_by_hand() {
        use crate::{Boundary, ContactModel, Domain, Materials, NewParticle, PairGran, World};
        let (e_mod, nu, rest, rho) = (5e6, 0.45, 0.3, 2500.0);
        let mut w = World::new(
            Domain::new(
                DVec3::splat(-0.01),
                DVec3::splat(0.01),
                [Boundary::Fixed; 3],
            )
            .unwrap(),
        );
        w.materials = Materials::uniform(1, e_mod, nu, rest, 0.5);
        let mut model = ContactModel::hertz_history();
        model.flags.tangential_damping = false;
        w.pair = Some(PairGran::new(model));
        w.neighbor.settings.skin = 0.001;
        let xs = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.004, 0.001, 0.0),
            DVec3::new(0.001, -0.003, 0.0005),
        ];
        let rs = [0.002, 0.0025, 0.0015];
        let vs = [
            DVec3::new(0.1, -0.05, 0.02),
            DVec3::new(-0.2, 0.03, 0.01),
            DVec3::new(0.05, 0.15, -0.07),
        ]
        .map(|v| 10.0 * v);
        for k in 0..3 {
            w.add_particle(&NewParticle::at(xs[k], rs[k], rho).with_v(vs[k]))
                .unwrap();
        }
        w.want_virial = true;
        w.setup().unwrap();
        let virial = w.current_virial().expect("computed at set-up").to_vec();

        // By hand: masses, the two contacts (1-2 and 1-3), Hertz normal force with damping.
        let m: Vec<f64> = rs
            .iter()
            .map(|r| rho * 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
            .collect();
        let e_star = 1.0 / (2.0 * (1.0 - nu * nu) / e_mod);
        let beta = rest.ln() / (rest.ln().powi(2) + std::f64::consts::PI.powi(2)).sqrt();
        let force = |i: usize, j: usize| -> DVec3 {
            let d = xs[i] - xs[j];
            let dist = d.length();
            let delta = rs[i] + rs[j] - dist;
            assert!(delta > 0.0);
            let n = d / dist;
            let r_star = rs[i] * rs[j] / (rs[i] + rs[j]);
            let m_star = m[i] * m[j] / (m[i] + m[j]);
            let sn = 2.0 * e_star * (r_star * delta).sqrt();
            let kn = 4.0 / 3.0 * e_star * (r_star * delta).sqrt();
            let gamma_n = -2.0 * (5.0f64 / 6.0).sqrt() * beta * (sn * m_star).sqrt();
            let vn = (vs[i] - vs[j]).dot(n);
            (kn * delta - gamma_n * vn) * n
        };
        let contacts = [(0usize, 1usize), (0, 2)];
        assert!((xs[1] - xs[2]).length() > rs[1] + rs[2], "2-3 apart");
        let mut want_w = [[0.0f64; 6]; 3];
        let mut rf = 0.0;
        for &(i, j) in &contacts {
            let f = force(i, j);
            let d = xs[i] - xs[j];
            let c = [
                d.x * f.x,
                d.y * f.y,
                d.z * f.z,
                d.x * f.y,
                d.x * f.z,
                d.y * f.z,
            ];
            for k in 0..6 {
                want_w[i][k] += 0.5 * c[k];
                want_w[j][k] += 0.5 * c[k];
            }
            rf += d.dot(f);
        }
        for (i, got_i) in virial.iter().enumerate() {
            let t = w.particles.tag[i] as usize - 1;
            for k in 0..6 {
                let (got, want) = (got_i[k], want_w[t][k]);
                assert!(
                    (got - want).abs() <= 1e-12 * want.abs().max(1e-30),
                    "virial {t} {k}: {got} vs {want}"
                );
            }
        }
        let mtot: f64 = m.iter().sum();
        let vavg = (0..3).map(|k| m[k] * vs[k]).sum::<DVec3>() / mtot;
        let kin: f64 = (0..3).map(|k| m[k] * (vs[k] - vavg).length_squared()).sum();
        let vol = 0.02f64.powi(3);
        let want_p = (kin + rf) / (3.0 * vol);

        let grid = EulerGrid::new(
            w.domain.boxlo,
            w.domain.boxhi,
            DVec3::splat(3.0 * 2.0 * 0.0025),
        );
        assert_eq!(grid.ncells(), 1);
        let cells = average(&grid, &w.particles, 1, &virial, None, &*w.comm);
        let p = cells.pressure[0];
        assert!(
            (p - want_p).abs() <= 1e-9 * want_p.abs(),
            "pressure {p} vs {want_p}"
        );
        assert!(kin > 0.05 * rf, "both terms matter ({kin} {rf})");
        assert!((cells.v_avg[0] - vavg).length() <= 1e-12 * vavg.length());
        let vsolid: f64 = rs
            .iter()
            .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
            .sum();
        assert!((cells.volume_fraction[0] - vsolid / vol).abs() <= 1e-12);
        assert!((cells.radius[0] - 0.002).abs() <= 1e-15);
        assert_eq!(cells.centre[0], DVec3::ZERO);
    }

    /// A contact across a periodic face gives both particles the same virial as the same
    /// contact inside the box (the ghost's share goes back to its owner).
    #[test]
    fn periodic_ghost_virial_goes_to_its_owner() {
        use crate::{Boundary, ContactModel, Domain, Materials, NewParticle, PairGran, World};
        let run = |shift: f64| -> Vec<[f64; 6]> {
            let mut w = World::new(
                Domain::new(
                    DVec3::splat(-0.01),
                    DVec3::splat(0.01),
                    [Boundary::Periodic, Boundary::Fixed, Boundary::Fixed],
                )
                .unwrap(),
            );
            w.materials = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
            w.pair = Some(PairGran::new(ContactModel::hertz_history()));
            w.neighbor.settings.skin = 0.001;
            let wrap = |x: f64| if x >= 0.01 { x - 0.02 } else { x };
            let a = DVec3::new(wrap(0.0065 + shift), 0.0, 0.0);
            let b = DVec3::new(wrap(0.0100 + shift), 0.0011, 0.0003);
            w.add_particle(&NewParticle::at(a, 0.002, 2500.0).with_v(DVec3::new(0.1, 0.0, 0.02)))
                .unwrap();
            w.add_particle(&NewParticle::at(b, 0.002, 2500.0).with_v(DVec3::new(-0.1, 0.05, 0.0)))
                .unwrap();
            w.want_virial = true;
            w.setup().unwrap();
            let mut v = w.current_virial().unwrap().to_vec();
            let tags: Vec<u64> = w.particles.tag[..2].to_vec();
            if tags[0] > tags[1] {
                v.swap(0, 1);
            }
            v
        };
        let inside = run(-0.003);
        let across = run(0.0);
        for i in 0..2 {
            for k in 0..6 {
                let (a, b) = (inside[i][k], across[i][k]);
                assert!(
                    (a - b).abs() <= 1e-12 * a.abs().max(1e-20),
                    "{i} {k}: {a} {b}"
                );
            }
        }
        assert!(inside[0][0] > 0.0);
    }
}
