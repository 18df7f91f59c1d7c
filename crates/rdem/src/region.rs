//! Regions (LIGGGHTS `region`): block, sphere, cylinder, cone, plane, union and intersect,
//! and LIGGGHTS-INL's wedge (a cylinder's sector),
//! with `side in|out`. A region answers whether a point is inside (boundary included, as
//! LAMMPS), gives a bounding box when it is finite, and samples uniform random points
//! (rejection in the bounding box) for insertion. A region may be posed (LIGGGHTS
//! `move`/`rotate`): displaced and turned about an axis, its shape unchanged. A
//! tetrahedral mesh ([`TetMesh`], LIGGGHTS `mesh/tet`) samples by volume instead.

use std::sync::Arc;

use glam::DVec3;

use crate::error::{Error, Result};
pub use crate::region_tet::TetMesh;

/// The most contacts [`Region::surface`] gives (regions that could give more are
/// refused by [`Region::max_surface_contacts`]).
pub const MAX_SURFACE_CONTACTS: usize = 24;

/// Shape of a region.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Axis-aligned box (bounds may be infinite).
    Block {
        /// Lower corner.
        lo: DVec3,
        /// Upper corner.
        hi: DVec3,
    },
    /// Sphere.
    Sphere {
        /// Centre.
        centre: DVec3,
        /// Radius.
        radius: f64,
    },
    /// Cylinder along `axis` (0 = x): the axis passes through (c1, c2) in the other two
    /// coordinates in increasing order (x: y z, y: x z, z: x y, as LAMMPS), from `lo` to
    /// `hi` along the axis.
    Cylinder {
        /// Axis direction.
        axis: usize,
        /// First other coordinate of the axis.
        c1: f64,
        /// Second other coordinate.
        c2: f64,
        /// Radius.
        radius: f64,
        /// Lower end along the axis.
        lo: f64,
        /// Upper end along the axis.
        hi: f64,
    },
    /// Truncated cone along `axis`: radius `rlo` at `lo`, `rhi` at `hi`.
    Cone {
        /// Axis direction.
        axis: usize,
        /// First other coordinate of the axis.
        c1: f64,
        /// Second other coordinate.
        c2: f64,
        /// Radius at `lo`.
        rlo: f64,
        /// Radius at `hi`.
        rhi: f64,
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// LIGGGHTS-INL's wedge: the sector of a cylinder along `axis` between the angles
    /// `start` and `start + span` (radians, counterclockwise about the axis), measured in
    /// the plane of the cyclically next coordinates (u, v) = (y, z), (z, x) or (x, y)
    /// from the u direction; the axis passes through (`cu`, `cv`).
    Wedge {
        /// Axis direction.
        axis: usize,
        /// The axis' u coordinate.
        cu: f64,
        /// The axis' v coordinate.
        cv: f64,
        /// Radius.
        radius: f64,
        /// Lower end along the axis.
        lo: f64,
        /// Upper end along the axis.
        hi: f64,
        /// Angle of the starting face.
        start: f64,
        /// Angle from the starting to the ending face, in (0, π] (LIGGGHTS-INL's limit).
        span: f64,
    },
    /// Parallelepiped (LAMMPS' `prism`): the origin `lo` and the edges
    /// A = (hi.x − lo.x, 0, 0), B = (xy, hi.y − lo.y, 0), C = (xz, yz, hi.z − lo.z), with
    /// `tilt` = (xy, xz, yz); a point is inside when its coordinates along A, B, C all lie
    /// in [0, 1] (boundary included), computed as LAMMPS' `region prism` does.
    Prism {
        /// The untilted lower bounds (the origin).
        lo: DVec3,
        /// The untilted upper bounds.
        hi: DVec3,
        /// The tilt factors (xy, xz, yz).
        tilt: DVec3,
    },
    /// Half space on the side the normal points to: (x − point)·normal ≥ 0.
    Plane {
        /// A point on the plane.
        point: DVec3,
        /// Normal (need not be unit).
        normal: DVec3,
    },
    /// The volume of a tetrahedral mesh (shared: a region is cloned at every use).
    TetMesh(Arc<TetMesh>),
    /// Inside any of the parts.
    Union(Vec<Region>),
    /// Inside all of the parts.
    Intersect(Vec<Region>),
}

/// A region: a shape, its side and its pose.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The shape.
    pub shape: Shape,
    /// `side out`: the region is everything outside the shape.
    pub outside: bool,
    /// Where the shape is now, if it moves (`None`: where it was defined).
    pub pose: Option<Pose>,
}

/// The rigid motion of a moving region from where it was defined: a point `x₀` of the
/// defined shape is now at `rot(x₀ − P) + P + shift`, where `rot` turns by `angle`
/// (right-handed) about `axis` through `P` (LAMMPS: the displacement also carries the
/// rotation point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Displacement.
    pub shift: DVec3,
    /// Point on the rotation axis (before the shift).
    pub point: DVec3,
    /// Rotation, about a unit axis through `point`.
    pub rotation: glam::DQuat,
}

impl Pose {
    /// A pose from a displacement and a turn of `angle` radians about `axis` (any
    /// non-zero length) through `point`.
    pub fn new(shift: DVec3, point: DVec3, axis: DVec3, angle: f64) -> Self {
        let rotation = if angle == 0.0 || axis.length_squared() == 0.0 {
            glam::DQuat::IDENTITY
        } else {
            glam::DQuat::from_axis_angle(axis.normalize(), angle)
        };
        Self {
            shift,
            point,
            rotation,
        }
    }

    /// Where the defined shape's point `x0` is now.
    pub fn forward(&self, x0: DVec3) -> DVec3 {
        self.rotation * (x0 - self.point) + self.point + self.shift
    }

    /// Which point of the defined shape is now at `x`.
    pub fn inverse(&self, x: DVec3) -> DVec3 {
        self.rotation.inverse() * (x - self.shift - self.point) + self.point
    }
}

