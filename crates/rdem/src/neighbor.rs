//! Binned half neighbor list with skin, the rebuild decision (`neigh_modify delay / every /
//! check`), and contact history that lives beside each listed pair and is carried across
//! rebuilds by particle tag.
//!
//! The list holds every pair closer than max((r_i + r_j)·f, reach) + skin once (the reach
//! is the longest bond with `cohesion bond`, else 0; f is the contact distance factor,
//! 1.1·maxSeparationDistanceRatio with liquid bridges, else 1): a local pair (i, j) with
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

use rayon::prelude::*;

mod hold;

use crate::comm::Carried;
use crate::error::{check, Error, Result};
use crate::par::{parallel, CHUNK};
use crate::particles::{Particles, Tag, REMOTE_GHOST};

/// `neighbor` and `neigh_modify` settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NeighborSettings {
    /// Skin distance added to r_i + r_j.
    pub skin: f64,
    /// Never rebuild until this many steps after the last build.
    pub delay: u64,
    /// Consider rebuilding only every this many steps.
    pub every: u64,
    /// Rebuild only if some particle moved more than skin/2 (`check yes`).
    pub check: bool,
}

impl Default for NeighborSettings {
    /// LIGGGHTS defaults: `delay 10 every 1 check yes`; the skin must be set by the user
    /// (0.001 here as a placeholder for SI granular runs).
    fn default() -> Self {
        Self {
            skin: 0.001,
            delay: 10,
            every: 1,
            check: true,
        }
    }
}

impl NeighborSettings {
    /// Checks the settings as LIGGGHTS does for `neighbor` and `neigh_modify`: the skin
    /// must be finite and >= 0 (a NaN skin would silently list no pair at all, a negative
    /// one would miss contacts), `every` at least 1, and `delay` 0 or a multiple of
    /// `every`.
    pub fn validate(&self) -> Result<()> {
        check("neighbor skin", self.skin, self.skin >= 0.0, "must be >= 0")?;
        if self.every == 0 {
            return Err(Error::InvalidParameter {
                what: "neigh_modify every",
                value: 0.0,
                reason: "must be >= 1",
            });
        }
        if self.delay > 0 && self.delay % self.every != 0 {
            return Err(Error::Invalid {
                what: "neigh_modify delay",
                reason: format!(
                    "{} must be 0 or a multiple of every ({})",
                    self.delay, self.every
                ),
            });
        }
        Ok(())
    }
}

/// Pairs that `neigh_modify exclude` leaves out of the neighbor list, so that they never
/// interact (LAMMPS' and LIGGGHTS' exclusion lists): by type pair and by group pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Exclusions {
    /// `exclude type M N`: a pair of types M and N (either way round).
    pub types: Vec<(u32, u32)>,
    /// `exclude group G1 G2` as group bit masks: one particle in G1, the other in G2.
    pub groups: Vec<(u32, u32)>,
    /// Pairs whose values of this per-particle property are equal and not zero: the
    /// spheres of one rigid clump ([`crate::multisphere`]; LIGGGHTS' `fix multisphere`
    /// excludes them so).
    pub same_body: Option<crate::particles::PropId>,
}

impl Exclusions {
    /// True when nothing is excluded.
    pub fn is_empty(&self) -> bool {
        self.types.is_empty() && self.groups.is_empty() && self.same_body.is_none()
    }

    /// True when the pair (i, j) is excluded.
    pub fn excludes(&self, p: &Particles, i: usize, j: usize) -> bool {
        if let Some(id) = self.same_body {
            let b = &p.props[id.0].data;
            if b[i] != 0.0 && b[i] == b[j] {
                return true;
            }
        }
        let (ti, tj) = (p.ty[i], p.ty[j]);
        let (mi, mj) = (p.mask[i], p.mask[j]);
        self.types
            .iter()
            .any(|&(a, b)| (ti == a && tj == b) || (ti == b && tj == a))
            || self
                .groups
                .iter()
                .any(|&(a, b)| (mi & a != 0 && mj & b != 0) || (mi & b != 0 && mj & a != 0))
    }
}

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

/// Marks "no row" in the history store's tag map and pair selection.
const NONE: u32 = u32::MAX;

