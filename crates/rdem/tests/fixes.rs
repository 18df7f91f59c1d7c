//! Time integration and the force fixes, each on a group.
//!
//! - `nve/sphere` + `gravity`: velocity Verlet is exact for constant acceleration, so a free
//!   particle follows z = z₀ + v₀t − g t²/2 to round-off; a constant torque spins a sphere
//!   up at τ/(0.4 m r²).
//! - `viscous γ`: F = −γ v with the force evaluated at the half-step velocity (as in
//!   LAMMPS), so with a = γ dt/m the step maps the half-step velocity by (1 − a) and
//!   v_n = v₀ (1 − a/2)² (1 − a)^{n−1} exactly; that approaches v₀ exp(−γt/m) with a
//!   relative error n a²/2 (1e-3 here).
//! - `addforce`, `setforce` (with NULL components) and `freeze` act only on their group.

use crate::common;
use common::*;
use rdem::{Boundary, ContactModel, DVec3, Fix, FixKind, NewParticle, World};

const R: f64 = 0.002;

fn empty_world() -> World {
    let mut w = World::new(
        rdem::Domain::new(
            DVec3::splat(-10.0),
            DVec3::splat(10.0),
            [Boundary::Fixed; 3],
        )
        .unwrap(),
    );
    w.materials = rdem::Materials::uniform(2, E, NU, 0.5, 0.5);
    w.pair = Some(rdem::PairGran::new(ContactModel::hertz_history()));
    w.set_timestep(1e-4).unwrap();
    w
}

#[test]
fn free_fall_is_exact_and_only_for_the_group() {
    let mut w = empty_world();
    // Group bit 2 ("falling") holds particle 1 only.
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(Fix::gravity("g", 2, 9.81, DVec3::new(0.0, 0.0, -2.0)).unwrap())
        .unwrap();
    let mut a =
        NewParticle::at(DVec3::new(0.0, 0.0, 5.0), R, RHO).with_v(DVec3::new(0.1, 0.0, 1.0));
    a.mask = 1 | 2;
    w.add_particle(&a).unwrap();
    w.add_particle(
        &NewParticle::at(DVec3::new(1.0, 0.0, 5.0), R, RHO).with_v(DVec3::new(0.0, 0.0, 1.0)),
    )
    .unwrap();
    w.run(1000).unwrap();
    let t = 0.1;
    let p = &w.particles;
    let z = 5.0 + 1.0 * t - 0.5 * 9.81 * t * t;
    assert!((p.x[0].z - z).abs() < 1e-12, "{} vs {z}", p.x[0].z);
    assert!((p.v[0].z - (1.0 - 9.81 * t)).abs() < 1e-12);
    assert!((p.x[0].x - 0.01).abs() < 1e-12);
    // Not in the gravity group: straight line.
    assert!((p.x[1].z - 5.1).abs() < 1e-12);
    assert_eq!(p.v[1].z, 1.0);
}

#[test]
fn constant_torque_spins_up_a_sphere() {
    let mut w = empty_world();
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_particle(&NewParticle::at(DVec3::ZERO, R, RHO))
        .unwrap();
    w.setup().unwrap();
    // No fix sets a torque directly; check the integrator's rotational half-kicks instead.
    let m = mass(R);
    let inertia = 0.4 * m * R * R;
    w.particles.torque[0] = DVec3::new(0.0, 0.0, 1e-6);
    rdem::fix::integrate::final_integrate(&mut w.particles, 1, 1e-4);
    rdem::fix::integrate::initial_integrate(&mut w.particles, 1, 1e-4);
    let expected = 1e-6 / inertia * 1e-4;
    assert!(rel(w.particles.omega[0].z, expected) < 1e-12);
}

#[test]
fn viscous_damping_decays_exponentially() {
    let mut w = empty_world();
    let m = mass(R);
    let gamma = 1e-3 * m / 1e-4; // γ dt / m = 1e-3
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(Fix::new("visc", 1, FixKind::Viscous { gamma }).unwrap())
        .unwrap();
    w.add_particle(&NewParticle::at(DVec3::ZERO, R, RHO).with_v(DVec3::new(1.0, 0.0, 0.0)))
        .unwrap();
    w.run(2000).unwrap();
    let a: f64 = 1e-3;
    let discrete = (1.0 - 0.5 * a).powi(2) * (1.0 - a).powi(1999);
    assert!(
        rel(w.particles.v[0].x, discrete) < 1e-12,
        "{} vs {discrete}",
        w.particles.v[0].x
    );
    let continuous = (-gamma * 0.2 / m).exp();
    assert!(rel(w.particles.v[0].x, continuous) < 1.1e-3);
}

