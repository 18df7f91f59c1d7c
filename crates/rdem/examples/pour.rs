//! A small pour, built with the engine API alone: 500 spheres (radii 1.5 mm and 2 mm,
//! density 2500) start on a jittered lattice in the upper half of a 4 cm × 4 cm × 8 cm
//! box, fall under gravity onto its floor and come to rest. Hertz contacts with tangential
//! history (E = 5e6, ν = 0.45, e = 0.3, μ = 0.5) between particles and with six primitive
//! plane walls; dt = 1e-5. Prints step, particle count and kinetic energies every 2000
//! steps, then the `Loop time` line the LIGGGHTS tools read.
//!
//! Run: `cargo run --release -p rdem --example pour`

use std::time::Instant;

use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, LostPolicy, Materials, NeighborSettings,
    NewParticle, PairGran, PrimitiveWall, WallShape, World,
};

const N: usize = 500;
const STEPS: u64 = 20_000;
const THERMO: u64 = 2_000;

fn main() -> rdem::Result<()> {
    let lo = DVec3::new(-0.02, -0.02, 0.0);
    let hi = DVec3::new(0.02, 0.02, 0.08);
    let mut world = World::new(Domain::new(lo, hi, [Boundary::Fixed; 3])?);
    world.materials = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
    let model = ContactModel::hertz_history();
    world.pair = Some(PairGran::new(model));
    world.neighbor.settings = NeighborSettings {
        skin: 0.002,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    world.set_timestep(1e-5)?;
    world.lost_policy = LostPolicy::Warn;

    let all = 1;
    world.add_fix(Fix::gravity("gravi", all, 9.81, DVec3::NEG_Z)?)?;
    for (axis, side, pos) in [
        (0, "lo", lo.x),
        (0, "hi", hi.x),
        (1, "lo", lo.y),
        (1, "hi", hi.y),
        (2, "lo", lo.z),
        (2, "hi", hi.z),
    ] {
        let id = format!("wall_{}{side}", ['x', 'y', 'z'][axis]);
        let wall = PrimitiveWall::new(&id, model, 1, WallShape::Plane { axis, pos })?;
        world.add_fix(Fix::new(&id, all, FixKind::WallGran(Box::new(wall)))?)?;
    }
    world.add_fix(Fix::new("integr", all, FixKind::NveSphere)?)?;

    // A jittered lattice of 4.4 mm cells from z = 3 cm up; half small, half large spheres.
    let mut rng = SplitMix64(2024);
    let spacing = 0.0044;
    let per_row = ((hi.x - lo.x) / spacing) as usize;
    for k in 0..N {
        let (ix, iy, iz) = (
            k % per_row,
            (k / per_row) % per_row,
            k / (per_row * per_row),
        );
        let centre = DVec3::new(
            lo.x + (ix as f64 + 0.5) * spacing,
            lo.y + (iy as f64 + 0.5) * spacing,
            0.03 + (iz as f64 + 0.5) * spacing,
        );
        let radius = if rng.next_f64() < 0.5 { 0.0015 } else { 0.002 };
        let jitter = DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5;
        let x = centre + (0.5 * spacing - radius) * jitter;
        let v = DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, -1.0) * 0.1;
        world.add_particle(&NewParticle::at(x, radius, 2500.0).with_v(v))?;
    }

    world.setup()?;
    println!("{:>8} {:>6} {:>14} {:>14}", "step", "atoms", "ke", "erot");
    let thermo = |w: &World| {
        let (ke, erot) = w.particles.kinetic_energy();
        println!(
            "{:>8} {:>6} {:>14.6e} {:>14.6e}",
            w.step,
            w.natoms(),
            ke,
            erot
        );
    };
    thermo(&world);
    let t0 = Instant::now();
    for _ in 0..STEPS / THERMO {
        for _ in 0..THERMO {
            world.advance()?;
        }
        thermo(&world);
    }
    let secs = t0.elapsed().as_secs_f64();
    println!(
        "Loop time of {secs:.6} on 1 procs for {STEPS} steps with {} atoms",
        world.natoms()
    );
    for w in &world.warnings {
        println!("WARNING: {w}");
    }
    Ok(())
}

/// splitmix64: a tiny seeded generator, enough for placing particles.
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
}
