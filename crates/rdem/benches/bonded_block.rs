//! Throughput of one full engine step ([`World::advance`]) with `cohesion bond`: a block of
//! 20 × 20 × 20 touching spheres (radius 1 mm, density 2500, E = 1e8, ν = 0.25) on a
//! simple cubic lattice, all 22,800 nearest-neighbour pairs bonded at step 1 (k_n = 5e10,
//! k_t = 2e10 per unit area, damping 0.1 on each load, breakage by stress at 5e6 Pa, far
//! above the load of the block's weight, so none breaks), resting under gravity on a
//! bonding floor; dt 1e-6, skin 0.4 mm (the bond reach, 1.1 × (2.02 mm + the 0.1 mm
//! stretch at 5e6 Pa), plus the skin stays below the lattice diagonal). The
//! timed work is one `advance()` per iteration; criterion reports elements/s =
//! particle-steps/s. A plain timed block follows and prints particle-steps/s.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, Throughput};
use rdem::bond::{BondCoefficients, BondFlags};
use rdem::{
    Boundary, CohesionKind, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NewParticle,
    PairGran, PrimitiveWall, WallShape, World,
};

/// Steps of the plain timed block.
const TIMED_STEPS: u64 = 500;

fn block() -> World {
    let side = 20;
    let (r, a) = (0.001, 0.002);
    let len = side as f64 * a;
    let mut w = World::new(
        Domain::new(
            DVec3::new(-0.01, -0.01, 0.0),
            DVec3::new(len + 0.01, len + 0.01, len + 0.01),
            [Boundary::Fixed; 3],
        )
        .unwrap(),
    );
    let mut m = Materials::uniform(1, 1e8, 0.25, 0.5, 0.5);
    let pair = |v: f64| Some(vec![v]);
    m.bond = BondCoefficients {
        radius_multiplier: pair(1.0),
        normal_stiffness: pair(5e10),
        tangential_stiffness: pair(2e10),
        max_sigma: pair(5e6),
        max_tau: pair(5e6),
        create_distance: pair(0.00202),
        ts_create: Some(1.0),
        damping_normal_force: pair(0.1),
        damping_tangential_force: pair(0.1),
        damping_normal_torque: pair(0.1),
        damping_tangential_torque: pair(0.1),
        ..Default::default()
    };
    w.materials = m;
    let model = ContactModel {
        cohesion: CohesionKind::Bond,
        bond: BondFlags {
            stress_break: true,
            ..Default::default()
        },
        ..ContactModel::hertz_history()
    };
    w.pair = Some(PairGran::new(model));
    w.neighbor.settings.skin = 0.0004;
    w.neighbor.settings.delay = 0;
    let floor =
        PrimitiveWall::new("floor", model, 1, WallShape::Plane { axis: 2, pos: 0.0 }).unwrap();
    w.add_fix(Fix::new("floor", 1, FixKind::WallGran(Box::new(floor))).unwrap())
        .unwrap();
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(
        Fix::new(
            "gravity",
            1,
            FixKind::Gravity {
                accel: DVec3::new(0.0, 0.0, -9.81),
            },
        )
        .unwrap(),
    )
    .unwrap();
    for i in 0..side {
        for j in 0..side {
            for k in 0..side {
                let x = DVec3::new(i as f64, j as f64, k as f64) * a + DVec3::splat(r);
                w.add_particle(&NewParticle::at(x, r, 2500.0)).unwrap();
            }
        }
    }
    w.set_timestep(1e-6).unwrap();
    w.run(20).expect("bonds made");
    let t = w.bond_tallies();
    assert_eq!(
        t[2],
        3 * side * side * (side - 1),
        "all nearest pairs bonded"
    );
    w
}

fn main() {
    let mut world = block();
    let np = world.particles.nlocal();
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_secs(2))
        .measurement_time(Duration::from_secs(10))
        .sample_size(20)
        .configure_from_args();
    {
        let mut group = c.benchmark_group("bonded_block");
        group.throughput(Throughput::Elements(np as u64));
        group.bench_function(BenchmarkId::new("advance", np), |b| {
            b.iter(|| black_box(&mut world).advance().expect("step"))
        });
        group.finish();
    }
    let t0 = Instant::now();
    for _ in 0..TIMED_STEPS {
        world.advance().expect("step");
    }
    let secs = t0.elapsed().as_secs_f64();
    let t = world.bond_tallies();
    println!(
        "bonded_block: {:.4e} particle-steps/s ({TIMED_STEPS} steps with {np} particles, {} bonds, {} broken so far, in {secs:.3} s)",
        (np as u64 * TIMED_STEPS) as f64 / secs,
        t[2],
        t[1]
    );
}
