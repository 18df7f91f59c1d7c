//! Binned half neighbor list with skin, the rebuild decision (`neigh_modify delay / every /
//! check`), and contact history that lives beside each listed pair and is carried across
//! rebuilds by particle tag.
//!
//! The list holds every pair closer than r_i + r_j + skin once: a local pair (i, j) with
//! j > i, and a pair of a local i with a ghost g when g lies "above" i (larger z, then y,
//! then x), which picks exactly one of the two periodic images of a pair across a
//! periodic face.

use glam::DVec3;

use crate::error::{check, Error, Result};
use crate::particles::{Particles, Tag};

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

/// Contact history saved by tag pair while the list is rebuilt. Each contact is stored in
/// both orientations, `(a, b)` and `(b, a)`, the second with its odd part negated, so a
/// new pair finds its history whichever particle lists it.
#[derive(Debug, Clone, Default)]
struct HistoryStore {
    keys: Vec<(Tag, Tag, u32)>,
    vals: Vec<f64>,
}

impl HistoryStore {
    fn clear(&mut self) {
        self.keys.clear();
        self.vals.clear();
    }

    /// Saves the history of `list`, whose rows are the first `list.first.len() - 1` local
    /// particles: owned particles appended since the build (which keep the indices of the
    /// others) have no row yet. Partners that no longer exist are skipped: dropped ghosts
    /// (beyond `tags`), and, once particles were appended (which drops the ghosts), every
    /// index past the original locals.
    fn save(&mut self, list: &NeighborList, tags: &[Tag], nlocal: usize) {
        self.clear();
        let w = list.width;
        let rows = list.first.len().saturating_sub(1);
        if w == 0 || rows > nlocal || list.hist.len() != list.partner.len() * w {
            return;
        }
        let valid = if rows < nlocal { rows } else { tags.len() };
        for i in 0..rows {
            for k in list.first[i] as usize..list.first[i + 1] as usize {
                let h = &list.hist[k * w..(k + 1) * w];
                if h.iter().all(|&v| v == 0.0) {
                    continue;
                }
                let j = list.partner[k] as usize;
                if j >= valid {
                    continue;
                }
                let n = (self.vals.len() / w) as u32;
                self.keys.push((tags[i], tags[j], n));
                self.vals.extend_from_slice(h);
                let n2 = n + 1;
                self.keys.push((tags[j], tags[i], n2));
                for (c, &v) in h.iter().enumerate() {
                    self.vals.push(if c < list.odd { -v } else { v });
                }
            }
        }
        self.keys.sort_unstable();
    }

