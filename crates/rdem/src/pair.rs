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

use crate::bond::{self, BondEvents, BondGeom, BondTable, Event};
use crate::contact::cohesion::Bridge;
use crate::contact::liquid::Separated;
use crate::contact::{
    clear_history, CoeffTable, ContactForce, ContactKernel, ContactModel, Geom, Materials,
    PairCoeff, Visitor,
};
use crate::error::Result;
use crate::multicontact::{MultiContact, State as MultiState};
use crate::neighbor::{Neighbor, NeighborList};
use crate::particles::{Particles, INERTIA_SPHERE};

mod liquid;
mod local;
mod near;
pub use liquid::{
    BridgeBreak, LiquidState, CONTENT as LIQUID_CONTENT, FLUX as LIQUID_FLUX,
    SOURCE as LIQUID_SOURCE,
};
pub use local::PairContacts;
use near::{NearList, Rows, WHOLE_FRACTION};

/// The granular pair style: a contact model, its mixed coefficients and the near list.
#[derive(Debug, Clone)]
pub struct PairGran {
    /// The contact model.
    pub model: ContactModel,
    table: CoeffTable,
    near: NearList,
    /// Phase 1's per-pair results, one per near-list pair (kept between steps).
    res: Vec<PairOut>,
    /// Phase 1's per-particle sums over its own pairs, one per owned particle.
    own: Vec<OwnSum>,
    /// Phase 1's per-pair virials (only used by [`PairGran::compute_with_virial`]).
    res_virial: Vec<[f64; 6]>,
    /// With `cohesion bond`: the bond parameters (made by [`PairGran::setup`]).
    bond: Option<BondTable>,
    /// Pair bonds created and broken on this rank so far.
    pub bond_events: BondEvents,
    /// The current step (set before each force pass; bonds are created at
    /// `tsCreateBond`).
    pub step: u64,
    /// Whether the "no bond will be created" warning was given.
    pub(crate) ts_warned: bool,
    /// With liquid bridges: the per-particle liquid properties and this pass's breaks.
    pub(crate) liquid: Option<LiquidState>,
    /// The near fraction from which the passes walk the whole neighbor list
    /// ([`WHOLE_FRACTION`]; tests raise it past 1 to keep a near list).
    whole_fraction: f64,
    /// With `surface multicontact`: the contacts' store ([`crate::multicontact`]).
    pub multicontact: Option<std::sync::Arc<MultiContact>>,
    /// The group bit of `fix freeze` (0 without one; set by the world's set-up). A
    /// contact with a frozen particle takes the other particle's mass as its effective
    /// mass, as if the frozen one were infinitely heavy, as LIGGGHTS does.
    pub(crate) freeze: u32,
    /// With `bond_style gran`: the pairs it takes out of contact (set by the world's
    /// set-up), see [`BondRules`].
    pub(crate) bond_rules: Option<BondRules>,
}

/// The pairs `bond_style gran` takes out of contact, as the forks' pair style tests them
/// at every step (a skipped pair keeps its contact history as it is):
///
/// - with `disableNormalContact 1`, a pair whose first sphere holds a bond to the second
///   that has not left (intact, broken but not yet dropped at a re-neighboring, or
///   separating); a bond of break styles 3 to 5 that leaves gives the contact back at
///   the next step;
/// - in Flexible_Fibers' form, two spheres of one molecule, one of which holds a bond,
///   while their centres are closer than half their radii sum (the fork tests the bond
///   of the pair's first sphere in its neighbor list, rdem of either sphere).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct BondRules {
    /// [`crate::bond_gran::PROP`].
    pub bonds: crate::particles::PropId,
    /// `disableNormalContact 1`.
    pub disable_contact: bool,
    /// [`crate::bond_gran::MOLECULE`], for the molecule rule (Flexible_Fibers' form).
    pub molecule: Option<crate::particles::PropId>,
}

/// [`BondRules`]' values in a pass.
#[derive(Clone, Copy)]
struct BondRulesIn<'a> {
    bonds: &'a [f64],
    width: usize,
    disable_contact: bool,
    molecule: Option<&'a [f64]>,
}

impl<'a> BondRulesIn<'a> {
    /// The rules `rules` on the per-particle properties `props`.
    fn of(rules: Option<BondRules>, props: &'a [crate::particles::Property]) -> Option<Self> {
        rules.map(|r| BondRulesIn {
            bonds: &props[r.bonds.0].data,
            width: props[r.bonds.0].width,
            disable_contact: r.disable_contact,
            molecule: r.molecule.map(|m| &props[m.0].data[..]),
        })
    }

