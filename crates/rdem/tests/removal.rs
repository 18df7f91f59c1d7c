//! Removing particles in the middle of a run (`World::remove_particles`, and the
//! deferred `World::remove_at_reneighbor` of `fix massflow/mesh delete_atoms`) leaves the
//! others exactly where they would be without the removed one.

use crate::common;
use common::*;
use rdem::{Boundary, ContactModel, DVec3, NewParticle, WallShape, World};

const R: f64 = 0.002;

/// A pile of spheres settling on a floor with friction (contact and wall history), plus
/// one far away (the last, or with `far_first` the first); `remove` (if any) takes it
/// out at step 300 by `how`, once the pile has landed and its contacts have tangential
/// springs (at step 200 it was still falling, and a removal that lost every contact
/// history passed). Returns the states (x, v, ω) of the pile every step from 250 to 500. There are no ghosts (fixed walls, one rank), so
/// the neighbor list holds its histories by index until something saves them.
fn run(remove: Option<fn(&mut World, usize)>, far_first: bool) -> Vec<Vec<[DVec3; 3]>> {
    let model = ContactModel::hertz_history();
    let lo = DVec3::new(-0.05, -0.05, -0.01);
    let hi = DVec3::new(0.05, 0.05, 0.1);
    let mut w = world(lo, hi, [Boundary::Fixed; 3], model, 0.5, 0.4);
    add_wall(
        &mut w,
        "floor",
        model,
        WallShape::Plane { axis: 2, pos: 0.0 },
    );
    add_gravity(&mut w, 9.81);
    let far = DVec3::new(0.04, 0.04, 0.05);
    if far_first {
        w.add_particle(&NewParticle::at(far, R, RHO)).unwrap();
    }
    let mut n = 0;
    for k in 0..4 {
        for j in 0..3 {
            for i in 0..3 {
                let x = DVec3::new(
                    (i as f64 - 1.0) * 2.1 * R + 1e-4 * k as f64,
                    (j as f64 - 1.0) * 2.1 * R,
                    R + k as f64 * 2.05 * R,
                );
                w.add_particle(&NewParticle::at(x, R, RHO)).unwrap();
                n += 1;
            }
        }
    }
    if !far_first {
        w.add_particle(&NewParticle::at(far, R, RHO)).unwrap();
    }
    // The pile's tags, and the far one's.
    let (pile, far_tag) = if far_first {
        (2..=n + 1, 1)
    } else {
        (1..=n, n + 1)
    };
    w.set_timestep(2e-5).unwrap();
    w.setup().unwrap();
    let mut out = Vec::new();
    for step in 1..=500 {
        if step == 300 {
            if let Some(f) = remove {
                let p = &w.particles;
                let i = (0..p.nlocal()).find(|&i| p.tag[i] as usize == far_tag);
                f(&mut w, i.expect("the far particle"));
            }
        }
        w.advance().unwrap();
        if step >= 250 {
            let p = &w.particles;
            // The pile by tag (indices shift when the far one goes).
            let mut s: Vec<(u64, [DVec3; 3])> = (0..p.nlocal())
                .filter(|&i| pile.contains(&(p.tag[i] as usize)))
                .map(|i| (p.tag[i], [p.x[i], p.v[i], p.omega[i]]))
                .collect();
            s.sort_by_key(|e| e.0);
            out.push(s.into_iter().map(|e| e.1).collect());
        }
    }
    out
}

#[test]
fn removing_a_particle_leaves_the_others_alone() {
    for far_first in [false, true] {
        removing_leaves_the_others_alone(far_first);
    }
}

/// [`removing_a_particle_leaves_the_others_alone`], the far particle last or first (its
/// removal then shifts every other index: rdem once lost the histories that way).
fn removing_leaves_the_others_alone(far_first: bool) {
    let keep = run(None, far_first);
    let now: fn(&mut World, usize) = |w, i| {
        let mut r = vec![false; w.particles.nlocal()];
        r[i] = true;
        assert_eq!(w.remove_particles(&r), 1);
    };
    let later: fn(&mut World, usize) = |w, i| w.remove_at_reneighbor(i).unwrap();
    for (name, how) in [("remove_particles", now), ("remove_at_reneighbor", later)] {
        let gone = run(Some(how), far_first);
        assert_eq!(keep.len(), gone.len());
        for (step, (a, b)) in keep.iter().zip(&gone).enumerate() {
            assert_eq!(a.len(), b.len());
            for (s, t) in a.iter().zip(b) {
                assert!(
                    s == t,
                    "{name} (far one first: {far_first}): step {}: {s:?} vs {t:?}",
                    step + 250
                );
            }
        }
    }
}
