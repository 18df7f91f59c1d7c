//! `pair_style gran`: the particle–particle force pass.
//!
//! The pass does not walk the whole neighbor list (every pair within r_i + r_j + skin)
//! but a sub-list of it, the *near list*: the pairs within r_i + r_j + `skin/10`, rebuilt
//! from the neighbor list whenever that is rebuilt or any particle has moved more than
//! `skin/20` since. No pair outside it can touch before then, it keeps the neighbor list's
//! order, and history stays in the neighbor list, so forces are bit-identical to a pass
//! over the full list at a fraction of the distance tests (the skin that makes rebuilds
//! rare makes the full list about three times longer than the contact count).

use glam::DVec3;

use crate::contact::{
    clear_history, CoeffTable, ContactKernel, ContactModel, Geom, Materials, Visitor,
};
use crate::error::Result;
use crate::neighbor::{Neighbor, NeighborList};
use crate::particles::{Particles, INERTIA_SPHERE};

/// Fraction of the skin that the near list adds to r_i + r_j.
const NEAR_MARGIN: f64 = 0.1;

/// The pairs of the neighbor list that may be in contact before any particle moves more
/// than half the margin; `slot` points back into the neighbor list (history).
#[derive(Debug, Clone, Default)]
struct NearList {
    first: Vec<u32>,
    partner: Vec<u32>,
    slot: Vec<u32>,
    xref: Vec<DVec3>,
    /// `Neighbor::nbuilds` of the list it was made from (0: none yet).
    built_for: u64,
    margin: f64,
    /// `Neighbor::growth` when the near list was built.
    growth_ref: f64,
}

/// The granular pair style: a contact model, its mixed coefficients and the near list.
#[derive(Debug, Clone)]
pub struct PairGran {
    /// The contact model.
    pub model: ContactModel,
    table: CoeffTable,
    near: NearList,
}

impl PairGran {
    /// A pair style with `model`; coefficients are mixed by [`PairGran::setup`].
    pub fn new(model: ContactModel) -> Self {
        Self {
            model,
            table: CoeffTable::default(),
            near: NearList::default(),
        }
    }

    /// Mixes the material table (called before every run).
    pub fn setup(&mut self, materials: &Materials) -> Result<()> {
        self.table = CoeffTable::new(materials, self.model.needs())?;
        Ok(())
    }

    /// The mixed coefficients.
    pub fn table(&self) -> &CoeffTable {
        &self.table
    }

    /// True when the near list must be rebuilt before the next force pass: the neighbor
    /// list was rebuilt, or some owned particle moved more than half the margin since.
    /// (With several ranks the caller combines the answers of all ranks.)
    pub fn near_list_stale(&self, x: &[DVec3], neighbor: &Neighbor) -> bool {
        let near = &self.near;
        if near.built_for != neighbor.nbuilds || near.xref.len() != x.len() {
            return true;
        }
        // Radius growth since the build eats into the margin as in `Neighbor::moved_too_far`.
        let half = 0.5 * near.margin - (neighbor.growth - near.growth_ref);
        if half <= 0.0 {
            return true;
        }
        let lim = half * half;
        x.iter()
            .zip(&near.xref)
            .any(|(a, b)| (*a - *b).length_squared() > lim)
    }

    /// Rebuilds the near list from the neighbor list.
    pub fn build_near_list(&mut self, p: &Particles, neighbor: &Neighbor) {
        let near = &mut self.near;
        let list = &neighbor.list;
        near.margin = NEAR_MARGIN * neighbor.settings.skin;
        near.built_for = neighbor.nbuilds;
        near.growth_ref = neighbor.growth;
        let nlocal = p.nlocal();
        near.xref.clear();
        near.xref.extend_from_slice(&p.x[..nlocal]);
        near.first.clear();
        near.partner.clear();
        near.slot.clear();
        near.first.push(0);
        let margin = near.margin;
        for i in 0..nlocal {
            let xi = p.x[i];
            let ri = p.radius[i] + margin;
            for k in list.first[i] as usize..list.first[i + 1] as usize {
                let j = list.partner[k] as usize;
                let rc = ri + p.radius[j];
                if (p.x[j] - xi).length_squared() < rc * rc {
                    near.partner.push(j as u32);
                    near.slot.push(k as u32);
                }
            }
            near.first.push(near.partner.len() as u32);
        }
    }

