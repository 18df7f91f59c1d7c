//! Rigid clumps in the step (`rdem::multisphere`): a dumbbell of two overlapping spheres.
//!
//! - Tilted and dropped on a frictionless elastic floor, it hits with its lower sphere
//!   first. Rigid-body impulse theory gives the outcome of that impact: with the contact
//!   point c (from the centre of mass), normal n and the normal velocity u of the contact
//!   point before, the impulse is J = −(1 + e) u / (1/M + (c × n)·I⁻¹(c × n)), the
//!   centre of mass gains J n / M and the angular velocity I⁻¹(c × J n). The contact
//!   lasts a few hundred steps, during which the body turns a little; with the floor
//!   stiff the overlap is under 0.2 % of the radius and the outcome must match within
//!   0.1 % (measured: 1.5·10⁻⁴). The spheres of the body (they overlap by 20 % of a
//!   radius) are never a pair of the neighbor list, and keep the template's distance.
//! - Falling freely under gravity it does not start to turn, although its spheres'
//!   masses differ (gravity acts at the centre of mass), and its centre falls by ½ g t².

use crate::common;
use common::*;
use rdem::multisphere::{ClumpTemplate, MassSource, NewClump, Sphere};
use rdem::{
    Boundary, ContactModel, DVec3, Domain, Materials, NeighborSettings, PairGran, WallShape, World,
};

const R: f64 = 0.001;

/// A dumbbell: spheres of radius R and 0.8 R, centres 1.6 R apart.
fn dumbbell() -> ClumpTemplate {
    let spheres = [
        Sphere {
            x: DVec3::ZERO,
            r: R,
        },
        Sphere {
            x: DVec3::new(1.6 * R, 0.0, 0.0),
            r: 0.8 * R,
        },
    ];
    ClumpTemplate::new(&spheres, 1_000_000, 12345, MassSource::Density(RHO)).unwrap()
}

/// A world without integrating fixes (the clumps integrate themselves), frictionless.
fn world(e: f64, stiff: f64) -> World {
    world_in(DVec3::splat(-0.02), DVec3::splat(0.02), e, stiff)
}

