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

/// The read-only per-particle arrays of the post-force passes, whole (indexed by particle,
/// owned particles first): what a post-force fix reads ([`crate::fix::ForceFix`]).
#[derive(Clone, Copy)]
pub struct View<'a> {
    /// Positions.
    pub x: &'a [DVec3],
    /// Velocities.
    pub v: &'a [DVec3],
    /// Angular velocities.
    pub omega: &'a [DVec3],
    /// Radii.
    pub radius: &'a [f64],
    /// Masses.
    pub rmass: &'a [f64],
    /// The contact masses ([`crate::particles::Particles::contact_mass`]).
    pub mcontact: &'a [f64],
    /// Atom types.
    pub ty: &'a [u32],
    /// Group masks.
    pub mask: &'a [u32],
    /// Tags.
    pub tag: &'a [crate::particles::Tag],
}

impl<'a> View<'a> {
    /// The view of `p`'s arrays, with its forces, torques and properties (dense and sparse) split off
    /// mutably.
    pub(crate) fn split(
        p: &'a mut Particles,
    ) -> (
        Self,
        &'a mut Vec<DVec3>,
        &'a mut Vec<DVec3>,
        &'a mut Vec<crate::particles::Property>,
        &'a mut Vec<crate::particles::SparseProperty>,
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
            sparse,
            mass_of_contact,
            tag,
            ..
        } = p;
        let view = View {
            x,
            v,
            omega,
            radius,
            mcontact: if mass_of_contact.is_empty() {
                rmass
            } else {
                mass_of_contact
            },
            rmass,
            ty,
            mask,
            tag,
        };
        (view, f, torque, props, sparse)
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

/// The processes of this run on this machine: Open MPI's `OMPI_COMM_WORLD_LOCAL_SIZE`
/// when it is set, else all the run's processes.
fn local_processes() -> usize {
    std::env::var("OMPI_COMM_WORLD_LOCAL_SIZE")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .unwrap_or_else(|| crate::comm::process_rank_size().1)
        .max(1)
}

/// This machine's cores shared between the run's processes on it (at least 1): the
/// default thread count of a process.
pub fn cores_per_process() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    (cores / local_processes()).max(1)
}

/// Runs `f` on the calling pool thread while the pool's other threads keep looking for
/// work instead of going to sleep, and gives its result.
///
/// Between two parallel loops of a timestep there is serial work (communication, force
/// clear, checks, output) long enough for an idle rayon worker to go to sleep, and waking
/// it again is a futex call that costs more than many a loop saves: on a 2-vCPU virtual
/// machine, 8.6 % of a 2-thread run's CPU samples were in futex calls. rayon has no
/// setting for how long its workers spin (rayon-rs/rayon#684 proposed one and was closed),
/// so each other worker is given a task that keeps taking the pool's jobs
/// ([`rayon::yield_now`]) until `f` returns, and gives its core up with
/// `std::thread::yield_now` whenever it finds none: another process with work on the
/// same core runs then (two 2-thread runs of the dense bench at once on 2 cores took
/// 10.4 s and 10.6 s with a helper that spun with `spin_loop`, 6.3 s and 6.5 s with
/// helpers that slept, 6.2 s and 6.5 s with this). Nothing `f` computes depends on which
/// thread runs a job, so the results are unchanged. On a pool of one thread, outside a
/// pool, or with more threads than [`cores_per_process`] (this machine's processes of
/// the run would have more threads than it has cores, and a helper would keep taking a
/// core from a thread of the run that has work), `f` just runs.
pub fn with_busy_pool<R>(f: impl FnOnce() -> R) -> R {
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let n = rayon::current_num_threads();
    if n <= 1 || n > cores_per_process() || rayon::current_thread_index().is_none() {
        return f();
    }
    let done = AtomicBool::new(false);
    let started = AtomicUsize::new(0);
    /// Sets `done` when dropped: the helpers stop even if `f` panics.
    struct Done<'a>(&'a AtomicBool);
    impl Drop for Done<'_> {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
        }
    }
    rayon::in_place_scope(|s| {
        let _done = Done(&done);
        for _ in 1..n {
            s.spawn(|_| {
                started.fetch_add(1, Ordering::AcqRel);
                while !done.load(Ordering::Acquire) {
                    if rayon::yield_now() != Some(rayon::Yield::Executed) {
                        std::thread::yield_now();
                    }
                }
            });
        }
        // Every helper must be running on another thread before `f` starts: a helper
        // that this thread took up itself while waiting for a job would never return.
        while started.load(Ordering::Acquire) < n - 1 {
            std::thread::yield_now();
        }
        f()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(n: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("a pool")
    }

    /// The parallel loops run inside give the serial result, and the helpers stop when
    /// `f` returns (else the scope would never end).
    #[test]
    fn busy_pool_runs_parallel_loops_and_ends() {
        for n in [1, 2, 4] {
            let sum = pool(n).install(|| {
                with_busy_pool(|| {
                    (0..20)
                        .map(|k| (0..100_000u64).into_par_iter().map(|i| i * k).sum::<u64>())
                        .sum::<u64>()
                })
            });
            assert_eq!(sum, 190 * (99_999 * 100_000 / 2), "{n} threads");
        }
    }

    /// A panic in `f` reaches the caller instead of leaving the helpers spinning.
    #[test]
    fn busy_pool_passes_a_panic_on() {
        let r = pool(2)
            .install(|| std::panic::catch_unwind(|| with_busy_pool(|| -> u32 { panic!("in f") })));
        assert!(r.is_err());
    }
}