#[test]
fn addforce_setforce_freeze_act_on_their_groups() {
    let mut w = empty_world();
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(
        Fix::new(
            "push",
            2,
            FixKind::AddForce {
                force: DVec3::new(1e-3, 0.0, 0.0),
            },
        )
        .unwrap(),
    )
    .unwrap();
    w.add_fix(
        Fix::new(
            "hold",
            4,
            FixKind::SetForce {
                force: [None, Some(2e-3), None],
            },
        )
        .unwrap(),
    )
    .unwrap();
    w.add_fix(Fix::new("stop", 8, FixKind::Freeze).unwrap())
        .unwrap();
    for (k, mask) in [(0, 1 | 2), (1, 1 | 2 | 4), (2, 1 | 2 | 8), (3, 1)] {
        let mut p = NewParticle::at(DVec3::new(k as f64, 0.0, 0.0), R, RHO)
            .with_omega(DVec3::new(0.0, 0.0, 1.0));
        p.mask = mask;
        w.add_particle(&p).unwrap();
    }
    w.run(100).unwrap();
    let p = &w.particles;
    let t = 0.01;
    let m = mass(R);
    assert!(rel(p.v[0].x, 1e-3 / m * t) < 1e-12);
    assert_eq!(p.v[0].y, 0.0);
    // setforce replaces y (2e-3) and keeps the added x.
    assert!(rel(p.v[1].x, 1e-3 / m * t) < 1e-12);
    assert!(rel(p.v[1].y, 2e-3 / m * t) < 1e-12);
    // freeze comes last: no force and no torque remain.
    assert_eq!(p.v[2].x, 0.0);
    assert_eq!(p.omega[2].z, 1.0);
    assert_eq!(p.v[3], DVec3::ZERO);
    assert_eq!(p.x[3].x, 3.0);
}

#[test]
fn fixes_refuse_bad_numbers() {
    assert!(Fix::new("v", 1, FixKind::Viscous { gamma: -1.0 }).is_err());
    assert!(Fix::new("v", 1, FixKind::Viscous { gamma: f64::NAN }).is_err());
    assert!(Fix::gravity("g", 1, 9.81, DVec3::ZERO).is_err());
    assert!(Fix::new(
        "a",
        1,
        FixKind::AddForce {
            force: DVec3::new(f64::INFINITY, 0.0, 0.0)
        }
    )
    .is_err());
    assert!(Fix::new(
        "s",
        1,
        FixKind::SetForce {
            force: [Some(f64::NAN), None, None]
        }
    )
    .is_err());
    let mut w = empty_world();
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    assert!(w
        .add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .is_err());
    assert!(w.remove_fix("nve"));
    assert!(!w.remove_fix("nve"));
}

/// `fix adapt`-style growth between rebuilds: two resting spheres 3 skins apart grow
/// until they overlap. No particle moves, so only the growth counted against the skin
/// can trigger the rebuild that brings the pair into the list; the contact force must
/// appear at the first step the spheres overlap, with the Hertz magnitude.
#[test]
fn radius_growth_between_rebuilds_is_never_missed() {
    let lo = DVec3::splat(-0.1);
    let hi = DVec3::splat(0.1);
    let mut w = common::world(
        lo,
        hi,
        [Boundary::Fixed; 3],
        ContactModel::hertz_history(),
        0.9,
        0.0,
    );
    w.fixes.clear(); // no integration: the spheres stay put
    w.set_timestep(1e-6).unwrap();
    let r0 = 0.01;
    let skin = w.neighbor.settings.skin;
    let gap = 3.0 * skin;
    w.add_particle(&NewParticle::at(DVec3::ZERO, r0, common::RHO))
        .unwrap();
    w.add_particle(&NewParticle::at(
        DVec3::new(2.0 * r0 + gap, 0.0, 0.0),
        r0,
        common::RHO,
    ))
    .unwrap();
    w.setup().unwrap();
    let builds0 = w.neighbor.nbuilds;
    let dr = gap / 2.0 / 40.0; // the gap closes after 40 growth events
    let mut r = r0;
    for k in 1..=50 {
        r += dr;
        w.set_radii(&[r, r]).unwrap();
        w.advance().unwrap();
        let overlap = 2.0 * r - (2.0 * r0 + gap);
        let f = w.particles.f[0].x;
        if overlap > 1e-12 {
            let r_star = r / 2.0;
            let expect = 4.0 / 3.0 * common::e_star() * r_star.sqrt() * overlap.powf(1.5);
            assert!(
                (-f - expect).abs() < 1e-9 * expect + 1e-12,
                "step {k}: force {f}, Hertz {expect}"
            );
        } else {
            assert_eq!(f, 0.0, "step {k}: force before contact");
        }
    }
    assert!(
        w.neighbor.nbuilds > builds0,
        "growth must trigger a rebuild"
    );
}
