//! Walls: primitive walls (planes and cylinders) and triangle-mesh walls, both through
//! the contact kernel's [`crate::contact::Geom`].

pub mod mesh;
pub mod mesh_local;
pub mod mesh_stress;
pub mod primitive;

pub use mesh::{MeshSurface, MeshWall};
pub use mesh_local::{WallContact, WallContacts};
pub use primitive::{PrimitiveWall, WallShape};

/// Whether each owned particle holds an intact wall bond, read from the wall's history
/// property `hist` at offset `flag` (none without bonds).
pub(crate) fn bonded<'a>(
    p: &'a crate::particles::Particles,
    hist: Option<crate::particles::PropId>,
    flag: Option<usize>,
) -> impl Iterator<Item = bool> + 'a {
    let rows = match (hist, flag) {
        (Some(id), Some(flag)) => {
            let prop = &p.props[id.0];
            let w = prop.width;
            Some((prop.data[..p.nlocal() * w].chunks_exact(w), flag))
        }
        _ => None,
    };
    rows.into_iter()
        .flat_map(|(rows, flag)| rows.map(move |h| crate::bond::is_bonded(&h[flag..])))
}

/// Intact wall bonds of the owned particles ([`bonded`]).
pub(crate) fn count_bonded(
    p: &crate::particles::Particles,
    hist: Option<crate::particles::PropId>,
    flag: Option<usize>,
) -> u64 {
    bonded(p, hist, flag).filter(|&b| b).count() as u64
}
