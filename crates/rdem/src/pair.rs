//! `pair_style gran`: the particle–particle force pass over the half neighbor list.

use glam::DVec3;

use crate::contact::{CoeffTable, ContactKernel, ContactModel, Geom, Materials, Visitor};
use crate::error::Result;
use crate::neighbor::NeighborList;
use crate::particles::{Particles, INERTIA_SPHERE};

/// The granular pair style: a contact model and its mixed coefficients.
#[derive(Debug, Clone)]
pub struct PairGran {
    /// The contact model.
    pub model: ContactModel,
    table: CoeffTable,
}

impl PairGran {
    /// A pair style with `model`; coefficients are mixed by [`PairGran::setup`].
    pub fn new(model: ContactModel) -> Self {
        Self {
            model,
            table: CoeffTable::default(),
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

    /// Adds contact forces and torques for every listed pair in contact (to ghosts too;
    /// reverse communication moves those to their owners). History of pairs out of
    /// contact is zeroed.
    pub fn compute(&self, p: &mut Particles, list: &mut NeighborList, dt: f64, update: bool) {
        self.model.dispatch(PairPass {
            pair: self,
            p,
            list,
            dt,
            update,
        });
    }
}

struct PairPass<'a> {
    pair: &'a PairGran,
    p: &'a mut Particles,
    list: &'a mut NeighborList,
    dt: f64,
    update: bool,
}

impl Visitor for PairPass<'_> {
    type Output = ();
    fn visit<K: ContactKernel>(self) {
        let PairPass {
            pair,
            p,
            list,
            dt,
            update,
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
            let ti = ty[i];
            let (s, e) = (list.first[i] as usize, list.first[i + 1] as usize);
            let mut fi = DVec3::ZERO;
            let mut tqi = DVec3::ZERO;
            for k in s..e {
                let j = list.partner[k] as usize;
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
                        hist.iter_mut().for_each(|h| *h = 0.0);
                    }
                    continue;
                }
                let dist = rsq.sqrt();
                let delta = radsum - dist;
                let n = if dist > 0.0 { d / dist } else { DVec3::Z };
                let mj = rmass[j];
                let g = Geom {
                    n,
                    delta,
                    dist,
                    ri,
                    rj,
                    r_star: ri * rj / radsum,
                    m_star: mi * mj / (mi + mj),
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
                let out = K::contact(&g, table.get(ti, ty[j]), flags, hist);
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
