//! The calculations behind the compute styles (and thermo's `ke`), on the world's
//! owned particles, summed over ranks.

use crate::error::Error;
use std::cell::RefCell;

use glam::DVec3;
use rdem::World;

use crate::atom_fields;

/// The mass of the group's particles and their centre of mass from the unwrapped
/// positions (`x + image · box length`), summed over ranks (`compute com`, `fix
/// momentum`, `fix store/state com yes`); the centre is 0 for an empty group.
pub fn group_com(w: &World, groupbit: u32) -> (f64, DVec3) {
    let p = &w.particles;
    let mut s = [0.0; 4];
    for i in (0..p.nlocal()).filter(|&i| p.mask[i] & groupbit != 0) {
        let x = w.domain.unmap(p.x[i], p.image[i].get());
        s[0] += p.rmass[i] * x.x;
        s[1] += p.rmass[i] * x.y;
        s[2] += p.rmass[i] * x.z;
        s[3] += p.rmass[i];
    }
    w.comm.sum_slice(&mut s);
    let com = if s[3] > 0.0 {
        DVec3::new(s[0], s[1], s[2]) / s[3]
    } else {
        DVec3::ZERO
    };
    (s[3], com)
}

/// `compute reduce` modes.
pub const REDUCE_MODES: [&str; 6] = ["sum", "min", "max", "ave", "sumsq", "avesq"];

/// Keywords of `compute stress/atom`. Only `ke`, `pair` and `virial` have terms in rdem
/// (no bonds, angles, ... or kspace; fixes add no virial, as LIGGGHTS' `wall/gran` adds
/// none), so the others select nothing.
pub const STRESS_KEYWORDS: [&str; 9] = [
    "ke", "pair", "bond", "angle", "dihedral", "improper", "kspace", "fix", "virial",
];

/// What `compute bond/counter` remembers between evaluations.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BondCounterState {
    /// Cumulative pair created, pair broken, wall created, wall broken at the last
    /// evaluation (summed over ranks).
    pub last: [f64; 4],
    /// Step of the last evaluation and its values (one evaluation per step, as LIGGGHTS).
    pub cached: Option<(u64, [f64; 6])>,
}

/// Σ ½ I ω² over the owned free spheres in `groupbit`, summed over ranks. The spheres of
/// a `fix multisphere` clump count nothing, as in LIGGGHTS 3.8, whose `erotate/sphere`
/// printed 0 on the tumbling stones of the tutorial multisphere_stone_restitution (their
/// spheres' omega up to 26 rad/s); the clumps' own energy is `erotate/multisphere`.
pub fn erotate(w: &World, groupbit: u32) -> f64 {
    let p = &w.particles;
    let clump = clump_spheres(w);
    let e: f64 = (0..p.nlocal())
        .filter(|&i| p.mask[i] & groupbit != 0 && !clump(i))
        .map(|i| 0.5 * p.inertia(i) * p.omega[i].length_squared())
        .sum();
    // An empty sum is -0 in Rust; LIGGGHTS prints 0.
    w.comm.sum(e) + 0.0
}

/// Σ ½ m v² over owned particles in `groupbit`.
pub fn kinetic(w: &World, groupbit: u32) -> f64 {
    let p = &w.particles;
    let e: f64 = (0..p.nlocal())
        .filter(|&i| p.mask[i] & groupbit != 0)
        .map(|i| 0.5 * p.rmass[i] * p.v[i].length_squared())
        .sum();
    w.comm.sum(e) + 0.0
}

/// `compute bond/counter`'s six values at the current step: pair bonds created and broken
/// since the last evaluation, intact pair bonds, then the same for wall bonds; summed over
/// ranks (every rank must call it). Evaluated once per step: later calls at the same step
/// return the same values. The intact counts are counted anew; they equal seed 003's
/// N + C⁺ − C⁻ (the count at the previous evaluation plus the bonds created and minus
/// those broken since), which is what LIGGGHTS-INL reports.
pub fn bond_counter(w: &World, state: &RefCell<BondCounterState>) -> [f64; 6] {
    let mut s = state.borrow_mut();
    if let Some((step, v)) = s.cached {
        if step == w.step {
            return v;
        }
    }
    let mut t = w.bond_tallies().map(|x| x as f64);
    w.comm.sum_slice(&mut t);
    let cum = [t[0], t[1], t[3], t[4]];
    let v = [
        cum[0] - s.last[0],
        cum[1] - s.last[1],
        t[2],
        cum[2] - s.last[2],
        cum[3] - s.last[3],
        t[5],
    ];
    s.last = cum;
    s.cached = Some((w.step, v));
    v
}

