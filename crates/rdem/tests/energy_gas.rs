//! A frictionless elastic gas in a fully periodic box conserves total energy.
//!
//! 125 polydisperse spheres with random velocities collide through the elastic Hertz law
//! (e = 1, μ = 0, no gravity, no walls). The Hertz force derives from the potential
//! U = 8/15 E* √R* δ^{5/2}, so kinetic plus elastic energy is a constant of motion, and
//! velocity Verlet (symplectic) keeps its error bounded. Over 10⁵ steps at dt = t_c/50 of
//! the shortest possible collision (smallest spheres, largest closing speed) the total
//! energy must stay within 1e-4 of its initial value. The
//! periodic images (ghosts) carry every collision across the faces, so this also checks
//! that ghost forces reach their owners exactly once.

use crate::common;
use common::*;
use rdem::{Boundary, ContactModel, DVec3, NewParticle, World};

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        // splitmix64
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn total_energy(w: &World) -> f64 {
    let p = &w.particles;
    let n = p.nlocal();
    let (et, er) = p.kinetic_energy();
    let prd = w.domain.prd();
    let mut u = 0.0;
    for i in 0..n {
        for j in i + 1..n {
            let mut d = p.x[i] - p.x[j];
            for a in 0..3 {
                d[a] -= prd[a] * (d[a] / prd[a]).round();
            }
            let delta = p.radius[i] + p.radius[j] - d.length();
            if delta > 0.0 {
                let rs = p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]);
                u += 8.0 / 15.0 * e_star() * rs.sqrt() * delta.powf(2.5);
            }
        }
    }
    et + er + u
}

#[test]
fn periodic_elastic_gas_conserves_energy() {
    let l = 0.06;
    let mut w = world(
        DVec3::ZERO,
        DVec3::splat(l),
        [Boundary::Periodic; 3],
        ContactModel::hertz_history(),
        1.0,
        0.0,
    );
    let mut rng = Rng(7);
    let n = 5;
    let h = l / n as f64;
    let v = 0.5;
    for a in 0..n {
        for b in 0..n {
            for c in 0..n {
                let x = DVec3::new(a as f64 + 0.5, b as f64 + 0.5, c as f64 + 0.5) * h;
                let r = 0.002 + 0.002 * rng.next();
                let vel =
                    DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 2.0 * v;
                w.add_particle(&NewParticle::at(x, r, RHO).with_v(vel))
                    .unwrap();
            }
        }
    }
    // Step from the shortest collision: the smallest spheres at the largest closing speed.
    let tc = hertz_tc(0.5 * mass(0.002), 0.001, e_star(), 2.0 * 3f64.sqrt() * v);
    w.set_timestep(tc / 50.0).unwrap();
    w.neighbor.settings.skin = 0.002;
    w.setup().unwrap();
    let e0 = total_energy(&w);
    let mut worst: f64 = 0.0;
    let mut collisions_seen = false;
    for _ in 0..100 {
        for _ in 0..1000 {
            w.advance().unwrap();
        }
        let e = total_energy(&w);
        worst = worst.max(rel(e, e0));
        collisions_seen |= w
            .particles
            .v
            .iter()
            .any(|v| v.length() > 1.5 * 0.5 * 3f64.sqrt());
    }
    assert!(worst < 1e-4, "energy drifted by {worst:e}");
    // The gas really collided: velocities were redistributed.
    assert!(collisions_seen || w.neighbor.nbuilds > 10);
    assert_eq!(w.particles.nlocal(), 125);
    eprintln!(
        "energy drift over 1e5 steps: {worst:e}, {} neighbor builds",
        w.neighbor.nbuilds
    );
}
