//! Shared settings of the elementwise parallel loops (integration, force clear, post-force
//! fixes and walls, finiteness checks, neighbor and near-list builds).
//!
//! Every parallel loop splits its range into fixed chunks of [`CHUNK`] particles (a
//! constant, never a function of the thread count) and either works on each particle
//! alone or combines the chunks' results in chunk order, so that every result is
//! bit-identical whatever the size of the rayon pool. Below [`PAR_MIN`] particles, or on a
//! pool of one thread, the loops run on the calling thread (rayon's fork–join costs more
//! than it saves on small systems).

use glam::DVec3;
use rayon::prelude::*;

use crate::particles::Particles;

/// Particles per chunk of work.
pub const CHUNK: usize = 1024;

/// Fewest particles for which the loops go parallel.
pub const PAR_MIN: usize = 2 * CHUNK;

/// Fewest particles for which the light, memory-bound loops (force clear, finiteness and
/// displacement checks) go parallel: below it a fork–join costs more than the pass.
pub const PAR_MIN_LIGHT: usize = 32 * CHUNK;

/// True when a loop over `n` particles should run on the rayon pool.
#[inline]
pub fn parallel(n: usize) -> bool {
    n >= PAR_MIN && rayon::current_num_threads() > 1
}

/// [`parallel`] for the light loops (see [`PAR_MIN_LIGHT`]).
#[inline]
pub fn parallel_light(n: usize) -> bool {
    n >= PAR_MIN_LIGHT && rayon::current_num_threads() > 1
}

/// The read-only per-particle arrays of the post-force passes, whole (indexed by particle).
#[derive(Clone, Copy)]
pub(crate) struct View<'a> {
    pub x: &'a [DVec3],
    pub v: &'a [DVec3],
    pub omega: &'a [DVec3],
    pub radius: &'a [f64],
    pub rmass: &'a [f64],
    pub ty: &'a [u32],
    pub mask: &'a [u32],
}

impl<'a> View<'a> {
    /// The view of `p`'s arrays, with its forces, torques and properties split off
    /// mutably.
    pub fn split(
        p: &'a mut Particles,
    ) -> (
        Self,
        &'a mut Vec<DVec3>,
        &'a mut Vec<DVec3>,
        &'a mut Vec<crate::particles::Property>,
    ) {
        let Particles {
            x,
            v,
            omega,
            radius,
            rmass,
            ty,
            mask,
            f,
            torque,
            props,
            ..
        } = p;
        let view = View {
            x,
            v,
            omega,
            radius,
            rmass,
            ty,
            mask,
        };
        (view, f, torque, props)
    }
}

/// True when every value of `a` and `b` is finite: x·0 is 0 for a finite x and NaN
/// otherwise, so the sum of those products is NaN exactly when something is not finite
/// (no overflow false alarms, independent lanes that vectorize).
pub(crate) fn all_finite(a: &[DVec3], b: &[DVec3]) -> bool {
    let mut acc = DVec3::ZERO;
    for (u, v) in a.iter().zip(b) {
        acc += *u * 0.0 + *v * 0.0;
    }
    acc.is_finite()
}

/// [`all_finite`] of `a[..n]` and `b[..n]`, in parallel over chunks for large `n`.
pub(crate) fn all_finite_par(a: &[DVec3], b: &[DVec3], n: usize) -> bool {
    let (a, b) = (&a[..n], &b[..n]);
    if !parallel_light(n) {
        return all_finite(a, b);
    }
    a.par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .all(|(a, b)| all_finite(a, b))
}

/// Sets `a` and `b` to zero, in parallel over chunks for long slices.
pub(crate) fn zero(a: &mut [DVec3], b: &mut [DVec3]) {
    if !parallel_light(a.len().max(b.len())) {
        a.fill(DVec3::ZERO);
        b.fill(DVec3::ZERO);
        return;
    }
    a.par_chunks_mut(CHUNK)
        .chain(b.par_chunks_mut(CHUNK))
        .for_each(|c| c.fill(DVec3::ZERO));
}