/// `dst.copy_from_slice(src)` for the few values of one pair's history, element by
/// element: a call to `memcpy` per pair would cost more than the copy.
#[inline(always)]
#[allow(clippy::manual_memcpy)]
fn copy_small(dst: &mut [f64], src: &[f64]) {
    assert_eq!(dst.len(), src.len());
    for c in 0..dst.len() {
        dst[c] = src[c];
    }
}

/// Contact history saved while the list is rebuilt, in compressed rows per local particle
/// of the old list: row `r` (old local `r`, tag `tags[r]`) holds `(partner tag, history)`
/// for every contact of that particle with non-zero history, whichever particle listed it
/// — as listed in the row of i, and with the odd part negated in the row of j's owner (j
/// itself, or the local that a serial periodic ghost copies). A ghost whose owner is not
/// local (an MPI ghost) keeps only i's side.
#[derive(Debug, Clone, Default)]
struct HistoryStore {
    /// Tags of the old local particles, one per row.
    tags: Vec<Tag>,
    /// Row offsets into `partner` and `vals`, `tags.len() + 1` entries (empty when nothing
    /// is stored).
    start: Vec<u32>,
    /// Partner tag of each stored contact.
    partner: Vec<Tag>,
    /// History of each stored contact, `width` values each, then one entry of zeros
    /// (values beyond it are stale).
    vals: Vec<f64>,
    /// History values per contact.
    width: usize,
    /// Largest tag in `tags`.
    max_tag: Tag,
    /// Scratch: the contacts to store, as (list slot, row of i); only grows.
    sel: Vec<(u32, u32)>,
    /// Scratch: the row of j's owner (or NONE) for each selected contact.
    owner: Vec<u32>,
    /// Scratch: fill cursors per row.
    fill: Vec<u32>,
    /// Scratch: tag -> old row, dense (indexed by tag) when the tags are compact enough.
    dense: Vec<u32>,
    /// Scratch: (tag, old row) sorted by tag, when they are not.
    sorted: Vec<(Tag, u32)>,
    /// Mirror entries for contacts with a ghost of another rank, per owner rank: (tag of
    /// the ghost, tag of the local, history with its odd part negated), flattened; sent to
    /// the owner by [`Neighbor::take_remote`] and stored there by
    /// [`Neighbor::append_history`].
    remote: Vec<Vec<f64>>,
    /// Entries received with migrating particles, flattened as in `remote`.
    pending: Vec<f64>,
    /// (tag, row) sorted by tag, for the rows that migrating particles take along; valid
    /// while `by_tag_fresh`.
    by_tag: Vec<(Tag, u32)>,
    by_tag_fresh: bool,
}

impl HistoryStore {
    /// Empties the store and gives its buffers back (all but the entries still to be
    /// sent or stored: `remote`, `pending`). They are not kept for the next build: at a
    /// million particles in contact they hold about 100 MB that would otherwise stay
    /// resident between builds and add to the peak of the next one.
    fn clear(&mut self) {
        let remote = std::mem::take(&mut self.remote);
        let pending = std::mem::take(&mut self.pending);
        *self = Self {
            remote,
            pending,
            ..Self::default()
        };
    }

    fn is_empty(&self) -> bool {
        self.partner.is_empty()
    }

