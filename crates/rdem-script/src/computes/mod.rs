//! Computes, one file per style in this folder, all listed in one registry
//! ([`REGISTRY`]). A compute is evaluated on demand from the current state (a LIGGGHTS
//! compute is evaluated when thermo, a dump, a variable or `fix ave/time` asks for it;
//! the values are the same). A style's file holds its parser and a type implementing
//! [`ScriptCompute`]: what it gives ([`Shape`]) and how to evaluate it.

mod bond_counter;
mod com;
mod contact_atom;
mod coord_atom;
mod displace_atom;
mod energy_atom;
mod erotate_sphere;
mod ke;
pub mod kernels;
mod multisphere;
mod nbond_atom;
mod nparticles_tracer_region;
mod pair_gran_local;
mod pair_gran_local_bond;
mod pe;
mod pressure;
mod property_atom;
mod property_local;
pub mod reduce;
mod rigid;
mod stress_atom;
pub mod temp;
mod wall_gran_local;

use crate::error::Error;
use rdem::World;

use crate::args::{Args, CmdResult};
use crate::registry::{Registry, Row};
use crate::sim::Sim;

pub use kernels::{erotate, kinetic};

/// What a compute gives: a global scalar, a global vector, per-atom values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Shape {
    /// A global scalar.
    pub scalar: bool,
    /// Length of the global vector (0: none).
    pub vector: usize,
    /// Per-atom values: `Some(0)` a vector, `Some(n)` an array of n columns.
    pub peratom: Option<usize>,
}

impl Shape {
    /// A global scalar.
    pub const fn scalar() -> Self {
        Self {
            scalar: true,
            vector: 0,
            peratom: None,
        }
    }

    /// A global vector of `n`.
    pub const fn vector(n: usize) -> Self {
        Self {
            scalar: false,
            vector: n,
            peratom: None,
        }
    }

    /// Per-atom values in `cols` columns (0: a vector).
    pub const fn peratom(cols: usize) -> Self {
        Self {
            scalar: false,
            vector: 0,
            peratom: Some(cols),
        }
    }
}

/// The words every compute starts with: `compute ID group style`.
#[derive(Debug, Clone)]
pub struct ComputeHead {
    /// Compute ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
}

/// A compute style's evaluation.
pub trait ScriptCompute: std::fmt::Debug {
    /// What it gives.
    fn shape(&self) -> Shape;

    /// Its global scalar (`idx` None) or element `idx` (1-based) of its global vector.
    fn global(&self, _sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let id = &c.id;
        Err(match idx {
            Some(k) => format!("c_{id}[{k}]: compute {id} has no global vector").into(),
            None => format!("compute {id} has no global scalar (it is per-atom)").into(),
        })
    }

    /// Its per-atom values (column `col`, 1-based, of an array) for the owned particles.
    fn peratom(&self, _sim: &Sim, c: &ComputeHead, _col: Option<usize>) -> Result<Vec<f64>, Error> {
        Err(format!("compute {} does not compute per-atom values", c.id).into())
    }

    /// True if thermo divides its global value by the atom count under
    /// `thermo_modify norm yes`.
    fn extensive(&self) -> bool {
        false
    }

    /// Number of columns of its local (per-contact) array, if it gives one.
    fn local_cols(&self) -> Option<usize> {
        None
    }

    /// The named groups of its local columns, in order: (name, first column, width), as
    /// `dump local/gran/vtk` writes them (`pos`, `vel`, `id`, `force`, ...).
    fn local_groups(&self) -> Vec<(&'static str, usize, usize)> {
        Vec::new()
    }

    /// Its local (per-contact) rows on this rank: `local_cols` values per row.
    fn local(&self, _sim: &Sim, c: &ComputeHead) -> Result<Vec<f64>, Error> {
        Err(format!("compute {} does not compute local values", c.id).into())
    }

    /// True if it needs the engine's per-particle contact virial at every step.
    fn needs_virial(&self) -> bool {
        false
    }

