//! The near list of the pair pass: the pairs of the neighbor list within
//! r_i + r_j + `skin/10`, rebuilt from the neighbor list whenever that is rebuilt or any
//! particle has moved more than `skin/20` since (see [`super`]).

use glam::DVec3;
use rayon::prelude::*;

use crate::neighbor::Neighbor;
use crate::par::{parallel, parallel_light, CHUNK};
use crate::particles::Particles;

/// Fraction of the skin that the near list adds to r_i + r_j.
const NEAR_MARGIN: f64 = 0.1;

/// When at least this fraction of the listed pairs is near at a neighbor build, the
/// passes walk the neighbor list itself (see [`NearList::whole`]).
pub(super) const WHOLE_FRACTION: f64 = 0.9;

/// The pairs of the neighbor list that may be in contact before any particle moves more
/// than half the margin; `slot` points back into the neighbor list (history).
#[derive(Debug, Clone, Default)]
pub(super) struct NearList {
    /// Whether the near list is the whole neighbor list: at the neighbor build nearly
    /// every listed pair ([`WHOLE_FRACTION`]) was near, as in a packed bed whose skin is
    /// small beside the particles. A copy would then hold almost the same pairs again
    /// (with the positions and slots, about 52 bytes per particle at a million), so the
    /// passes walk the neighbor list ([`NearList::rows`]) and `first`, `partner`, `slot`
    /// and `xref` stay empty. The pairs beyond the margin are then tested each step and
    /// never touch; the list stays valid as long as the neighbor list does.
    pub(super) whole: bool,
    pub(super) first: Vec<u32>,
    pub(super) partner: Vec<u32>,
    pub(super) slot: Vec<u32>,
    /// Reverse CSR over all particles (ghosts too): `rk[rfirst[j]..rfirst[j + 1]]` are the
    /// near-list positions of the pairs whose partner is j, increasing. Only the parallel
    /// pass reads it, and it makes it ([`NearList::build_reverse`]) when it finds it empty:
    /// a one-thread run never holds it.
    pub(super) rfirst: Vec<u32>,
    pub(super) rk: Vec<u32>,
    pub(super) xref: Vec<DVec3>,
    /// `Neighbor::nbuilds` of the list it was made from (0: none yet).
    pub(super) built_for: u64,
    pub(super) margin: f64,
    /// `Neighbor::growth` when the near list was built.
    pub(super) growth_ref: f64,
    /// Centre distance below which a pair is listed whatever its radii (the bond reach).
    pub(super) reach: f64,
    /// Contact distance factor: pairs within (r_i + r_j)·factor are listed.
    pub(super) factor: f64,
}

/// The rows the passes walk: the near list's, or with [`NearList::whole`] the neighbor
/// list's (whose history slot is then the pair's own position).
#[derive(Debug, Clone, Copy)]
pub(super) struct Rows<'a> {
    pub(super) first: &'a [u32],
    pub(super) partner: &'a [u32],
    /// Each pair's position in the neighbor list (`None`: the same as in `partner`).
    pub(super) slot: Option<&'a [u32]>,
}

impl Rows<'_> {
    /// The history slot (neighbor-list position) of pair `k`.
    #[inline(always)]
    pub(super) fn slot(&self, k: usize) -> usize {
        match self.slot {
            Some(s) => s[k] as usize,
            None => k,
        }
    }

    /// The pairs of positions `s..e`: partner and history slot.
    #[inline(always)]
    pub(super) fn pairs(&self, s: usize, e: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.partner[s..e]
            .iter()
            .zip(s..e)
            .map(|(&j, k)| (j as usize, self.slot(k)))
    }
}

impl NearList {
    /// Whether there are rows for `nlocal` owned particles to walk (a near list made
    /// for them, or the whole neighbor list).
    pub(super) fn has_rows(&self, nlocal: usize) -> bool {
        self.whole || self.first.len() == nlocal + 1
    }

