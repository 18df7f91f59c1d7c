//! Oblique impacts on a plane wall in the gross-sliding regime.
//!
//! A sphere hits the floor at angle θ from the normal with speed v. If the contact slides
//! for the whole impact (tan θ ≥ 3.5 μ (1+e)), the friction impulse is μ times the normal
//! impulse m(1+e) v cos θ, so rigid-body impulse theory gives the tangential restitution
//! e_t = v_t'/v_t = 1 − μ(1+e)/tan θ and the spin |ω'| = 2.5 μ (1+e) v cos θ / R
//! (about +y for motion along +x on a floor below). The lever arm is the contact radius
//! r − δ/2, so the wall is made stiff (E = 5 GPa) to keep δ/R below 0.2 %; with that the
//! relations must hold within 0.5 %. The normal restitution e is the measured one (exactly
//! 1 for the elastic case; `limitForce on` keeps the normal force repulsive so that the
//! normal impulse is exactly m(1+e)v cos θ).
//!
//! With damping, the damped cases switch `tangential_damping off`: in the LIGGGHTS model
//! the tangential dashpot acts whenever the spring alone is below the Coulomb limit, and
//! early in an impact the damped normal force (dominated by γ_n v_n) makes that limit
//! large while the spring is still short, so spring plus dashpot exceed μ F_n for a few
//! steps and the friction impulse comes out about 1.6 % above μ times the normal impulse
//! (e = 0.6, μ = 0.2, tan θ = 2.5). That is the reference's behaviour, kept on purpose.
//! For strong damping (e = 0.3) the spring needs a noticeable part of the impact to load
//! up to the Coulomb limit, during which friction is below μ F_n, and the spin comes out
//! 0.8 % low; the checks use e ≥ 0.6.

use crate::common;
use common::*;
use rdem::{Boundary, ContactModel, DVec3, Materials, NewParticle, WallShape};

const R: f64 = 0.005;
const V: f64 = 0.2;
const STIFF: f64 = 5.0e9;

/// Returns (measured e_n, e_t, ω_y) for restitution `e`, friction `mu`, tan θ.
fn impact(e: f64, mu: f64, tan_theta: f64) -> (f64, f64, f64) {
    let mut model = ContactModel::hertz_history();
    model.flags.limit_force = true;
    model.flags.tangential_damping = e == 1.0;
    let lo = DVec3::new(-1.0, -0.1, 0.0);
    let hi = DVec3::new(1.0, 0.1, 0.1);
    let mut w = world(lo, hi, [Boundary::Fixed; 3], model, e, mu);
    w.materials = Materials::uniform(1, STIFF, NU, e, mu);
    add_wall(
        &mut w,
        "floor",
        model,
        WallShape::Plane { axis: 2, pos: 0.0 },
    );
    let theta = tan_theta.atan();
    let v0 = DVec3::new(V * theta.sin(), 0.0, -V * theta.cos());
    w.add_particle(&NewParticle::at(DVec3::new(0.0, 0.0, R + 1e-4), R, RHO).with_v(v0))
        .unwrap();
    let e_star = 1.0 / (2.0 * (1.0 - NU * NU) / STIFF);
    let tc = hertz_tc(mass(R), R, e_star, V * theta.cos());
    let dm = hertz_delta_max(mass(R), R, e_star, V * theta.cos());
    assert!(
        dm / R < 2e-3,
        "overlap too large for the rigid-body comparison: {}",
        dm / R
    );
    w.set_timestep(tc / 100.0).unwrap();
    w.setup().unwrap();
    let mut touched = false;
    for _ in 0..1_000_000 {
        w.advance().unwrap();
        let gap = w.particles.x[0].z - R;
        if gap < 0.0 {
            touched = true;
        } else if touched && gap > 0.0 {
            break;
        }
    }
    assert!(touched);
    let p = &w.particles;
    (p.v[0].z / (V * theta.cos()), p.v[0].x / v0.x, p.omega[0].y)
}

fn check(e: f64, mu: f64, tan_theta: f64) {
    let (en, et, wy) = impact(e, mu, tan_theta);
    let theta = tan_theta.atan();
    assert!(
        tan_theta >= 3.5 * mu * (1.0 + en),
        "not in the gross-sliding regime"
    );
    let et_expected = 1.0 - mu * (1.0 + en) / tan_theta;
    let w_expected = 2.5 * mu * (1.0 + en) * V * theta.cos() / R;
    assert!(
        rel(et, et_expected) < 0.005,
        "e {e} mu {mu} tan {tan_theta}: e_t {et} vs {et_expected}"
    );
    assert!(
        rel(wy, w_expected) < 0.005,
        "e {e} mu {mu} tan {tan_theta}: omega {wy} vs {w_expected}"
    );
}

#[test]
fn elastic_oblique_impact_gross_sliding() {
    check(1.0, 0.1, 2.0);
    check(1.0, 0.3, 3.0);
}

#[test]
fn damped_oblique_impact_gross_sliding() {
    check(0.6, 0.2, 2.5);
    check(0.8, 0.1, 1.5);
}

#[test]
fn normal_restitution_with_limit_force_is_measured() {
    // The elastic case returns exactly the impact speed.
    let (en, _, _) = impact(1.0, 0.1, 2.0);
    assert!(rel(en, 1.0) < 1e-4, "elastic normal restitution {en}");
}
