//! Multisphere clumps (`fix particletemplate/multisphere`, `fix multisphere`): rigid
//! bodies made of overlapping spheres.
//!
//! [`template`] holds a clump's spheres and its Monte Carlo mass properties in its body
//! frame; [`body`] integrates one rigid body; [`bodies`] holds a world's clumps and their
//! stages in the step.

pub mod bodies;
pub mod body;
pub mod template;

pub use bodies::{BodyInfo, Multisphere, NewClump};
pub use body::RigidBody;
pub use template::{ClumpTemplate, MassProperties, MassSource, Sphere};
