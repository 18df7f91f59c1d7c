//! The binned search that builds the neighbor list (see [`super`]).

use glam::DVec3;

use rayon::prelude::*;

use crate::par::{parallel, CHUNK};
use crate::particles::Particles;

use super::above;
use super::NeighborList;

/// A particle in bin order: position and radius.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Slot {
    pub(super) x: DVec3,
    pub(super) r: f64,
}

/// Scratch buffers of the binned search (given back by the end of each build).
#[derive(Debug, Clone, Default)]
pub(super) struct Bins {
    /// Bin of each particle.
    pub(super) bin_of: Vec<u32>,
    /// Slot ranges of the locals per bin (`nbins + 1` offsets into `slots`).
    pub(super) lstart: Vec<u32>,
    /// Slot ranges of the ghosts per bin (offsets into `slots`, from `nlocal` on; empty
    /// without ghosts).
    pub(super) gstart: Vec<u32>,
    /// Particles in bin order: locals, then ghosts.
    pub(super) slots: Vec<Slot>,
    /// Particle index of each slot.
    pub(super) index: Vec<u32>,
    /// Stencil rows as bin ranges `b + r.0 .. b + r.1` around bin `b` of the padded
    /// grid: the half stencil (rows after the bin's own) and the full stencil.
    pub(super) half: Vec<(isize, isize)>,
    pub(super) full: Vec<(isize, isize)>,
    /// Bins within the stencil's box of a ghost bin (1) or not (0), and a scratch copy.
    pub(super) near: Vec<u8>,
    pub(super) near_tmp: Vec<u8>,
    /// Search buffers: one, or one per layer of bins in parallel.
    pub(super) parts: Vec<Part>,
}

impl Bins {
    /// Fills `list.first` and `list.partner` (which must be empty) with every pair closer
    /// than max(r_i + r_j, `bond_reach`) + skin, as described in the module docs.
    pub(super) fn search(
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
pub(super) struct Part {
    /// Pairs found, as (row, partner), before they are laid out in rows; only grows.
    pub(super) pairs: Vec<(u32, u32)>,
    pub(super) np: usize,
    /// Slot ranges of the current bin's half-stencil rows (locals) and full-stencil rows
    /// (ghosts).
    pub(super) lranges: Vec<(usize, usize)>,
    pub(super) granges: Vec<(usize, usize)>,
}

/// The read-only inputs of the search.
pub(super) struct Search<'a> {
    pub(super) lstart: &'a [u32],
    pub(super) gstart: &'a [u32],
    pub(super) slots: &'a [Slot],
    pub(super) index: &'a [u32],
    pub(super) half: &'a [(isize, isize)],
    pub(super) full: &'a [(isize, isize)],
    pub(super) near: &'a [u8],
    pub(super) ghosts: bool,
    pub(super) skin: f64,
    pub(super) reach: f64,
    pub(super) factor: f64,
    pub(super) sx: usize,
    pub(super) sy: usize,
    pub(super) nx: usize,
    pub(super) ny: usize,
    pub(super) px: usize,
    pub(super) py: usize,
    pub(super) m0: usize,
}

impl Search<'_> {
    /// Appends the pairs found from the bins of layer `cz` (of the padded grid) to
    /// `part`.
    pub(super) fn layer(&self, cz: usize, part: &mut Part) {
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
