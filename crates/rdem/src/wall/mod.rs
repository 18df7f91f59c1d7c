//! Walls: primitive walls (planes and cylinders) and triangle-mesh walls, both through
//! the contact kernel's [`crate::contact::Geom`].

pub mod mesh;
pub mod mesh_stress;
pub mod primitive;

pub use mesh::{MeshSurface, MeshWall};
pub use primitive::{PrimitiveWall, WallShape};