    /// True when the touching pair (i, j), `rsq` = |x_i − x_j|² and `radsum` = r_i + r_j,
    /// has no contact.
    #[inline(always)]
    fn skips(
        &self,
        i: usize,
        j: usize,
        tag_j: crate::particles::Tag,
        rsq: f64,
        radsum: f64,
    ) -> bool {
        let w = self.width;
        let row = |k: usize| &self.bonds[k * w..(k + 1) * w];
        if self.disable_contact && crate::bond_gran::keeps_apart(row(i), tag_j) {
            return true;
        }
        match self.molecule {
            Some(m) if rsq < 0.25 * radsum * radsum => {
                m[i] == m[j]
                    && (crate::bond_gran::holds_any(row(i)) || crate::bond_gran::holds_any(row(j)))
            }
            _ => false,
        }
    }
}

impl PairGran {
    /// A pair style with `model`; coefficients are mixed by [`PairGran::setup`].
    pub fn new(model: ContactModel) -> Self {
        Self {
            model,
            table: CoeffTable::default(),
            near: NearList::default(),
            res: Vec::new(),
            own: Vec::new(),
            res_virial: Vec::new(),
            bond: None,
            bond_events: BondEvents::default(),
            step: 0,
            ts_warned: false,
            liquid: None,
            whole_fraction: WHOLE_FRACTION,
            multicontact: None,
            freeze: 0,
            bond_rules: None,
        }
    }

    /// Mixes the material table, and the bond table with `cohesion bond` (called before
    /// every run).
    pub fn setup(&mut self, materials: &Materials) -> Result<()> {
        self.model.resolve_jkr(materials)?;
        self.table = CoeffTable::new(materials, self.model.needs())?;
        self.bond = BondTable::for_model(&self.model, materials)?;
        Ok(())
    }

    /// The bond parameters, with `cohesion bond` (after [`PairGran::setup`]).
    pub fn bond_table(&self) -> Option<&BondTable> {
        self.bond.as_ref()
    }

    /// Centre distance up to which pairs must be listed whatever their radii: the longest
    /// bond (0 without bonds).
    pub fn reach(&self) -> f64 {
        self.bond.as_ref().map_or(0.0, |b| b.pair_reach)
    }

    /// Intact pair bonds held in `list` (rows of owned particles: each pair once).
    pub fn count_bonds(&self, list: &NeighborList) -> u64 {
        if self.bond.is_none() || list.width == 0 {
            return 0;
        }
        let w = list.width;
        let flag = w - self.bond.as_ref().map_or(0, |b| b.layout().pair_tail);
        list.hist
            .chunks_exact(w)
            .filter(|h| bond::is_bonded(&h[flag..]))
            .count() as u64
    }

    /// The mixed coefficients.
    pub fn table(&self) -> &CoeffTable {
        &self.table
    }

    /// True when the near list must be rebuilt before the next force pass: the neighbor
    /// list was rebuilt, or some particle of the list (`x`: owned particles and ghosts)
    /// moved more than half the margin since. Ghosts are checked too, so that each rank
    /// decides for its own list without asking the others.
    pub fn near_list_stale(&self, x: &[DVec3], neighbor: &Neighbor) -> bool {
        self.near.stale(x, neighbor)
    }

    /// Gives back the near list's buffers and phase 1's (called when the neighbor list is
    /// about to be rebuilt, which makes them stale): they are not resident while the
    /// neighbor search runs. The next force pass builds the near list anew.
    pub fn release_near_list(&mut self) {
        self.near = NearList::default();
        self.res = Vec::new();
        self.own = Vec::new();
        self.res_virial = Vec::new();
    }

    /// Rebuilds the near list from the neighbor list.
    pub fn build_near_list(&mut self, p: &Particles, neighbor: &Neighbor) {
        let reach = self.bond.as_ref().map_or(0.0, |b| b.pair_reach);
        self.near.build(p, neighbor, reach, self.whole_fraction);
    }

    /// Adds contact forces and torques for every pair of the near list in contact (to
    /// ghosts too; reverse communication moves those to their owners). History of pairs
    /// out of contact is zeroed. The near list must be current (see
    /// [`PairGran::near_list_stale`]). Runs on the current rayon pool; the result is
    /// bit-identical whatever its size (see [`PairPass`]).
    pub fn compute(&mut self, p: &mut Particles, list: &mut NeighborList, dt: f64, update: bool) {
        debug_assert!(self.near.has_rows(p.nlocal()));
        self.begin_liquid(p, update);
        let model = self.model;
        model.dispatch(PairPass {
            pair: self,
            p,
            list,
            dt,
            update,
            virial: None,
        });
        self.end_liquid(p);
    }

