//! rdem engine: the state of a granular DEM simulation and one timestep of it — particles,
//! domain, neighbor lists, granular contact laws with history, primitive walls and time
//! integration. No parsing and no files: the script front end and the writers live in
//! other crates.
//!
//! The order of a timestep is written down once, in [`step`].

#![warn(missing_docs)]

pub mod bond;
pub mod bond_gran;
pub mod comm;
pub mod contact;
pub mod domain;
pub mod error;
pub mod euler;
pub mod fix;
pub mod heat;
pub mod heat_radiation;
pub mod insert;
pub mod lost;
pub mod massflow;
pub mod mesh;
pub mod mesh_motion;
pub mod mesh_servo;
#[cfg(feature = "mpi")]
pub mod mpi_comm;
pub mod multicontact;
pub mod multisphere;
pub mod neighbor;
pub mod pair;
pub mod par;
pub mod particles;
pub mod region;
pub mod region_tet;
pub mod restart;
pub mod shear;
pub mod sort;
pub mod sph;
mod stages;
pub mod step;
pub mod timers;
pub mod wall;
pub mod world;

pub use glam::DVec3;

pub use contact::{
    CohesionKind, ContactModel, Flags, Materials, NormalKind, RollingKind, SurfaceKind,
    TangentialKind,
};
pub use domain::{Boundary, Domain};
pub use error::{Error, Result};
pub use fix::{Fix, FixKind};
pub use neighbor::{Exclusions, NeighborSettings};
pub use pair::PairGran;
pub use particles::{NewParticle, Particles, Tag};
pub use step::{HookMask, NoHooks, StepHooks, StepHost};
pub use wall::{PrimitiveWall, WallShape};
pub use world::{LostPolicy, SortSettings, World};