/// Per-atom contact counts (pairs closer than r_i + r_j), owned particles.
pub fn contact_counts(w: &World) -> Vec<f64> {
    let p = &w.particles;
    let nlocal = p.nlocal();
    let mut c = vec![0.0; p.len()];
    let list = &w.neighbor.list;
    // Each touching pair counts for both particles; a ghost's count goes to its owner.
    // (A list older than the particles, after an insertion, counts nothing.)
    let rows = if list.first.len() == nlocal + 1 {
        nlocal
    } else {
        0
    };
    for i in 0..rows {
        for &j in list.partners(i) {
            let j = j as usize;
            if j >= p.len() {
                continue;
            }
            let r = p.radius[i] + p.radius[j];
            if (p.x[i] - p.x[j]).length_squared() < r * r {
                c[i] += 1.0;
                c[j] += 1.0;
            }
        }
    }
    w.comm.reverse_scalar(p, &mut c);
    c.truncate(nlocal);
    c
}

/// Column `col` (0..6: xx yy zz xy xz yz) of `compute stress/atom` for the owned particles:
/// −(m v_a v_b + W_ab) for particles in `groupbit`, 0 for the others, in stress × volume
/// units (N m), as LAMMPS/LIGGGHTS report it. The pair term needs the virial of the
/// current step ([`rdem::World::current_virial`]).
pub fn stress_atom(
    w: &World,
    groupbit: u32,
    ke: bool,
    pair: bool,
    col: usize,
) -> Result<Vec<f64>, Error> {
    const AB: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
    let p = &w.particles;
    let n = p.nlocal();
    let virial = if pair {
        Some(w.current_virial().ok_or_else(|| {
            "compute stress/atom: the contact virial is not available at this step (a run computes it on every step while the compute exists)".to_string()
        })?)
    } else {
        None
    };
    let (a, b) = AB[col];
    Ok((0..n)
        .map(|i| {
            if p.mask[i] & groupbit == 0 {
                return 0.0;
            }
            let mut s = 0.0;
            if let Some(v) = virial {
                s += v[i][col];
            }
            if ke {
                s += p.rmass[i] * p.v[i][a] * p.v[i][b];
            }
            -s
        })
        .collect())
}

/// Per-atom values of `field` for owned particles (unknown field: `None`).
pub fn field_values(w: &World, field: &str) -> Option<Vec<f64>> {
    let n = w.particles.nlocal();
    (0..n)
        .map(|i| atom_fields::value(w, field, i))
        .collect::<Option<Vec<f64>>>()
        .or_else(|| (n == 0 && atom_fields::is_field(field)).then(Vec::new))
}

/// Reduces `values` over owned particles in `groupbit`. An empty group gives 0 for sum
/// and ave, and 1e20 for min, −1e20 for max, as LIGGGHTS prints.
pub fn reduce(w: &World, mode: &str, groupbit: u32, values: &[f64]) -> f64 {
    let p = &w.particles;
    let sel = values
        .iter()
        .enumerate()
        .filter(|&(i, _)| p.mask[i] & groupbit != 0)
        .map(|(_, v)| *v);
    reduce_over(w, mode, sel)
}

/// [`reduce`] of this rank's `values` (all of them, no group), over the ranks: a local
/// (per-contact) column, which LAMMPS' `compute reduce` takes whole.
pub fn reduce_over(w: &World, mode: &str, sel: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut sq, mut n) = (0.0, 0.0, 0u64);
    let (mut lo, mut hi) = (1e20f64, -1e20f64);
    for v in sel {
        sum += v;
        sq += v * v;
        n += 1;
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let sum = w.comm.sum(sum);
    let sq = w.comm.sum(sq);
    let n = w.comm.sum_count(n);
    let lo = w.comm.min(lo);
    let hi = w.comm.max(hi);
    match mode {
        "sum" => sum,
        "sumsq" => sq,
        "min" => lo,
        "max" => hi,
        "ave" => {
            if n > 0 {
                sum / n as f64
            } else {
                0.0
            }
        }
        _ => {
            if n > 0 {
                sq / n as f64
            } else {
                0.0
            }
        }
    }
}

/// Whether owned particle `i` is a sphere of a `fix multisphere` clump.
pub fn clump_spheres(w: &World) -> impl Fn(usize) -> bool + '_ {
    let p = &w.particles;
    let body = p.property(rdem::multisphere::bodies::BODY_PROP);
    move |i| body.is_some_and(|b| p.props[b.0].data[i] != 0.0)
}

/// Σ ½ ω·L over every clump of `fix multisphere` (the group is ignored, as LIGGGHTS does;
/// every rank holds every clump, so every rank has the whole sum).
pub fn erotate_clumps(w: &World) -> f64 {
    let e: f64 = w.multisphere.as_ref().map_or(0.0, |ms| {
        ms.bodies.iter().map(|b| b.kinetic_energy().1).sum()
    });
    e + 0.0 // an empty sum is -0; LIGGGHTS prints 0
}