    /// [`PairGran::compute`] that also adds each contact's virial to `virial` (one entry
    /// per particle, ghosts included; xx yy zz xy xz yz): for the force F on i from j and
    /// r = x_i − x_j, both i and j get ½ r ⊗ F (the per-atom virial of LAMMPS'
    /// `compute stress/atom`). A separate monomorphization of the pass, so that the plain
    /// force pass carries no trace of it.
    pub fn compute_with_virial(
        &mut self,
        p: &mut Particles,
        list: &mut NeighborList,
        dt: f64,
        update: bool,
        virial: &mut [[f64; 6]],
    ) {
        debug_assert!(self.near.has_rows(p.nlocal()));
        assert!(virial.len() >= p.len(), "one virial entry per particle");
        self.begin_liquid(p, update);
        let model = self.model;
        model.dispatch(PairPass {
            pair: self,
            p,
            list,
            dt,
            update,
            virial: Some(virial),
        });
        self.end_liquid(p);
    }
}

/// Particles per block of work in both phases of the pass. A constant, not a function of
/// the thread count, so that the work and every sum are the same whatever the pool.
const BLOCK: usize = 256;

/// What one near-list pair gives its partner j: the force on i (j gets its negative) and
/// the torque on j. (What it gives i is summed per particle in phase 1, see [`OwnSum`].)
#[derive(Debug, Clone, Copy, Default)]
struct PairOut {
    f_i: DVec3,
    t_j: DVec3,
}

/// The sums of force and torque over an owned particle's own pairs (its row of the near
/// list), in row order from zero: what a serial pass adds to it at the end of its row.
#[derive(Debug, Clone, Copy, Default)]
struct OwnSum {
    f: DVec3,
    t: DVec3,
}

/// The force pass, in two phases that make the result independent of the thread count:
///
/// 1. in parallel over blocks of [`BLOCK`] owned particles, every near pair's kernel
///    runs, writes the pair's own history slot and stores its [`PairOut`] (and virial)
///    in the pair's entry of a buffer indexed by near-list position, and each owned
///    particle's sums over its row go to its [`OwnSum`];
/// 2. in parallel over blocks of all particles (ghosts too), each particle sums what its
///    pairs left for it, in increasing near-list position: first the pairs where it is j
///    and i is before it, then its own pairs (summed apart, then added), then the pairs
///    where it is j and i is after it (the reverse CSR of the near list gives those).
///
/// Phase 2 repeats, operation for operation, the sums of a serial pass over the near list
/// (i ascending: `f[i] += Σ own`, `f[j] -= f_i` as they come), so the result is the
/// serial pass's, bit for bit. Pairs out of contact leave zeros, which change no sum
/// (an accumulator that starts at +0 is never −0).
struct PairPass<'a> {
    pair: &'a mut PairGran,
    p: &'a mut Particles,
    list: &'a mut NeighborList,
    dt: f64,
    update: bool,
    virial: Option<&'a mut [[f64; 6]]>,
}

impl Visitor for PairPass<'_> {
    type Output = ();
    fn visit<K: ContactKernel>(self) {
        debug_assert_eq!(self.pair.bond.is_some(), K::BONDS);
        // `K::BONDS` is a constant: each kernel is compiled with or without bonds, not both.
        if K::BONDS {
            self.run(
                &|ph, h, t, f, tq| ph.serial::<K, true>(h, t, f, tq),
                &|ph, b, r, h, t, o| ph.block::<K, true>(b, r, h, t, o),
            )
        } else {
            self.run(
                &|ph, h, t, f, tq| ph.serial::<K, false>(h, t, f, tq),
                &|ph, b, r, h, t, o| ph.block::<K, false>(b, r, h, t, o),
            )
        }
    }
}

/// The whole pass of one kernel on the calling thread: `(inputs, hist, touch, f, torque)`
/// as [`Phase1::serial`] takes them.
type SerialFn = dyn Fn(&Phase1, &mut [f64], &mut [u8], &mut [DVec3], &mut [DVec3]);

/// One block of phase 1 with a given kernel: `(inputs, block, res, hist, touch, own)`
/// as [`Phase1::block`] takes them.
type BlockFn = dyn Fn(&Phase1, usize, &mut [PairOut], &mut [f64], &mut [u8], &mut [OwnSum]) + Sync;

/// Phase 1's read-only inputs.
struct Phase1<'a> {
    near: Rows<'a>,
    table: &'a CoeffTable,
    flags: crate::contact::Flags,
    list_first: &'a [u32],
    width: usize,
    nlocal: usize,
    x: &'a [DVec3],
    v: &'a [DVec3],
    omega: &'a [DVec3],
    radius: &'a [f64],
    rmass: &'a [f64],
    ty: &'a [u32],
    dt: f64,
    update: bool,
    /// Bond parameters and switches (with `cohesion bond`).
    bond: Option<&'a BondTable>,
    bond_flags: bond::BondFlags,
    /// Whether bonds are created in this pass.
    create_now: bool,
    /// With `cohesion bond`: every particle's [`bond::RANDOM_ID`] (empty if none has
    /// one), and the step, when the history advances (else empty).
    random_id: &'a [f64],
    step: u64,
    events: &'a BondEvents,
    /// Liquid contents of all particles (liquid bridges; else empty).
    lq: &'a [f64],
    /// Where liquid bridges record their breaks (liquid bridges only).
    breaks: Option<&'a liquid::Breaks>,
    /// With `surface multicontact`: the store (to record into) and its last records.
    mc: Option<(&'a MultiContact, &'a MultiState)>,
    /// Tags of all particles.
    tag: &'a [crate::particles::Tag],
    /// Group masks of all particles, and the frozen group's bit ([`PairGran::freeze`]).
    mask: &'a [u32],
    freeze: u32,
    /// [`PairGran::bond_rules`]' values.
    bond_rules: Option<BondRulesIn<'a>>,
}

