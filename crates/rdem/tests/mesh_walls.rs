//! Triangle-mesh walls against primitive planes and the Hertz law at edges and corners.

use crate::common;
use common::*;
use rdem::mesh::TriMesh;
use rdem::wall::{MeshSurface, MeshWall};
use rdem::{Boundary, ContactModel, DVec3, Fix, FixKind, NewParticle, WallShape, World};

const R: f64 = 0.002;

/// A mesh wall of `tris` (material type 1).
fn add_mesh(w: &mut World, model: ContactModel, tris: &[[DVec3; 3]]) {
    let (mesh, _) = TriMesh::from_triangles(tris, 1e-12, false).unwrap();
    let k = w.add_mesh(MeshSurface::new("cad", mesh, 1));
    let wall = MeshWall::new("mw", model, vec![k]).unwrap();
    w.add_fix(Fix::new("mw", 1, FixKind::MeshWall(Box::new(wall))).unwrap())
        .unwrap();
}

/// The floor z = 0 over −L..L in x and y as `n` × `n` squares of two triangles each
/// (every square split along a diagonal, alternating, so edges and corners are shared by
/// up to eight triangles).
fn floor(n: usize, l: f64) -> Vec<[DVec3; 3]> {
    let h = 2.0 * l / n as f64;
    let p = |i: usize, j: usize| DVec3::new(-l + i as f64 * h, -l + j as f64 * h, 0.0);
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            if (i + j) % 2 == 0 {
                t.push([a, b, c]);
                t.push([a, c, d]);
            } else {
                t.push([a, b, d]);
                t.push([b, c, d]);
            }
        }
    }
    t
}

/// One sphere launched at `v0` with spin `w0` from `x0` onto the floor, with gravity, for
/// `steps` steps, against a primitive plane (`mesh` false) or the meshed floor; returns
/// the trajectory of (x, v, ω, f) at every step.
fn run(mesh: bool, x0: DVec3, v0: DVec3, w0: DVec3, steps: usize) -> Vec<[DVec3; 4]> {
    let model = ContactModel::hertz_history();
    let lo = DVec3::new(-0.05, -0.05, -0.01);
    let hi = DVec3::new(0.05, 0.05, 0.05);
    let mut w = world(lo, hi, [Boundary::Fixed; 3], model, 0.5, 0.4);
    if mesh {
        add_mesh(&mut w, model, &floor(8, 0.04));
    } else {
        add_wall(
            &mut w,
            "floor",
            model,
            WallShape::Plane { axis: 2, pos: 0.0 },
        );
    }
    add_gravity(&mut w, 9.81);
    let mut np = NewParticle::at(x0, R, RHO).with_v(v0);
    np.omega = w0;
    w.add_particle(&np).unwrap();
    w.set_timestep(2e-6).unwrap();
    w.setup().unwrap();
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        w.advance().unwrap();
        let p = &w.particles;
        out.push([p.x[0], p.v[0], p.omega[0], p.f[0]]);
    }
    out
}

/// A sphere bouncing, sliding and rolling over a floor of 128 triangles (crossing shared
/// edges and corners of the triangulation) moves exactly as over the primitive plane
/// z = 0: position, velocity, spin and force equal at every step within 1e-9 (relative to
/// the largest value of each).
#[test]
fn meshed_floor_equals_the_primitive_plane() {
    let x0 = DVec3::new(-0.015, -0.012, R + 0.0001);
    let v0 = DVec3::new(0.6, 0.45, -0.05);
    let w0 = DVec3::new(0.0, 30.0, -20.0);
    let a = run(false, x0, v0, w0, 20000);
    let b = run(true, x0, v0, w0, 20000);
    let scale: [f64; 4] = [0, 1, 2, 3].map(|k| {
        a.iter()
            .map(|s| s[k].abs().max_element())
            .fold(0.0, f64::max)
    });
    let mut contacts = 0;
    for (s, (pa, pb)) in a.iter().zip(&b).enumerate() {
        if pa[3].z > 0.0 {
            contacts += 1;
        }
        for k in 0..4 {
            let d = (pa[k] - pb[k]).abs().max_element();
            assert!(
                d <= 1e-9 * scale[k],
                "step {s}, quantity {k}: plane {} mesh {}",
                pa[k],
                pb[k]
            );
        }
    }
    // The sphere must have been on the floor most of the time, and travelled across
    // several triangles.
    assert!(contacts > 5000, "{contacts} steps in contact");
    let travel = (a.last().unwrap()[0] - x0).truncate().length();
    assert!(travel > 0.01, "travelled {travel}");
}

