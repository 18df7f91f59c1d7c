//! Lees–Edwards image counts (`rdem::shear`): a free particle's unwrapped position
//! x + n ⊙ L + n_y d x̂ (d the offset) moves at its own velocity through a wrap across a
//! y face and through the offset's wraps by L_x, which the step makes up for by adding
//! k n_y to n_x. A rigid clump's spheres are placed from this relation, so a jump in it
//! would throw them a box length away between two re-neighborings.

use rdem::shear::Shear;
use rdem::{Boundary, DVec3, Domain, Fix, FixKind, Materials, NewParticle, World};

#[test]
fn the_unwrapped_position_is_continuous_through_the_offsets_wraps() {
    let l = 0.02;
    let mut w =
        World::new(Domain::new(DVec3::ZERO, DVec3::splat(l), [Boundary::Periodic; 3]).unwrap());
    w.materials = Materials::uniform(1, 1e7, 0.3, 0.5, 0.5);
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    let dt = 1e-5;
    w.set_timestep(dt).unwrap();
    // γ̇ L_y dt = 500 · 0.02 · 1e-5 = 1e-4 per step: the offset wraps every 200 steps.
    w.domain.shear = Some(Shear::new(500.0));
    let v = DVec3::new(0.3, -1.0, 0.0);
    let x0 = DVec3::new(0.01, 0.001, 0.01);
    w.add_particle(&NewParticle::at(x0, 0.001, 2500.0).with_v(v))
        .unwrap();
    let mut wraps = 0;
    let mut last = 0.0;
    for step in 1..=700 {
        w.advance().unwrap();
        let s = w.domain.shear.unwrap();
        if s.offset < last {
            wraps += 1;
        }
        last = s.offset;
        let p = &w.particles;
        let n = p.image[0].get();
        let u = p.x[0]
            + DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) * l
            + DVec3::X * (n[1] as f64 * s.offset);
        let want = x0 + DVec3::new(v.x, v.y, 0.0) * (step as f64 * dt);
        assert!(
            (u - want).length() < 1e-12,
            "step {step}: unwrapped {u} against {want} (image {n:?}, offset {})",
            s.offset
        );
    }
    // It crossed the lower face (after 100 steps) and the offset wrapped three times.
    assert_eq!(w.particles.image[0].get()[1], -1);
    assert_eq!(wraps, 3);
}