impl Phase1<'_> {
    /// Runs blocks `b0..b1`; `res` and `hist` start at the first pair and the first
    /// history value of block `b0`, `own` at its first particle.
    /// Each block runs through `leaf` (the kernel's [`Phase1::block`]), so that the
    /// fork–join is compiled once rather than once per kernel; the indirect call is one
    /// per block of [`BLOCK`] particles.
    #[allow(clippy::too_many_arguments)]
    fn blocks(
        &self,
        b0: usize,
        b1: usize,
        res: &mut [PairOut],
        hist: &mut [f64],
        touch: &mut [u8],
        own: &mut [OwnSum],
        leaf: &BlockFn,
    ) {
        if b1 - b0 > 1 {
            let mid = (b0 + b1) / 2;
            let (lo, m) = (b0 * BLOCK, mid * BLOCK);
            let kn = (self.near.first[m] - self.near.first[lo]) as usize;
            let kp = (self.list_first[m] - self.list_first[lo]) as usize;
            let kh = kp * self.width;
            let (ra, rb) = res.split_at_mut(kn);
            let (ha, hb) = hist.split_at_mut(kh);
            let (ta, tb) = touch.split_at_mut(if touch.is_empty() { 0 } else { kp });
            let (oa, ob) = own.split_at_mut(m - lo);
            rayon::join(
                || self.blocks(b0, mid, ra, ha, ta, oa, leaf),
                || self.blocks(mid, b1, rb, hb, tb, ob, leaf),
            );
        } else {
            leaf(self, b0, res, hist, touch, own);
        }
    }

    /// One block of owned particles.
    #[inline(always)]
    fn block<K: ContactKernel, const BOND: bool>(
        &self,
        b: usize,
        res: &mut [PairOut],
        hist: &mut [f64],
        touch: &mut [u8],
        own: &mut [OwnSum],
    ) {
        let w = self.width;
        let (lo, hi) = (b * BLOCK, ((b + 1) * BLOCK).min(self.nlocal));
        let near = self.near;
        let k0 = near.first[lo] as usize;
        let h0 = self.list_first[lo] as usize;
        let mut empty: [f64; 0] = [];
        let mut no_touch = 0u8;
        for i in lo..hi {
            let coeff_row = self.table.row(self.ty[i]);
            let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
            let mut sum = OwnSum::default();
            for (kk, (j, slot)) in near.pairs(s, e).enumerate() {
                let r = s - k0 + kk;
                let slot = slot - h0;
                let (hist, touch): (&mut [f64], &mut u8) = if w > 0 {
                    (&mut hist[slot * w..(slot + 1) * w], &mut touch[slot])
                } else {
                    (&mut empty, &mut no_touch)
                };
                let Some((_, out)) = self.eval::<K, BOND>(i, j, s + kk, coeff_row, hist, touch)
                else {
                    res[r] = PairOut::default();
                    continue;
                };
                res[r] = PairOut {
                    f_i: out.f_i,
                    t_j: out.t_j,
                };
                sum.f += out.f_i;
                sum.t += out.t_i;
            }
            own[i - lo] = sum;
        }
    }
    /// The pair of owned particle `i` with `j` (`coeff_row`: i's row of the table):
    /// `None` when they neither touch nor are bonded (the contact history cleared); else
    /// r = x_i − x_j and the force and torques (contact, and with `BOND` the bond).
    #[inline(always)]
    fn eval<K: ContactKernel, const BOND: bool>(
        &self,
        i: usize,
        j: usize,
        k: usize,
        coeff_row: &[PairCoeff],
        hist: &mut [f64],
        touch: &mut u8,
    ) -> Option<(DVec3, ContactForce)> {
        let d = self.x[i] - self.x[j];
        let rsq = d.length_squared();
        if !BOND {
            return self
                .contact::<K>(i, j, k, coeff_row, hist, touch, d, rsq)
                .map(|o| (d, o));
        }
        let table = self.bond.expect("bond table");
        let (vecs, rest) = hist.split_at_mut(table.layout().vec);
        let (hc, tail) = rest.split_at_mut(K::HIST);
        let mut out = self.contact::<K>(i, j, k, coeff_row, hc, touch, d, rsq);
        if out.is_none() {
            // With bonds the neighbor reach exceeds the contact, and a listed pair apart
            // loses its contact history at every evaluation, as in LIGGGHTS-INL (its
            // models forget their springs when surfaces are close but apart): a pair that
            // touches again starts its springs anew, bonded or not.
            clear_history(hc);
        }
        let (ti, tj) = (self.ty[i], self.ty[j]);
        let c = table.get(ti, tj);
        if !bond::is_bonded(tail) {
            let by_id = !self.random_id.is_empty()
                && bond::same_random_id(self.random_id[i], self.random_id[j], self.step);
            if !self.create_now && !by_id {
                return out.map(|o| (d, o));
            }
            let dist = rsq.sqrt();
            if !bond::creates(c, true, dist) {
                return out.map(|o| (d, o));
            }
            bond::create(vecs, tail, dist);
            self.events.count(Event::Created);
        }
        let g = BondGeom {
            d,
            ri: self.radius[i],
            rj: self.radius[j],
            vr: self.v[i] - self.v[j],
            wi: self.omega[i],
            wj: self.omega[j],
            dt: self.dt,
            update: self.update,
            reach: table.pair_reach,
        };
        let (b, e) = table.force(&g, ti, tj, self.bond_flags, vecs, tail);
        self.events.count(e);
        // A bonded pair keeps its history at a build whether it touches or not.
        if bond::is_bonded(tail) {
            *touch = 1;
        }
        if e != Event::Broken {
            let o = out.get_or_insert_with(ContactForce::default);
            if table.law().replaces_normal_contact() && o.fn_total != 0.0 {
                o.f_i -= o.fn_total * (d * (1.0 / rsq.sqrt()));
                o.fn_total = 0.0;
            }
            o.f_i += b.f_i;
            o.t_i += b.t_i;
            o.t_j += b.t_j;
        }
        out.map(|o| (d, o))
    }

    /// The contact of owned particle `i` with `j` (near-list position `k`) at r = `d`
    /// (`rsq` = |d|²): `None`, with the history `hist` cleared, when they do not touch
    /// (a liquid bridge between them keeps its own history and may still pull, or break);
    /// else the kernel's output.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn contact<K: ContactKernel>(
        &self,
        i: usize,
        j: usize,
        k: usize,
        coeff_row: &[PairCoeff],
        hist: &mut [f64],
        touch: &mut u8,
        d: DVec3,
        rsq: f64,
    ) -> Option<ContactForce> {
        let (v, omega, radius, rmass, ty) = (self.v, self.omega, self.radius, self.rmass, self.ty);
        let (flags, dt, update) = (self.flags, self.dt, self.update);
        let ri = radius[i];
        let mi = rmass[i];
        let rj = radius[j];
        let radsum = ri + rj;
        // Written as "not closer" so that a NaN distance counts as no contact and
        // a broken particle does not poison its neighbours (it is reported by tag).
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let apart = !(rsq < radsum * radsum);
        // Under `surface multicontact` a pair just apart may touch once its radii are
        // corrected (LIGGGHTS checks the corrected overlap): the shaping below decides.
        if apart && (self.mc.is_none() || K::BRIDGE || !rsq.is_finite()) {
            if K::BRIDGE {
                // The contact's history is cleared; a live bridge keeps the pair's.
                let out = self.apart::<K>(i, j, k, coeff_row, hist, d, rsq);
                let bridge = &hist[K::HIST - K::BRIDGE_HIST..];
                *touch = bridge.iter().any(|&h| h != 0.0) as u8;
                return out;
            }
            // A JKR neck holds apart down to δ = −δ_c: the contact goes on below.
            let neck = K::NECK && rsq.is_finite() && {
                let r_star = ri * rj / radsum;
                let c = &coeff_row[ty[j] as usize - 1];
                K::holds(radsum - rsq.sqrt(), r_star, c, hist, update)
            };
            if !neck {
                *touch = 0;
                // The history stays, as in LIGGGHTS 3.8: a pair that touches again
                // before the next neighbor build goes on from it (see
                // `NeighborList::touch`).
                return None;
            }
        }
        if let Some(rules) = self.bond_rules {
            // Left alone, history and all, as the forks skip the pair.
            if rules.skips(i, j, self.tag[j], rsq, radsum) {
                return None;
            }
        }
        *touch = 1;
        let dist = rsq.sqrt();
        let mut delta = radsum - dist;
        let n = if dist > 0.0 {
            d * (1.0 / dist)
        } else {
            DVec3::Z
        };
        let mj = rmass[j];
        // R* = r_i r_j/(r_i + r_j) and m* = m_i m_j/(m_i + m_j) with one division.
        let inv = 1.0 / (radsum * (mi + mj));
        let mut r_star = ri * rj * (mi + mj) * inv;
        let mut m_star = mi * mj * radsum * inv;
        if self.freeze != 0 {
            // A frozen particle counts as infinitely heavy: the other's mass (if both
            // are frozen, i's, as in LIGGGHTS; their forces are zeroed anyway).
            if self.mask[i] & self.freeze != 0 {
                m_star = mj;
            }
            if self.mask[j] & self.freeze != 0 {
                m_star = mi;
            }
        }
        let mut shape = None;
        let (mut ci, mut cj) = (ri - 0.5 * delta, rj - 0.5 * delta);
        if let Some((_, mc)) = self.mc {
            // The model's pair is ordered by tag; d runs from the first to the second.
            let (a, b) = if self.tag[i] < self.tag[j] {
                (i, j)
            } else {
                (j, i)
            };
            let Some(s) = mc.pair(
                (self.tag[a], ty[a], self.x[a], radius[a]),
                (self.tag[b], ty[b], self.x[b], radius[b]),
                dist,
            ) else {
                // Not touching once corrected: the history stays, as for any pair apart.
                *touch = 0;
                return None;
            };
            delta = s.delta;
            r_star = s.r_star;
            (ci, cj) = if a == i {
                s.levers
            } else {
                (s.levers.1, s.levers.0)
            };
            shape = Some((a, b, s));
        }
        let g = Geom {
            n,
            delta,
            dist,
            ri,
            rj,
            r_star,
            m_star,
            ci,
            cj,
            vr: v[i] - v[j],
            wi: omega[i],
            wj: omega[j],
            roll_scale: 1.0,
            inertia_i: (INERTIA_SPHERE + 1.0) * mi * ri * ri,
            inertia_j: (INERTIA_SPHERE + 1.0) * mj * rj * rj,
            dt,
            lq_i: if K::BRIDGE { self.lq[i] } else { 0.0 },
            lq_j: if K::BRIDGE { self.lq[j] } else { 0.0 },
            update,
        };
        let out = K::contact(&g, &coeff_row[ty[j] as usize - 1], flags, hist);
        if let (Some((store, _)), Some((a, b, s)), true) = (self.mc, shape, update) {
            let (xa, xb) = (self.x[a], self.x[b]);
            store.record_pair((self.tag[a], xa), (self.tag[b], xb), dist, &s, out.fn_total);
        }
        Some(out)
    }

    /// A pair that does not touch, with a liquid-bridge kernel: the contact's history is
    /// cleared, the bridge's kept; a bridge pulls (`Some`) or breaks (its liquid flux
    /// recorded for pair `k`).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn apart<K: ContactKernel>(
        &self,
        i: usize,
        j: usize,
        k: usize,
        coeff_row: &[PairCoeff],
        hist: &mut [f64],
        d: DVec3,
        rsq: f64,
    ) -> Option<ContactForce> {
        let (h_contact, h_bridge) = hist.split_at_mut(K::HIST - K::BRIDGE_HIST);
        if !h_contact.is_empty() {
            clear_history(h_contact);
        }
        if h_bridge.iter().all(|&h| h == 0.0) || !rsq.is_finite() {
            return None;
        }
        let s = Separated {
            d,
            r: rsq.sqrt(),
            ri: self.radius[i],
            rj: self.radius[j],
            vr: self.v[i] - self.v[j],
            wi: self.omega[i],
            wj: self.omega[j],
            lq_i: self.lq[i],
            lq_j: self.lq[j],
            dt: self.dt,
        };
        match K::separated(&s, &coeff_row[self.ty[j] as usize - 1], h_bridge) {
            Bridge::None => None,
            Bridge::Force(f) => Some(f),
            Bridge::Breaks { flux_i, flux_j } => {
                if let Some(b) = self.breaks {
                    b.push(BridgeBreak {
                        k: k as u32,
                        i: i as u32,
                        j: j as u32,
                        flux_i,
                        flux_j,
                    });
                }
                None
            }
        }
    }
    /// The whole pass on the calling thread, fused (no per-pair buffer): the serial pass
    /// whose sums phase 2 repeats, so its result is the two-phase pass's, bit for bit.
    /// Used when the pool has one thread. `hist` starts at the first history value of
    /// particle 0.
    fn serial<K: ContactKernel, const BOND: bool>(
        &self,
        hist: &mut [f64],
        touch: &mut [u8],
        f: &mut [DVec3],
        torque: &mut [DVec3],
    ) {
        let w = self.width;
        let near = self.near;
        let h0 = self.list_first[0] as usize;
        let mut empty: [f64; 0] = [];
        let mut no_touch = 0u8;
        for i in 0..self.nlocal {
            let coeff_row = self.table.row(self.ty[i]);
            let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
            let mut fi = DVec3::ZERO;
            let mut tqi = DVec3::ZERO;
            for (kk, (j, slot)) in near.pairs(s, e).enumerate() {
                let slot = slot - h0;
                let (hist, touch): (&mut [f64], &mut u8) = if w > 0 {
                    (&mut hist[slot * w..(slot + 1) * w], &mut touch[slot])
                } else {
                    (&mut empty, &mut no_touch)
                };
                let Some((_, out)) = self.eval::<K, BOND>(i, j, s + kk, coeff_row, hist, touch)
                else {
                    continue;
                };
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

/// The touch flags of pairs `a..b` (none when the model keeps no history).
fn touch_range(touch: &mut [u8], a: usize, b: usize) -> &mut [u8] {
    if touch.is_empty() {
        touch
    } else {
        &mut touch[a..b]
    }
}

/// The virial of each listed pair of the owned particles (rows `near`), from the force
/// phase 1 left in `res`: pairs out of contact have a zero force, whose virial changes
/// no sum. Apart from the passes, so that they are compiled once per kernel, not twice;
/// serial, as it runs only on the steps that need a virial.
fn pair_virials(near: Rows, nlocal: usize, x: &[DVec3], res: &[PairOut], rv: &mut [[f64; 6]]) {
    let k0 = near.first[0] as usize;
    for i in 0..nlocal {
        let (s, e) = (near.first[i] as usize, near.first[i + 1] as usize);
        for (kk, (j, _)) in near.pairs(s, e).enumerate() {
            let r = s - k0 + kk;
            rv[r] = virial_of(x[i] - x[j], res[r].f_i);
        }
    }
}

/// A contact's virial, ½ r ⊗ F (xx yy zz xy xz yz), as each of its two particles gets it.
#[inline(always)]
fn virial_of(d: DVec3, f: DVec3) -> [f64; 6] {
    [
        0.5 * (d.x * f.x),
        0.5 * (d.y * f.y),
        0.5 * (d.z * f.z),
        0.5 * (d.x * f.y),
        0.5 * (d.x * f.z),
        0.5 * (d.y * f.z),
    ]
}

/// Phase 2's read-only inputs.
struct Phase2<'a> {
    near: Rows<'a>,
    rfirst: &'a [u32],
    rk: &'a [u32],
    res: &'a [PairOut],
    own: &'a [OwnSum],
    rv: &'a [[f64; 6]],
    nlocal: usize,
    n: usize,
}

impl Phase2<'_> {
    /// Sums blocks `b0..b1`; the slices start at particle `b0 * BLOCK`.
    fn blocks<const VIRIAL: bool>(
        &self,
        b0: usize,
        b1: usize,
        f: &mut [DVec3],
        tq: &mut [DVec3],
        vir: &mut [[f64; 6]],
    ) {
        if b1 - b0 > 1 {
            let mid = (b0 + b1) / 2;
            let m = (mid - b0) * BLOCK;
            let (fa, fb) = f.split_at_mut(m);
            let (ta, tb) = tq.split_at_mut(m);
            let (va, vb) = if VIRIAL {
                vir.split_at_mut(m)
            } else {
                (&mut [][..], &mut [][..])
            };
            rayon::join(
                || self.blocks::<VIRIAL>(b0, mid, fa, ta, va),
                || self.blocks::<VIRIAL>(mid, b1, fb, tb, vb),
            );
        } else {
            self.block::<VIRIAL>(b0, f, tq, vir);
        }
    }

    /// One block of particles, owned or ghosts.
    #[inline(always)]
    fn block<const VIRIAL: bool>(
        &self,
        b: usize,
        f: &mut [DVec3],
        tq: &mut [DVec3],
        vir: &mut [[f64; 6]],
    ) {
        let (near, rfirst, rk) = (self.near, self.rfirst, self.rk);
        let (res, rv) = (self.res, self.rv);
        let lo = b * BLOCK;
        let hi = ((b + 1) * BLOCK).min(self.n);
        for q in lo..hi {
            let a = q - lo;
            let rs = &rk[rfirst[q] as usize..rfirst[q + 1] as usize];
            let (own_pairs, before, after) = if q < self.nlocal {
                let (s, e) = (near.first[q], near.first[q + 1]);
                let split = rs.partition_point(|&k| k < s);
                let (before, after) = rs.split_at(split);
                (s as usize..e as usize, before, after)
            } else {
                (0..0, rs, &[][..])
            };
            let (mut fq, mut tqq) = (f[a], tq[a]);
            for &k in before {
                let o = &res[k as usize];
                fq -= o.f_i;
                tqq += o.t_j;
            }
            if q < self.nlocal {
                let o = &self.own[q];
                fq += o.f;
                tqq += o.t;
            }
            for &k in after {
                let o = &res[k as usize];
                fq -= o.f_i;
                tqq += o.t_j;
            }
            f[a] = fq;
            tq[a] = tqq;
            if VIRIAL {
                let mut vq = vir[a];
                let mut add = |w: &[f64; 6]| {
                    for (x, y) in vq.iter_mut().zip(w) {
                        *x += y;
                    }
                };
                for &k in before {
                    add(&rv[k as usize]);
                }
                for w in &rv[own_pairs] {
                    add(w);
                }
                for &k in after {
                    add(&rv[k as usize]);
                }
                vir[a] = vq;
            }
        }
    }
}

impl PairPass<'_> {
    /// The pass with a kernel, which `serial` (one thread) or `leaf` (phase 1's blocks)
    /// runs; the contact virial goes into `virial` when it is asked for (then in two
    /// phases whatever the thread count: they give the serial pass's sums, bit for bit).
    /// Not generic over the kernel, so that the set-up and phase 2 are compiled once, not
    /// once per kernel.
    fn run(self, serial: &SerialFn, leaf: &BlockFn) {
        let PairPass {
            pair,
            p,
            list,
            dt,
            update,
            virial,
        } = self;
        let w = list.width;
        debug_assert_eq!(w, pair.model.history_width());
        let nlocal = p.nlocal();
        let n = p.len();
        let PairGran {
            model,
            table,
            near,
            res,
            own,
            res_virial,
            bond,
            bond_events,
            step,
            ts_warned: _,
            liquid,
            whole_fraction: _,
            multicontact,
            freeze,
            bond_rules,
        } = pair;
        let mc_state = multicontact.as_ref().map(|m| m.read());
        let create_now = update && bond.as_ref().is_some_and(|b| b.creates_at(*step));
        let random_id = match bond
            .as_ref()
            .and_then(|b| p.property(b.law().random_id_property()))
        {
            Some(id) if update => &p.props[id.0].data[..n],
            _ => &[][..],
        };
        // Two phases with several threads, or for the virial (phase 1's per-pair forces).
        let two_phase = rayon::current_num_threads() > 1 || virial.is_some();
        if two_phase && near.rfirst.len() != n + 1 {
            near.build_reverse(&list.partner, n);
        }
        let (p0, p1) = (list.first[0] as usize, list.first[nlocal] as usize);
        let (h0, h1) = (p0 * w, p1 * w);
        let ph1 = Phase1 {
            near: near.rows(&list.first, &list.partner),
            table,
            flags: model.kernel_flags(),
            list_first: &list.first,
            width: w,
            nlocal,
            x: &p.x,
            v: &p.v,
            omega: &p.omega,
            radius: &p.radius,
            rmass: if p.mass_of_contact.is_empty() {
                &p.rmass
            } else {
                &p.mass_of_contact
            },
            ty: &p.ty,
            dt,
            update,
            bond: bond.as_ref(),
            bond_flags: model.bond,
            create_now,
            random_id,
            step: *step,
            events: bond_events,
            lq: liquid
                .as_ref()
                .map_or(&[][..], |l| &p.props[l.content.0].data[..]),
            breaks: liquid.as_ref().map(|l| &l.breaks),
            mc: multicontact.as_deref().zip(mc_state.as_deref()),
            tag: &p.tag,
            mask: &p.mask,
            freeze: *freeze,
            bond_rules: BondRulesIn::of(*bond_rules, &p.props),
        };
        if !two_phase {
            let (f, torque) = (&mut p.f, &mut p.torque);
            let hist = &mut list.hist[h0..h1];
            let touch = touch_range(&mut list.touch, p0, p1);
            serial(&ph1, hist, touch, f, torque);
            return;
        }
        let npairs = ph1.near.partner.len();
        res.resize(npairs, PairOut::default());
        own.resize(nlocal, OwnSum::default());
        let nb_own = nlocal.div_ceil(BLOCK);
        if nb_own > 0 {
            let touch = touch_range(&mut list.touch, p0, p1);
            ph1.blocks(0, nb_own, res, &mut list.hist[h0..h1], touch, own, leaf);
        }
        if virial.is_some() {
            res_virial.resize(npairs, [0.0; 6]);
            pair_virials(ph1.near, nlocal, &p.x, res, res_virial);
        }
        let ph2 = Phase2 {
            near: ph1.near,
            rfirst: &near.rfirst,
            rk: &near.rk,
            res,
            own,
            rv: if virial.is_some() { res_virial } else { &[] },
            nlocal,
            n,
        };
        let nb_all = n.div_ceil(BLOCK);
        if nb_all > 0 {
            match virial {
                Some(v) => {
                    ph2.blocks::<true>(0, nb_all, &mut p.f[..n], &mut p.torque[..n], &mut v[..n])
                }
                None => ph2.blocks::<false>(0, nb_all, &mut p.f[..n], &mut p.torque[..n], &mut []),
            }
        }
    }
}

#[cfg(test)]
mod tests;
