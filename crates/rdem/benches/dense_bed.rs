//! Throughput of one full engine step ([`World::advance`]) on a settled dense bed: the
//! material, walls and neighbor settings of `../shared/bench/in.dense` (hertz + tangential
//! history, E = 5e6, ν = 0.45, e = 0.3, μ = 0.5, density 2500, radii 1.5 mm (30 % by mass)
//! and 2 mm (70 %), six primitive plane walls around −0.05..0.05 × −0.05..0.05 × 0..0.06,
//! gravity 9.81 along −z, dt 1e-5, skin 0.002, `neigh_modify delay 0`).
//!
//! Set-up: 10,000 spheres are placed at random without overlap (random sequential
//! addition, seeded) at about 26 % volume fraction in a column 1.5 times as tall as the
//! box (random placement jams near 38 %; in.dense's `insert/pack` asks for 45 % and
//! places 8656 spheres, about 34 % of its box) and left to settle under gravity with the
//! top wall raised; then the top wall is lowered to z = 0.06 and the bed is run a little
//! longer. The timed work is one `advance()` per iteration; criterion reports elements/s =
//! particle-steps/s. A plain timed block follows and prints particle-steps/s, the stage
//! breakdown and the number of neighbor-list builds.
//!
//! `RDEM_BENCH_N` overrides the particle count (e.g. 2000 for a quick look).

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput};
use rdem::timers::Stage;

mod bed;
use bed::{contacts, settled_bed};

/// Steps of the plain timed block.
const TIMED_STEPS: u64 = 1_000;

fn main() {
    let n: usize = std::env::var("RDEM_BENCH_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let mut world = settled_bed(n);
    let np = world.particles.nlocal();
    let (pair, wall, listed) = contacts(&world);
    println!(
        "dense_bed: N = {np}, contacts per particle {:.2} (particle-particle {:.2} + wall {:.2}), neighbor-list pairs per particle {:.2} (half list, LIGGGHTS' \"Ave neighs/atom\")",
        (2 * pair + wall) as f64 / np as f64,
        2.0 * pair as f64 / np as f64,
        wall as f64 / np as f64,
        listed as f64 / np as f64
    );

    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(10))
        .sample_size(20)
        .configure_from_args();
    {
        let mut group = c.benchmark_group("dense_bed");
        group.throughput(Throughput::Elements(np as u64));
        group.bench_function(BenchmarkId::new("advance", np), |b| {
            b.iter(|| black_box(&mut world).advance().expect("step"))
        });
        group.finish();
    }

    // A plain timed block with the stage breakdown.
    world.timers.reset();
    let builds = world.neighbor.nbuilds;
    let t0 = Instant::now();
    for _ in 0..TIMED_STEPS {
        world.advance().expect("step");
    }
    let secs = t0.elapsed().as_secs_f64();
    let np = world.particles.nlocal();
    println!(
        "dense_bed: {:.4e} particle-steps/s ({TIMED_STEPS} steps with {np} particles in {secs:.3} s, {} neighbor builds)",
        (np as u64 * TIMED_STEPS) as f64 / secs,
        world.neighbor.nbuilds - builds
    );
    let stages = [
        ("pair", Stage::Pair),
        ("neigh", Stage::Neigh),
        ("comm", Stage::Comm),
        ("modify (integrate, walls, gravity)", Stage::Modify),
        ("other (force clear, finiteness)", Stage::Other),
    ];
    for (name, stage) in stages {
        let t = world.timers.get(stage).as_secs_f64();
        println!(
            "dense_bed:   {name:<36} {t:8.3} s {:5.1} %",
            100.0 * t / secs
        );
    }
    c.final_summary();
}
