//! Walls: primitive walls (planes and cylinders) and triangle-mesh walls, both through
//! the contact kernel's [`crate::contact::Geom`].

mod any;
pub mod mesh;
pub mod mesh_local;
pub mod mesh_stress;
pub mod primitive;
pub mod touch;

pub use any::{MultiSlot, Wall};
pub use mesh::{MeshSurface, MeshWall};
pub use mesh_local::{WallContact, WallContacts};
pub use primitive::{PrimitiveWall, WallShape};
pub use touch::{Touches, TOUCH_PROPERTY, TOUCH_WIDTH};

/// Whether each owned particle holds an intact wall bond, read from the wall's history
/// property `hist` at offset `flag` (none without bonds).
pub(crate) fn bonded<'a>(
    p: &'a crate::particles::Particles,
    hist: Option<crate::particles::SparseId>,
    flag: Option<usize>,
) -> impl Iterator<Item = bool> + 'a {
    let rows = match (hist, flag) {
        (Some(id), Some(flag)) => Some((&p.sparse[id.0], flag)),
        _ => None,
    };
    rows.into_iter().flat_map(move |(h, flag)| {
        (0..p.nlocal()).map(move |i| crate::bond::is_bonded(&h.get(i)[flag..]))
    })
}

/// Intact wall bonds of the owned particles ([`bonded`]).
pub(crate) fn count_bonded(
    p: &crate::particles::Particles,
    hist: Option<crate::particles::SparseId>,
    flag: Option<usize>,
) -> u64 {
    bonded(p, hist, flag).filter(|&b| b).count() as u64
}

/// A wall's history rows (`w` values each; row `c` belongs to particle `rows[c]`,
/// `rows` ascending, as [`crate::particles::SparseProperty::keep_rows`] lays them out)
/// cut at the particle chunks ([`crate::par::CHUNK`]) of `n` particles: piece `k` holds
/// the rows of the particles in chunk `k`.
pub(crate) fn chunk_rows<'a>(
    rows: &[u32],
    mut data: &'a mut [f64],
    w: usize,
    n: usize,
) -> Vec<&'a mut [f64]> {
    let chunk = crate::par::CHUNK;
    let mut out = Vec::with_capacity(n.div_ceil(chunk));
    let mut a = 0;
    for k in 0..n.div_ceil(chunk) {
        let hi = ((k + 1) * chunk).min(n);
        let b = a + rows[a..].partition_point(|&i| (i as usize) < hi);
        let len = if w > 0 { (b - a) * w } else { 0 };
        let (head, tail) = std::mem::take(&mut data).split_at_mut(len);
        out.push(head);
        data = tail;
        a = b;
    }
    out
}

/// Registers (or finds) the `store_force` property `name`: 3 values per particle, 0 for
/// new particles.
pub(crate) fn store_prop(
    name: Option<&str>,
    p: &mut crate::particles::Particles,
) -> crate::error::Result<Option<crate::particles::PropId>> {
    name.map(|n| p.add_property(n, 3, &[0.0; 3])).transpose()
}

/// With `store_force`: before a wall's pass over particles `f.len()` (their forces `f`,
/// their stored values `store`, 3 each), parks each force in its stored slots and zeroes
/// it, so the pass leaves just the wall's force in `f`.
#[inline]
pub(crate) fn store_begin(f: &mut [glam::DVec3], store: &mut [f64]) {
    for (fi, s) in f.iter_mut().zip(store.chunks_exact_mut(3)) {
        s.copy_from_slice(&fi.to_array());
        *fi = glam::DVec3::ZERO;
    }
}

/// After the pass ([`store_begin`]): each particle's force becomes the parked force plus
/// the wall's, and the stored slots keep the wall's.
#[inline]
pub(crate) fn store_end(f: &mut [glam::DVec3], store: &mut [f64]) {
    for (fi, s) in f.iter_mut().zip(store.chunks_exact_mut(3)) {
        let wall = *fi;
        *fi = glam::DVec3::from_slice(s) + wall;
        s.copy_from_slice(&wall.to_array());
    }
}