/// [`world`] in the box `lo`–`hi`.
fn world_in(lo: DVec3, hi: DVec3, e: f64, stiff: f64) -> World {
    let mut w = World::new(Domain::new(lo, hi, [Boundary::Fixed; 3]).unwrap());
    w.materials = Materials::uniform(1, stiff, NU, e, 0.0);
    let model = ContactModel::hertz_history();
    w.pair = Some(PairGran::new(model));
    w.neighbor.settings = NeighborSettings {
        skin: 0.2 * R,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    w
}

/// Distance between the two spheres' centres.
fn span(w: &World) -> f64 {
    (w.particles.x[0] - w.particles.x[1]).length()
}

#[test]
fn tilted_dumbbell_first_impact_follows_impulse_theory() {
    let stiff = 2.0e10;
    let t = dumbbell();
    let mut w = world(1.0, stiff);
    let model = ContactModel::hertz_history();
    add_wall(
        &mut w,
        "floor",
        model,
        WallShape::Plane {
            axis: 2,
            pos: -0.01,
        },
    );
    // Tilted by 30° about y, the large sphere lowest, just above the floor.
    let q = glam::DQuat::from_rotation_y(-(30f64.to_radians()));
    let body_q = q * glam::DQuat::from_mat3(&t.axes);
    let v0 = DVec3::new(0.0, 0.0, -0.3);
    // Where the large sphere's centre goes for a centre of mass at the origin.
    let big = body_q * t.spheres[0].x;
    let small = body_q * t.spheres[1].x;
    assert!(big.z < small.z, "the large sphere must hang lowest");
    let x = DVec3::new(0.0, 0.0, -0.01 + R + 1e-5) - big;
    let tag = w
        .add_clump(
            &t,
            &NewClump {
                x,
                q: body_q,
                v: v0,
                omega: DVec3::ZERO,
                ty: 1,
                mask: 1,
            },
        )
        .unwrap();
    assert_eq!(tag, 1);
    let want_span = (t.spheres[0].x - t.spheres[1].x).length();
    let e_star = 1.0 / (2.0 * (1.0 - NU * NU) / stiff);
    let m = t.props.mass;
    let tc = hertz_tc(m, R, e_star, 0.3);
    let dm = hertz_delta_max(m, R, e_star, 0.3);
    assert!(dm < 2e-3 * R, "overlap {}", dm / R);
    w.set_timestep(tc / 200.0).unwrap();
    w.setup().unwrap();
    assert!(
        w.neighbor.list.partner.is_empty(),
        "a body's spheres are listed"
    );
    // The closed form, from the state just before the impact.
    let b0 = w.multisphere.as_ref().unwrap().bodies[0];
    let c = body_q * t.spheres[0].x - R * DVec3::Z;
    let n = DVec3::Z;
    let inertia = glam::DMat3::from_quat(b0.q)
        * glam::DMat3::from_diagonal(b0.moments)
        * glam::DMat3::from_quat(b0.q).transpose();
    let inv_i = inertia.inverse();
    let u = (b0.v + b0.omega().cross(c)).dot(n);
    let cn = c.cross(n);
    let j = -2.0 * u / (1.0 / m + cn.dot(inv_i * cn));
    let want_v = b0.v + j * n / m;
    let want_w = inv_i * (c.cross(j * n));
    let e0 = b0.kinetic_energy();
    let mut touched = false;
    for _ in 0..200_000 {
        w.advance().unwrap();
        assert!((span(&w) - want_span).abs() < 1e-12, "the body came apart");
        let low = w.particles.x[0].z - R + 0.01;
        let other = w.particles.x[1].z - 0.8 * R + 0.01;
        assert!(
            other > 0.0,
            "the upper sphere touched during the first impact"
        );
        if low < 0.0 {
            touched = true;
        } else if touched {
            break;
        }
    }
    assert!(touched);
    let b = w.multisphere.as_ref().unwrap().bodies[0];
    let dv = (b.v - want_v).length() / v0.length();
    let dw = (b.omega() - want_w).length() / want_w.length();
    assert!(dv < 1e-3, "velocity {} against {want_v} ({dv:e})", b.v);
    assert!(dw < 1e-3, "spin {} against {want_w} ({dw:e})", b.omega());
    // Elastic and frictionless: the kinetic energy is back.
    let e1 = b.kinetic_energy();
    let (k0, k1) = (e0.0 + e0.1, e1.0 + e1.1);
    assert!(((k1 - k0) / k0).abs() < 1e-3, "energy {k0} -> {k1}");
    // The spheres move with the body.
    let (_, v_big) = b.point(b.q.inverse() * (w.particles.x[0] - b.x));
    assert!((w.particles.v[0] - v_big).length() < 1e-12);
    assert!((w.particles.omega[1] - b.omega()).length() < 1e-12);
}

#[test]
fn gravity_acts_at_the_centre_of_mass() {
    let t = dumbbell();
    let mut w = world(0.5, 1e7);
    add_gravity(&mut w, 9.81);
    let x0 = DVec3::new(0.0, 0.0, 0.01);
    w.add_clump(
        &t,
        &NewClump {
            x: x0,
            q: glam::DQuat::from_rotation_z(0.4),
            v: DVec3::ZERO,
            omega: DVec3::ZERO,
            ty: 1,
            mask: 1,
        },
    )
    .unwrap();
    // The spheres' masses differ, and add up to the body's.
    let p = &w.particles;
    assert!((p.rmass[0] + p.rmass[1] - t.props.mass).abs() < 1e-15 * t.props.mass);
    assert!(p.rmass[0] > 1.5 * p.rmass[1]);
    let dt = 1e-5;
    w.set_timestep(dt).unwrap();
    w.setup().unwrap();
    let n = 1000;
    for _ in 0..n {
        w.advance().unwrap();
    }
    let b = w.multisphere.as_ref().unwrap().bodies[0];
    assert_eq!(b.angmom, DVec3::ZERO);
    let time = n as f64 * dt;
    let want = x0.z - 0.5 * 9.81 * time * time;
    assert!((b.x.z - want).abs() < 1e-12, "{} against {want}", b.x.z);
    assert!((b.v.z + 9.81 * time).abs() < 1e-12);
}

/// A dumbbell dropped flat (its axis horizontal) on a damped frictionless floor, against
/// LIGGGHTS 3.8 on the same case. The large sphere's bottom is lower, so it lands first
/// and the body bounces off turning. LIGGGHTS' contact takes the body's mass for m*;
/// with the sphere's own mass the damping is another and so is the rebound.
///
/// How the LIGGGHTS figures were got: `liggghts -in in.drop -var e 0.5 -var orient
/// template -var n 8000` on a script with this case (si units, E = 1e7, ν = 0.3,
/// e = 0.5, μ = 0, Hertz with tangential history, `fix wall/gran ... primitive zplane 0`,
/// gravity 9.81, dt = 1e-6, `fix particletemplate/multisphere ... nspheres 2 ntry 1000000
/// spheres 0 0 0 0.001 0.0016 0 0 0.0008`, `fix insert/pack ... vel constant 0 0 -0.5
/// orientation template particles_in_region 1`, `fix multisphere`, thermo of the spheres'
/// z and vz). The state at step 1 (inserted, one half kick) is this test's start: the
/// centre at z = 4.452581838 mm, vz = -0.500004905 m/s. At step 8001: the large sphere
/// at z = 1.363229372 mm with vz = 0.3165271457 m/s, the small one at vz = 0.1090014293
/// m/s, the clumps' translational energy (`compute ke/multisphere`) 4.775679506e-07 J.
/// LIGGGHTS' clump mass was 1.571545e-05 kg (its Monte Carlo estimate of the union).
#[test]
fn flat_dumbbell_bounces_as_in_liggghts() {
    let spheres = [
        Sphere {
            x: DVec3::ZERO,
            r: R,
        },
        Sphere {
            x: DVec3::new(1.6 * R, 0.0, 0.0),
            r: 0.8 * R,
        },
    ];
    let t = ClumpTemplate::new(&spheres, 1_000_000, 15485863, MassSource::Density(RHO)).unwrap();
    let mut w = world(0.5, 1e7);
    add_gravity(&mut w, 9.81);
    add_wall(
        &mut w,
        "floor",
        ContactModel::hertz_history(),
        WallShape::Plane { axis: 2, pos: 0.0 },
    );
    w.add_clump(
        &t,
        &NewClump {
            x: DVec3::new(0.0, 0.0, 4.452581838e-3),
            q: glam::DQuat::from_mat3(&t.axes),
            v: DVec3::new(0.0, 0.0, -0.500004905),
            omega: DVec3::ZERO,
            ty: 1,
            mask: 1,
        },
    )
    .unwrap();
    w.set_timestep(1e-6).unwrap();
    w.setup().unwrap();
    for _ in 0..8000 {
        w.advance().unwrap();
    }
    let p = &w.particles;
    let b = w.multisphere.as_ref().unwrap().bodies[0];
    let got = [p.x[0].z, p.v[0].z, p.v[1].z, b.kinetic_energy().0];
    let want = [1.363229372e-3, 0.3165271457, 0.1090014293, 4.775679506e-07];
    eprintln!("rdem {got:?}\nLIGGGHTS {want:?}");
    for (k, (g, l)) in got.iter().zip(want).enumerate() {
        assert!(
            ((g - l) / l).abs() < 0.01,
            "value {k}: {g} against LIGGGHTS' {l}"
        );
    }
}

/// The bodies of one run on a rayon pool of `threads`: 1200 dumbbells (2400 spheres, so
/// the force passes go parallel) on a lattice, turned at random, falling onto a floor and
/// onto each other for 3000 steps; their positions, velocities, orientations and angular
/// momenta as bits.
fn pile_bits(threads: usize) -> Vec<u64> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let t = dumbbell();
        let (lo, hi) = (
            DVec3::new(-0.03, -0.03, -0.02),
            DVec3::new(0.03, 0.03, 0.04),
        );
        let mut w = world_in(lo, hi, 0.5, 1e7);
        add_gravity(&mut w, 9.81);
        add_wall(
            &mut w,
            "floor",
            ContactModel::hertz_history(),
            WallShape::Plane {
                axis: 2,
                pos: -0.02,
            },
        );
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let a = 3.8 * R;
        for k in 0..1200 {
            let (i, j, l) = (k % 10, (k / 10) % 10, k / 100);
            let x = DVec3::new(
                -0.019 + a * (i as f64 + 0.5),
                -0.019 + a * (j as f64 + 0.5),
                -0.0175 + a * l as f64,
            );
            let axis = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
            let q = glam::DQuat::from_axis_angle(axis, 6.0 * rnd());
            let v = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5);
            let c = NewClump {
                x,
                q,
                v,
                omega: DVec3::ZERO,
                ty: 1,
                mask: 1,
            };
            w.add_clump(&t, &c).unwrap();
        }
        w.set_timestep(2e-6).unwrap();
        w.setup().unwrap();
        for _ in 0..3000 {
            w.advance().unwrap();
        }
        let ms = w.multisphere.as_ref().unwrap();
        // Only contacts turn a body (gravity acts at the centre of mass).
        let hit = ms.bodies.iter().filter(|b| b.angmom != DVec3::ZERO).count();
        assert!(hit > 300, "{hit} bodies touched another or the floor");
        ms.bodies
            .iter()
            .flat_map(|b| {
                let mut v = b.x.to_array().to_vec();
                v.extend(b.v.to_array());
                v.extend(b.q.to_array());
                v.extend(b.angmom.to_array());
                v
            })
            .map(f64::to_bits)
            .collect()
    })
}