    /// Saves the history of `list`, whose rows are the first `list.first.len() - 1` local
    /// particles: owned particles appended since the build (which keep the indices of the
    /// others) have no row yet. Partners that no longer exist are skipped: dropped ghosts
    /// (beyond `tags`), and, once particles were appended (which drops the ghosts), every
    /// index past the original locals.
    fn save(&mut self, list: &NeighborList, tags: &[Tag], ghost_origin: &[usize], nlocal: usize) {
        self.clear();
        let w = list.width;
        let rows = list.first.len().saturating_sub(1);
        if w == 0 || rows > nlocal || list.hist.len() != list.partner.len() * w {
            return;
        }
        let valid = if rows < nlocal { rows } else { tags.len() };
        // Pass 1: select the contacts with non-zero history (written unconditionally,
        // kept by advancing the end: no unpredictable branch). `sel` only grows.
        let npairs = list.partner.len();
        if self.sel.len() < npairs {
            self.sel.resize(npairs, (0, 0));
        }
        let mut ns = 0;
        for i in 0..rows {
            for k in list.first[i] as usize..list.first[i + 1] as usize {
                // Zero when every value is +0 or -0 (a NaN counts as non-zero, as v != 0.0).
                let bits = list.hist[k * w..(k + 1) * w]
                    .iter()
                    .fold(0u64, |a, v| a | (v.to_bits() << 1));
                let keep = (bits != 0) & ((list.partner[k] as usize) < valid);
                self.sel[ns] = (k as u32, i as u32);
                ns += keep as usize;
            }
        }
        if ns == 0 {
            return;
        }
        let sel = &self.sel[..ns];
        // Pass 2: the row of j's owner, and the number of entries per row.
        self.start.resize(rows + 1, 0);
        self.owner.clear();
        for &(k, i) in sel {
            let j = list.partner[k as usize] as usize;
            let owner = if j < rows {
                j as u32
            } else {
                // A ghost (`rows` is `nlocal` here: with fewer rows, no partner is
                // past them): its owner's row, if the owner is one of the old locals.
                match ghost_origin.get(j - rows) {
                    Some(&o) if o < rows && tags[o] == tags[j] => o as u32,
                    Some(&o) if o >= REMOTE_GHOST => {
                        let rank = o - REMOTE_GHOST;
                        if self.remote.len() <= rank {
                            self.remote.resize(rank + 1, Vec::new());
                        }
                        let out = &mut self.remote[rank];
                        out.push(tags[j] as f64);
                        out.push(tags[i as usize] as f64);
                        let h = &list.hist[k as usize * w..(k as usize + 1) * w];
                        out.extend(mirrored(h, list.odd));
                        NONE
                    }
                    _ => NONE,
                }
            };
            self.owner.push(owner);
            self.start[i as usize + 1] += 1;
            if owner != NONE {
                self.start[owner as usize + 1] += 1;
            }
        }
        for r in 0..rows {
            self.start[r + 1] += self.start[r];
        }
        // Pass 3: fill the rows.
        let total = self.start[rows] as usize;
        self.partner.resize(total, 0);
        // One more entry, all zero, for pairs without saved history (see `restore`). The
        // others are all overwritten below, so the old values are not cleared first.
        self.vals.resize((total + 1) * w, 0.0);
        self.vals[total * w..].fill(0.0);
        self.fill.clear();
        self.fill.extend_from_slice(&self.start[..rows]);
        for (&(k, i), &owner) in sel.iter().zip(&self.owner) {
            let (k, i) = (k as usize, i as usize);
            let h = &list.hist[k * w..(k + 1) * w];
            let j = list.partner[k] as usize;
            let q = self.fill[i] as usize;
            self.fill[i] += 1;
            self.partner[q] = tags[j];
            copy_small(&mut self.vals[q * w..(q + 1) * w], h);
            if owner != NONE {
                let q = self.fill[owner as usize] as usize;
                self.fill[owner as usize] += 1;
                self.partner[q] = tags[i];
                for (d, v) in self.vals[q * w..(q + 1) * w]
                    .iter_mut()
                    .zip(mirrored(h, list.odd))
                {
                    *d = v;
                }
            }
        }
        self.tags.extend_from_slice(&tags[..rows]);
        self.max_tag = self.tags.iter().copied().max().unwrap_or(0);
        self.width = w;
    }

    /// The row of tag `t` (migration), by a binary search in an index made once per set
    /// of rows.
    fn row_of(&mut self, t: Tag) -> Option<usize> {
        if !self.by_tag_fresh {
            self.by_tag.clear();
            self.by_tag
                .extend(self.tags.iter().enumerate().map(|(r, &t)| (t, r as u32)));
            self.by_tag.sort_unstable();
            self.by_tag_fresh = true;
        }
        let k = self.by_tag.binary_search_by_key(&t, |e| e.0).ok()?;
        Some(self.by_tag[k].1 as usize)
    }

