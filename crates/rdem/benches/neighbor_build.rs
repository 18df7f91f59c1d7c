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
use rdem::timers::Stage;
use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, LostPolicy, Materials, NeighborSettings,
    NewParticle, PairGran, Particles, PrimitiveWall, WallShape, World,
};

const LO: DVec3 = DVec3::new(-0.05, -0.05, 0.0);
const HI: DVec3 = DVec3::new(0.05, 0.05, 0.06);
const RADII: [f64; 2] = [0.0015, 0.002];
const MASS_FRACTION: [f64; 2] = [0.3, 0.7];
const DENSITY: f64 = 2500.0;
const DT: f64 = 1e-5;
const FILL_TOP: f64 = 0.09;
const SETTLE_STEPS: u64 = 16_000;
const REST_STEPS: u64 = 2_000;

/// splitmix64, as in `dense_bed.rs`.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

fn empty_world(top: f64) -> World {
    let domain = Domain::new(LO, HI, [Boundary::ShrinkMin; 3]).expect("box");
    let mut world = World::new(domain);
    world.materials = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
    let model = ContactModel::hertz_history();
    world.pair = Some(PairGran::new(model));
    world.neighbor.settings = NeighborSettings {
        skin: 0.002,
        delay: 0,
        every: 1,
        check: true,
    };
    world.set_timestep(DT).expect("dt");
    world.lost_policy = LostPolicy::Ignore;
    world
        .add_fix(Fix::gravity("gravi", 1, 9.81, DVec3::NEG_Z).expect("gravity"))
        .expect("fix");
    let walls = [
        ("xwalls1", 0, LO.x),
        ("xwalls2", 0, HI.x),
        ("ywalls1", 1, LO.y),
        ("ywalls2", 1, HI.y),
        ("zwalls1", 2, LO.z),
        ("zwalls2", 2, top),
    ];
    for (id, axis, pos) in walls {
        let wall = PrimitiveWall::new(id, model, 1, WallShape::Plane { axis, pos }).expect("wall");
        world
            .add_fix(Fix::new(id, 1, FixKind::WallGran(Box::new(wall))).expect("fix"))
            .expect("fix");
    }
    world
        .add_fix(Fix::new("integr", 1, FixKind::NveSphere).expect("fix"))
        .expect("fix");
    world
}

/// Random sequential addition, as in `dense_bed.rs`.
fn place(world: &mut World, n: usize, top: f64, rng: &mut SplitMix64) -> usize {
    let vol = RADII.map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r);
    let w = [MASS_FRACTION[0] / vol[0], MASS_FRACTION[1] / vol[1]];
    let p_small = w[0] / (w[0] + w[1]);
    let h = 2.0 * RADII[1];
    let lo = LO;
    let hi = DVec3::new(HI.x, HI.y, top);
    let nc = [0, 1, 2].map(|a| ((hi[a] - lo[a]) / h).ceil() as usize);
    let cell = |x: DVec3| [0, 1, 2].map(|a| (((x[a] - lo[a]) / h) as usize).min(nc[a] - 1));
    let mut grid: Vec<Vec<(DVec3, f64)>> = vec![Vec::new(); nc[0] * nc[1] * nc[2]];
    let mut placed = 0;
    let mut attempts = 0usize;
    let draw = |rng: &mut SplitMix64| {
        if rng.next_f64() < p_small {
            RADII[0]
        } else {
            RADII[1]
        }
    };
    let mut r = draw(rng);
    while placed < n && attempts < 200 * n {
        attempts += 1;
        let x = DVec3::new(
            rng.range(lo.x + r, hi.x - r),
            rng.range(lo.y + r, hi.y - r),
            rng.range(lo.z + r, hi.z - r),
        );
        let c = cell(x);
        let mut free = true;
        'search: for cz in c[2].saturating_sub(1)..(c[2] + 2).min(nc[2]) {
            for cy in c[1].saturating_sub(1)..(c[1] + 2).min(nc[1]) {
                for cx in c[0].saturating_sub(1)..(c[0] + 2).min(nc[0]) {
                    for &(y, ry) in &grid[(cz * nc[1] + cy) * nc[0] + cx] {
                        if (x - y).length_squared() < (r + ry) * (r + ry) {
                            free = false;
                            break 'search;
                        }
                    }
                }
            }
        }
        if free {
            grid[(c[2] * nc[1] + c[1]) * nc[0] + c[0]].push((x, r));
            world
                .add_particle(&NewParticle::at(x, r, DENSITY))
                .expect("particle");
            placed += 1;
            r = draw(rng);
        }
    }
    placed
}

fn settled_bed(n: usize) -> World {
    let t0 = Instant::now();
    let mut world = empty_world(FILL_TOP);
    let mut rng = SplitMix64(0x5EED_0DE5_u64);
    place(&mut world, n, FILL_TOP, &mut rng);
    world.setup().expect("setup");
    for _ in 0..SETTLE_STEPS {
        world.advance().expect("settling step");
    }
    for fix in &mut world.fixes {
        if let (FixKind::WallGran(w), "zwalls2") = (&mut fix.kind, fix.id.as_str()) {
            w.shape = WallShape::Plane { axis: 2, pos: HI.z };
        }
    }
    for _ in 0..REST_STEPS {
        world.advance().expect("settling step");
    }
    let neigh = world.timers.get(Stage::Neigh).as_secs_f64();
    let builds = world.neighbor.nbuilds;
    println!(
        "neighbor_build: settled {} spheres in {:.1} s ({} steps, {builds} neighbor builds; neigh stage {neigh:.2} s, {:.2} ms per build)",
        world.particles.nlocal(),
        t0.elapsed().as_secs_f64(),
        SETTLE_STEPS + REST_STEPS,
        1e3 * neigh / builds.max(1) as f64
    );
    world
}

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
