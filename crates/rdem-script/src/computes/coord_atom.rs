//! `compute ID group coord/atom cutoff [mix yes|no | typeN ...]`: for each particle of
//! the group, the number of particles (of any group) whose centre is closer than
//! `cutoff`; particles outside the group get 0.
//!
//! As LIGGGHTS 3.8 (measured, see tests/coord_atom.rs):
//! - no type keyword (or `*`): one count of all neighbours, a per-atom vector; one
//!   `typeN` (a type or an asterisk range `*`, `*n`, `n*`, `m*n`): a vector counting
//!   those types; several: a per-atom array of one column per keyword;
//! - `mix yes` (only as the two words after the cutoff, as LIGGGHTS parses them): a
//!   vector counting the neighbours whose type differs from the particle's;
//! - the neighbours are those of LIGGGHTS' neighbor list: a pair of types (a, b) is
//!   counted only while its centres are within rmax_a + rmax_b + skin, rmax_t the largest
//!   radius of type t (LIGGGHTS reads them at the run's set-up, rdem at each evaluation
//!   from the current particles of all ranks); with one radius per type this is no limit
//!   for any cutoff LIGGGHTS accepts;
//! - a cutoff longer than the neighbor cutoff 2 rmax + skin is an error ("cutoff is
//!   longer than neigh cutoff");
//! - ghost particles count: periodic images and particles of other ranks, one per image.

use crate::error::Error;
use rdem::World;

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "coord/atom",
    parse,
    "`cutoff`, then `mix yes\\|no` or type ranges (`2`, `*`, `*n`, `n*`, `m*n`; several: one column each): neighbours closer than the cutoff, per particle",
)
.notes("as LIGGGHTS 3.8, a pair of types a, b counts only within rmax_a + rmax_b + skin (the reach of its neighbor list), and a cutoff beyond 2 rmax + skin is an error; rdem takes the radii of the current particles at each evaluation (LIGGGHTS at the run's set-up, with the insertion templates')");

/// A defined `compute coord/atom`.
#[derive(Debug)]
pub struct CoordAtom {
    /// Counting distance.
    pub cutoff: f64,
    /// Inclusive 1-based type ranges, one per column.
    pub ranges: Vec<(u32, u32)>,
    /// `mix yes`: count only neighbours of another type.
    pub mix: bool,
}

/// Reads a type or an asterisk range over `1..=n`, as LAMMPS' `bounds`.
fn type_range(a: &mut Args, n: usize) -> CmdResult<(u32, u32)> {
    let w = a.word("atom type or range")?;
    let n = n as u32;
    let num = |s: &str| s.parse::<u32>().ok();
    let range = match w.split_once('*') {
        None => num(w).map(|t| (t, t)),
        Some((lo, hi)) => {
            let lo = if lo.is_empty() { Some(1) } else { num(lo) };
            let hi = if hi.is_empty() { Some(n) } else { num(hi) };
            lo.zip(hi)
        }
    };
    let help = Some(format!(
        "a type 1..{n} or a range *, *n, n*, m*n (or mix yes|no alone)"
    ));
    let Some((lo, hi)) = range else {
        return Err(a.error_prev(format!("coord/atom: '{w}' is not an atom type"), help));
    };
    if lo < 1 || hi > n {
        return Err(a.error_prev(
            format!("coord/atom: type {w} is out of range: the box has {n} atom type(s)"),
            help,
        ));
    }
    if lo > hi {
        return Err(a.error_prev(format!("coord/atom: empty type range '{w}'"), help));
    }
    Ok((lo, hi))
}

fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    let n = sim.world_ref(a)?.materials.ntypes;
    let cutoff = a.positive("coord/atom cutoff")?;
    let mut mix = false;
    let mut ranges = Vec::new();
    // LIGGGHTS reads `mix` only as exactly the two words after the cutoff.
    if a.peek() == Some("mix") && a.remaining() == 2 {
        a.word("mix")?;
        mix = a.yes_no("mix")?;
    } else {
        while !a.is_done() {
            ranges.push(type_range(a, n)?);
        }
    }
    if ranges.is_empty() {
        ranges.push((1, n.max(1) as u32));
    }
    Ok(Box::new(CoordAtom {
        cutoff,
        ranges,
        mix,
    }))
}

impl ScriptCompute for CoordAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(if self.ranges.len() > 1 {
            self.ranges.len()
        } else {
            0
        })
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let id = &c.id;
        let ncols = self.ranges.len();
        let k = match (col, ncols) {
            (None, 1) => 0,
            (Some(_), 1) => {
                return Err(format!("compute {id} is a per-atom vector: use c_{id}").into())
            }
            (Some(k), n) if (1..=n).contains(&k) => k - 1,
            (Some(k), n) => return Err(format!("c_{id}[{k}]: compute {id} has {n} columns").into()),
            (None, n) => return Err(format!("compute {id} has {n} columns: use c_{id}[i]").into()),
        };
        let w = super::world(sim)?;
        let reach = type_reach(w);
        let ntypes = w.materials.ntypes;
        let cutmax = (0..ntypes * ntypes).fold(0.0f64, |m, k| m.max(reach[k]));
        let any = w.comm.sum_count(w.particles.nlocal() as u64) > 0;
        if any && self.cutoff > cutmax {
            return Err(format!(
                "compute {id}: coord/atom cutoff {} is longer than the neighbor cutoff {cutmax} (2 × largest radius + skin), as LIGGGHTS 3.8 refuses",
                self.cutoff
            ).into());
        }
        Ok(coord_counts(
            w,
            c.groupbit,
            self.cutoff,
            &reach,
            self.ranges[k],
            self.mix,
        ))
    }
}