    /// Adds entries `[row tag, partner tag, width values]...` to the rows of their tags
    /// (rows are created as needed; an entry for a pair the row already has is dropped).
    fn append(&mut self, entries: &[f64], width: usize) {
        let stride = 2 + width;
        if entries.is_empty() || width == 0 {
            return;
        }
        if self.is_empty() {
            self.width = width;
        } else if self.width != width {
            return;
        }
        let w = width;
        // (row tag, partner tag, source): a source below `old` is an existing entry.
        let mut all: Vec<(Tag, Tag, usize)> = Vec::new();
        for (r, &t) in self.tags.iter().enumerate() {
            if self.start.is_empty() {
                break;
            }
            for q in self.start[r] as usize..self.start[r + 1] as usize {
                all.push((t, self.partner[q], q));
            }
        }
        let old = self.partner.len();
        for (e, c) in entries.chunks_exact(stride).enumerate() {
            all.push((c[0] as Tag, c[1] as Tag, old + e));
        }
        // Stable: existing entries before received ones of the same pair.
        all.sort_by_key(|&(t, pt, _)| (t, pt));
        all.dedup_by_key(|e| (e.0, e.1));
        let mut vals = Vec::with_capacity((all.len() + 1) * w);
        let (mut tags, mut start, mut partner) = (Vec::new(), vec![0u32], Vec::new());
        for &(t, pt, src) in &all {
            if tags.last() != Some(&t) {
                if !tags.is_empty() {
                    start.push(partner.len() as u32);
                }
                tags.push(t);
            }
            partner.push(pt);
            if src < old {
                vals.extend_from_slice(&self.vals[src * w..(src + 1) * w]);
            } else {
                let c = (src - old) * stride + 2;
                vals.extend_from_slice(&entries[c..c + w]);
            }
        }
        start.push(partner.len() as u32);
        vals.extend(std::iter::repeat_n(0.0, w));
        self.max_tag = tags.iter().copied().max().unwrap_or(0);
        self.by_tag_fresh = false;
        self.tags = tags;
        self.start = start;
        self.partner = partner;
        self.vals = vals;
    }

    /// Copies the saved history into `list` (freshly built for particles with tags `tags`,
    /// history zeroed): pair (i, j) gets the entry of tag j in the old row of tag i.
    fn restore(&mut self, list: &mut NeighborList, tags: &[Tag], nlocal: usize) {
        let w = list.width;
        if self.is_empty() || w == 0 || w != self.width {
            return;
        }
        let rows = self.tags.len();
        let dense = self.max_tag <= 4 * rows as Tag + 1024;
        if dense {
            self.dense.clear();
            self.dense.resize(self.max_tag as usize + 1, NONE);
            for (r, &t) in self.tags.iter().enumerate() {
                self.dense[t as usize] = r as u32;
            }
        } else {
            self.sorted.clear();
            self.sorted
                .extend(self.tags.iter().enumerate().map(|(r, &t)| (t, r as u32)));
            self.sorted.sort_unstable();
        }
        for i in 0..nlocal {
            let t = tags[i];
            let r = if dense {
                match self.dense.get(t as usize) {
                    Some(&r) if r != NONE => r as usize,
                    _ => continue,
                }
            } else {
                match self.sorted.binary_search_by_key(&t, |e| e.0) {
                    Ok(p) => self.sorted[p].1 as usize,
                    Err(_) => continue,
                }
            };
            let (s, e) = (self.start[r] as usize, self.start[r + 1] as usize);
            if s == e {
                continue;
            }
            // Without a branch on the outcome: the first entry of tag j, or the zero entry
            // after the last row when there is none (the history is zero already).
            let old = &self.partner[s..e];
            let zero = self.partner.len();
            for k in list.first[i] as usize..list.first[i + 1] as usize {
                let tj = tags[list.partner[k] as usize];
                let mut q = zero;
                for (c, &x) in old.iter().enumerate().rev() {
                    q = if x == tj { s + c } else { q };
                }
                copy_small(
                    &mut list.hist[k * w..(k + 1) * w],
                    &self.vals[q * w..(q + 1) * w],
                );
            }
        }
    }
}

/// A particle in bin order: position and radius.
#[derive(Debug, Clone, Copy, Default)]
struct Slot {
    x: DVec3,
    r: f64,
}

