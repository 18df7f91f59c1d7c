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
use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, LostPolicy, Materials, NeighborSettings,
    NewParticle, PairGran, PrimitiveWall, WallShape, World,
};

const LO: DVec3 = DVec3::new(-0.05, -0.05, 0.0);
const HI: DVec3 = DVec3::new(0.05, 0.05, 0.06);
const RADII: [f64; 2] = [0.0015, 0.002];
const MASS_FRACTION: [f64; 2] = [0.3, 0.7];
const DENSITY: f64 = 2500.0;
const DT: f64 = 1e-5;
/// Height of the column the particles are poured from (top wall during settling).
const FILL_TOP: f64 = 0.09;
/// Steps of free settling, then steps with the top wall at its final place.
const SETTLE_STEPS: u64 = 16_000;
const REST_STEPS: u64 = 2_000;
/// Steps of the plain timed block.
const TIMED_STEPS: u64 = 1_000;

/// splitmix64: a tiny, good-enough seeded generator for placement.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// The in.dense world without particles, its top wall at `top`.
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
    let all = 1;
    world
        .add_fix(Fix::gravity("gravi", all, 9.81, DVec3::NEG_Z).expect("gravity"))
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
            .add_fix(Fix::new(id, all, FixKind::WallGran(Box::new(wall))).expect("fix"))
            .expect("fix");
    }
    world
        .add_fix(Fix::new("integr", all, FixKind::NveSphere).expect("fix"))
        .expect("fix");
    world
}

/// Random sequential addition of `n` non-overlapping spheres in the box footprint up to
/// `top`. Each sphere's radius is drawn once (number fractions from the mass fractions) and
/// positions are tried until one is free, so rejections do not bias the mix towards the
/// small spheres; a cell grid keeps the overlap check local. Returns how many were placed.
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

/// Contacts in the current state: particle–particle overlaps over the neighbor list and
/// particle–wall overlaps. Returns (pair contacts, wall contacts, listed pairs).
fn contacts(world: &World) -> (usize, usize, usize) {
    let p = &world.particles;
    let list = &world.neighbor.list;
    let nlocal = p.nlocal();
    let mut pair = 0;
    for i in 0..nlocal {
        for &j in list.partners(i) {
            let j = j as usize;
            let rs = p.radius[i] + p.radius[j];
            if (p.x[i] - p.x[j]).length_squared() < rs * rs {
                pair += 1;
            }
        }
    }
    let mut wall = 0;
    for fix in &world.fixes {
        if let FixKind::WallGran(w) = &fix.kind {
            wall += (0..nlocal)
                .filter(|&i| w.shape.distance(p.x[i]).0 < p.radius[i])
                .count();
        }
    }
    (pair, wall, list.len())
}

fn set_top_wall(world: &mut World, top: f64) {
    for fix in &mut world.fixes {
        if let (FixKind::WallGran(w), "zwalls2") = (&mut fix.kind, fix.id.as_str()) {
            w.shape = WallShape::Plane { axis: 2, pos: top };
        }
    }
}

fn settled_bed(n: usize) -> World {
    let t0 = Instant::now();
    let mut world = empty_world(FILL_TOP);
    let mut rng = SplitMix64(0x5EED_0DE5_u64);
    let placed = place(&mut world, n, FILL_TOP, &mut rng);
    world.setup().expect("setup");
    for _ in 0..SETTLE_STEPS {
        world.advance().expect("settling step");
    }
    let zmax = world.particles.x[..world.particles.nlocal()]
        .iter()
        .zip(&world.particles.radius)
        .map(|(x, r)| x.z + r)
        .fold(0.0, f64::max);
    assert!(
        zmax < HI.z,
        "bed top {zmax} above the box top {}: settle longer or use fewer particles",
        HI.z
    );
    set_top_wall(&mut world, HI.z);
    for _ in 0..REST_STEPS {
        world.advance().expect("settling step");
    }
    let (et, er) = world.particles.kinetic_energy();
    let solid: f64 = world.particles.radius[..world.particles.nlocal()]
        .iter()
        .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
        .sum();
    let footprint = (HI.x - LO.x) * (HI.y - LO.y);
    println!(
        "dense_bed: placed {placed} spheres at {:.1} % volume fraction, settled in {:.1} s ({} steps): bed top z = {zmax:.4} m, {:.1} % solid below it, ke {et:.3e} J, erot {er:.3e} J",
        100.0 * solid / (footprint * (FILL_TOP - LO.z)),
        t0.elapsed().as_secs_f64(),
        SETTLE_STEPS + REST_STEPS,
        100.0 * solid / (footprint * (zmax - LO.z)),
    );
    world
}

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
