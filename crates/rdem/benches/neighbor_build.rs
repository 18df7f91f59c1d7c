//! Cost of one neighbor-list build ([`Neighbor::build`] after [`Neighbor::save_history`])
//! on the settled dense bed of `dense_bed.rs` (same material, walls, skin 0.002 and
//! settling procedure; 10,000 spheres by default, `RDEM_BENCH_N` overrides).
//!
//! Settling prints the number of builds and the time of the `neigh` stage (remap, sort,
//! build) per build in that flowing phase. Then three cases, all on the same particles
//! (so each iteration saves the history of the previous build and restores it into an
//! identical list, as a rebuild of a bed that barely moved does):
//!
//! * `save_and_build`: the bed as is (shrink-wrapped, no ghosts), with its tangential
//!   history — the full cost of a rebuild in the neighbor module;
//! * `build_no_history`: the same without history (width 0), i.e. binning and pair search;
//! * `periodic_save_and_build`: the bed in a box periodic along x and y, with the serial
//!   periodic ghosts, so the ghost bins and the "above" rule are timed too.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput};
use rdem::comm::{Comm, Serial};
use rdem::neighbor::Neighbor;
use rdem::{Boundary, Domain, Particles};

mod bed;
use bed::{settled_bed, HI, LO};

/// Mean time of `f` over `reps` calls after two warm-up calls.
fn mean_time(reps: u32, mut f: impl FnMut()) -> Duration {
    f();
    f();
    let t0 = Instant::now();
    for _ in 0..reps {
        f();
    }
    t0.elapsed() / reps
}

fn main() {
    let n: usize = std::env::var("RDEM_BENCH_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let world = settled_bed(n);
    let step = world.step;
    let np = world.particles.nlocal();

    // The bed as is: locals only, with history.
    let p_bed = world.particles.clone();
    let mut nb_bed: Neighbor = world.neighbor.clone();
    // Without history.
    let mut nb_plain = nb_bed.clone();
    nb_plain.set_history_layout(0, 0);
    nb_plain.build(&p_bed, step);
    // Periodic along x and y, with serial periodic ghosts.
    let mut p_per: Particles = world.particles.clone();
    p_per.clear_ghosts();
    let dom = Domain::new(
        LO,
        HI,
        [Boundary::Periodic, Boundary::Periodic, Boundary::Fixed],
    )
    .expect("box");
    let mut serial = Serial::new();
    serial.borders(&mut p_per, &dom, nb_bed.cutoff);
    let mut nb_per = nb_bed.clone();
    nb_per.save_history(&world.particles);
    nb_per.build(&p_per, step);

    let hist_pairs = nb_bed
        .list
        .hist
        .chunks(nb_bed.list.width.max(1))
        .filter(|h| h.iter().any(|&v| v != 0.0))
        .count();
    println!(
        "neighbor_build: N = {np}, {} listed pairs, {hist_pairs} with history; periodic: {} ghosts, {} pairs",
        nb_bed.list.len(),
        p_per.nghost(),
        nb_per.list.len()
    );

    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sample_size(30)
        .configure_from_args();
    {
        let mut group = c.benchmark_group("neighbor_build");
        group.throughput(Throughput::Elements(np as u64));
        group.bench_function(BenchmarkId::new("save_and_build", np), |b| {
            b.iter(|| {
                nb_bed.save_history(black_box(&p_bed));
                nb_bed.build(black_box(&p_bed), step);
            })
        });
        group.bench_function(BenchmarkId::new("build_no_history", np), |b| {
            b.iter(|| nb_plain.build(black_box(&p_bed), step))
        });
        group.bench_function(BenchmarkId::new("periodic_save_and_build", np), |b| {
            b.iter(|| {
                nb_per.save_history(black_box(&p_per));
                nb_per.build(black_box(&p_per), step);
            })
        });
        group.finish();
    }
    // A plain summary.
    let full = mean_time(200, || {
        nb_bed.save_history(&p_bed);
        nb_bed.build(&p_bed, step);
    });
    let plain = mean_time(200, || nb_plain.build(&p_bed, step));
    let per = mean_time(200, || {
        nb_per.save_history(&p_per);
        nb_per.build(&p_per, step);
    });
    println!(
        "neighbor_build: save + build {:.3} ms, build without history {:.3} ms, periodic save + build {:.3} ms",
        full.as_secs_f64() * 1e3,
        plain.as_secs_f64() * 1e3,
        per.as_secs_f64() * 1e3
    );
    c.final_summary();
}