/// Scratch buffers of the binned search (given back by the end of each build).
#[derive(Debug, Clone, Default)]
struct Bins {
    /// Bin of each particle.
    bin_of: Vec<u32>,
    /// Slot ranges of the locals per bin (`nbins + 1` offsets into `slots`).
    lstart: Vec<u32>,
    /// Slot ranges of the ghosts per bin (offsets into `slots`, from `nlocal` on; empty
    /// without ghosts).
    gstart: Vec<u32>,
    /// Particles in bin order: locals, then ghosts.
    slots: Vec<Slot>,
    /// Particle index of each slot.
    index: Vec<u32>,
    /// Stencil rows as bin ranges `b + r.0 .. b + r.1` around bin `b` of the padded
    /// grid: the half stencil (rows after the bin's own) and the full stencil.
    half: Vec<(isize, isize)>,
    full: Vec<(isize, isize)>,
    /// Bins within the stencil's box of a ghost bin (1) or not (0), and a scratch copy.
    near: Vec<u8>,
    near_tmp: Vec<u8>,
    /// Search buffers: one, or one per layer of bins in parallel.
    parts: Vec<Part>,
}

impl Bins {
    /// Fills `list.first` and `list.partner` (which must be empty) with every pair closer
    /// than max(r_i + r_j, `bond_reach`) + skin, as described in the module docs.
    fn search(
        &mut self,
        p: &Particles,
        cut: f64,
        skin: f64,
        bond_reach: f64,
        factor: f64,
        list: &mut NeighborList,
    ) {
        let n = p.len();
        let nlocal = p.nlocal();
        // Bins of at least cut/2 over the bounding box of all particles.
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &x in &p.x {
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let ext = (hi - lo).max(DVec3::splat(1e-300));
        let size = 0.5 * cut;
        let mut nb = [0, 1, 2].map(|a| ((ext[a] / size).floor() as usize).clamp(1, 1 << 20));
        // Keep the total bin count bounded for very sparse systems (the padding below adds
        // at most three bins on each side of an axis).
        while nb[0] * nb[1] * nb[2] > 8 * n + 64 {
            for b in &mut nb {
                *b = (*b).div_ceil(2);
            }
        }
        let [nx, ny, nz] = nb;
        let inv = DVec3::new(nx as f64 / ext.x, ny as f64 / ext.y, nz as f64 / ext.z);

        // Stencil: rows (dy, dz) of bins, each with the largest |dx| whose bins' nearest
        // points are closer than the cutoff. A bin index may be off by the round-off of
        // (x - lo) * inv, a few ulps of the extent, so the gaps between bins are taken
        // 1e-12 of the extent smaller, and the cutoff 1e-12 larger: no pair at the cutoff
        // is missed at a bin face (extra candidates fail the exact distance test).
        let width = DVec3::new(ext.x / nx as f64, ext.y / ny as f64, ext.z / nz as f64);
        let reach = cut * (1.0 + 1e-12);
        let reach2 = reach * reach;
        let margin = 2e-12 * ext;
        // Bins beyond the grid are never needed (an infinite width gives 0).
        let span = |a: usize| (((reach + margin[a]) / width[a]).ceil() as usize).min(nb[a] - 1);
        let (sx, sy, sz) = (span(0), span(1), span(2));
        // The grid is padded with `s` empty bins on each side, so that every stencil row
        // of an inner bin is a contiguous range of bins inside the padded grid.
        let (px, py, pz) = (nx + 2 * sx, ny + 2 * sy, nz + 2 * sz);
        let nbins = px * py * pz;
        // Gap between a bin and the bin `d` further along axis `a`.
        let gap = |d: isize, a: usize| {
            if d.abs() <= 1 {
                0.0
            } else {
                ((d.abs() - 1) as f64 * width[a] - margin[a]).max(0.0)
            }
        };
        self.half.clear();
        self.full.clear();
        let mut m0 = 0;
        for dz in -(sz as isize)..=sz as isize {
            for dy in -(sy as isize)..=sy as isize {
                let dyz2 = gap(dy, 1).powi(2) + gap(dz, 2).powi(2);
                if dyz2 >= reach2 {
                    continue;
                }
                let mut m = sx as isize;
                while m > 0 && gap(m, 0).powi(2) + dyz2 >= reach2 {
                    m -= 1;
                }
                let off = (dz * py as isize + dy) * px as isize;
                let row = (off - m, off + m + 1);
                self.full.push(row);
                if dz > 0 || (dz == 0 && dy > 0) {
                    self.half.push(row);
                } else if dz == 0 && dy == 0 {
                    m0 = m as usize;
                }
            }
        }

        // Counting sort into bins: locals in slots 0..nlocal, ghosts in nlocal..n, each
        // in index order within a bin. Without ghosts there are no ghost bins (at a
        // million particles the bin arrays are about 20 MB each).
        let ghosts = n > nlocal;
        self.bin_of.clear();
        self.lstart.clear();
        self.lstart.resize(nbins + 1, 0);
        self.gstart.clear();
        if ghosts {
            self.gstart.resize(nbins + 1, 0);
        }
        for (i, &x) in p.x.iter().enumerate() {
            let c = (x - lo) * inv;
            let [cx, cy, cz] = [0, 1, 2].map(|a| (c[a].max(0.0) as usize).min(nb[a] - 1));
            let b = ((cz + sz) * py + cy + sy) * px + cx + sx;
            self.bin_of.push(b as u32);
            if i < nlocal {
                self.lstart[b + 1] += 1;
            } else {
                self.gstart[b + 1] += 1;
            }
        }
        for b in 0..nbins {
            self.lstart[b + 1] += self.lstart[b];
        }
        if ghosts {
            self.gstart[0] = nlocal as u32;
            for b in 0..nbins {
                self.gstart[b + 1] += self.gstart[b];
            }
        }
        self.slots.clear();
        self.slots.resize(n, Slot::default());
        self.index.clear();
        self.index.resize(n, 0);
        // Filled from the end of each bin backwards, the last particle first, with the
        // bin's end as its cursor (no cursor array): start[b + 1] then holds the start
        // of bin b, and the starts are shifted back into place after.
        let mut fill = |start: &mut Vec<u32>, range: std::ops::Range<usize>| {
            for i in range.clone().rev() {
                let b = self.bin_of[i] as usize;
                start[b + 1] -= 1;
                let s = start[b + 1] as usize;
                self.slots[s] = Slot {
                    x: p.x[i],
                    r: p.radius[i],
                };
                self.index[s] = i as u32;
            }
            let end = range.end as u32;
            start.copy_within(1..nbins + 1, 0);
            start[nbins] = end;
        };
        fill(&mut self.lstart, 0..nlocal);
        if ghosts {
            fill(&mut self.gstart, nlocal..n);
        }
        // The search reads the bins through the slots: each particle's bin is not needed
        // any more (4 bytes a particle off the build's peak).
        self.bin_of = Vec::new();

        // Bins within reach of a ghost: the ghost bins dilated by the stencil's box, one
        // axis at a time (rows of bins overlap at their ends, which only adds bins), so
        // that bins far from every ghost skip the ghost search.
        if ghosts {
            let (near, tmp) = (&mut self.near, &mut self.near_tmp);
            tmp.clear();
            tmp.extend((0..nbins).map(|b| {
                let (a, e) = (b.saturating_sub(sx), (b + sx + 1).min(nbins));
                u8::from(self.gstart[e] > self.gstart[a])
            }));
            for (stride, s) in [(px, sy), (px * py, sz)] {
                near.clear();
                near.extend_from_slice(tmp);
                for d in 1..=s {
                    let shift = d * stride;
                    if shift >= nbins {
                        break;
                    }
                    for (a, &c) in near[shift..].iter_mut().zip(&tmp[..nbins - shift]) {
                        *a |= c;
                    }
                    for (a, &c) in near[..nbins - shift].iter_mut().zip(&tmp[shift..]) {
                        *a |= c;
                    }
                }
                std::mem::swap(near, tmp);
            }
            std::mem::swap(near, tmp);
        }

        // Search, bin by bin, one layer of bins (cz) after the other: every candidate is
        // written to `pairs` as (row, partner) and kept (the end advanced) only if it is
        // closer than the cutoff, without a branch. Local pairs go to the row of the
        // lower index; a ghost pair to the local's row. In parallel, each layer has its
        // own buffer and the buffers are read in layer order: the pairs come in the
        // serial order whatever the thread count.
        let ctx = Search {
            lstart: &self.lstart,
            gstart: &self.gstart,
            slots: &self.slots,
            index: &self.index,
            half: &self.half,
            full: &self.full,
            near: &self.near,
            ghosts,
            skin,
            reach: bond_reach,
            factor,
            sx,
            sy,
            nx,
            ny,
            px,
            py,
            m0,
        };
        let parts = &mut self.parts;
        if !parallel(nlocal) {
            parts.truncate(1);
            parts.resize_with(1, Default::default);
            let part = &mut parts[0];
            part.np = 0;
            for cz in sz..sz + nz {
                ctx.layer(cz, part);
            }
        } else {
            parts.resize_with(nz.max(parts.len()), Default::default);
            parts.truncate(nz);
            parts.par_iter_mut().enumerate().for_each(|(l, part)| {
                part.np = 0;
                ctx.layer(sz + l, part);
            });
        }
        // All but the pairs found is given back before the list is laid out (the bins and
        // slots: about 60 bytes per particle at a million; the build's peak is then the
        // search, not the layout), and the pairs when this returns. Builds are rare, and
        // the scratch kept between them was a quarter of the resident memory at a
        // million particles.
        let parts = std::mem::take(&mut self.parts);
        *self = Bins::default();
        let pairs = parts.iter().flat_map(|part| &part.pairs[..part.np]);
        let np = parts.iter().map(|part| part.np).sum();

        // Lay the pairs out in rows: count, offsets, then fill in the order found.
        list.first.clear();
        list.first.resize(nlocal + 1, 0);
        for &(a, _) in pairs.clone() {
            list.first[a as usize + 1] += 1;
        }
        for i in 0..nlocal {
            list.first[i + 1] += list.first[i];
        }
        let mut cursor = list.first[..nlocal].to_vec();
        list.partner.clear();
        list.partner.resize(np, 0);
        for &(a, b) in pairs {
            let q = &mut cursor[a as usize];
            list.partner[*q as usize] = b;
            *q += 1;
        }
        // Partners in increasing index order: the force passes then walk the particle
        // arrays forwards (about 30 % faster on a settled bed than in bin order), and the
        // row does not depend on the binning (nor on the search order).
        let first = &list.first;
        // Rows lo..lo + CHUNK, which start at `rows`.
        let sort_rows = |lo: usize, rows: &mut [u32]| {
            let mut rest = rows;
            for i in lo..(lo + CHUNK).min(nlocal) {
                let (row, tail) = rest.split_at_mut((first[i + 1] - first[i]) as usize);
                row.sort_unstable();
                rest = tail;
            }
        };
        if !parallel(nlocal) {
            let mut rest = &mut list.partner[..];
            for lo in (0..nlocal).step_by(CHUNK) {
                let hi = (lo + CHUNK).min(nlocal);
                let (rows, tail) = rest.split_at_mut((first[hi] - first[lo]) as usize);
                sort_rows(lo, rows);
                rest = tail;
            }
        } else {
            let mut chunks = Vec::with_capacity(nlocal.div_ceil(CHUNK));
            let mut rest = &mut list.partner[..];
            for lo in (0..nlocal).step_by(CHUNK) {
                let hi = (lo + CHUNK).min(nlocal);
                let (rows, tail) = rest.split_at_mut((first[hi] - first[lo]) as usize);
                chunks.push((lo, rows));
                rest = tail;
            }
            chunks
                .into_par_iter()
                .for_each(|(lo, rows)| sort_rows(lo, rows));
        }
    }
}

/// One layer's search buffers: the pairs found (`pairs[..np]`) and the slot ranges of the
/// current bin's stencil rows.
#[derive(Debug, Clone, Default)]
struct Part {
    /// Pairs found, as (row, partner), before they are laid out in rows; only grows.
    pairs: Vec<(u32, u32)>,
    np: usize,
    /// Slot ranges of the current bin's half-stencil rows (locals) and full-stencil rows
    /// (ghosts).
    lranges: Vec<(usize, usize)>,
    granges: Vec<(usize, usize)>,
}

/// The read-only inputs of the search.
struct Search<'a> {
    lstart: &'a [u32],
    gstart: &'a [u32],
    slots: &'a [Slot],
    index: &'a [u32],
    half: &'a [(isize, isize)],
    full: &'a [(isize, isize)],
    near: &'a [u8],
    ghosts: bool,
    skin: f64,
    reach: f64,
    factor: f64,
    sx: usize,
    sy: usize,
    nx: usize,
    ny: usize,
    px: usize,
    py: usize,
    m0: usize,
}

