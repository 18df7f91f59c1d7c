//! Computes: `erotate/sphere`, `ke`, `reduce`, `property/atom` and `contact/atom`,
//! evaluated on demand from the current state (a LIGGGHTS compute is evaluated when
//! thermo, a dump, a variable or `fix ave/time` asks for it; the values are the same).

use rdem::World;

use crate::atom_fields;

/// `compute reduce` modes.
pub const REDUCE_MODES: [&str; 6] = ["sum", "min", "max", "ave", "sumsq", "avesq"];

/// Valid compute styles.
pub const STYLES: [&str; 5] = [
    "erotate/sphere",
    "ke",
    "reduce",
    "property/atom",
    "contact/atom",
];

/// One input of `compute reduce`.
#[derive(Debug, Clone, PartialEq)]
pub enum ReduceInput {
    /// A per-atom field (`x`, `vx`, `radius`, ...).
    Field(String),
    /// `c_ID` or `c_ID[i]` of a per-atom compute.
    Compute(String, Option<usize>),
    /// `v_name` of an atom-style variable.
    Variable(String),
}

/// What a compute calculates.
#[derive(Debug, Clone, PartialEq)]
pub enum ComputeKind {
    /// Σ ½ I ω² over the group.
    ERotateSphere,
    /// Σ ½ m v² over the group.
    Ke,
    /// A reduction of per-atom inputs over the group.
    Reduce {
        /// `sum`, `min`, `max`, `ave`, `sumsq`, `avesq`.
        mode: String,
        /// Inputs (one gives a scalar, several a vector).
        inputs: Vec<ReduceInput>,
    },
    /// Per-atom fields (one: a vector, several: an array).
    PropertyAtom(Vec<String>),
    /// Per-atom number of particle contacts.
    ContactAtom,
}

/// A compute.
#[derive(Debug, Clone, PartialEq)]
pub struct Compute {
    /// Compute ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
    /// What it computes.
    pub kind: ComputeKind,
}

impl Compute {
    /// True for a global scalar compute.
    pub fn is_scalar(&self) -> bool {
        match &self.kind {
            ComputeKind::ERotateSphere | ComputeKind::Ke => true,
            ComputeKind::Reduce { inputs, .. } => inputs.len() == 1,
            _ => false,
        }
    }

    /// True for a per-atom compute.
    pub fn is_peratom(&self) -> bool {
        matches!(
            self.kind,
            ComputeKind::PropertyAtom(_) | ComputeKind::ContactAtom
        )
    }

    /// Number of per-atom columns (0 = a single vector).
    pub fn peratom_cols(&self) -> usize {
        match &self.kind {
            ComputeKind::PropertyAtom(f) if f.len() > 1 => f.len(),
            _ => 0,
        }
    }

    /// Length of the global vector (reduce with several inputs), else 0.
    pub fn vector_len(&self) -> usize {
        match &self.kind {
            ComputeKind::Reduce { inputs, .. } if inputs.len() > 1 => inputs.len(),
            _ => 0,
        }
    }
}

/// Σ ½ I ω² over owned particles in `groupbit`.
pub fn erotate(w: &World, groupbit: u32) -> f64 {
    let p = &w.particles;
    let e: f64 = (0..p.nlocal())
        .filter(|&i| p.mask[i] & groupbit != 0)
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

/// Per-atom contact counts (pairs closer than r_i + r_j), owned particles.
pub fn contact_counts(w: &World) -> Vec<f64> {
    let p = &w.particles;
    let nlocal = p.nlocal();
    let mut c = vec![0.0; nlocal];
    let list = &w.neighbor.list;
    if list.first.len() != nlocal + 1 {
        return c;
    }
    for i in 0..nlocal {
        for &j in list.partners(i) {
            let j = j as usize;
            if j >= p.len() {
                continue;
            }
            let r = p.radius[i] + p.radius[j];
            if (p.x[i] - p.x[j]).length_squared() < r * r {
                c[i] += 1.0;
                let o = if j < nlocal { j } else { p.origin[j] };
                if o < nlocal && (j < nlocal || o != i) {
                    c[o] += 1.0;
                }
            }
        }
    }
    c
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