    /// Adds contact forces and torques for every pair of the near list in contact (to
    /// ghosts too; reverse communication moves those to their owners). History of pairs
    /// out of contact is zeroed. The near list must be current (see
    /// [`PairGran::near_list_stale`]).
    pub fn compute(&self, p: &mut Particles, list: &mut NeighborList, dt: f64, update: bool) {
        debug_assert_eq!(self.near.first.len(), p.nlocal() + 1);
        self.model.dispatch(PairPass {
            pair: self,
            p,
            list,
            dt,
            update,
            virial: None,
        });
    }

    /// [`PairGran::compute`] that also adds each contact's virial to `virial` (one entry
    /// per particle, ghosts included; xx yy zz xy xz yz): for the force F on i from j and
    /// r = x_i − x_j, both i and j get ½ r ⊗ F (the per-atom virial of LAMMPS'
    /// `compute stress/atom`). A separate monomorphization of the pass, so that the plain
    /// force pass carries no trace of it.
    pub fn compute_with_virial(
        &self,
        p: &mut Particles,
        list: &mut NeighborList,
        dt: f64,
        update: bool,
        virial: &mut [[f64; 6]],
    ) {
        debug_assert_eq!(self.near.first.len(), p.nlocal() + 1);
        assert!(virial.len() >= p.len(), "one virial entry per particle");
        self.model.dispatch(PairPass {
            pair: self,
            p,
            list,
            dt,
            update,
            virial: Some(virial),
        });
    }
}

struct PairPass<'a> {
    pair: &'a PairGran,
    p: &'a mut Particles,
    list: &'a mut NeighborList,
    dt: f64,
    update: bool,
    virial: Option<&'a mut [[f64; 6]]>,
}

impl Visitor for PairPass<'_> {
    type Output = ();
    fn visit<K: ContactKernel>(mut self) {
        match self.virial.take() {
            None => self.run::<K, false>(&mut []),
            Some(v) => self.run::<K, true>(v),
        }
    }
}