    /// When a run is set up (LAMMPS' `init`): what the compute counts once per run.
    fn init(&mut self, _w: &World, _c: &ComputeHead) {}

    /// `compute_modify ID keyword ...`: reads the value(s) of `keyword` (already read) if
    /// the style takes it and returns true; false leaves the keyword to `compute_modify`'s
    /// generic handling.
    fn modify(&mut self, _keyword: &str, _a: &mut Args) -> CmdResult<bool> {
        Ok(false)
    }
}

/// A compute's parser: reads the words after `compute ID group style` (all of them).
pub type ComputeParse = fn(&Sim, &mut Args) -> CmdResult<Box<dyn ScriptCompute>>;

/// A row of the compute registry.
pub type ComputeRow = Row<ComputeParse>;

/// Every compute style: those rdem runs, then LIGGGHTS styles it does not run yet.
pub static REGISTRY: Registry<ComputeParse> = Registry {
    family: "compute style",
    readme_prefix: "compute ",
    rows: &[
        erotate_sphere::ROW,
        erotate_sphere::ROW_ALL,
        multisphere::ROW_EROTATE,
        multisphere::ROW_KE,
        rigid::ROW,
        rigid::ROW_RIGID,
        rigid::ROW_SINGLE,
        energy_atom::ROW_EROTATE,
        ke::ROW,
        com::ROW,
        energy_atom::ROW_KE,
        pe::ROW,
        pressure::ROW,
        displace_atom::ROW,
        reduce::ROW,
        reduce::ROW_REGION,
        nparticles_tracer_region::ROW,
        property_atom::ROW,
        contact_atom::ROW,
        coord_atom::ROW,
        stress_atom::ROW,
        bond_counter::ROW,
        nbond_atom::ROW,
        temp::ROW,
        pair_gran_local::ROW,
        pair_gran_local_bond::ROW,
        property_local::ROW,
        wall_gran_local::ROW,
        Row::not_yet("msd", ""),
        Row::not_yet("rdf", ""),
    ],
};

/// A compute as the script defined it.
#[derive(Debug)]
pub struct Compute {
    /// ID and group.
    pub head: ComputeHead,
    /// Style, as in the registry.
    pub style: &'static str,
    /// The compute.
    pub imp: Box<dyn ScriptCompute>,
}

impl Compute {
    /// Compute ID.
    pub fn id(&self) -> &str {
        &self.head.id
    }

    /// True for a per-atom compute.
    pub fn is_peratom(&self) -> bool {
        self.imp.shape().peratom.is_some()
    }

    /// Number of per-atom columns (0 = a single vector).
    pub fn peratom_cols(&self) -> usize {
        self.imp.shape().peratom.unwrap_or(0)
    }

    /// True if `c_ID[I]` names atom I's value (LAMMPS' rule): a per-atom vector with no
    /// global vector, whose one index can only be an atom ID.
    pub fn indexes_atoms(&self) -> bool {
        self.is_peratom() && self.peratom_cols() == 0 && self.imp.shape().vector == 0
    }

    /// True if the global value is extensive (see [`ScriptCompute::extensive`]).
    pub fn is_extensive(&self) -> bool {
        self.imp.extensive()
    }
}

/// The world, or the error of a compute evaluated before the box exists.
pub(crate) fn world(sim: &Sim) -> Result<&World, Error> {
    sim.world.as_ref().ok_or(Error::NoBox)
}

/// The 0-based position of `c_ID` / `c_ID[k]` among `n` values (columns or vector
/// elements): no index is only valid for a single value.
pub(crate) fn pick_index(id: &str, idx: Option<usize>, n: usize) -> Result<usize, Error> {
    match (idx, n) {
        (None, 1) => Ok(0),
        (Some(k), n) if k >= 1 && k <= n => Ok(k - 1),
        (None, n) => Err(format!("compute {id} gives {n} values: use c_{id}[i]").into()),
        (Some(k), n) => Err(format!("c_{id}[{k}]: compute {id} gives {n} value(s)").into()),
    }
}
