//! Binned half neighbor list with skin, the rebuild decision (`neigh_modify delay / every /
//! check`), and contact history that lives beside each listed pair and is carried across
//! rebuilds by particle tag.
//!
//! The list holds every pair closer than max((r_i + r_j)·f, reach) + skin once (the reach
//! is the longest bond with `cohesion bond`, else 0; f is the contact distance factor,
//! 1.1·maxSeparationDistanceRatio with liquid bridges, else 1; with `model jkr` the
//! longest neck is added to the skin, see [`Neighbor::neck`]): a local pair (i, j) with
//! j > i, and a pair of a local i with a ghost g when g lies "above" i (larger z, then y,
//! then x), which picks exactly one of the two periodic images of a pair across a
//! periodic face. The order of the partners within a row follows the bin traversal; it is
//! deterministic but not sorted. In a periodic box shorter than twice the cutoff the list
//! may hold several images of one partner (each image pair once, by the same rule); only
//! one of them can touch, and only it keeps the history (see
//! [`Neighbor::short_periodic`]).
//!
//! Binning (LAMMPS' default): bins of at least half the cutoff over the bounding box of
//! all particles, and a stencil of the bin offsets whose nearest points are closer than
//! the cutoff. Locals and ghosts are binned separately, and positions and radii are copied
//! in bin order, so the search reads contiguous memory. Each local–local pair is found
//! once, from the bin that comes first (or, within one bin, from the earlier particle)
//! with a half stencil, and stored in the row of the lower index, so that which particle
//! lists a pair does not depend on the binning. Locals in bins near a ghost search the
//! ghost bins with the full stencil and the "above" rule.
//!
//! History: at [`Neighbor::save_history`] every contact with non-zero history is stored
//! twice, in compressed rows per old local particle — in the row of i as (tag of j, h)
//! and in the row of j's owner as (tag of i, h with its odd part negated) — together with
//! the old tags. [`Neighbor::build`] maps each new local particle to its old row by tag
//! and finds each listed partner in that (short) row by a linear scan.

use glam::DVec3;

mod bins;
mod history;
mod hold;
mod settings;

use bins::Bins;
use history::HistoryStore;
pub use settings::{Exclusions, NeighborSettings};

use crate::comm::Carried;
use crate::particles::{Particles, Tag};

/// A half neighbor list in compressed rows: the partners of local particle `i` are
/// `partner[first[i]..first[i + 1]]`, and pair `k` owns `hist[k * width..(k + 1) * width]`.
#[derive(Debug, Clone, Default)]
pub struct NeighborList {
    /// Row offsets, `nlocal + 1` entries.
    pub first: Vec<u32>,
    /// Partner indices (local or ghost).
    pub partner: Vec<u32>,
    /// Contact history, `width` values per pair.
    pub hist: Vec<f64>,
    /// Per pair (with a history width above 0), 1 where the pair touched at the last
    /// force pass. A pair that stops touching keeps its history, as in LIGGGHTS 3.8,
    /// until the history is next saved ([`Neighbor::save_history`], before a build),
    /// which keeps only the pairs that touch; a pair that touches again before then
    /// goes on from it.
    pub touch: Vec<u8>,
    /// History values per pair.
    pub width: usize,
    /// Leading history values that change sign when the pair is seen from the other side.
    pub odd: usize,
}

impl NeighborList {
    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.partner.len()
    }
    /// True when no pairs are listed.
    pub fn is_empty(&self) -> bool {
        self.partner.is_empty()
    }
    /// Partners of local particle `i`.
    pub fn partners(&self, i: usize) -> &[u32] {
        &self.partner[self.first[i] as usize..self.first[i + 1] as usize]
    }
}

