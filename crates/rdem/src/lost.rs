//! What a particle lost through a fixed face of the box went through on its way out, for
//! the lost-particle report: its straight path traced back from where it was found (along
//! −v) to the first wall surface it crosses, primitive or mesh. A particle that leaked
//! through a wall usually flies straight from the leak to the box face, so this names the
//! wall (and the mesh triangle) to look at; one that left through an opening crosses
//! none. Computed only when a particle is lost, over every triangle: no cost per step.

use glam::DVec3;

use crate::fix::{Fix, FixKind};
use crate::wall::{MeshSurface, WallShape};

/// The first wall surface on a lost particle's path traced back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Index of the wall fix in the world's fixes.
    pub fix: usize,
    /// For a mesh wall: the mesh (index in the world's meshes) and its triangle.
    pub mesh: Option<(usize, u32)>,
    /// Where the path crosses the surface.
    pub point: DVec3,
    /// Distance back along the path from the particle's position to that point.
    pub back: f64,
}

/// The first wall surface of `fixes` (walls of `meshes`) that the path from `x` back
/// against the velocity `v` crosses, if any.
pub fn crossing(fixes: &[Fix], meshes: &[MeshSurface], x: DVec3, v: DVec3) -> Option<Crossing> {
    let speed = v.length();
    if speed == 0.0 || !speed.is_finite() {
        return None;
    }
    let d = -v / speed;
    let mut best: Option<Crossing> = None;
    let mut keep = |c: Crossing| {
        if best.is_none_or(|b| c.back < b.back) {
            best = Some(c);
        }
    };
    for (k, fix) in fixes.iter().enumerate() {
        match &fix.kind {
            FixKind::WallGran(wall) => {
                if let Some(s) = ray_shape(&wall.shape, x, d) {
                    keep(Crossing {
                        fix: k,
                        mesh: None,
                        point: x + s * d,
                        back: s,
                    });
                }
            }
            FixKind::MeshWall(wall) => {
                for &m in &wall.meshes {
                    let mesh = &meshes[m].mesh;
                    for (t, tri) in mesh.tris.iter().enumerate() {
                        let [a, b, c] = tri.map(|i| mesh.verts[i as usize]);
                        if let Some(s) = ray_triangle(x, d, a, b, c) {
                            keep(Crossing {
                                fix: k,
                                mesh: Some((m, t as u32)),
                                point: x + s * d,
                                back: s,
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    best
}

/// `v` rounded to 6 significant digits and written short (as C's `%g` would give them:
/// 0.01, 1.06e-3), for reports.
pub fn g6(v: f64) -> f64 {
    format!("{v:.5e}").parse().unwrap_or(v)
}

/// A vector as `(x, y, z)`, each to 6 significant digits ([`g6`]).
pub fn show(v: DVec3) -> String {
    format!("({}, {}, {})", g6(v.x), g6(v.y), g6(v.z))
}

/// The distance `s > 0` at which the ray `x + s d` (`d` a unit vector) meets the
/// primitive wall `shape`, if it does. For a general cone the report names no wall.
fn ray_shape(shape: &WallShape, x: DVec3, d: DVec3) -> Option<f64> {
    match *shape {
        WallShape::GeneralPlane { point, normal } => {
            let s = (point - x).dot(normal) / d.dot(normal);
            (s > 0.0 && s.is_finite()).then_some(s)
        }
        WallShape::GeneralCylinder {
            radius,
            point,
            axis,
        } => {
            let w = x - point;
            ray_cylinder(w - w.dot(axis) * axis, d - d.dot(axis) * axis, radius)
        }
        WallShape::GeneralCone { .. } => None,
        WallShape::Plane { axis, pos } => {
            let s = (pos - x[axis]) / d[axis];
            (s > 0.0 && s.is_finite()).then_some(s)
        }
        WallShape::Cylinder {
            axis,
            radius,
            c1,
            c2,
        } => {
            let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
            let (mut p, mut q) = (DVec3::ZERO, DVec3::ZERO);
            (p[a1], p[a2]) = (x[a1] - c1, x[a2] - c2);
            (q[a1], q[a2]) = (d[a1], d[a2]);
            ray_cylinder(p, q, radius)
        }
    }
}

/// The smallest `s > 0` with |p + s q|² = R²: where a ray meets a cylinder of `radius`,
/// `p` and `q` being the ray's start and direction less their components along the axis.
fn ray_cylinder(p: DVec3, q: DVec3, radius: f64) -> Option<f64> {
    let (a, b, c) = (q.dot(q), 2.0 * p.dot(q), p.dot(p) - radius * radius);
    let disc = b * b - 4.0 * a * c;
    if a == 0.0 || disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    [(-b - root) / (2.0 * a), (-b + root) / (2.0 * a)]
        .into_iter()
        .find(|&s| s > 0.0)
}

/// The distance `s > 0` at which the ray `x + s d` meets the triangle `a b c`, if it does
/// (Möller–Trumbore; a ray in the triangle's plane meets it nowhere).
fn ray_triangle(x: DVec3, d: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let h = d.cross(e2);
    let det = e1.dot(h);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let w = x - a;
    let u = w.dot(h) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = w.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let s = e2.dot(q) * inv;
    (s > 0.0).then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_meet_planes_cylinders_and_triangles() {
        let x = DVec3::new(0.5, 0.2, -0.3);
        // Back along +z from below the plane z = 0.
        let plane = WallShape::Plane { axis: 2, pos: 0.0 };
        assert_eq!(ray_shape(&plane, x, DVec3::Z), Some(0.3));
        assert_eq!(ray_shape(&plane, x, -DVec3::Z), None);
        // Outside a z cylinder of radius 0.1 about (0.5, 0), at y = 0.2: a path along
        // −x passes beside it.
        let cyl = WallShape::Cylinder {
            axis: 2,
            radius: 0.1,
            c1: 0.5,
            c2: 0.0,
        };
        assert_eq!(ray_shape(&cyl, x, -DVec3::X), None);
        // Back along −y from y = 0.2 meets the cylinder at y = 0.1: 0.1 back.
        let s = ray_shape(&cyl, x, -DVec3::Y).unwrap();
        assert!((s - 0.1).abs() < 1e-15, "{s}");
        // From the axis, any radial direction meets it at R.
        let s = ray_shape(&cyl, DVec3::new(0.5, 0.0, 0.0), DVec3::X).unwrap();
        assert!((s - 0.1).abs() < 1e-15, "{s}");
        // A triangle in z = 0: hit inside, missed beside, parallel rays miss.
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let s = ray_triangle(DVec3::new(0.2, 0.2, -0.5), DVec3::Z, a, b, c).unwrap();
        assert!((s - 0.5).abs() < 1e-15);
        assert_eq!(
            ray_triangle(DVec3::new(0.8, 0.8, -0.5), DVec3::Z, a, b, c),
            None
        );
        assert_eq!(
            ray_triangle(DVec3::new(0.2, 0.2, -0.5), DVec3::X, a, b, c),
            None
        );
    }
}
