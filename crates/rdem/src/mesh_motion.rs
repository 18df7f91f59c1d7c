//! `fix move/mesh`: prescribed rigid motions of a mesh (linear, wiggle, rotate, riggle,
//! viblin, vibrot), evaluated analytically at each step, with the velocity of every
//! vertex (which the wall contact uses).
//!
//! Several motions on one mesh superpose as in LIGGGHTS: a later motion acts in the frame
//! the earlier ones move, so the mesh's vertices are
//! `X(t) = T₁(t − t₁) ∘ T₂(t − t₂) ∘ … ∘ Tₙ(t − tₙ) (X_base)`, where `X_base` are the
//! positions when the first motion began and `tᵢ` the time motion `i` was defined (each
//! `Tᵢ` is the identity at its start, so adding a motion never makes the mesh jump).
//! Removing the last motion bakes it into `X_base`, so the mesh stays where it is.

use glam::{DQuat, DVec3};

use crate::error::{Error, Result};

/// One prescribed motion (`fix move/mesh` style and arguments).
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// `linear vx vy vz`: constant velocity.
    Linear(DVec3),
    /// `wiggle amplitude ax ay az period T`: `A sin(2π τ / T)`.
    Wiggle {
        /// Amplitude vector.
        amplitude: DVec3,
        /// Period.
        period: f64,
    },
    /// `rotate origin .. axis .. period T`: rotation at 2π / T about the axis through
    /// the origin (right-hand rule).
    Rotate {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Period.
        period: f64,
    },
    /// `riggle origin .. axis .. period T amplitude deg`: rotation by
    /// `amplitude sin(2π τ / T)` about the axis.
    Riggle {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Period.
        period: f64,
        /// Amplitude in radians.
        amplitude: f64,
    },
    /// `viblin axis .. order n amplitude C.. phase p.. period T..`: displacement
    /// `axis Σ Cₖ cos(2π τ / Tₖ + pₖ)` (LIGGGHTS' formula; the mesh jumps by
    /// `axis Σ Cₖ cos pₖ` when the motion starts unless the phases make it zero).
    Viblin {
        /// Unit direction.
        axis: DVec3,
        /// (amplitude, phase, period) of each term.
        terms: Vec<[f64; 3]>,
    },
    /// `vibrot origin .. axis .. order n amplitude C.. phase p.. period T..`: rotation by
    /// `Σ Cₖ cos(2π τ / Tₖ + pₖ)` radians about the axis.
    Vibrot {
        /// A point of the axis.
        origin: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// (amplitude, phase, period) of each term.
        terms: Vec<[f64; 3]>,
    },
}

/// A rigid transform `y ↦ R (y − o) + o + d` and its rate: the velocity of the image of
/// a carried point `p` is `ω × (p − (o + d)) + ḋ`.
#[derive(Debug, Clone, Copy)]
struct Pose {
    rot: DQuat,
    origin: DVec3,
    d: DVec3,
    omega: DVec3,
    d_dot: DVec3,
}

impl Pose {
    fn translation(d: DVec3, d_dot: DVec3) -> Self {
        Self {
            rot: DQuat::IDENTITY,
            origin: DVec3::ZERO,
            d,
            omega: DVec3::ZERO,
            d_dot,
        }
    }

    fn rotation(origin: DVec3, axis: DVec3, angle: f64, rate: f64) -> Self {
        Self {
            rot: DQuat::from_axis_angle(axis, angle),
            origin,
            d: DVec3::ZERO,
            omega: axis * rate,
            d_dot: DVec3::ZERO,
        }
    }

    fn apply(&self, y: DVec3) -> DVec3 {
        self.rot * (y - self.origin) + self.origin + self.d
    }

    fn velocity_at(&self, p: DVec3) -> DVec3 {
        self.omega.cross(p - (self.origin + self.d)) + self.d_dot
    }
}

/// Σ Cₖ cos(ωₖ τ + pₖ) and its time derivative.
fn series(terms: &[[f64; 3]], tau: f64) -> (f64, f64) {
    terms.iter().fold((0.0, 0.0), |(s, ds), &[c, p, per]| {
        let w = std::f64::consts::TAU / per;
        (
            s + c * (w * tau + p).cos(),
            ds - c * w * (w * tau + p).sin(),
        )
    })
}