    /// The rows to walk, over the neighbor list whose rows are `first` and `partner`.
    pub(super) fn rows<'a>(&'a self, first: &'a [u32], partner: &'a [u32]) -> Rows<'a> {
        if self.whole {
            Rows {
                first,
                partner,
                slot: None,
            }
        } else {
            Rows {
                first: &self.first,
                partner: &self.partner,
                slot: Some(&self.slot),
            }
        }
    }

    /// Makes the reverse CSR (`rfirst`, `rk`) over `n` particles by counting sort
    /// (stable: increasing k within each partner), over the neighbor list's `partner`
    /// when the near list is [`NearList::whole`].
    pub(super) fn build_reverse(&mut self, list_partner: &[u32], n: usize) {
        let NearList {
            whole,
            partner,
            rfirst,
            rk,
            ..
        } = self;
        let partner = if *whole { list_partner } else { &partner[..] };
        rfirst.clear();
        rfirst.resize(n + 2, 0);
        for &j in partner {
            rfirst[j as usize + 2] += 1;
        }
        for a in 2..n + 2 {
            rfirst[a] += rfirst[a - 1];
        }
        rk.clear();
        rk.resize(partner.len(), 0);
        for (k, &j) in partner.iter().enumerate() {
            let c = &mut rfirst[j as usize + 1];
            rk[*c as usize] = k as u32;
            *c += 1;
        }
        rfirst.truncate(n + 1);
    }

    /// True when the near list must be rebuilt before the next force pass: the neighbor
    /// list was rebuilt, or some particle of the list (`x`: owned particles and ghosts)
    /// moved more than half the margin since. Ghosts are checked too, so that each rank
    /// decides for its own list without asking the others.
    pub(super) fn stale(&self, x: &[DVec3], neighbor: &Neighbor) -> bool {
        let near = self;
        if near.built_for != neighbor.nbuilds || near.factor != neighbor.factor() {
            return true;
        }
        if near.whole {
            return false;
        }
        if near.xref.len() != x.len() {
            return true;
        }
        // Radius growth since the build eats into the margin as in `Neighbor::moved_too_far`.
        let half = 0.5 * near.margin - (neighbor.growth - near.growth_ref);
        if half <= 0.0 {
            return true;
        }
        let lim = half * half;
        let far = |(a, b): (&DVec3, &DVec3)| (*a - *b).length_squared() > lim;
        if parallel_light(x.len()) {
            x.par_iter().zip(&near.xref).any(far)
        } else {
            x.iter().zip(&near.xref).any(far)
        }
    }

    /// Rebuilds the near list from the neighbor list (`reach`: the bond reach, listed
    /// whatever the radii; `whole_fraction`: see [`WHOLE_FRACTION`]).
    pub(super) fn build(
        &mut self,
        p: &Particles,
        neighbor: &Neighbor,
        reach: f64,
        whole_fraction: f64,
    ) {
        let near = self;
        let list = &neighbor.list;
        near.margin = NEAR_MARGIN * neighbor.settings.skin;
        near.growth_ref = neighbor.growth;
        near.reach = reach;
        near.factor = neighbor.factor();
        let reach = near.reach;
        let factor = near.factor;
        // A JKR neck holds beyond contact (see `Neighbor::neck`).
        let neck = neighbor.neck_len;
        let nlocal = p.nlocal();
        let margin = near.margin;
        let is_near = |i: usize, j: usize| {
            let rc = ((p.radius[i] + p.radius[j]) * factor).max(reach) + margin + neck;
            (p.x[j] - p.x[i]).length_squared() < rc * rc
        };
        // The first build for this neighbor list decides whether the near list is the
        // whole list (the later ones, after particles moved half the margin, keep a
        // near list).
        let fresh = near.built_for != neighbor.nbuilds;
        near.built_for = neighbor.nbuilds;
        near.whole = false;
        // The reverse CSR of the old list is stale: the parallel pass makes it anew.
        near.rfirst.clear();
        near.rk.clear();
        if fresh {
            let count = |lo: usize, hi: usize| {
                (lo..hi)
                    .map(|i| {
                        let ks = list.first[i] as usize..list.first[i + 1] as usize;
                        list.partner[ks]
                            .iter()
                            .filter(|&&j| is_near(i, j as usize))
                            .count()
                    })
                    .sum::<usize>()
            };
            let n_near = if parallel(nlocal) {
                (0..nlocal.div_ceil(CHUNK))
                    .into_par_iter()
                    .map(|c| count(c * CHUNK, ((c + 1) * CHUNK).min(nlocal)))
                    .sum()
            } else {
                count(0, nlocal)
            };
            let listed = list.first[nlocal] as usize - list.first[0] as usize;
            if n_near as f64 >= whole_fraction * listed as f64 {
                near.whole = true;
                near.first = Vec::new();
                near.partner = Vec::new();
                near.slot = Vec::new();
                near.xref = Vec::new();
                return;
            }
        }
        near.xref.clear();
        near.xref.extend_from_slice(&p.x);
        near.first.clear();
        near.partner.clear();
        near.slot.clear();
        near.first.push(0);
        // Rows lo..hi: the pairs within the margin, appended in list order, and the end
        // of each row (relative to the first pair of row lo).
        let rows = |lo: usize,
                    hi: usize,
                    partner: &mut Vec<u32>,
                    slot: &mut Vec<u32>,
                    ends: &mut Vec<u32>| {
            let base = partner.len();
            for i in lo..hi {
                for k in list.first[i] as usize..list.first[i + 1] as usize {
                    let j = list.partner[k] as usize;
                    if is_near(i, j) {
                        partner.push(j as u32);
                        slot.push(k as u32);
                    }
                }
                ends.push((partner.len() - base) as u32);
            }
        };
        if !parallel(nlocal) {
            let mut ends = std::mem::take(&mut near.first);
            rows(0, nlocal, &mut near.partner, &mut near.slot, &mut ends);
            near.first = ends;
        } else {
            // In parallel over chunks of rows, joined in chunk order: the same list.
            let parts: Vec<(Vec<u32>, Vec<u32>, Vec<u32>)> = (0..nlocal.div_ceil(CHUNK))
                .into_par_iter()
                .map(|c| {
                    let (lo, hi) = (c * CHUNK, ((c + 1) * CHUNK).min(nlocal));
                    let mut part = (Vec::new(), Vec::new(), Vec::with_capacity(hi - lo));
                    rows(lo, hi, &mut part.0, &mut part.1, &mut part.2);
                    part
                })
                .collect();
            for (partner, slot, ends) in parts {
                let base = near.partner.len() as u32;
                near.first.extend(ends.iter().map(|e| base + e));
                near.partner.extend_from_slice(&partner);
                near.slot.extend_from_slice(&slot);
            }
        }
    }
}
