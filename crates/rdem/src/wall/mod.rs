//! Walls. Primitive walls (planes and cylinders) here; triangle meshes are a later issue
//! and will plug into the same contact kernel through [`crate::contact::Geom`].

pub mod primitive;

pub use primitive::{PrimitiveWall, WallShape};
