//! The contacts of the pair style one by one, for per-contact output (`compute
//! pair/gran/local`). As LIGGGHTS 3.8 does when such a compute is invoked, the contact
//! model is evaluated again from the current positions, velocities and stored history,
//! without changing the history ([`crate::contact::Geom::update`] off): at the end of a
//! step this is the state the output describes. Nothing is done on steps without output.
//!
//! [`PairGran::bonds`] does the same for the intact bonds of `cohesion bond` (`compute
//! pair/gran/local/bond` of LIGGGHTS-INL): one entry per bonded pair, with the whole force
//! and torque the pair gives i (contact law and bond) and the pair's whole history row.

use glam::DVec3;

use super::{BondRulesIn, PairGran, Phase1};
use crate::bond::{self, BondEvents};
use crate::contact::{ContactForce, ContactKernel, Visitor};
use crate::neighbor::NeighborList;
use crate::particles::Particles;

/// The pair contacts of the owned particles: one entry per touching pair (i owned, j
/// owned or ghost), and per liquid bridge that pulls on particles apart, in
/// neighbor-list order.
#[derive(Debug, Clone, Default)]
pub struct PairContacts {
    /// Local index of i (owned).
    pub i: Vec<u32>,
    /// Local index of j (owned or ghost).
    pub j: Vec<u32>,
    /// Contact force on i (the contact law's; bonds not included).
    pub f: Vec<DVec3>,
    /// Torque on i from the contact law.
    pub t_i: Vec<DVec3>,
    /// Overlap r_i + r_j − |x_i − x_j|.
    pub delta: Vec<f64>,
    /// Contact history values of the contact law, [`PairContacts::width`] per contact.
    pub hist: Vec<f64>,
    /// History values per contact.
    pub width: usize,
}

impl PairContacts {
    /// Number of contacts.
    pub fn len(&self) -> usize {
        self.i.len()
    }

    /// True without contacts.
    pub fn is_empty(&self) -> bool {
        self.i.is_empty()
    }

    /// Adds the pair of i and j (overlap `delta`, history row `hist`) with the force and
    /// torque on i of `c`.
    fn push(&mut self, i: usize, j: usize, c: &ContactForce, delta: f64, hist: &[f64]) {
        self.i.push(i as u32);
        self.j.push(j as u32);
        self.f.push(c.f_i);
        self.t_i.push(c.t_i);
        self.delta.push(delta);
        self.hist.extend_from_slice(hist);
    }
}

impl PairGran {
    /// The touching pairs of the near list (current after a force pass) and what the
    /// contact law gives for each, evaluated again without changing the history. Ghost
    /// velocities must be current (as for a force pass).
    pub fn contacts(&self, p: &Particles, list: &NeighborList, dt: f64) -> PairContacts {
        let model = self.model;
        model.dispatch(Records {
            pair: self,
            p,
            list,
            dt,
            bonds: false,
        })
    }

    /// The intact bonds of the near list (none without `cohesion bond`), each with the
    /// force and torque on i of the contact law and the bond together, evaluated as a
    /// force pass that does not advance the history would give them (the bond's
    /// incremental loads include one increment from the current velocities, as at a run's
    /// set-up), and the pair's whole history row (`hist`, [`PairContacts::width`] values:
    /// the bond's [`bond::VEC`] vectors, the contact law's values, flag and d₀).
    pub fn bonds(&self, p: &Particles, list: &NeighborList, dt: f64) -> PairContacts {
        if self.bond.is_none() {
            return PairContacts::default();
        }
        let model = self.model;
        model.dispatch(Records {
            pair: self,
            p,
            list,
            dt,
            bonds: true,
        })
    }
}

struct Records<'a> {
    pair: &'a PairGran,
    p: &'a Particles,
    list: &'a NeighborList,
    dt: f64,
    /// Bonded pairs (through [`Phase1::eval`]) instead of touching ones.
    bonds: bool,
}

impl Visitor for Records<'_> {
    type Output = PairContacts;
    fn visit<K: ContactKernel>(self) -> PairContacts {
        if self.bonds {
            // Only `cohesion bond` kernels have bonds (and only they compile this path).
            debug_assert!(K::BONDS);
            if K::BONDS {
                let w = self.list.width;
                return self.collect(w, &|ph1, pair, p, list, out| {
                    bond_records::<K>(ph1, pair, p, list, out)
                });
            }
            return PairContacts {
                width: self.list.width,
                ..PairContacts::default()
            };
        }
        self.collect(K::HIST, &|ph1, pair, p, list, out| {
            touching_records::<K>(ph1, pair, p, list, out)
        })
    }
}