    fn find(&self, a: Tag, b: Tag) -> Option<usize> {
        self.keys
            .binary_search_by(|&(x, y, _)| (x, y).cmp(&(a, b)))
            .ok()
            .map(|p| self.keys[p].2 as usize)
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
    last_build: u64,
    /// True from a build until the history is saved: the list's indices still refer to
    /// the particles (ghosts included) it was built for.
    live: bool,
    xhold: Vec<DVec3>,
    store: HistoryStore,
    bin_of: Vec<u32>,
    bin_start: Vec<u32>,
    bin_members: Vec<u32>,
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

    /// The neighbor cutoff for particles of largest radius `rmax`: 2·rmax + skin.
    pub fn cutoff_for(&self, rmax: f64) -> f64 {
        2.0 * rmax + self.settings.skin
    }

    /// LAMMPS' decision at step `step`: rebuild when at least `delay` steps have passed
    /// since the last build, the step is a multiple of `every` after it, and (with `check`)
    /// some local particle moved more than skin/2 since then.
    pub fn decide(&mut self, step: u64, x: &[DVec3]) -> bool {
        let ago = step.saturating_sub(self.last_build);
        let s = self.settings;
        if ago < s.delay || (s.every > 1 && ago % s.every != 0) {
            return false;
        }
        if !s.check {
            return true;
        }
        let moved = self.moved_too_far(x);
        if moved && ago == s.every.max(1).max(s.delay) {
            self.ndangerous += 1;
        }
        moved
    }

    /// True if any particle moved more than skin/2 since the last build (or the particle
    /// count changed).
    pub fn moved_too_far(&self, x: &[DVec3]) -> bool {
        if x.len() != self.xhold.len() {
            return true;
        }
        let lim = 0.25 * self.settings.skin * self.settings.skin;
        x.iter()
            .zip(&self.xhold)
            .any(|(a, b)| (*a - *b).length_squared() > lim)
    }

    /// Saves the contact history of the current list by tag pair. Call before particles
    /// are reordered, removed, migrated or re-imaged, or ghosts dropped. Only the first
    /// call after a build saves: later calls (ghosts may be gone by then, and the list's
    /// indices stale) keep what was saved, until the next [`Neighbor::build`] restores it.
    pub fn save_history(&mut self, p: &Particles) {
        if !self.live {
            return;
        }
        self.store.save(&self.list, &p.tag, p.nlocal());
        self.live = false;
    }

    /// Builds the list for the current particles (locals and ghosts) at step `step` and
    /// restores saved history by tag pair.
    pub fn build(&mut self, p: &Particles, step: u64) {
        let n = p.len();
        let nlocal = p.nlocal();
        let skin = self.settings.skin;
        let rmax = p.radius.iter().copied().fold(0.0, f64::max);
        let cut = self.cutoff_for(rmax);
        self.cutoff = cut;
        self.last_build = step;
        self.nbuilds += 1;
        self.live = true;
        self.xhold.clear();
        self.xhold.extend_from_slice(&p.x[..nlocal]);
        self.list.first.clear();
        self.list.partner.clear();
        self.list.hist.clear();
        if n == 0 {
            self.list.first.push(0);
            return;
        }
        // Bins of size >= cutoff over the bounding box of all particles.
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &x in &p.x {
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let ext = (hi - lo).max(DVec3::splat(1e-300));
        let nb = [0, 1, 2].map(|a| ((ext[a] / cut).floor() as usize).clamp(1, 1 << 20));
        // Keep the total bin count bounded for very sparse systems.
        let mut nb = nb;
        while nb[0] * nb[1] * nb[2] > 8 * n + 64 {
            for b in &mut nb {
                *b = (*b).div_ceil(2);
            }
        }
        let inv = DVec3::new(
            nb[0] as f64 / ext.x,
            nb[1] as f64 / ext.y,
            nb[2] as f64 / ext.z,
        );
        let nbins = nb[0] * nb[1] * nb[2];
        let coord = |x: DVec3| -> [usize; 3] {
            let c = (x - lo) * inv;
            [0, 1, 2].map(|a| (c[a].max(0.0) as usize).min(nb[a] - 1))
        };
        // Counting sort of all particles by bin.
        self.bin_of.clear();
        self.bin_start.clear();
        self.bin_start.resize(nbins + 1, 0);
        for &x in &p.x {
            let c = coord(x);
            let b = (c[2] * nb[1] + c[1]) * nb[0] + c[0];
            self.bin_of.push(b as u32);
            self.bin_start[b + 1] += 1;
        }
        for b in 0..nbins {
            self.bin_start[b + 1] += self.bin_start[b];
        }
        self.bin_members.clear();
        self.bin_members.resize(n, 0);
        {
            let mut fill: Vec<u32> = self.bin_start[..nbins].to_vec();
            for (i, &b) in self.bin_of.iter().enumerate() {
                self.bin_members[fill[b as usize] as usize] = i as u32;
                fill[b as usize] += 1;
            }
        }
        // Rows.
        self.list.first.push(0);
        for i in 0..nlocal {
            let xi = p.x[i];
            let ri = p.radius[i];
            let c = coord(xi);
            for dz in -1i64..=1 {
                let z = c[2] as i64 + dz;
                if z < 0 || z >= nb[2] as i64 {
                    continue;
                }
                for dy in -1i64..=1 {
                    let y = c[1] as i64 + dy;
                    if y < 0 || y >= nb[1] as i64 {
                        continue;
                    }
                    for dx in -1i64..=1 {
                        let x = c[0] as i64 + dx;
                        if x < 0 || x >= nb[0] as i64 {
                            continue;
                        }
                        let b = ((z as usize * nb[1] + y as usize) * nb[0]) + x as usize;
                        let (s, e) = (self.bin_start[b] as usize, self.bin_start[b + 1] as usize);
                        for &j in &self.bin_members[s..e] {
                            let j = j as usize;
                            if j < nlocal {
                                if j <= i {
                                    continue;
                                }
                            } else if !above(xi, p.x[j]) {
                                continue;
                            }
                            let rc = ri + p.radius[j] + skin;
                            if (p.x[j] - xi).length_squared() < rc * rc {
                                self.list.partner.push(j as u32);
                            }
                        }
                    }
                }
            }
            // Deterministic order within a row, independent of the binning.
            let s = *self.list.first.last().unwrap() as usize;
            self.list.partner[s..].sort_unstable();
            self.list.first.push(self.list.partner.len() as u32);
        }
        // History.
        let w = self.list.width;
        self.list.hist.resize(self.list.partner.len() * w, 0.0);
        if w > 0 && !self.store.keys.is_empty() {
            for i in 0..nlocal {
                for k in self.list.first[i] as usize..self.list.first[i + 1] as usize {
                    let j = self.list.partner[k] as usize;
                    if let Some(slot) = self.store.find(p.tag[i], p.tag[j]) {
                        self.list.hist[k * w..(k + 1) * w]
                            .copy_from_slice(&self.store.vals[slot * w..(slot + 1) * w]);
                    }
                }
            }
        }
        self.store.clear();
    }

    /// Positions at the last build (for tests and diagnostics).
    pub fn xhold(&self) -> &[DVec3] {
        &self.xhold
    }
}
