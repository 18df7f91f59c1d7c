//! Shared set-up for the physics tests: a world with one or two materials and the Hertz
//! closed forms of SPEC §3.
#![allow(dead_code)]

use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NeighborSettings, PairGran,
    PrimitiveWall, WallShape, World,
};

/// Material of every test: E, ν, density.
pub const E: f64 = 1.0e7;
pub const NU: f64 = 0.3;
pub const RHO: f64 = 2500.0;

/// E* of two bodies of the test material.
pub fn e_star() -> f64 {
    1.0 / (2.0 * (1.0 - NU * NU) / E)
}

/// Mass of a sphere of radius `r` of the test material.
pub fn mass(r: f64) -> f64 {
    RHO * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3)
}

/// Hertz contact time t_c = 2.868 (m*²/(R* E*² v))^{1/5}.
pub fn hertz_tc(m_star: f64, r_star: f64, e_star: f64, v: f64) -> f64 {
    2.868 * (m_star * m_star / (r_star * e_star * e_star * v)).powf(0.2)
}

/// Hertz peak overlap δ_max = (15 m* v² / (16 E* √R*))^{2/5}.
pub fn hertz_delta_max(m_star: f64, r_star: f64, e_star: f64, v: f64) -> f64 {
    (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4)
}

/// A world in a box with the given boundaries, one material type with restitution `e`
/// and friction `mu`, the given contact model on particles, and `nve/sphere` on all.
pub fn world(
    lo: DVec3,
    hi: DVec3,
    boundary: [Boundary; 3],
    model: ContactModel,
    e: f64,
    mu: f64,
) -> World {
    let mut w = World::new(Domain::new(lo, hi, boundary).unwrap());
    w.materials = Materials::uniform(1, E, NU, e, mu);
    w.pair = Some(PairGran::new(model));
    w.neighbor.settings = NeighborSettings {
        skin: 0.001,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w
}

/// Adds a primitive wall fix.
pub fn add_wall(w: &mut World, id: &str, model: ContactModel, shape: WallShape) {
    let wall = PrimitiveWall::new(id, model, 1, shape).unwrap();
    w.add_fix(Fix::new(id, 1, FixKind::WallGran(Box::new(wall))).unwrap())
        .unwrap();
}

/// Adds gravity g along −z.
pub fn add_gravity(w: &mut World, g: f64) {
    w.add_fix(Fix::gravity("grav", 1, g, DVec3::new(0.0, 0.0, -1.0)).unwrap())
        .unwrap();
}

/// Zero crossing by linear interpolation between (t0, y0) and (t1, y1).
pub fn crossing(t0: f64, y0: f64, t1: f64, y1: f64) -> f64 {
    t0 + (t1 - t0) * y0 / (y0 - y1)
}

/// Peak of the parabola through three equally spaced samples (spacing h, middle at t).
pub fn parabola_peak(t: f64, h: f64, y0: f64, y1: f64, y2: f64) -> (f64, f64) {
    let denom = y0 - 2.0 * y1 + y2;
    if denom == 0.0 {
        return (t, y1);
    }
    let s = 0.5 * (y0 - y2) / denom;
    (t + s * h, y1 - 0.25 * (y0 - y2) * s)
}

/// Relative difference.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}