impl PairPass<'_> {
    /// The pass with kernel `K`; with `VIRIAL` the contact virial goes into `virial`.
    #[inline(always)]
    fn run<K: ContactKernel, const VIRIAL: bool>(self, virial: &mut [[f64; 6]]) {
        let PairPass {
            pair,
            p,
            list,
            dt,
            update,
            virial: _,
        } = self;
        let flags = pair.model.flags;
        let table = &pair.table;
        let w = K::HIST;
        debug_assert_eq!(list.width, w);
        let nlocal = p.nlocal();
        let (x, v, omega, radius, rmass, ty) = (&p.x, &p.v, &p.omega, &p.radius, &p.rmass, &p.ty);
        let (f, torque) = (&mut p.f, &mut p.torque);
        let mut empty: [f64; 0] = [];
        for i in 0..nlocal {
            let xi = x[i];
            let ri = radius[i];
            let mi = rmass[i];
            let coeff_row = table.row(ty[i]);
            let near = &pair.near;
            let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
            let mut fi = DVec3::ZERO;
            let mut tqi = DVec3::ZERO;
            for (&j, &k) in near.partner[s..e].iter().zip(&near.slot[s..e]) {
                let (j, k) = (j as usize, k as usize);
                let d = xi - x[j];
                let rj = radius[j];
                let radsum = ri + rj;
                let rsq = d.length_squared();
                let hist: &mut [f64] = if w > 0 {
                    &mut list.hist[k * w..(k + 1) * w]
                } else {
                    &mut empty
                };
                // Written as "not closer" so that a NaN distance counts as no contact and
                // a broken particle does not poison its neighbours (it is reported by tag).
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                if !(rsq < radsum * radsum) {
                    if w > 0 {
                        clear_history(hist);
                    }
                    continue;
                }
                let dist = rsq.sqrt();
                let delta = radsum - dist;
                let n = if dist > 0.0 {
                    d * (1.0 / dist)
                } else {
                    DVec3::Z
                };
                let mj = rmass[j];
                // R* = r_i r_j/(r_i + r_j) and m* = m_i m_j/(m_i + m_j) with one division.
                let inv = 1.0 / (radsum * (mi + mj));
                let r_star = ri * rj * (mi + mj) * inv;
                let m_star = mi * mj * radsum * inv;
                let g = Geom {
                    n,
                    delta,
                    dist,
                    ri,
                    rj,
                    r_star,
                    m_star,
                    ci: ri - 0.5 * delta,
                    cj: rj - 0.5 * delta,
                    vr: v[i] - v[j],
                    wi: omega[i],
                    wj: omega[j],
                    roll_scale: 1.0,
                    inertia_i: (INERTIA_SPHERE + 1.0) * mi * ri * ri,
                    inertia_j: (INERTIA_SPHERE + 1.0) * mj * rj * rj,
                    dt,
                    update,
                };
                let out = K::contact(&g, &coeff_row[ty[j] as usize - 1], flags, hist);
                if VIRIAL {
                    let f = out.f_i;
                    let w = [
                        0.5 * (d.x * f.x),
                        0.5 * (d.y * f.y),
                        0.5 * (d.z * f.z),
                        0.5 * (d.x * f.y),
                        0.5 * (d.x * f.z),
                        0.5 * (d.y * f.z),
                    ];
                    for (a, b) in virial[i].iter_mut().zip(&w) {
                        *a += b;
                    }
                    for (a, b) in virial[j].iter_mut().zip(&w) {
                        *a += b;
                    }
                }
                fi += out.f_i;
                tqi += out.t_i;
                f[j] -= out.f_i;
                torque[j] += out.t_j;
            }
            f[i] += fi;
            torque[i] += tqi;
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{
        Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NewParticle, PairGran,
        PrimitiveWall, WallShape, World,
    };

    /// Every touching pair of a moving, colliding gas in a walled box is in the near list at
    /// every step, every particle touching a wall is among that wall's candidates, and the
    /// near list is a sub-list of the neighbor list.
    #[test]
    fn near_list_never_misses_a_contact() {
        let mut w =
            World::new(Domain::new(DVec3::ZERO, DVec3::splat(0.04), [Boundary::Fixed; 3]).unwrap());
        w.materials = Materials::uniform(1, 1e7, 0.3, 0.9, 0.3);
        w.pair = Some(PairGran::new(ContactModel::hertz_history()));
        w.neighbor.settings.skin = 0.002;
        w.neighbor.settings.delay = 0;
        w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
            .unwrap();
        for axis in 0..3 {
            for (k, pos) in [0.0, 0.04].into_iter().enumerate() {
                let shape = WallShape::Plane { axis, pos };
                let id = format!("wall{axis}{k}");
                let wall =
                    PrimitiveWall::new(&id, ContactModel::hertz_history(), 1, shape).unwrap();
                w.add_fix(Fix::new(&id, 1, FixKind::WallGran(Box::new(wall))).unwrap())
                    .unwrap();
            }
        }
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for a in 0..6 {
            for b in 0..6 {
                for c in 0..6 {
                    let x = DVec3::new(a as f64 + 0.5, b as f64 + 0.5, c as f64 + 0.5) * 0.0066;
                    let v = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 2.0;
                    w.add_particle(&NewParticle::at(x, 0.002 + 0.0012 * rnd(), 2500.0).with_v(v))
                        .unwrap();
                }
            }
        }
        w.set_timestep(2e-6).unwrap();
        w.setup().unwrap();
        let mut touching_seen = 0;
        let mut wall_touches = 0;
        let mut near_rebuilds = 0;
        let mut last = w.pair.as_ref().unwrap().near.xref.clone();
        for _ in 0..3000 {
            w.advance().unwrap();
            let p = &w.particles;
            let pair = w.pair.as_ref().unwrap();
            if pair.near.xref != last {
                near_rebuilds += 1;
                last = pair.near.xref.clone();
            }
            let n = p.nlocal();
            for i in 0..n {
                for j in i + 1..n {
                    let rs = p.radius[i] + p.radius[j];
                    if (p.x[i] - p.x[j]).length_squared() < rs * rs {
                        touching_seen += 1;
                        let listed = |a: usize, b: usize| {
                            let (s, e) =
                                (pair.near.first[a] as usize, pair.near.first[a + 1] as usize);
                            pair.near.partner[s..e].contains(&(b as u32))
                        };
                        assert!(
                            listed(i, j) || listed(j, i),
                            "touching pair {i} {j} not in the near list"
                        );
                    }
                }
            }
            for fix in &w.fixes {
                if let FixKind::WallGran(wall) = &fix.kind {
                    for i in 0..n {
                        if wall.shape.distance(p.x[i]).0 < p.radius[i] {
                            wall_touches += 1;
                            assert!(
                                wall.candidates().contains(&(i as u32)),
                                "wall contact of {i} missed"
                            );
                        }
                    }
                }
            }
            for (k, &slot) in pair.near.slot.iter().enumerate() {
                assert_eq!(w.neighbor.list.partner[slot as usize], pair.near.partner[k]);
            }
        }
        assert!(
            touching_seen > 1000,
            "the gas must collide ({touching_seen})"
        );
        assert_eq!(w.particles.nlocal(), 216);
        assert!(wall_touches > 100, "the walls must be hit ({wall_touches})");
        assert!(
            near_rebuilds > 10 && near_rebuilds < 3000,
            "{near_rebuilds} near-list rebuilds"
        );
    }
}