impl Motion {
    /// Checks the numbers (periods > 0, a direction for axes).
    pub fn validate(&self) -> Result<()> {
        let bad = |what: &'static str, reason: &str| {
            Err(Error::Invalid {
                what,
                reason: reason.into(),
            })
        };
        let unit = |a: DVec3| a.is_finite() && (a.length() - 1.0).abs() < 1e-9;
        match self {
            Motion::Linear(v) if !v.is_finite() => bad("velocity", "must be finite"),
            Motion::Wiggle { period, .. }
            | Motion::Rotate { period, .. }
            | Motion::Riggle { period, .. }
                if period.is_nan() || *period <= 0.0 =>
            {
                bad("period", "must be > 0")
            }
            Motion::Rotate { axis, .. }
            | Motion::Riggle { axis, .. }
            | Motion::Vibrot { axis, .. }
            | Motion::Viblin { axis, .. }
                if !unit(*axis) =>
            {
                bad("axis", "must be a unit vector (give a non-zero direction)")
            }
            Motion::Viblin { terms, .. } | Motion::Vibrot { terms, .. }
                if terms.is_empty() || terms.iter().any(|t| t[2].is_nan() || t[2] <= 0.0) =>
            {
                bad("period", "each term needs a period > 0 (order >= 1)")
            }
            _ => Ok(()),
        }
    }

    /// The transform `τ` after the motion began.
    fn pose(&self, tau: f64) -> Pose {
        use std::f64::consts::TAU;
        match self {
            Motion::Linear(v) => Pose::translation(*v * tau, *v),
            Motion::Wiggle { amplitude, period } => {
                let w = TAU / period;
                Pose::translation(
                    *amplitude * (w * tau).sin(),
                    *amplitude * w * (w * tau).cos(),
                )
            }
            Motion::Rotate {
                origin,
                axis,
                period,
            } => {
                let w = TAU / period;
                Pose::rotation(*origin, *axis, w * tau, w)
            }
            Motion::Riggle {
                origin,
                axis,
                period,
                amplitude,
            } => {
                let w = TAU / period;
                Pose::rotation(
                    *origin,
                    *axis,
                    amplitude * (w * tau).sin(),
                    amplitude * w * (w * tau).cos(),
                )
            }
            Motion::Viblin { axis, terms } => {
                let (s, ds) = series(terms, tau);
                Pose::translation(*axis * s, *axis * ds)
            }
            Motion::Vibrot {
                origin,
                axis,
                terms,
            } => {
                let (s, ds) = series(terms, tau);
                Pose::rotation(*origin, *axis, s, ds)
            }
        }
    }
}

/// Calls `f` with the transforms of `movers` at time `t`, in their order: on the stack
/// for the usual few motions (no allocation per step), in a `Vec` beyond.
fn with_poses<R>(movers: &[(String, Motion, f64)], t: f64, f: impl FnOnce(&[Pose]) -> R) -> R {
    const STACK: usize = 8;
    if movers.len() <= STACK {
        let mut buf = [Pose::translation(DVec3::ZERO, DVec3::ZERO); STACK];
        for (b, (_, m, t0)) in buf.iter_mut().zip(movers) {
            *b = m.pose(t - t0);
        }
        f(&buf[..movers.len()])
    } else {
        let poses: Vec<Pose> = movers.iter().map(|(_, m, t0)| m.pose(t - t0)).collect();
        f(&poses)
    }
}

/// The place and velocity of the point at `b` when the motions began, carried by the
/// transforms `poses` (innermost motion first, each carrying the point and its velocity).
fn carry_through(poses: &[Pose], b: DVec3) -> (DVec3, DVec3) {
    let (mut y, mut u) = (b, DVec3::ZERO);
    for pose in poses.iter().rev() {
        u = pose.rot * u;
        y = pose.apply(y);
        u += pose.velocity_at(y);
    }
    (y, u)
}

/// The motions of one mesh and the positions they act on.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshMotion {
    /// (fix ID, motion, start time) in definition order.
    pub movers: Vec<(String, Motion, f64)>,
    /// Vertex positions when the first motion began (later removals bake into them).
    pub base: Vec<DVec3>,
    /// Other points carried with the mesh (the stress's reference point), where they
    /// were when the first motion began, as [`MeshMotion::base`].
    pub carried: Vec<DVec3>,
    /// Vertex velocities at the last update (empty for a mesh at rest).
    pub vel: Vec<DVec3>,
    /// Vertex positions at the last candidate build (for the re-neighboring decision).
    pub built: Vec<DVec3>,
}

