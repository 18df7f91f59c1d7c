//! Contact history saved while the neighbor list is rebuilt and carried to the new list
//! by tag (see [`super`]).

use crate::particles::{Tag, REMOTE_GHOST};

use super::mirrored;
use super::NeighborList;

/// Marks "no row" in the history store's tag map and pair selection.
pub(super) const NONE: u32 = u32::MAX;

/// `dst.copy_from_slice(src)` for the few values of one pair's history, element by
/// element: a call to `memcpy` per pair would cost more than the copy.
#[inline(always)]
#[allow(clippy::manual_memcpy)]
pub(super) fn copy_small(dst: &mut [f64], src: &[f64]) {
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
pub(super) struct HistoryStore {
    /// Tags of the old local particles, one per row.
    pub(super) tags: Vec<Tag>,
    /// Row offsets into `partner` and `vals`, `tags.len() + 1` entries (empty when nothing
    /// is stored).
    pub(super) start: Vec<u32>,
    /// Partner tag of each stored contact.
    pub(super) partner: Vec<Tag>,
    /// History of each stored contact, `width` values each, then one entry of zeros
    /// (values beyond it are stale).
    pub(super) vals: Vec<f64>,
    /// History values per contact.
    pub(super) width: usize,
    /// Largest tag in `tags`.
    pub(super) max_tag: Tag,
    /// Scratch: the contacts to store, as (list slot, row of i); only grows.
    pub(super) sel: Vec<(u32, u32)>,
    /// Scratch: the row of j's owner (or NONE) for each selected contact.
    pub(super) owner: Vec<u32>,
    /// Scratch: fill cursors per row.
    pub(super) fill: Vec<u32>,
    /// Scratch: tag -> old row, dense (indexed by tag) when the tags are compact enough.
    pub(super) dense: Vec<u32>,
    /// Scratch: (tag, old row) sorted by tag, when they are not.
    pub(super) sorted: Vec<(Tag, u32)>,
    /// Mirror entries for contacts with a ghost of another rank, per owner rank: (tag of
    /// the ghost, tag of the local, history with its odd part negated), flattened; sent to
    /// the owner by [`Neighbor::take_remote`] and stored there by
    /// [`Neighbor::append_history`].
    pub(super) remote: Vec<Vec<f64>>,
    /// Entries received with migrating particles, flattened as in `remote`.
    pub(super) pending: Vec<f64>,
    /// (tag, row) sorted by tag, for the rows that migrating particles take along; valid
    /// while `by_tag_fresh`.
    pub(super) by_tag: Vec<(Tag, u32)>,
    pub(super) by_tag_fresh: bool,
}

impl HistoryStore {
    /// Empties the store and gives its buffers back (all but the entries still to be
    /// sent or stored: `remote`, `pending`). They are not kept for the next build: at a
    /// million particles in contact they hold about 100 MB that would otherwise stay
    /// resident between builds and add to the peak of the next one.
    pub(super) fn clear(&mut self) {
        let remote = std::mem::take(&mut self.remote);
        let pending = std::mem::take(&mut self.pending);
        *self = Self {
            remote,
            pending,
            ..Self::default()
        };
    }

    /// Renames every tag the store holds (rows, partners, the entries still to be sent
    /// or stored) with `new`, which maps a removed particle's tag to 0 (no particle has
    /// it, so its entries are never restored).
    pub(super) fn renumber(&mut self, new: &dyn Fn(Tag) -> Tag) {
        for t in self.tags.iter_mut().chain(self.partner.iter_mut()) {
            *t = new(*t);
        }
        self.max_tag = self.tags.iter().copied().max().unwrap_or(0);
        self.by_tag_fresh = false;
        let rec = 2 + self.width;
        for buf in self
            .remote
            .iter_mut()
            .chain(std::iter::once(&mut self.pending))
        {
            for r in buf.chunks_exact_mut(rec) {
                r[0] = new(r[0] as Tag) as f64;
                r[1] = new(r[1] as Tag) as f64;
            }
        }
    }

    pub(super) fn is_empty(&self) -> bool {
        self.partner.is_empty()
    }

    /// Saves the history of `list`, whose rows are the first `list.first.len() - 1` local
    /// particles: owned particles appended since the build (which keep the indices of the
    /// others) have no row yet. Partners that no longer exist are skipped: dropped ghosts
    /// (beyond `tags`), and, once particles were appended (which drops the ghosts), every
    /// index past the original locals.
    pub(super) fn save(
        &mut self,
        list: &NeighborList,
        tags: &[Tag],
        ghost_origin: &[usize],
        nlocal: usize,
    ) {
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
                // A pair apart at the last force pass drops its history here (LIGGGHTS
                // keeps the histories of the pairs that touch when it rebuilds).
                let touching = list.touch.get(k).is_none_or(|&t| t != 0);
                let keep = (bits != 0) & ((list.partner[k] as usize) < valid) & touching;
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
    pub(super) fn row_of(&mut self, t: Tag) -> Option<usize> {
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
    pub(super) fn append(&mut self, entries: &[f64], width: usize) {
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
    pub(super) fn restore(&mut self, list: &mut NeighborList, tags: &[Tag], nlocal: usize) {
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
                if let Some(t) = list.touch.get_mut(k) {
                    *t = (q != zero) as u8;
                }
            }
        }
    }
}