/// rmax_a + rmax_b + skin for each type pair (row-major, 0-based), the largest radius of
/// each type over the particles of all ranks (every rank must call it).
fn type_reach(w: &World) -> Vec<f64> {
    let n = w.materials.ntypes;
    let p = &w.particles;
    let mut rmax = vec![0.0f64; n];
    for i in 0..p.nlocal() {
        if let Some(r) = rmax.get_mut(p.ty[i] as usize - 1) {
            *r = r.max(p.radius[i]);
        }
    }
    let rmax: Vec<f64> = rmax.into_iter().map(|r| w.comm.max(r)).collect();
    let skin = w.neighbor.settings.skin;
    let mut reach = vec![0.0; n * n];
    for a in 0..n {
        for b in 0..n {
            reach[a * n + b] = rmax[a] + rmax[b] + skin;
        }
    }
    reach
}

/// The counts of the owned particles: neighbours j (owned or ghost, j ≠ i) of type in
/// `range` (or of another type than i's with `mix`) with |x_i − x_j| < `cutoff` and within
/// the reach of their type pair; 0 outside `groupbit`. A cell search over the owned and
/// ghost particles, made for each evaluation.
fn coord_counts(
    w: &World,
    groupbit: u32,
    cutoff: f64,
    reach: &[f64],
    range: (u32, u32),
    mix: bool,
) -> Vec<f64> {
    let p = &w.particles;
    let (nlocal, n) = (p.nlocal(), p.len());
    let ntypes = w.materials.ntypes;
    let mut counts = vec![0.0; nlocal];
    if nlocal == 0 {
        return counts;
    }
    let (mut lo, mut hi) = (p.x[0], p.x[0]);
    for x in &p.x[..n] {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    // Cells of at least the cutoff, at most about 8 per particle.
    let mut h = cutoff;
    let cells = |h: f64| -> [usize; 3] {
        let e = hi - lo;
        [e.x, e.y, e.z].map(|l| ((l / h).floor() as usize).max(1))
    };
    while cells(h).iter().map(|&c| c as f64).product::<f64>() > 8.0 * n as f64 + 64.0 {
        h *= 2.0;
    }
    let nc = cells(h);
    let cell_of = |x: glam::DVec3| -> [usize; 3] {
        let d = (x - lo) / h;
        let v = [d.x, d.y, d.z];
        [0, 1, 2].map(|a| (v[a].floor().max(0.0) as usize).min(nc[a] - 1))
    };
    let flat = |c: [usize; 3]| (c[2] * nc[1] + c[1]) * nc[0] + c[0];
    // Counting sort of the particles by cell.
    let ncell = nc[0] * nc[1] * nc[2];
    let mut start = vec![0usize; ncell + 1];
    let cell: Vec<usize> = p.x[..n].iter().map(|&x| flat(cell_of(x))).collect();
    for &c in &cell {
        start[c + 1] += 1;
    }
    for k in 0..ncell {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut order = vec![0usize; n];
    for (j, &c) in cell.iter().enumerate() {
        order[fill[c]] = j;
        fill[c] += 1;
    }
    let cut2 = cutoff * cutoff;
    for (i, out) in counts.iter_mut().enumerate() {
        if p.mask[i] & groupbit == 0 {
            continue;
        }
        let ti = p.ty[i] as usize - 1;
        let ci = cell_of(p.x[i]);
        let mut count = 0u32;
        for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let c = [ci[0] as i64 + dx, ci[1] as i64 + dy, ci[2] as i64 + dz];
                    if (0..3).any(|a| c[a] < 0 || c[a] >= nc[a] as i64) {
                        continue;
                    }
                    let f = flat(c.map(|v| v as usize));
                    for &j in &order[start[f]..start[f + 1]] {
                        if j == i {
                            continue;
                        }
                        let tj = p.ty[j];
                        let wanted = if mix {
                            tj as usize - 1 != ti
                        } else {
                            (range.0..=range.1).contains(&tj)
                        };
                        if !wanted {
                            continue;
                        }
                        let r2 = (p.x[i] - p.x[j]).length_squared();
                        let rc = reach[ti * ntypes + tj as usize - 1];
                        if r2 < cut2 && r2 <= rc * rc {
                            count += 1;
                        }
                    }
                }
            }
        }
        *out = f64::from(count);
    }
    counts
}