/// Hertz at a corner and at an edge: a sphere pressed onto the apex of a pyramid (a
/// corner shared by four triangles) or onto a ridge (an edge shared by two) feels one
/// contact, the sphere–wall Hertz force 4/3 E* √(r δ) δ along the line from the corner or
/// edge to its centre.
#[test]
fn corner_and_edge_give_one_hertz_contact() {
    let model = ContactModel::hertz_history();
    let apex = DVec3::new(0.0, 0.0, 0.01);
    let base = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let pyramid = vec![
        [base(-0.01, -0.01), base(0.01, -0.01), apex],
        [base(0.01, -0.01), base(0.01, 0.01), apex],
        [base(0.01, 0.01), base(-0.01, 0.01), apex],
        [base(-0.01, 0.01), base(-0.01, -0.01), apex],
    ];
    let ridge = vec![
        [
            base(-0.01, -0.01),
            base(0.01, -0.01),
            DVec3::new(0.01, 0.0, 0.01),
        ],
        [
            base(-0.01, -0.01),
            DVec3::new(0.01, 0.0, 0.01),
            DVec3::new(-0.01, 0.0, 0.01),
        ],
        [
            base(0.01, 0.01),
            base(-0.01, 0.01),
            DVec3::new(-0.01, 0.0, 0.01),
        ],
        [
            base(0.01, 0.01),
            DVec3::new(-0.01, 0.0, 0.01),
            DVec3::new(0.01, 0.0, 0.01),
        ],
    ];
    // Centres at distance r − δ from the apex / ridge, off the symmetry line.
    let delta = 2e-5;
    let dir = DVec3::new(0.2, 0.1, 1.0).normalize();
    let dir_r = DVec3::new(0.0, 0.15, 1.0).normalize();
    for (tris, contact, dir) in [
        (pyramid, apex, dir),
        (ridge, DVec3::new(0.003, 0.0, 0.01), dir_r),
    ] {
        let lo = DVec3::splat(-0.05);
        let hi = DVec3::splat(0.05);
        let mut w = world(lo, hi, [Boundary::Fixed; 3], model, 0.5, 0.4);
        add_mesh(&mut w, model, &tris);
        let x = contact + (R - delta) * dir;
        w.add_particle(&NewParticle::at(x, R, RHO)).unwrap();
        w.set_timestep(1e-7).unwrap();
        w.setup().unwrap();
        let f = w.particles.f[0];
        let want = 4.0 / 3.0 * e_star_wall() * (R * delta).sqrt() * delta;
        assert!(rel(f.length(), want) < 1e-9, "force {f}, want {want}");
        assert!(
            (f.normalize() - dir).length() < 1e-9,
            "direction {f} vs {dir}"
        );
    }
}

/// E* of a particle against a wall of the same material.
fn e_star_wall() -> f64 {
    1.0 / (2.0 * (1.0 - NU * NU) / E)
}

/// One contact per flat surface: a sphere over the corner (h, h) of a square hole in the
/// floor z = 0 (|x|, |y| < h cut out; eight triangles) overlaps both rim edges that meet
/// there, edges of two different but coplanar triangles. It feels only the deeper one —
/// the sphere–line Hertz force 4/3 E* √(r δ) δ along the line from that edge to its
/// centre, within 1e-9 — as LIGGGHTS counts one contact per coplanar neighbourhood. With
/// the floor folded up by 1° along the diagonal y = x through that corner, the folded
/// side (which the sphere now touches on a face) and the edge x = h both count; with
/// `curvature 2` (degrees) the two sides are one surface again and the deeper counts.
#[test]
fn a_flat_surface_touches_a_sphere_once() {
    let model = ContactModel::hertz_history();
    let h = 0.004;
    let l = 0.02;
    // Triangles on the side y <= x stay at z = 0; the side y >= x rises by tan(fold).
    let floor = |fold: f64| {
        let p = |x: f64, y: f64| DVec3::new(x, y, (y - x).max(0.0) * fold.tan());
        vec![
            [p(-l, -l), p(l, -l), p(h, -h)],
            [p(-l, -l), p(h, -h), p(-h, -h)],
            [p(l, -l), p(l, l), p(h, h)],
            [p(l, -l), p(h, h), p(h, -h)],
            [p(l, l), p(-l, l), p(-h, h)],
            [p(l, l), p(-h, h), p(h, h)],
            [p(-l, l), p(-l, -l), p(-h, -h)],
            [p(-l, l), p(-h, -h), p(-h, h)],
        ]
    };
    // Over the hole near its corner: 60 µm from the edge x = h, 30 µm from y = h.
    let x = DVec3::new(h - 6e-5, h - 3e-5, R - 4e-5);
    let force = |tris: &[[DVec3; 3]], curvature: Option<f64>| {
        let lo = DVec3::splat(-0.05);
        let hi = DVec3::splat(0.05);
        let mut w = world(lo, hi, [Boundary::Fixed; 3], model, 0.5, 0.4);
        add_mesh(&mut w, model, tris);
        if let Some(deg) = curvature {
            w.meshes[0].coplanar_cos = f64::to_radians(deg).cos();
        }
        w.add_particle(&NewParticle::at(x, R, RHO)).unwrap();
        w.set_timestep(1e-7).unwrap();
        w.setup().unwrap();
        w.particles.f[0]
    };
    let hertz = |q: DVec3| {
        let d = x - q;
        let delta = R - d.length();
        4.0 / 3.0 * e_star_wall() * (R * delta).sqrt() * delta * d.normalize()
    };
    let close = |f: DVec3, want: DVec3| {
        assert!((f - want).length() < 1e-9 * want.length(), "{f} vs {want}");
    };
    let on_x = DVec3::new(h, x.y, 0.0);
    // Flat: the closer edge y = h alone.
    close(force(&floor(0.0), None), hertz(DVec3::new(x.x, h, 0.0)));
    // Folded by 1° (more than the default 0.26°): both sides.
    let fold = 1f64.to_radians();
    // On the folded side the sphere's closest point is inside the face of the triangle
    // (l, l), (−h, h), (h, h): the foot of the perpendicular on its plane.
    let n = DVec3::new(fold.tan(), -fold.tan(), 1.0).normalize();
    let on_y = x - (x - DVec3::new(h, h, 0.0)).dot(n) * n;
    close(force(&floor(fold), None), hertz(on_y) + hertz(on_x));
    // Folded, with curvature 2: one surface, the deeper contact.
    let deeper = if (x - on_y).length() < (x - on_x).length() {
        on_y
    } else {
        on_x
    };
    close(force(&floor(fold), Some(2.0)), hertz(deeper));
}
