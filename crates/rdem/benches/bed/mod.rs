//! The settled dense bed shared by the benchmarks: the material, walls and neighbor
//! settings of `../shared/bench/in.dense`, filled by seeded random sequential addition and
//! settled under gravity (see `dense_bed.rs` for the full description).
#![allow(dead_code)]

use std::time::Instant;

use rdem::timers::Stage;
use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, LostPolicy, Materials, NeighborSettings,
    NewParticle, PairGran, PrimitiveWall, WallShape, World,
};

pub const LO: DVec3 = DVec3::new(-0.05, -0.05, 0.0);
pub const HI: DVec3 = DVec3::new(0.05, 0.05, 0.06);
pub const RADII: [f64; 2] = [0.0015, 0.002];
pub const MASS_FRACTION: [f64; 2] = [0.3, 0.7];
pub const DENSITY: f64 = 2500.0;
pub const DT: f64 = 1e-5;
/// Height of the column the particles are poured from (top wall during settling).
pub const FILL_TOP: f64 = 0.09;
/// Steps of free settling, then steps with the top wall at its final place.
pub const SETTLE_STEPS: u64 = 16_000;
pub const REST_STEPS: u64 = 2_000;

/// splitmix64: a tiny, good-enough seeded generator for placement.
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// The in.dense world without particles, its top wall at `top`.
pub fn empty_world(top: f64) -> World {
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
        contact_distance_factor: 1.0,
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
pub fn place(world: &mut World, n: usize, top: f64, rng: &mut SplitMix64) -> usize {
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
pub fn contacts(world: &World) -> (usize, usize, usize) {
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

pub fn set_top_wall(world: &mut World, top: f64) {
    for fix in &mut world.fixes {
        if let (FixKind::WallGran(w), "zwalls2") = (&mut fix.kind, fix.id.as_str()) {
            w.shape = WallShape::Plane { axis: 2, pos: top };
        }
    }
}

pub fn settled_bed(n: usize) -> World {
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
    let neigh = world.timers.get(Stage::Neigh).as_secs_f64();
    let builds = world.neighbor.nbuilds;
    println!(
        "bed: placed {placed} spheres at {:.1} % volume fraction, settled in {:.1} s ({} steps, {builds} neighbor builds, {:.2} ms of neigh stage per build): bed top z = {zmax:.4} m, {:.1} % solid below it, ke {et:.3e} J, erot {er:.3e} J",
        100.0 * solid / (footprint * (FILL_TOP - LO.z)),
        t0.elapsed().as_secs_f64(),
        SETTLE_STEPS + REST_STEPS,
        1e3 * neigh / builds.max(1) as f64,
        100.0 * solid / (footprint * (zmax - LO.z)),
    );
    world
}