/// Neighbor list, its rebuild bookkeeping and scratch buffers.
#[derive(Debug, Clone, Default)]
pub struct Neighbor {
    /// Settings.
    pub settings: NeighborSettings,
    /// The current list.
    pub list: NeighborList,
    /// Largest r_i + r_j + skin at the last build.
    pub cutoff: f64,
    /// Number of builds so far.
    pub nbuilds: u64,
    /// "Dangerous" builds, counted as LAMMPS does: the distance check found a particle
    /// beyond skin/2 at the first step it was allowed to run (`ago == max(every, delay)`),
    /// so the list may already have been stale before (only with `check yes`).
    pub ndangerous: u64,
    /// Largest radius growth of any particle since the last build (`fix adapt`): it eats
    /// into the skin, so the distance check allows skin/2 − growth of motion.
    pub growth: f64,
    /// How far the Lees–Edwards images have slid since the last build
    /// ([`crate::shear::Shear::drift`]; 0 without shear): a pair across a y face closes
    /// by that much more than its particles moved, so it too eats into the skin.
    pub shear_drift: f64,
    /// Centre distance below which every pair is listed whatever its radii: the longest
    /// bond (`cohesion bond`), 0 without bonds.
    pub reach: f64,
    /// LIGGGHTS' contact distance factor: pairs are listed up to (r_i + r_j)·factor + skin
    /// (liquid bridges reach beyond contact; values below 1, the default 0 included,
    /// count as 1).
    pub contact_factor: f64,
    /// `model jkr`: a contact holds apart down to δ = −δ_c, and δ_c ≤ `neck`·R*^⅓
    /// ([`crate::contact::CoeffTable::neck_reach`]); pairs are listed that much farther,
    /// for the largest radius (0 without it).
    pub neck: f64,
    /// The neck's length added at the last build (`neck`·rmax^⅓).
    pub neck_len: f64,
    /// Pairs left out of the list (`neigh_modify exclude`); takes effect at the next build.
    pub exclude: Exclusions,
    /// Half the shortest periodic length that is below twice the cutoff, when there is
    /// one (set before each build). The list may then hold two images of one partner,
    /// and the history saved by tag would be handed to both: [`Neighbor::build`] keeps it
    /// only on pairs closer than this, the one image that can interact (the box is at
    /// least twice the largest contact distance, see
    /// [`crate::domain::Domain::check_periodic_contact`]).
    pub short_periodic: Option<f64>,
    last_build: u64,
    /// True from a build until the history is saved: the list's indices still refer to
    /// the particles (ghosts included) it was built for.
    live: bool,
    xhold: hold::Hold,
    store: HistoryStore,
    bins: Bins,
}

/// The saved history travels with a migrating particle: its row, as
/// `[n, (partner tag, values) × n]`.
impl Carried for Neighbor {
    fn pack(&mut self, tag: Tag, buf: &mut Vec<f64>) {
        let row = self.store.row_of(tag);
        let st = &self.store;
        let w = st.width;
        match row.filter(|_| !st.start.is_empty()) {
            Some(r) => {
                let (s, e) = (st.start[r] as usize, st.start[r + 1] as usize);
                buf.push((e - s) as f64);
                for q in s..e {
                    buf.push(st.partner[q] as f64);
                    buf.extend_from_slice(&st.vals[q * w..(q + 1) * w]);
                }
            }
            None => buf.push(0.0),
        }
    }

    fn unpack(&mut self, tag: Tag, buf: &[f64]) -> usize {
        let n = buf[0] as usize;
        let w = self.list.width;
        let mut k = 1;
        for _ in 0..n {
            self.store.pending.push(tag as f64);
            self.store.pending.extend_from_slice(&buf[k..k + 1 + w]);
            k += 1 + w;
        }
        k
    }
}

/// A pair's history as seen from its other particle: the odd (antisymmetric) part negated.
fn mirrored(h: &[f64], odd: usize) -> impl Iterator<Item = f64> + '_ {
    h.iter()
        .enumerate()
        .map(move |(c, &v)| if c < odd { -v } else { v })
}

/// True when ghost `b` lies above `a` in (z, y, x) order.
#[inline(always)]
fn above(a: DVec3, b: DVec3) -> bool {
    if b.z != a.z {
        b.z > a.z
    } else if b.y != a.y {
        b.y > a.y
    } else {
        b.x > a.x
    }
}

impl Neighbor {
    /// A neighbor manager with the given settings.
    pub fn new(settings: NeighborSettings) -> Self {
        Self {
            settings,
            ..Default::default()
        }
    }

    /// Sets the per-pair history layout (called when the contact model is chosen).
    pub fn set_history_layout(&mut self, width: usize, odd: usize) {
        if self.list.width != width || self.list.odd != odd {
            self.list.width = width;
            self.list.odd = odd;
            self.list.hist = vec![0.0; self.list.len() * width];
            self.list.touch = vec![0; if width > 0 { self.list.len() } else { 0 }];
            self.store.clear();
        }
    }

    /// The neighbor cutoff for particles of largest radius `rmax`: max(2·rmax·f, reach) +
    /// skin (f the contact distance factor).
    pub fn cutoff_for(&self, rmax: f64) -> f64 {
        self.contact_for(rmax) + self.settings.skin
    }

    /// The contact distance factor in use (at least 1).
    pub fn factor(&self) -> f64 {
        self.contact_factor.max(1.0)
    }

    /// LAMMPS' decision at step `step`: rebuild when at least `delay` steps have passed
    /// since the last build, the step is a multiple of `every` after it, and (with `check`)
    /// some particle moved more than skin/2 since then. `any` combines the local answer
    /// of the distance check over all ranks (the identity serially).
    pub fn decide(&mut self, step: u64, x: &[DVec3], any: impl Fn(bool) -> bool) -> bool {
        let (due, dangerous) = self.due(step, x, any);
        if dangerous {
            self.ndangerous += 1;
        }
        due
    }