impl Search<'_> {
    /// Appends the pairs found from the bins of layer `cz` (of the padded grid) to
    /// `part`.
    fn layer(&self, cz: usize, part: &mut Part) {
        let Search {
            lstart,
            gstart,
            slots,
            index,
            half,
            full,
            near,
            ghosts,
            skin,
            reach,
            factor,
            sx,
            sy,
            nx,
            ny,
            px,
            py,
            m0,
        } = *self;
        let Part {
            pairs,
            np,
            lranges,
            granges,
        } = part;
        let mut np = *np;
        for cy in sy..sy + ny {
            let base = (cz * py + cy) * px;
            for b in base + sx..base + sx + nx {
                let (ls, le) = (lstart[b] as usize, lstart[b + 1] as usize);
                if ls == le {
                    continue;
                }
                // Slot ranges of the stencil rows for this bin.
                let own_end = lstart[b + m0 + 1] as usize;
                lranges.clear();
                let mut lsum = 0;
                for &(r0, r1) in half.iter() {
                    let s = lstart[(b as isize + r0) as usize] as usize;
                    let e = lstart[(b as isize + r1) as usize] as usize;
                    if s < e {
                        lranges.push((s, e));
                        lsum += e - s;
                    }
                }
                granges.clear();
                let mut gsum = 0;
                if ghosts && near[b] != 0 {
                    for &(r0, r1) in full.iter() {
                        let s = gstart[(b as isize + r0) as usize] as usize;
                        let e = gstart[(b as isize + r1) as usize] as usize;
                        if s < e {
                            granges.push((s, e));
                            gsum += e - s;
                        }
                    }
                }
                for s in ls..le {
                    // Room for every candidate of this particle.
                    let need = np + (own_end - s - 1) + lsum + gsum;
                    if pairs.len() < need {
                        pairs.resize(need.max(2 * pairs.len()), (0, 0));
                    }
                    let buf = &mut pairs[..];
                    let Slot { x: xi, r: ri } = slots[s];
                    let i = index[s];
                    let mut local = |t: usize| {
                        let o = slots[t];
                        let rc = ((ri + o.r) * factor).max(reach) + skin;
                        let hit = (o.x - xi).length_squared() < rc * rc;
                        let j = index[t];
                        buf[np] = (i.min(j), i.max(j));
                        np += hit as usize;
                    };
                    // The rest of this bin and the bins after it in the same row.
                    for t in s + 1..own_end {
                        local(t);
                    }
                    for &(a, e) in lranges.iter() {
                        for t in a..e {
                            local(t);
                        }
                    }
                    for &(a, e) in granges.iter() {
                        for t in a..e {
                            let o = slots[t];
                            let rc = ((ri + o.r) * factor).max(reach) + skin;
                            let hit = above(xi, o.x) & ((o.x - xi).length_squared() < rc * rc);
                            buf[np] = (i, index[t]);
                            np += hit as usize;
                        }
                    }
                }
            }
        }
        part.np = np;
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
    /// Centre distance below which every pair is listed whatever its radii: the longest
    /// bond (`cohesion bond`), 0 without bonds.
    pub reach: f64,
    /// LIGGGHTS' contact distance factor: pairs are listed up to (r_i + r_j)·factor + skin
    /// (liquid bridges reach beyond contact; values below 1, the default 0 included,
    /// count as 1).
    pub contact_factor: f64,
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
        let ago = step.saturating_sub(self.last_build);
        let s = self.settings;
        if ago < s.delay || (s.every > 1 && ago % s.every != 0) {
            return false;
        }
        if !s.check {
            return true;
        }
        let moved = any(self.moved_too_far(x));
        if moved && ago == s.every.max(1).max(s.delay) {
            self.ndangerous += 1;
        }
        moved
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
        self.xhold
            .moved_beyond(x, 0.5 * self.settings.skin - self.growth)
    }

    /// Saves the contact history of the current list by tag pair (contacts whose history
    /// is all zero are not kept). Call before particles
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
        if n == 0 {
            self.list.first.push(0);
            return;
        }
        let factor = self.factor();
        // The search gives its scratch back (see its end).
        self.bins
            .search(p, cut, skin, self.reach, factor, &mut self.list);
        if !self.exclude.is_empty() {
            self.drop_excluded(p);
        }
        let w = self.list.width;
        self.list.hist.resize(self.list.partner.len() * w, 0.0);
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
        (2.0 * rmax * self.factor()).max(self.reach)
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
                    if h.iter().all(|&v| v == 0.0) {
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