impl MeshMotion {
    /// Adds motion `id` starting at time `t` on a mesh whose vertices are now `verts`,
    /// carrying `points` with it ([`MeshMotion::carry`]).
    pub fn add(
        &mut self,
        id: &str,
        motion: Motion,
        t: f64,
        verts: &[DVec3],
        points: &[DVec3],
    ) -> Result<()> {
        motion.validate()?;
        if self.movers.is_empty() {
            self.base = verts.to_vec();
            self.carried = points.to_vec();
        }
        self.movers.push((id.to_string(), motion, t));
        Ok(())
    }

    /// Removes motion `id` at time `t` (it must be the last one added, as in LIGGGHTS);
    /// the mesh stays where the motions have put it.
    pub fn remove(&mut self, id: &str, t: f64) -> Result<()> {
        let Some(k) = self.movers.iter().position(|m| m.0 == id) else {
            return Ok(());
        };
        if k + 1 != self.movers.len() {
            return Err(Error::Invalid {
                what: "unfix",
                reason: format!(
                    "move/mesh fixes on one mesh must be removed in reverse order: remove {} first",
                    self.movers.last().map(|m| m.0.as_str()).unwrap_or("")
                ),
            });
        }
        let (_, m, t0) = self.movers.pop().expect("k is valid");
        let pose = m.pose(t - t0);
        for b in self.base.iter_mut().chain(&mut self.carried) {
            *b = pose.apply(*b);
        }
        if self.movers.is_empty() {
            self.vel.clear();
        }
        Ok(())
    }

    /// True if the mesh moves.
    pub fn is_moving(&self) -> bool {
        !self.movers.is_empty()
    }

    /// Sets `verts` to the positions at time `t` and [`MeshMotion::vel`] to their
    /// velocities (innermost motion first, each carrying the point and its velocity).
    pub fn update(&mut self, t: f64, verts: &mut [DVec3]) {
        if self.movers.is_empty() {
            return;
        }
        self.vel.resize(verts.len(), DVec3::ZERO);
        with_poses(&self.movers, t, |poses| {
            for ((x, v), &b) in verts.iter_mut().zip(&mut self.vel).zip(&self.base) {
                (*x, *v) = carry_through(poses, b);
            }
        });
    }

    /// Where the motions put the carried point `k` ([`MeshMotion::carried`]) at time
    /// `t`, as they put the vertices; `None` without motions or such a point.
    pub fn carry(&self, t: f64, k: usize) -> Option<DVec3> {
        let b = *self.carried.get(k)?;
        if self.movers.is_empty() {
            return None;
        }
        Some(with_poses(&self.movers, t, |poses| {
            carry_through(poses, b).0
        }))
    }