/// A records loop of one kernel: `(inputs, pair style, particles, list, records so far)`.
type RecordsFn =
    dyn Fn(&Phase1, &PairGran, &Particles, &NeighborList, PairContacts) -> PairContacts;

impl Records<'_> {
    /// The records of `each` (the kernel's loop), `width` history values each, with
    /// phase 1's inputs set up for an evaluation that leaves the history as it is. Not
    /// generic over the kernel, so that the set-up is compiled once.
    fn collect(self, width: usize, each: &RecordsFn) -> PairContacts {
        let Records {
            pair, p, list, dt, ..
        } = self;
        let nlocal = p.nlocal();
        let events = BondEvents::default();
        let out = PairContacts {
            width,
            ..PairContacts::default()
        };
        if !pair.near.has_rows(nlocal) {
            return out;
        }
        let mc_state = pair.multicontact.as_ref().map(|m| m.read());
        let ph1 = Phase1 {
            near: pair.near.rows(&list.first, &list.partner),
            table: &pair.table,
            flags: pair.model.kernel_flags(),
            list_first: &list.first,
            width: list.width,
            nlocal,
            x: &p.x,
            v: &p.v,
            omega: &p.omega,
            radius: &p.radius,
            rmass: p.contact_mass(),
            mask: &p.mask,
            freeze: pair.freeze,
            ty: &p.ty,
            dt,
            update: false,
            bond: pair.bond.as_ref(),
            bond_flags: pair.model.bond,
            create_now: false,
            random_id: &[],
            step: pair.step,
            events: &events,
            lq: pair
                .liquid
                .as_ref()
                .map_or(&[][..], |l| &p.props[l.content.0].data[..]),
            breaks: None,
            mc: pair.multicontact.as_deref().zip(mc_state.as_deref()),
            tag: &p.tag,
            bond_rules: BondRulesIn::of(pair.bond_rules, &p.props),
        };
        each(&ph1, pair, p, list, out)
    }
}

/// The touching pairs of the near list for [`PairGran::contacts`].
fn touching_records<K: ContactKernel>(
    ph1: &Phase1,
    pair: &PairGran,
    p: &Particles,
    list: &NeighborList,
    mut out: PairContacts,
) -> PairContacts {
    // The contact law's values sit after the bond's vectors when there are bonds.
    let off = pair.bond.as_ref().map_or(0, |b| b.layout().vec);
    let w = list.width;
    let mut scratch = vec![0.0; K::HIST];
    let near = ph1.near;
    for i in 0..p.nlocal() {
        let coeff_row = pair.table.row(p.ty[i]);
        let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
        for (kk, (j, slot)) in near.pairs(s, e).enumerate() {
            let d = p.x[i] - p.x[j];
            let rsq = d.length_squared();
            let h = &list.hist[slot * w + off..slot * w + off + K::HIST];
            scratch.copy_from_slice(h);
            let Some(c) = ph1.contact::<K>(i, j, s + kk, coeff_row, &mut scratch, &mut 0, d, rsq)
            else {
                continue;
            };
            out.push(i, j, &c, p.radius[i] + p.radius[j] - rsq.sqrt(), h);
        }
    }
    out
}

/// The bonded pairs of the near list for [`PairGran::bonds`].
fn bond_records<K: ContactKernel>(
    ph1: &Phase1,
    pair: &PairGran,
    p: &Particles,
    list: &NeighborList,
    mut out: PairContacts,
) -> PairContacts {
    let w = list.width;
    let flag = w - pair.bond.as_ref().map_or(0, |b| b.layout().pair_tail);
    let mut scratch = vec![0.0; w];
    let near = ph1.near;
    for i in 0..p.nlocal() {
        let coeff_row = pair.table.row(p.ty[i]);
        let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
        for (kk, (j, slot)) in near.pairs(s, e).enumerate() {
            let h = &list.hist[slot * w..(slot + 1) * w];
            if !bond::is_bonded(&h[flag..]) {
                continue;
            }
            scratch.copy_from_slice(h);
            let Some((d, c)) = ph1.eval::<K, true>(i, j, s + kk, coeff_row, &mut scratch, &mut 0)
            else {
                continue;
            };
            out.push(i, j, &c, p.radius[i] + p.radius[j] - d.length(), h);
        }
    }
    out
}