/// The same bits on 1, 2 and 4 threads: a body's force and torque are summed over its
/// spheres in particle order, whatever the pool.
#[test]
fn clumps_do_not_depend_on_the_thread_count() {
    let one = pile_bits(1);
    assert_eq!(pile_bits(2), one);
    assert_eq!(pile_bits(4), one);
}

/// Two tilted, spinning dumbbells flying at each other along x in a box periodic in x
/// (12 mm long), their centres 5 mm apart; `shift` moves both along x before the start.
/// Returns the bodies after 3000 steps of 1 µs (they meet after about 1.5 ms and part).
fn periodic_collision(shift: f64) -> Vec<rdem::multisphere::RigidBody> {
    let t = dumbbell();
    let lo = DVec3::new(-0.006, -0.01, -0.01);
    let hi = DVec3::new(0.006, 0.01, 0.01);
    let faces = [Boundary::Periodic, Boundary::Fixed, Boundary::Fixed];
    let mut w = world_in(lo, hi, 0.5, 1e7);
    w.domain = Domain::new(lo, hi, faces).unwrap();
    let axes = glam::DQuat::from_mat3(&t.axes);
    for (x, v, q, omega) in [
        (
            DVec3::new(-0.0025, 2e-4, 0.0),
            DVec3::new(0.5, 0.0, 0.0),
            glam::DQuat::from_rotation_z(0.35) * axes,
            DVec3::new(0.0, 0.0, 30.0),
        ),
        (
            DVec3::new(0.0025, -2e-4, 1e-4),
            DVec3::new(-0.5, 0.0, 0.0),
            glam::DQuat::from_rotation_y(0.7) * axes,
            DVec3::new(10.0, -20.0, 0.0),
        ),
    ] {
        let c = NewClump {
            x: x + DVec3::new(shift, 0.0, 0.0),
            q,
            v,
            omega,
            ty: 1,
            mask: 1,
        };
        w.add_clump(&t, &c).unwrap();
    }
    w.set_timestep(1e-6).unwrap();
    w.setup().unwrap();
    for step in 0..3000 {
        w.advance().unwrap();
        // A sphere sits at its body's point, less whole box lengths along x only.
        let ms = w.multisphere.as_ref().unwrap();
        let p = &w.particles;
        let off = p.property(rdem::multisphere::bodies::OFFSET_PROP).unwrap();
        let body = p.property(rdem::multisphere::bodies::BODY_PROP).unwrap();
        for i in 0..p.nlocal() {
            let b = &ms.bodies[ms.body_of(p.props[body.0].data[i]).unwrap()];
            let d = b.q * DVec3::from_slice(&p.props[off.0].data[3 * i..3 * i + 3]);
            let gap = b.x + d - p.x[i];
            let n = (gap.x / 0.012).round();
            assert!(
                (gap - DVec3::new(n * 0.012, 0.0, 0.0)).length() < 1e-12,
                "step {step}, shift {shift}: sphere {i} off its body: {gap}, x {}, body {}, d {d}",
                p.x[i],
                b.x
            );
            assert!(p.x[i].x >= lo.x - 1e-3 && p.x[i].x < hi.x + 1e-3);
        }
    }
    w.multisphere.unwrap().bodies
}

/// Clumps cross a periodic face whole: the two dumbbells of [`periodic_collision`] meet
/// in the middle of the box, and again (shifted by half the box) right on the periodic
/// face, where each touches the other's image. The two runs must agree to round-off
/// (1e-9 relative; the coordinates differ, so the last bits may), and the collision must
/// have happened (each centre of mass's x velocity changed by more than 10 %).
#[test]
fn clumps_collide_across_a_periodic_face() {
    let inside = periodic_collision(0.0);
    let across = periodic_collision(0.006);
    for (a, b) in inside.iter().zip(&across) {
        assert!((a.v.x.abs() - 0.5).abs() > 0.05, "no collision: {}", a.v);
        assert!((b.x - a.x - DVec3::new(0.006, 0.0, 0.0)).length() < 1e-12);
        assert!(
            (b.v - a.v).length() < 1e-9 * a.v.length(),
            "{} {}",
            a.v,
            b.v
        );
        let l = a.angmom.length();
        assert!(
            (b.angmom - a.angmom).length() < 1e-9 * l,
            "{} {}",
            a.angmom,
            b.angmom
        );
        assert!((b.q.dot(a.q).abs() - 1.0).abs() < 1e-12);
    }
}