    /// The largest distance a vertex has moved since the last candidate build.
    pub fn max_drift(&self, verts: &[DVec3]) -> f64 {
        if self.built.len() != verts.len() {
            return f64::INFINITY;
        }
        verts
            .iter()
            .zip(&self.built)
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verts() -> Vec<DVec3> {
        vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 0.5),
            DVec3::new(-0.3, 0.1, 1.0),
        ]
    }

    /// Velocity by central differences of the positions, to compare with the analytic one.
    fn fd_velocity(m: &MeshMotion, t: f64) -> Vec<DVec3> {
        let h = 1e-6;
        let mut a = verts();
        let mut b = verts();
        m.clone().update(t + h, &mut a);
        m.clone().update(t - h, &mut b);
        a.iter()
            .zip(&b)
            .map(|(a, b)| (*a - *b) / (2.0 * h))
            .collect()
    }

    #[test]
    fn linear_and_rotate() {
        let mut m = MeshMotion::default();
        let mut x = verts();
        m.add(
            "lin",
            Motion::Linear(DVec3::new(0.5, 0.0, -0.3)),
            2.0,
            &x,
            &[],
        )
        .unwrap();
        m.update(2.0 + 0.4, &mut x);
        for (a, b) in x.iter().zip(verts()) {
            assert!((*a - (b + DVec3::new(0.2, 0.0, -0.12))).length() < 1e-15);
        }
        assert!(m
            .vel
            .iter()
            .all(|v| (*v - DVec3::new(0.5, 0.0, -0.3)).length() < 1e-15));
        // One period of a rotation brings every vertex back.
        let mut m = MeshMotion::default();
        let mut x = verts();
        let rot = Motion::Rotate {
            origin: DVec3::new(0.1, 0.2, 0.0),
            axis: DVec3::Y,
            period: 2.0,
        };
        m.add("rot", rot, 0.0, &x, &[]).unwrap();
        m.update(2.0, &mut x);
        for (a, b) in x.iter().zip(verts()) {
            assert!((*a - b).length() < 1e-12);
        }
        // A quarter turn about y through the origin: (x, z) -> (z, -x) about the origin.
        m.update(0.5, &mut x);
        let p = verts()[0] - DVec3::new(0.1, 0.2, 0.0);
        let want = DVec3::new(p.z, p.y, -p.x) + DVec3::new(0.1, 0.2, 0.0);
        assert!((x[0] - want).length() < 1e-12, "{:?} {want:?}", x[0]);
        // Velocity ω × r with ω = π about y.
        let w = DVec3::Y * std::f64::consts::PI;
        assert!((m.vel[0] - w.cross(x[0] - DVec3::new(0.1, 0.2, 0.0))).length() < 1e-12);
    }

    /// Every style's analytic velocities equal the time derivative of its positions, also
    /// when stacked (a wiggle carried by a rotation).
    #[test]
    fn velocities_are_the_derivative_of_positions() {
        let o = DVec3::new(0.2, -0.1, 0.3);
        let ax = DVec3::new(1.0, 2.0, 2.0) / 3.0;
        let styles = [
            Motion::Wiggle {
                amplitude: DVec3::new(0.1, 0.0, -0.2),
                period: 0.7,
            },
            Motion::Riggle {
                origin: o,
                axis: ax,
                period: 0.9,
                amplitude: 0.3,
            },
            Motion::Viblin {
                axis: ax,
                terms: vec![[0.4, 1.3, 0.2], [0.1, 2.0, 0.7]],
            },
            Motion::Vibrot {
                origin: o,
                axis: ax,
                terms: vec![[0.4, 1.3, 0.2], [0.1, 0.0, 0.4]],
            },
        ];
        for s in styles {
            let mut m = MeshMotion::default();
            m.add("a", s.clone(), 0.1, &verts(), &[]).unwrap();
            let mut x = verts();
            m.update(0.37, &mut x);
            for (a, b) in m.vel.iter().zip(fd_velocity(&m, 0.37)) {
                assert!(
                    (*a - b).length() < 1e-6 * (1.0 + b.length()),
                    "{s:?}: {a:?} {b:?}"
                );
            }
            // Stacked under a rotation.
            let mut m2 = MeshMotion::default();
            let rot = Motion::Rotate {
                origin: DVec3::ZERO,
                axis: DVec3::Z,
                period: 1.3,
            };
            m2.add("r", rot, 0.0, &verts(), &[]).unwrap();
            m2.add("a", s.clone(), 0.1, &verts(), &[]).unwrap();
            let mut x = verts();
            m2.update(0.37, &mut x);
            for (a, b) in m2.vel.iter().zip(fd_velocity(&m2, 0.37)) {
                assert!(
                    (*a - b).length() < 1e-6 * (1.0 + b.length()),
                    "{s:?}: {a:?} {b:?}"
                );
            }
        }
        // wiggle at a quarter period: the full amplitude.
        let mut m = MeshMotion::default();
        let a = DVec3::new(0.1, 0.0, -0.2);
        m.add(
            "w",
            Motion::Wiggle {
                amplitude: a,
                period: 0.8,
            },
            0.0,
            &verts(),
            &[],
        )
        .unwrap();
        let mut x = verts();
        m.update(0.2, &mut x);
        assert!((x[1] - (verts()[1] + a)).length() < 1e-15);
    }

    /// Removing the last motion leaves the mesh in place; a later motion then starts from
    /// there; motions must go in reverse order.
    #[test]
    fn removal_bakes_the_motion() {
        let mut m = MeshMotion::default();
        let mut x = verts();
        m.add("lin", Motion::Linear(DVec3::X), 0.0, &x, &[])
            .unwrap();
        let rot = Motion::Rotate {
            origin: DVec3::ZERO,
            axis: DVec3::Z,
            period: 4.0,
        };
        m.add("rot", rot.clone(), 0.5, &x, &[]).unwrap();
        assert!(m.remove("lin", 1.0).is_err());
        m.update(1.0, &mut x);
        let at = x.clone();
        m.remove("rot", 1.0).unwrap();
        m.remove("lin", 1.0).unwrap();
        assert!(!m.is_moving());
        let mut y = at.clone();
        m.add("rot2", rot, 1.0, &y, &[]).unwrap();
        m.update(1.0, &mut y);
        for (a, b) in y.iter().zip(&at) {
            assert!((*a - *b).length() < 1e-12);
        }
    }
}