    /// What [`Neighbor::decide`] would answer at `step`, and whether that build would be
    /// a dangerous one, without counting it.
    pub fn due(&self, step: u64, x: &[DVec3], any: impl Fn(bool) -> bool) -> (bool, bool) {
        let ago = step.saturating_sub(self.last_build);
        let s = self.settings;
        if ago < s.delay || (s.every > 1 && ago % s.every != 0) {
            return (false, false);
        }
        if !s.check {
            return (true, false);
        }
        let moved = any(self.moved_too_far(x));
        (moved, moved && ago == s.every.max(1).max(s.delay))
    }

    /// True if any particle may have moved more than skin/2 − [`Neighbor::growth`] since
    /// the last build (or the particle count changed). With r_i + r_j grown by at most
    /// 2·growth and each centre moved at most skin/2 − growth, no pair can close more than
    /// the skin. The positions at the build are held in single precision where the
    /// coordinates allow ([`hold`]): the allowance is then smaller by their rounding, at
    /// most 1/16 of skin/2.
    pub fn moved_too_far(&self, x: &[DVec3]) -> bool {
        if x.len() != self.xhold.len() {
            return true;
        }
        self.xhold.moved_beyond(
            x,
            0.5 * (self.settings.skin - self.shear_drift) - self.growth,
        )
    }

    /// Saves the contact history of the current list by tag pair (contacts whose history
    /// is all zero, or that did not touch at the last force pass, are not kept). Call before particles
    /// are reordered, removed, migrated or re-imaged, or ghosts dropped. Only the first
    /// call after a build saves: later calls (ghosts may be gone by then, and the list's
    /// indices stale) keep what was saved, until the next [`Neighbor::build`] restores it.
    pub fn save_history(&mut self, p: &Particles) {
        if !self.live {
            return;
        }
        self.store
            .save(&self.list, &p.tag, p.ghost_origins(), p.nlocal());
        self.live = false;
    }

    /// Renames the tags of the history saved by [`Neighbor::save_history`] with `new`
    /// (old tag to new; removed particles to 0), for particles renumbered between the
    /// save and the next build (`fix remove ... compress yes`).
    pub fn renumber_saved(&mut self, new: &dyn Fn(Tag) -> Tag) {
        self.store.renumber(new);
    }

    /// Takes the mirror entries of contacts with other ranks' ghosts saved by
    /// [`Neighbor::save_history`], one buffer per rank (`nranks` of them).
    pub fn take_remote(&mut self, nranks: usize) -> Vec<Vec<f64>> {
        let mut out = std::mem::take(&mut self.store.remote);
        out.resize(nranks, Vec::new());
        out
    }

    /// Stores history entries `[row tag, partner tag, values]...` received from other
    /// ranks (mirror entries, or the rows of particles that migrated here).
    pub fn append_history(&mut self, entries: &[f64]) {
        self.store.append(entries, self.list.width);
    }

    /// Stores the rows received with migrating particles ([`Carried::unpack`]).
    pub fn merge_carried(&mut self) {
        let pending = std::mem::take(&mut self.store.pending);
        self.append_history(&pending);
    }

    /// Builds the list for the current particles (locals and ghosts) at step `step` and
    /// restores the history saved by [`Neighbor::save_history`] by tag pair (pairs without
    /// saved history start at zero).
    pub fn build(&mut self, p: &Particles, step: u64) {
        let n = p.len();
        let nlocal = p.nlocal();
        let skin = self.settings.skin;
        let rmax = p.radius.iter().copied().fold(0.0, f64::max);
        let cut = self.cutoff_for(rmax);
        self.neck_len = self.neck_for(rmax);
        self.cutoff = cut;
        self.last_build = step;
        self.nbuilds += 1;
        self.growth = 0.0;
        self.live = true;
        self.xhold = hold::Hold::new(&p.x[..nlocal], skin);
        // The old list's buffers are given back before the search allocates its own
        // (its history is in the store by now): the peak of a build is then the new
        // list, the store and the search's scratch, not the old list as well.
        self.list.first = Vec::new();
        self.list.partner = Vec::new();
        self.list.hist = Vec::new();
        self.list.touch = Vec::new();
        if n == 0 {
            self.list.first.push(0);
            return;
        }
        let factor = self.factor();
        // The search gives its scratch back (see its end).
        self.bins.search(
            p,
            cut,
            skin + self.neck_len,
            self.reach,
            factor,
            &mut self.list,
        );
        if !self.exclude.is_empty() {
            self.drop_excluded(p);
        }
        let w = self.list.width;
        self.list.hist.resize(self.list.partner.len() * w, 0.0);
        if w > 0 {
            self.list.touch.resize(self.list.partner.len(), 0);
        }
        self.store.restore(&mut self.list, &p.tag, nlocal);
        self.store.clear();
        if let Some(half) = self.short_periodic {
            self.keep_history_of_near_images(p, half);
        }
    }