/// The two axes other than `axis`, in increasing order.
fn others(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The offset of `x` from the line along `axis` through (c1, c2), at right angles to it.
fn radial(x: DVec3, axis: usize, c1: f64, c2: f64) -> DVec3 {
    let (a, b) = others(axis);
    let mut d = DVec3::ZERO;
    d[a] = x[a] - c1;
    d[b] = x[b] - c2;
    d
}

/// Squared distance of `x` from the line along `axis` through (c1, c2).
fn radial2(x: DVec3, axis: usize, c1: f64, c2: f64) -> f64 {
    radial(x, axis, c1, c2).length_squared()
}

/// `v` as (length, unit vector), if it is not zero: a contact from the surface point
/// `x − v` to `x`.
fn split(v: DVec3) -> Option<(f64, DVec3)> {
    let r = v.length();
    (r > 0.0).then(|| (r, v / r))
}

/// The box around a cylinder of radius `r` along `axis` from `lo` to `hi`.
fn axial_box(axis: usize, c1: f64, c2: f64, r: f64, lo: f64, hi: f64) -> Option<(DVec3, DVec3)> {
    let (a, b) = others(axis);
    let (mut l, mut h) = (DVec3::ZERO, DVec3::ZERO);
    l[axis] = lo;
    h[axis] = hi;
    l[a] = c1 - r;
    h[a] = c1 + r;
    l[b] = c2 - r;
    h[b] = c2 + r;
    Some((l, h))
}

/// The point of the segment from `p0` to `p1` nearest to `q` (in a plane).
fn nearest_on_segment(q: (f64, f64), p0: (f64, f64), p1: (f64, f64)) -> (f64, f64) {
    let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
    let len2 = dx * dx + dy * dy;
    let s = if len2 > 0.0 {
        (((q.0 - p0.0) * dx + (q.1 - p0.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p0.0 + s * dx, p0.1 + s * dy)
}

/// Finite and > 0 (false for NaN).
/// A wedge's view of `x`: the coordinate along its axis, the offset (u, v) from its axis,
/// and the signed distances from the planes of its starting and ending faces (≤ 0 on
/// the wedge's side of each), as LIGGGHTS-INL tests them.
fn wedge_at(
    axis: usize,
    cu: f64,
    cv: f64,
    start: f64,
    span: f64,
    x: DVec3,
) -> (f64, (f64, f64), (f64, f64)) {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let d = (x[u] - cu, x[v] - cv);
    let (s0, c0) = start.sin_cos();
    let (s1, c1) = (start + span).sin_cos();
    // Outward normals: the starting face's points back from the sector, the ending
    // face's forward.
    (x[axis], d, (d.0 * s0 - d.1 * c0, d.1 * c1 - d.0 * s1))
}

/// True if a sphere of radius `r` at distance `rad` from a cylinder's axis and at `t`
/// along it lies wholly outside the cylinder of radius `radius` from `lo` to `hi`.
fn clear_of_cylinder(rad: f64, t: f64, radius: f64, lo: f64, hi: f64, r: f64) -> bool {
    let dr = (rad - radius).max(0.0);
    let dt = (lo - t).max(t - hi).max(0.0);
    dr * dr + dt * dt >= r * r
}

/// The rows of the inverse of a prism's edge matrix (upper triangular, as LAMMPS
/// writes it): a point's coordinates along the edges are `row · (x − lo)`.
fn prism_rows(lo: DVec3, hi: DVec3, tilt: DVec3) -> [DVec3; 3] {
    let h = hi - lo;
    let (xy, xz, yz) = (tilt.x, tilt.y, tilt.z);
    [
        DVec3::new(
            1.0 / h.x,
            -xy / (h.x * h.y),
            (xy * yz - h.y * xz) / (h.x * h.y * h.z),
        ),
        DVec3::new(0.0, 1.0 / h.y, -yz / (h.y * h.z)),
        DVec3::new(0.0, 0.0, 1.0 / h.z),
    ]
}

/// A prism's eight corners.
fn prism_corners(lo: DVec3, hi: DVec3, tilt: DVec3) -> [DVec3; 8] {
    let h = hi - lo;
    let (a, b, c) = (
        DVec3::new(h.x, 0.0, 0.0),
        DVec3::new(tilt.x, h.y, 0.0),
        DVec3::new(tilt.y, tilt.z, h.z),
    );
    std::array::from_fn(|k| {
        let f = |bit: usize| if k & bit == 0 { 0.0 } else { 1.0 };
        lo + f(1) * a + f(2) * b + f(4) * c
    })
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

fn bad(what: &'static str, reason: String) -> Error {
    Error::Invalid { what, reason }
}

impl Region {
    /// A region with `side in`, after checking the shape's numbers.
    pub fn new(shape: Shape) -> Result<Self> {
        match &shape {
            Shape::Block { lo, hi } => {
                if lo.is_nan() || hi.is_nan() || (0..3).any(|a| lo[a] > hi[a]) {
                    return Err(bad(
                        "region block",
                        format!("bounds {lo} .. {hi}: each lower bound must be <= its upper bound"),
                    ));
                }
            }
            Shape::Sphere { centre, radius } => {
                let ok = centre.is_finite() && positive(*radius);
                if !ok {
                    return Err(bad("region sphere", format!("centre {centre}, radius {radius}: need a finite centre and a radius > 0")));
                }
            }
            Shape::Cylinder {
                axis,
                c1,
                c2,
                radius,
                lo,
                hi,
            } => {
                let ok =
                    *axis <= 2 && c1.is_finite() && c2.is_finite() && positive(*radius) && lo <= hi;
                if !ok {
                    return Err(bad(
                        "region cylinder",
                        format!("radius {radius}, ends {lo} {hi}: need a radius > 0 and lo <= hi"),
                    ));
                }
            }
            Shape::Cone {
                axis,
                c1,
                c2,
                rlo,
                rhi,
                lo,
                hi,
            } => {
                let ok = *axis <= 2
                    && c1.is_finite()
                    && c2.is_finite()
                    && *rlo >= 0.0
                    && *rhi >= 0.0
                    && positive(rlo.max(*rhi))
                    && lo.is_finite()
                    && hi.is_finite()
                    && lo < hi;
                if !ok {
                    return Err(bad("region cone", format!("radii {rlo} {rhi}, ends {lo} {hi}: need radii >= 0 (not both 0) and finite lo < hi")));
                }
            }
            Shape::Wedge {
                axis,
                cu,
                cv,
                radius,
                lo,
                hi,
                start,
                span,
            } => {
                let ok = *axis <= 2
                    && cu.is_finite()
                    && cv.is_finite()
                    && positive(*radius)
                    && lo.is_finite()
                    && hi.is_finite()
                    && lo <= hi
                    && start.is_finite()
                    && *span > 0.0
                    && *span <= std::f64::consts::PI;
                if !ok {
                    return Err(bad("region wedge", format!("radius {radius}, bounds {lo} {hi}, angle {} degrees: need a radius > 0, finite lo <= hi and an angle in (0, 180] (LIGGGHTS-INL's limit)", span.to_degrees())));
                }
            }
            Shape::Prism { lo, hi, tilt } => {
                let ok = lo.is_finite()
                    && hi.is_finite()
                    && tilt.is_finite()
                    && (0..3).all(|a| lo[a] < hi[a]);
                if !ok {
                    return Err(bad(
                        "region prism",
                        format!("bounds {lo} .. {hi}, tilt {tilt}: need finite numbers and each lower bound below its upper bound"),
                    ));
                }
            }
            Shape::Plane { point, normal } => {
                if !point.is_finite() || !normal.is_finite() || normal.length_squared() == 0.0 {
                    return Err(bad("region plane", format!("point {point}, normal {normal}: need a finite point and a non-zero normal")));
                }
            }
            Shape::TetMesh(_) => {}
            Shape::Union(parts) | Shape::Intersect(parts) => {
                if parts.is_empty() {
                    return Err(bad(
                        "region union/intersect",
                        "needs at least one region".into(),
                    ));
                }
            }
        }
        Ok(Self {
            shape,
            outside: false,
            pose: None,
        })
    }

    /// The same region with `side out`.
    pub fn side_out(mut self) -> Self {
        self.outside = !self.outside;
        self
    }

    /// The same region, moved to `pose` (from where it was defined).
    pub fn posed(mut self, pose: Pose) -> Self {
        self.pose = Some(pose);
        self
    }

    /// The point of the shape as defined that is now at `x`.
    fn local(&self, x: DVec3) -> DVec3 {
        self.pose.map_or(x, |p| p.inverse(x))
    }

    /// The most surface contacts [`Region::surface`] gives for this region, or `None`
    /// for a region it does not know: a block (6 inside, 1 outside), a sphere, a
    /// cylinder or a cone (3 inside, 1 outside) or a plane, either side, and unions and
    /// intersections of those, either side, up to [`MAX_SURFACE_CONTACTS`]; where they
    /// were defined or moved (posed).
    pub fn max_surface_contacts(&self) -> Option<usize> {
        self.max_contacts(false)
    }

    /// [`Region::max_surface_contacts`] with the side turned over if `flip` (the parts
    /// of a side-out union or intersection count from outside).
    fn max_contacts(&self, flip: bool) -> Option<usize> {
        let outside = self.outside != flip;
        match &self.shape {
            Shape::Block { .. } => Some(if outside { 1 } else { 6 }),
            Shape::Cylinder { .. } | Shape::Cone { .. } => Some(if outside { 1 } else { 3 }),
            Shape::Sphere { .. } | Shape::Plane { .. } => Some(1),
            Shape::Union(parts) | Shape::Intersect(parts) => parts
                .iter()
                .map(|p| p.max_contacts(outside))
                .sum::<Option<usize>>()
                .filter(|&n| n <= MAX_SURFACE_CONTACTS),
            Shape::TetMesh(_) | Shape::Wedge { .. } | Shape::Prism { .. } => None,
        }
    }

    /// The parts of the surface within `reach` of a point `x` in the region, seen from
    /// the region, as LAMMPS' `surface`: `(distance, unit normal into the region)` for
    /// each, written to `out`; their number (none when `x` is not strictly in the
    /// region). A region [`Region::max_surface_contacts`] does not know gives none (a
    /// tetrahedral mesh), or only the first [`MAX_SURFACE_CONTACTS`] (a union of too
    /// many parts): check it once, where the region is chosen.
    ///
    /// - `side in`: each of a block's faces, a sphere's surface, a cylinder's curved
    ///   surface or a cone's slanted side (its nearest point), and each finite end cap
    ///   counts on its own (LAMMPS' `surface_interior`);
    /// - `side out`: the one nearest point of the block, sphere, cylinder or cone (an
    ///   edge, a rim or a corner, too) (LAMMPS' `surface_exterior`);
    /// - a plane: the distance from it, on either side;
    /// - a union keeps the contacts of its parts whose point on the surface lies in no
    ///   other part; an intersection those whose point lies in every other part. Side
    ///   out, the parts' contacts are taken from outside each part, as LAMMPS does;
    /// - a moving region: the contacts of its shape where it was defined, at the point
    ///   that is now at `x`, with the normals turned as the region has turned.
    pub fn surface(
        &self,
        x: DVec3,
        reach: f64,
        out: &mut [(f64, DVec3); MAX_SURFACE_CONTACTS],
    ) -> usize {
        self.surface_from(x, reach, out, 0, false)
    }

    /// [`Region::surface`] writing from `out[n]` on, with the side turned over if
    /// `flip`; the new count.
    fn surface_from(
        &self,
        x: DVec3,
        reach: f64,
        out: &mut [(f64, DVec3); MAX_SURFACE_CONTACTS],
        n: usize,
        flip: bool,
    ) -> usize {
        let first = n;
        let n = self.surface_of_shape(self.local(x), reach, out, n, self.outside != flip);
        if let Some(p) = &self.pose {
            for c in &mut out[first..n] {
                c.1 = p.rotation * c.1;
            }
        }
        n
    }

    /// The contacts of the shape as defined, seen from inside it or from `outside`, at
    /// the point `x` of its own frame.
    fn surface_of_shape(
        &self,
        x: DVec3,
        reach: f64,
        out: &mut [(f64, DVec3); MAX_SURFACE_CONTACTS],
        mut n: usize,
        outside: bool,
    ) -> usize {
        let mut add = |r: f64, normal: DVec3| {
            if r < reach && n < MAX_SURFACE_CONTACTS {
                out[n] = (r, normal);
                n += 1;
            }
        };
        match (&self.shape, outside) {
            (&Shape::Block { lo, hi }, false) if (0..3).all(|a| lo[a] < x[a] && x[a] < hi[a]) => {
                for a in 0..3 {
                    let e = DVec3::AXES[a];
                    add(x[a] - lo[a], e);
                    add(hi[a] - x[a], -e);
                }
            }
            (&Shape::Block { lo, hi }, true) => {
                if let Some((r, u)) = split(x - x.clamp(lo, hi)) {
                    add(r, u);
                }
            }
            (&Shape::Sphere { centre, radius }, outside) => {
                let d = x - centre;
                let rho = d.length();
                if rho > 0.0 {
                    if !outside && rho < radius {
                        add(radius - rho, -d / rho);
                    } else if outside && rho > radius {
                        add(rho - radius, d / rho);
                    }
                }
            }
            (
                &Shape::Cylinder {
                    axis,
                    c1,
                    c2,
                    radius,
                    lo,
                    hi,
                },
                outside,
            ) => {
                let d = radial(x, axis, c1, c2);
                let rho = d.length();
                let t = x[axis];
                let e = DVec3::AXES[axis];
                if !outside {
                    if rho < radius && lo < t && t < hi {
                        if rho > 0.0 {
                            add(radius - rho, -d / rho);
                        }
                        add(t - lo, e);
                        add(hi - t, -e);
                    }
                } else {
                    // The nearest point of the solid cylinder: radially within the
                    // radius, axially within the ends.
                    let radial = if rho > radius {
                        d * (1.0 - radius / rho)
                    } else {
                        DVec3::ZERO
                    };
                    let axial = (t - t.clamp(lo, hi)) * e;
                    if let Some((r, u)) = split(radial + axial) {
                        add(r, u);
                    }
                }
            }
            (
                &Shape::Cone {
                    axis,
                    c1,
                    c2,
                    rlo,
                    rhi,
                    lo,
                    hi,
                },
                outside,
            ) => {
                // In the half-plane through the axis and x: (ρ, t) of x, the lateral
                // surface the segment from (rlo, lo) to (rhi, hi).
                let d = radial(x, axis, c1, c2);
                let rho = d.length();
                let u = if rho > 0.0 {
                    d / rho
                } else {
                    DVec3::AXES[others(axis).0]
                };
                let e = DVec3::AXES[axis];
                let t = x[axis];
                let (p0, p1) = ((rlo, lo), (rhi, hi));
                let on_side = nearest_on_segment((rho, t), p0, p1);
                let radius = rlo + (rhi - rlo) * (t - lo) / (hi - lo);
                // A point of the half-plane as a vector from x.
                let from_x = |(pr, pt): (f64, f64)| (pr - rho) * u + (pt - t) * e;
                if !outside {
                    if lo < t && t < hi && rho < radius {
                        if let Some((r, u)) = split(-from_x(on_side)) {
                            add(r, u);
                        }
                        add(t - lo, e);
                        add(hi - t, -e);
                    }
                } else if !(lo <= t && t <= hi && rho <= radius) {
                    // The nearest point of the solid cone: on its side or on a cap.
                    let caps = [(rho.min(rlo), lo), (rho.min(rhi), hi)];
                    let v = [on_side, caps[0], caps[1]]
                        .map(|q| -from_x(q))
                        .into_iter()
                        .min_by(|p, q| p.length_squared().total_cmp(&q.length_squared()))
                        .expect("three candidates");
                    if let Some((r, u)) = split(v) {
                        add(r, u);
                    }
                }
            }
            (&Shape::Plane { point, normal }, outside) => {
                let u = if outside { -normal } else { normal }.normalize();
                let r = (x - point).dot(u);
                if r > 0.0 {
                    add(r, u);
                }
            }
            (Shape::Union(parts) | Shape::Intersect(parts), outside) => {
                let union = matches!(self.shape, Shape::Union(_));
                for (i, part) in parts.iter().enumerate() {
                    let start = n;
                    let end = part.surface_from(x, reach, out, start, outside);
                    // Keep the contacts whose point on the surface is on the whole
                    // region's surface.
                    for k in start..end {
                        let (r, normal) = out[k];
                        let xs = x - r * normal;
                        let mut others = parts.iter().enumerate().filter(|&(j, _)| j != i);
                        let keep = if union {
                            !others.any(|(_, q)| q.contains(xs))
                        } else {
                            others.all(|(_, q)| q.contains(xs))
                        };
                        if keep {
                            out[n] = out[k];
                            n += 1;
                        }
                    }
                }
            }
            _ => {}
        }
        n
    }

    /// True if `x` is in the region (boundary included for `side in`).
    pub fn contains(&self, x: DVec3) -> bool {
        self.in_shape(self.local(x)) != self.outside
    }

    fn in_shape(&self, x: DVec3) -> bool {
        match &self.shape {
            Shape::Block { lo, hi } => (0..3).all(|a| lo[a] <= x[a] && x[a] <= hi[a]),
            Shape::Sphere { centre, radius } => (x - *centre).length_squared() <= radius * radius,
            Shape::Cylinder {
                axis,
                c1,
                c2,
                radius,
                lo,
                hi,
            } => {
                let d2 = radial2(x, *axis, *c1, *c2);
                *lo <= x[*axis] && x[*axis] <= *hi && d2 <= radius * radius
            }
            Shape::Cone {
                axis,
                c1,
                c2,
                rlo,
                rhi,
                lo,
                hi,
            } => {
                let t = x[*axis];
                if t < *lo || t > *hi {
                    return false;
                }
                let r = rlo + (rhi - rlo) * (t - lo) / (hi - lo);
                radial2(x, *axis, *c1, *c2) <= r * r
            }
            &Shape::Wedge {
                axis,
                cu,
                cv,
                radius,
                lo,
                hi,
                start,
                span,
            } => {
                let (t, d, (s1, s2)) = wedge_at(axis, cu, cv, start, span, x);
                let within = lo <= t && t <= hi && d.0 * d.0 + d.1 * d.1 <= radius * radius;
                within && s1 <= 0.0 && s2 <= 0.0
            }
            Shape::Prism { lo, hi, tilt } => {
                let d = x - *lo;
                prism_rows(*lo, *hi, *tilt)
                    .iter()
                    .all(|r| (0.0..=1.0).contains(&r.dot(d)))
            }
            Shape::Plane { point, normal } => (x - *point).dot(*normal) >= 0.0,
            Shape::TetMesh(m) => m.contains(x),
            Shape::Union(parts) => parts.iter().any(|p| p.contains(x)),
            Shape::Intersect(parts) => parts.iter().all(|p| p.contains(x)),
        }
    }

    /// True if the whole sphere of radius `r` at `x` lies in the region (insertion with
    /// `all_in yes`). Exact for blocks, spheres, cylinders, planes and their `side out`,
    /// and for a conforming tetrahedral mesh (the distance to its surface faces); for
    /// cones, unions, side-out combinations and a tetrahedral mesh's `side out` (whole
    /// ball outside the mesh's bounding box) it is conservative (it may refuse a sphere
    /// that would fit, never accept one that does not).
    pub fn contains_sphere(&self, x: DVec3, r: f64) -> bool {
        self.sphere_test(x, r, self.outside)
    }

    fn sphere_test(&self, x: DVec3, r: f64, out: bool) -> bool {
        let x = self.local(x);
        match &self.shape {
            Shape::Block { lo, hi } => {
                if out {
                    let d = (*lo - x).max(x - *hi).max(DVec3::ZERO);
                    d.length_squared() >= r * r
                } else {
                    (0..3).all(|a| lo[a] + r <= x[a] && x[a] <= hi[a] - r)
                }
            }
            Shape::Sphere { centre, radius } => {
                let d = (x - *centre).length();
                if out {
                    d >= radius + r
                } else {
                    d <= radius - r
                }
            }
            Shape::Cylinder {
                axis,
                c1,
                c2,
                radius,
                lo,
                hi,
            } => {
                let rad = radial2(x, *axis, *c1, *c2).sqrt();
                let t = x[*axis];
                if out {
                    clear_of_cylinder(rad, t, *radius, *lo, *hi, r)
                } else {
                    rad <= radius - r && lo + r <= t && t <= hi - r
                }
            }
            Shape::Cone {
                axis,
                c1,
                c2,
                rlo,
                rhi,
                lo,
                hi,
            } => {
                let rad = radial2(x, *axis, *c1, *c2).sqrt();
                let t = x[*axis];
                let slope = (rhi - rlo) / (hi - lo);
                if out {
                    rad >= rlo.max(*rhi) + r || t <= lo - r || t >= hi + r
                } else {
                    let rt = rlo + slope * (t - lo);
                    lo + r <= t && t <= hi - r && rad <= rt - r * (1.0 + slope * slope).sqrt()
                }
            }
            &Shape::Wedge {
                axis,
                cu,
                cv,
                radius,
                lo,
                hi,
                start,
                span,
            } => {
                let (t, d, (s1, s2)) = wedge_at(axis, cu, cv, start, span, x);
                let rad = (d.0 * d.0 + d.1 * d.1).sqrt();
                if out {
                    // Clear of the whole cylinder (conservative).
                    clear_of_cylinder(rad, t, radius, lo, hi, r)
                } else {
                    s1 <= -r && s2 <= -r && rad <= radius - r && lo + r <= t && t <= hi - r
                }
            }
            Shape::Prism { lo, hi, tilt } => {
                // Distances to the faces a = 0 and a = 1 of each edge coordinate a.
                let d = x - *lo;
                let gaps = prism_rows(*lo, *hi, *tilt).map(|row| {
                    let (u, g) = (row.dot(d), row.length());
                    (u / g, (1.0 - u) / g)
                });
                if out {
                    // Wholly beyond one face's plane (conservative near edges).
                    gaps.iter().any(|&(a, b)| a <= -r || b <= -r)
                } else {
                    gaps.iter().all(|&(a, b)| a >= r && b >= r)
                }
            }
            Shape::Plane { point, normal } => {
                let d = (x - *point).dot(*normal) / normal.length();
                if out {
                    d <= -r
                } else {
                    d >= r
                }
            }
            Shape::TetMesh(m) => {
                if out {
                    let (lo, hi) = m.bounding_box();
                    let d = (lo - x).max(x - hi).max(DVec3::ZERO);
                    d.length_squared() >= r * r
                } else {
                    m.contains_sphere(x, r)
                }
            }
            Shape::Union(parts) => {
                if out {
                    parts.iter().all(|p| p.sphere_test(x, r, !p.outside))
                } else {
                    parts.iter().any(|p| p.contains_sphere(x, r))
                }
            }
            Shape::Intersect(parts) => {
                if out {
                    parts.iter().any(|p| p.sphere_test(x, r, !p.outside))
                } else {
                    parts.iter().all(|p| p.contains_sphere(x, r))
                }
            }
        }
    }

    /// Volume of the region within `clip`: exact for a block, and for a tetrahedral mesh
    /// that lies within `clip`; otherwise Monte Carlo with `samples` points of `uniform`
    /// in the bounding box.
    pub fn volume(
        &self,
        clip: (DVec3, DVec3),
        samples: usize,
        mut uniform: impl FnMut() -> f64,
    ) -> f64 {
        let (lo, hi) = match self.bounding_box() {
            Some((l, h)) => (l.max(clip.0), h.min(clip.1)),
            None => clip,
        };
        let ext = (hi - lo).max(DVec3::ZERO);
        let boxvol = ext.x * ext.y * ext.z;
        if let (Shape::Block { .. }, false) = (&self.shape, self.outside) {
            return boxvol;
        }
        if let (Shape::Prism { lo: l0, hi: h0, .. }, false) = (&self.shape, self.outside) {
            let (l, h) = self.bounding_box().expect("a prism is bounded");
            if l.cmpge(clip.0).all() && h.cmple(clip.1).all() {
                let e = *h0 - *l0;
                return e.x * e.y * e.z;
            }
        }
        if let (Shape::TetMesh(m), false) = (&self.shape, self.outside) {
            let (l, h) = self.bounding_box().expect("a mesh is bounded");
            if l.cmpge(clip.0).all() && h.cmple(clip.1).all() {
                return m.volume();
            }
        }
        if boxvol == 0.0 || samples == 0 {
            return 0.0;
        }
        let inside = (0..samples)
            .filter(|_| self.contains(DVec3::new(uniform(), uniform(), uniform()) * ext + lo))
            .count();
        boxvol * inside as f64 / samples as f64
    }

    /// A box containing the region, or `None` if it is unbounded.
    pub fn bounding_box(&self) -> Option<(DVec3, DVec3)> {
        let (lo, hi) = self.defined_box()?;
        let Some(pose) = self.pose else {
            return Some((lo, hi));
        };
        // The box around the moved corners of the defined shape's box.
        let (mut l, mut h) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for k in 0..8 {
            let c = DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            );
            let c = pose.forward(c);
            l = l.min(c);
            h = h.max(c);
        }
        Some((l, h))
    }

    /// The bounding box of the shape where it was defined.
    fn defined_box(&self) -> Option<(DVec3, DVec3)> {
        if self.outside {
            return None;
        }
        let finite = |lo: DVec3, hi: DVec3| (lo.is_finite() && hi.is_finite()).then_some((lo, hi));
        match &self.shape {
            Shape::Block { lo, hi } => finite(*lo, *hi),
            Shape::Sphere { centre, radius } => finite(*centre - *radius, *centre + *radius),
            Shape::Cylinder {
                axis,
                c1,
                c2,
                radius,
                lo,
                hi,
            } => axial_box(*axis, *c1, *c2, *radius, *lo, *hi).and_then(|(l, h)| finite(l, h)),
            Shape::Cone {
                axis,
                c1,
                c2,
                rlo,
                rhi,
                lo,
                hi,
            } => {
                axial_box(*axis, *c1, *c2, rlo.max(*rhi), *lo, *hi).and_then(|(l, h)| finite(l, h))
            }
            &Shape::Wedge {
                axis,
                cu,
                cv,
                radius,
                lo,
                hi,
                ..
            } => {
                // The whole cylinder's box; the wedge's centre is in cyclic order
                // (axis + 1, axis + 2), `axial_box` takes it in axis order.
                let mut c = DVec3::ZERO;
                (c[(axis + 1) % 3], c[(axis + 2) % 3]) = (cu, cv);
                let (a, b) = others(axis);
                axial_box(axis, c[a], c[b], radius, lo, hi).and_then(|(l, h)| finite(l, h))
            }
            Shape::Prism { lo, hi, tilt } => {
                let c = prism_corners(*lo, *hi, *tilt);
                let l = c.iter().fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(p));
                let h = c
                    .iter()
                    .fold(DVec3::splat(f64::NEG_INFINITY), |m, &p| m.max(p));
                finite(l, h)
            }
            Shape::Plane { .. } => None,
            Shape::TetMesh(m) => Some(m.bounding_box()),
            Shape::Union(parts) => {
                let mut acc: Option<(DVec3, DVec3)> = None;
                for p in parts {
                    let (l, h) = p.bounding_box()?;
                    acc = Some(match acc {
                        None => (l, h),
                        Some((al, ah)) => (al.min(l), ah.max(h)),
                    });
                }
                acc
            }
            Shape::Intersect(parts) => {
                let mut acc: Option<(DVec3, DVec3)> = None;
                for (l, h) in parts.iter().filter_map(|p| p.bounding_box()) {
                    acc = Some(match acc {
                        None => (l, h),
                        Some((al, ah)) => (al.max(l), ah.min(h)),
                    });
                }
                acc
            }
        }
    }

    /// A uniformly distributed point of the region within `clip` (lower, upper corner; e.g.
    /// the simulation box), drawn by rejection from the bounding box with `uniform`
    /// giving numbers in [0, 1) (a tetrahedral mesh draws from its own volume and
    /// rejects what `clip` cuts off). `None` after `max_tries` rejections.
    pub fn sample(
        &self,
        clip: (DVec3, DVec3),
        mut uniform: impl FnMut() -> f64,
        max_tries: usize,
    ) -> Option<DVec3> {
        if let (Shape::TetMesh(m), false) = (&self.shape, self.outside) {
            for _ in 0..max_tries {
                let x0 = m.sample(&mut uniform);
                let x = self.pose.map_or(x0, |p| p.forward(x0));
                // A sampled point on a face (round-off) would fail the strict test.
                if x.cmpge(clip.0).all() && x.cmple(clip.1).all() && self.contains(x) {
                    return Some(x);
                }
            }
            return None;
        }
        let (lo, hi) = match self.bounding_box() {
            Some((l, h)) => (l.max(clip.0), h.min(clip.1)),
            None => clip,
        };
        if (0..3).any(|a| lo[a] > hi[a]) {
            return None;
        }
        for _ in 0..max_tries {
            let x = DVec3::new(uniform(), uniform(), uniform()) * (hi - lo) + lo;
            if self.contains(x) {
                return Some(x);
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn inside_tests_include_the_boundary() {
        let b = Region::new(Shape::Block {
            lo: v(0., 0., 0.),
            hi: v(1., 2., 3.),
        })
        .unwrap();
        assert!(b.contains(v(1., 2., 3.)) && b.contains(v(0., 0., 0.)));
        assert!(!b.contains(v(1.0 + 1e-12, 1., 1.)));
        assert!(b.clone().side_out().contains(v(-1., 0., 0.)));
        assert!(!b.clone().side_out().contains(v(0.5, 0.5, 0.5)));
        let s = Region::new(Shape::Sphere {
            centre: v(1., 1., 1.),
            radius: 0.5,
        })
        .unwrap();
        assert!(s.contains(v(1.5, 1., 1.)) && !s.contains(v(1.5, 1.01, 1.)));
        // ycylinder through x = 1, z = 2 (increasing axis order, as LAMMPS).
        let c = Region::new(Shape::Cylinder {
            axis: 1,
            c1: 1.0,
            c2: 2.0,
            radius: 0.5,
            lo: 0.0,
            hi: 4.0,
        })
        .unwrap();
        assert!(c.contains(v(1.5, 4.0, 2.0)));
        assert!(!c.contains(v(1.0, 4.1, 2.0)));
        assert!(!c.contains(v(2.0, 1.0, 1.0)));
        let k = Region::new(Shape::Cone {
            axis: 2,
            c1: 0.,
            c2: 0.,
            rlo: 1.0,
            rhi: 0.0,
            lo: 0.0,
            hi: 2.0,
        })
        .unwrap();
        assert!(k.contains(v(0.5, 0., 1.0)) && !k.contains(v(0.51, 0., 1.0)));
        let p = Region::new(Shape::Plane {
            point: v(0., 0., 1.),
            normal: v(0., 0., -2.),
        })
        .unwrap();
        assert!(
            p.contains(v(5., 5., 1.)) && p.contains(v(0., 0., -3.)) && !p.contains(v(0., 0., 1.1))
        );
        let u = Region::new(Shape::Union(vec![b.clone(), s.clone()])).unwrap();
        let i = Region::new(Shape::Intersect(vec![b.clone(), p.clone()])).unwrap();
        assert!(u.contains(v(1.4, 1., 1.)) && u.contains(v(0.1, 0.1, 0.1)));
        assert!(i.contains(v(0.5, 0.5, 0.5)) && !i.contains(v(0.5, 0.5, 2.0)));
        assert_eq!(i.bounding_box(), Some((v(0., 0., 0.), v(1., 2., 3.))));
        assert_eq!(u.bounding_box(), Some((v(0., 0., 0.), v(1.5, 2., 3.))));
        assert_eq!(p.bounding_box(), None);
    }

    #[test]
    fn whole_spheres_inside_and_outside() {
        let b = Region::new(Shape::Block {
            lo: v(0., 0., 0.),
            hi: v(1., 1., 1.),
        })
        .unwrap();
        assert!(b.contains_sphere(v(0.5, 0.5, 0.5), 0.5));
        assert!(!b.contains_sphere(v(0.5, 0.5, 0.4), 0.5));
        let bo = b.clone().side_out();
        assert!(
            bo.contains_sphere(v(1.5, 0.5, 0.5), 0.5) && !bo.contains_sphere(v(1.4, 0.5, 0.5), 0.5)
        );
        // Corner: distance √2·0.3 ≈ 0.424 from the edge.
        assert!(
            bo.contains_sphere(v(1.3, 1.3, 0.5), 0.42)
                && !bo.contains_sphere(v(1.3, 1.3, 0.5), 0.43)
        );
        let c = Region::new(Shape::Cylinder {
            axis: 2,
            c1: 0.,
            c2: 0.,
            radius: 1.,
            lo: 0.,
            hi: 2.,
        })
        .unwrap();
        assert!(c.contains_sphere(v(0.5, 0., 1.), 0.5) && !c.contains_sphere(v(0.51, 0., 1.), 0.5));
        assert!(!c.contains_sphere(v(0., 0., 0.4), 0.5));
        let s = Region::new(Shape::Sphere {
            centre: v(0., 0., 0.),
            radius: 1.0,
        })
        .unwrap();
        assert!(s.contains_sphere(v(0.7, 0., 0.), 0.3) && !s.contains_sphere(v(0.71, 0., 0.), 0.3));
        // Every point of an accepted sphere is inside (cone, conservative).
        let k = Region::new(Shape::Cone {
            axis: 2,
            c1: 0.,
            c2: 0.,
            rlo: 1.0,
            rhi: 0.2,
            lo: 0.0,
            hi: 2.0,
        })
        .unwrap();
        for (x, r) in [
            (v(0.3, 0.1, 0.6), 0.2),
            (v(0.0, 0.0, 1.5), 0.1),
            (v(0.5, 0.0, 0.3), 0.25),
        ] {
            if k.contains_sphere(x, r) {
                for d in [
                    DVec3::X,
                    DVec3::NEG_X,
                    DVec3::Y,
                    DVec3::Z,
                    DVec3::NEG_Z,
                    v(0.6, 0.0, 0.8),
                    v(0.6, 0.0, -0.8),
                ] {
                    assert!(k.contains(x + r * d.normalize()), "{x} {r} {d}");
                }
            }
        }
        assert!(k.contains_sphere(v(0.0, 0.0, 1.0), 0.1));
    }

    /// A posed region is the defined one moved rigidly: a block shifted by (1, 0, 0) and
    /// turned by 90° about z through (0, 0, 0) after the shift carries the rotation point.
    #[test]
    fn posed_regions_move_rigidly() {
        let b = Region::new(Shape::Block {
            lo: v(0., 0., 0.),
            hi: v(2., 1., 1.),
        })
        .unwrap();
        let shifted = b
            .clone()
            .posed(Pose::new(v(1., 0., 0.), DVec3::ZERO, DVec3::Z, 0.0));
        assert!(shifted.contains(v(2.9, 0.5, 0.5)) && !shifted.contains(v(0.9, 0.5, 0.5)));
        assert_eq!(shifted.bounding_box(), Some((v(1., 0., 0.), v(3., 1., 1.))));
        // Right-handed quarter turn about z: (x, y) -> (-y, x), then the shift.
        let turned = b.clone().posed(Pose::new(
            v(1., 0., 0.),
            DVec3::ZERO,
            v(0., 0., 5.),
            std::f64::consts::FRAC_PI_2,
        ));
        assert!(turned.contains(v(0.5, 1.9, 0.5)) && !turned.contains(v(1.5, 0.5, 0.5)));
        assert!(!turned.contains(v(0.5, 2.1, 0.5)));
        let (l, h) = turned.bounding_box().unwrap();
        assert!((l - v(0., 0., 0.)).length() < 1e-12 && (h - v(1., 2., 1.)).length() < 1e-12);
        // The whole-sphere test follows the pose (the sphere of radius 0.5 touches four
        // faces: 0.49 fits, 0.51 does not); side out too.
        assert!(turned.contains_sphere(v(0.5, 1.0, 0.5), 0.49));
        assert!(!turned.contains_sphere(v(0.5, 1.0, 0.5), 0.51));
        let out = turned.clone().side_out();
        assert!(out.contains(v(1.5, 0.5, 0.5)) && !out.contains(v(0.5, 1.9, 0.5)));
        // Forward and inverse agree.
        let p = Pose::new(v(0.3, -2., 1.), v(1., 2., 3.), v(1., 1., 0.), 0.7);
        let x = v(0.4, -0.2, 5.);
        assert!((p.inverse(p.forward(x)) - x).length() < 1e-14);
    }

    /// LIGGGHTS-INL's manual example, `wedge axis y center 0 0 radius 10 bounds 0 10
    /// angle0 -22.5 angle 45`: about y the angles run from z towards x, so the sector
    /// holds the points near +z within ±22.5°; a wedge's angle is at most 180°; whole
    /// spheres must clear both faces.
    #[test]
    fn wedges_are_sectors_about_their_axis() {
        let wedge = |start: f64, span: f64| {
            Region::new(Shape::Wedge {
                axis: 1,
                cu: 0.0,
                cv: 0.0,
                radius: 10.0,
                lo: 0.0,
                hi: 10.0,
                start: start.to_radians(),
                span: span.to_radians(),
            })
        };
        let w = wedge(-22.5, 45.0).unwrap();
        for (p, inside) in [
            (v(0.0, 5.0, 5.0), true),
            (v(1.0, 5.0, 5.0), true),
            (v(-1.0, 5.0, 5.0), true),
            (v(5.0, 5.0, 5.0), false),
            (v(0.0, 5.0, -5.0), false),
            (v(0.0, 11.0, 5.0), false),
            (v(0.0, 5.0, 10.5), false),
            (v(0.0, 0.0, 0.0), true),
        ] {
            assert_eq!(w.contains(p), inside, "{p}");
        }
        assert!(w.contains_sphere(v(0.0, 5.0, 5.0), 1.0));
        assert!(!w.contains_sphere(v(1.5, 5.0, 5.0), 1.0));
        assert!(w.side_out().contains(v(5.0, 5.0, 5.0)));
        assert!(wedge(0.0, 180.0).is_ok());
        // The box of the whole cylinder; about y the centre is (z, x) = (cu, cv).
        let off = Region::new(Shape::Wedge {
            axis: 1,
            cu: 1.0,
            cv: 2.0,
            radius: 0.5,
            lo: -1.0,
            hi: 3.0,
            start: 0.0,
            span: 1.0,
        })
        .unwrap();
        assert_eq!(
            off.bounding_box(),
            Some((v(1.5, -1.0, 0.5), v(2.5, 3.0, 1.5)))
        );
        assert!(wedge(0.0, 200.0).is_err());
        assert!(wedge(0.0, 0.0).is_err());
    }

    #[test]
    fn bad_regions_are_refused() {
        assert!(Region::new(Shape::Block {
            lo: v(1., 0., 0.),
            hi: v(0., 1., 1.)
        })
        .is_err());
        assert!(Region::new(Shape::Sphere {
            centre: v(0., 0., 0.),
            radius: 0.0
        })
        .is_err());
        assert!(Region::new(Shape::Cylinder {
            axis: 3,
            c1: 0.,
            c2: 0.,
            radius: 1.,
            lo: 0.,
            hi: 1.
        })
        .is_err());
        assert!(Region::new(Shape::Cone {
            axis: 2,
            c1: 0.,
            c2: 0.,
            rlo: 0.,
            rhi: 0.,
            lo: 0.,
            hi: 1.
        })
        .is_err());
        assert!(Region::new(Shape::Plane {
            point: v(0., 0., 0.),
            normal: DVec3::ZERO
        })
        .is_err());
        assert!(Region::new(Shape::Union(vec![])).is_err());
    }

    /// Sampling is uniform: the fraction of cylinder samples in the inner half radius is
    /// 1/4 (area ratio) within 3 standard deviations, and every sample is inside.
    #[test]
    fn samples_are_inside_and_uniform() {
        let c = Region::new(Shape::Cylinder {
            axis: 2,
            c1: 0.0,
            c2: 0.0,
            radius: 1.0,
            lo: 0.0,
            hi: 1.0,
        })
        .unwrap();
        let mut s = 1u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let n = 20_000;
        let mut inner = 0;
        for _ in 0..n {
            let x = c
                .sample((DVec3::splat(-10.0), DVec3::splat(10.0)), &mut rnd, 1000)
                .unwrap();
            assert!(c.contains(x));
            if x.x * x.x + x.y * x.y < 0.25 {
                inner += 1;
            }
        }
        let f = inner as f64 / n as f64;
        let sigma = (0.25f64 * 0.75 / n as f64).sqrt();
        assert!((f - 0.25).abs() < 3.0 * sigma, "{f}");
        // Volume by Monte Carlo: π r² h = π within 1 %.
        let vol = c.volume((DVec3::splat(-10.0), DVec3::splat(10.0)), 200_000, &mut rnd);
        assert!((vol / std::f64::consts::PI - 1.0).abs() < 0.01, "{vol}");
        // Clipped to an empty box: nothing.
        assert!(c
            .sample((v(5., 5., 5.), v(6., 6., 6.)), &mut rnd, 100)
            .is_none());
    }
}
