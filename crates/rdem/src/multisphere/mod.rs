//! Multisphere clumps (`fix particletemplate/multisphere`, `fix multisphere`): rigid
//! bodies made of overlapping spheres.
//!
//! [`template`] holds a clump's spheres and its Monte Carlo mass properties in its body
//! frame; [`body`] integrates one rigid body. Both are the engine's building blocks; the
//! step does not call them yet (see the README's notes on clumps).

pub mod body;
pub mod template;

pub use body::RigidBody;
pub use template::{ClumpTemplate, MassProperties, MassSource, Sphere};