    /// In a periodic box shorter than twice the cutoff: clears the restored history of
    /// every pair at least `half` apart. The history is saved by tag pair, so every
    /// listed image of a partner receives it; only one image can interact (two images
    /// of one partner are a box length apart, at least twice the largest contact
    /// distance, so at most one lies within it). The others would keep a copy
    /// that the force pass never clears (it skips pairs beyond its near list) and that
    /// a bond or a liquid bridge would act on. A pair `half` or more apart cannot touch
    /// at the next force pass (positions do not change between a build and that pass),
    /// so clearing it changes nothing else.
    fn keep_history_of_near_images(&mut self, p: &Particles, half: f64) {
        let list = &mut self.list;
        let w = list.width;
        if w == 0 {
            return;
        }
        let lim = half * half;
        for i in 0..list.first.len() - 1 {
            for k in list.first[i] as usize..list.first[i + 1] as usize {
                let j = list.partner[k] as usize;
                if (p.x[j] - p.x[i]).length_squared() >= lim {
                    list.hist[k * w..(k + 1) * w].fill(0.0);
                }
            }
        }
    }

    /// Largest distance at which two particles of largest radius `rmax` interact: the
    /// cutoff without the skin, max(2·rmax·f, reach).
    pub fn contact_for(&self, rmax: f64) -> f64 {
        (2.0 * rmax * self.factor()).max(self.reach) + self.neck_for(rmax)
    }

    /// The longest JKR neck of particles of largest radius `rmax` (see [`Neighbor::neck`]).
    pub fn neck_for(&self, rmax: f64) -> f64 {
        self.neck * rmax.cbrt()
    }

    /// Removes the excluded pairs from the freshly searched list (before histories are
    /// attached), keeping the rows compressed.
    fn drop_excluded(&mut self, p: &Particles) {
        let list = &mut self.list;
        let nrows = list.first.len() - 1;
        let mut out = 0usize;
        for i in 0..nrows {
            let (start, end) = (list.first[i] as usize, list.first[i + 1] as usize);
            list.first[i] = out as u32;
            for k in start..end {
                let j = list.partner[k];
                if !self.exclude.excludes(p, i, j as usize) {
                    list.partner[out] = j;
                    out += 1;
                }
            }
        }
        list.first[nrows] = out as u32;
        list.partner.truncate(out);
    }

    /// Every contact with non-zero history, for a restart file: from the list while it
    /// is live (as listed, in the row of its first particle), else from the history saved
    /// since (which holds each contact from both sides).
    pub fn history_state(&self, p: &Particles) -> crate::restart::HistoryState {
        let (w, odd) = (self.list.width, self.list.odd);
        let mut entries = Vec::new();
        if w > 0 && self.live {
            let rows = self.list.first.len().saturating_sub(1);
            for i in 0..rows {
                for k in self.list.first[i] as usize..self.list.first[i + 1] as usize {
                    let h = &self.list.hist[k * w..(k + 1) * w];
                    // A pair apart at the last force pass is not written: the next
                    // build drops its history (see `NeighborList::touch`).
                    let apart = self.list.touch.get(k) == Some(&0);
                    if apart || h.iter().all(|&v| v == 0.0) {
                        continue;
                    }
                    entries.push(p.tag[i] as f64);
                    entries.push(p.tag[self.list.partner[k] as usize] as f64);
                    entries.extend_from_slice(h);
                }
            }
        } else if w > 0 && self.store.width == w && !self.store.start.is_empty() {
            let st = &self.store;
            for (r, &t) in st.tags.iter().enumerate() {
                for q in st.start[r] as usize..st.start[r + 1] as usize {
                    entries.push(t as f64);
                    entries.push(st.partner[q] as f64);
                    entries.extend_from_slice(&st.vals[q * w..(q + 1) * w]);
                }
            }
        }
        crate::restart::HistoryState {
            width: w,
            odd,
            entries,
        }
    }

    /// Positions at the last build (for tests and diagnostics), as held: in single
    /// precision where that costs the rebuild check little (see [`hold`]).
    pub fn xhold(&self) -> Vec<DVec3> {
        self.xhold.positions()
    }

    /// Bytes held by the positions at the last build.
    pub fn xhold_bytes(&self) -> usize {
        self.xhold.memory_bytes()
    }
}
