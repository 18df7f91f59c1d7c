//! `fix move`: particles of a group follow a prescribed motion (LAMMPS/LIGGGHTS
//! `fix move` `linear`, `wiggle`, `rotate`, `variable`) instead of being integrated.
//!
//! Each particle's original position (unwrapped with its image flags) is kept in a named
//! per-particle property ([`Move::property_name`]: x0, y0, z0 and a flag saying it is
//! set), so it travels with the particle through sorting, removal and migration. A
//! particle whose flag is not set yet (every particle at the first step after the
//! definition, and particles created later) gets the original position that puts it where
//! it is now at the time of its current position, so it joins the motion without a jump
//! (as LAMMPS' `set_arrays`).
//!
//! At step n the elapsed time is δ = (n − n₀)·dt, n₀ being the step of the definition:
//! - `linear V`: x = x0 + V δ, v = V;
//! - `wiggle A T`: x = x0 + A sin(ω δ), v = A ω cos(ω δ), ω = 2π/T;
//! - `rotate P R T`: x0 turned by ω δ about the axis through P along R (right-hand
//!   rule), v = ω R̂ × (x − c) with c the foot of x on the axis, and the angular
//!   velocity of the sphere set to ω R̂;
//! - `variable`: per component a displacement d (x = x0 + d) and/or a velocity w
//!   (v = w; x advances by dt·w when only w is given), the values set by the front end
//!   before each step ([`MoveStyle::Variable`]).
//!
//! A component given as NULL (for `variable`, both NULL) is integrated by velocity Verlet
//! with its force component, as `fix nve` would; the angular velocity is left alone
//! except by `rotate`.

use glam::DVec3;

use crate::domain::Domain;
use crate::particles::Particles;

/// The motion of a `fix move`.
#[derive(Debug, Clone, PartialEq)]
pub enum MoveStyle {
    /// `linear Vx Vy Vz` (NULL: `None`).
    Linear {
        /// Velocity per component.
        v: [Option<f64>; 3],
    },
    /// `wiggle Ax Ay Az period` (NULL: `None`).
    Wiggle {
        /// Amplitude per component.
        amplitude: [Option<f64>; 3],
        /// Angular frequency 2π/period.
        omega: f64,
    },
    /// `rotate Px Py Pz Rx Ry Rz period`.
    Rotate {
        /// A point on the axis.
        point: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Angular velocity 2π/period.
        omega: f64,
    },
    /// `variable v_dx v_dy v_dz v_vx v_vy v_vz`: the displacement and velocity of each
    /// component at the coming step, set by the front end before the step (NULL or not
    /// evaluated yet: `None`).
    Variable {
        /// Displacement from the original position per component.
        displacement: [Option<f64>; 3],
        /// Velocity per component.
        velocity: [Option<f64>; 3],
        /// The displacement of the step before (for particles that join the motion:
        /// their original position is where they are minus it; none before the first
        /// step, so that the original positions are those at the definition).
        previous: [Option<f64>; 3],
    },
}

/// A `fix move`: its motion and the step it was defined at.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// The motion.
    pub style: MoveStyle,
    /// Step of the definition (time origin).
    pub origin_step: u64,
    /// Name of the per-particle property holding the original positions.
    property: String,
}

/// Values per particle of the original-position property: x0, y0, z0, set flag.
const WIDTH: usize = 4;

impl Move {
    /// The motion `style` of fix `id`, defined at step `origin_step`.
    pub fn new(id: &str, style: MoveStyle, origin_step: u64) -> Self {
        Self {
            style,
            origin_step,
            property: Self::property_name(id),
        }
    }

    /// Name of the per-particle property with the original positions of fix `id`.
    pub fn property_name(id: &str) -> String {
        format!("fix_move:{id}")
    }

    /// Which components are prescribed (the others are integrated).
    fn prescribed(&self) -> [bool; 3] {
        match &self.style {
            MoveStyle::Linear { v } => v.map(|c| c.is_some()),
            MoveStyle::Wiggle { amplitude, .. } => amplitude.map(|c| c.is_some()),
            MoveStyle::Rotate { .. } => [true; 3],
            MoveStyle::Variable {
                displacement,
                velocity,
                ..
            } => [0, 1, 2].map(|d| displacement[d].is_some() || velocity[d].is_some()),
        }
    }

    /// Position relative to the original one at elapsed time `t`, for a particle whose
    /// original position is `x0` (per prescribed component; rotate uses all three).
    fn displaced(&self, x0: DVec3, t: f64) -> DVec3 {
        match &self.style {
            MoveStyle::Linear { v } => {
                DVec3::from_array([0, 1, 2].map(|d| x0[d] + v[d].map_or(0.0, |c| c * t)))
            }
            MoveStyle::Wiggle { amplitude, omega } => {
                let s = (omega * t).sin();
                DVec3::from_array([0, 1, 2].map(|d| x0[d] + amplitude[d].map_or(0.0, |a| a * s)))
            }
            MoveStyle::Rotate { point, axis, omega } => {
                let (c, a, b) = rotation_frame(x0, *point, *axis);
                let (s, co) = (omega * t).sin_cos();
                c + a * co + b * s
            }
            MoveStyle::Variable { displacement, .. } => {
                DVec3::from_array([0, 1, 2].map(|d| x0[d] + displacement[d].unwrap_or(0.0)))
            }
        }
    }

    /// The original position of a particle at unwrapped position `x` at elapsed time `t`
    /// (the inverse of [`Move::displaced`]).
    fn original(&self, x: DVec3, t: f64) -> DVec3 {
        match &self.style {
            MoveStyle::Rotate { point, axis, omega } => {
                let (c, a, b) = rotation_frame(x, *point, *axis);
                let (s, co) = (omega * t).sin_cos();
                c + a * co - b * s
            }
            MoveStyle::Variable { previous, .. } => {
                x - DVec3::from_array(previous.map(|d| d.unwrap_or(0.0)))
            }
            _ => x - (self.displaced(DVec3::ZERO, t)),
        }
    }

    /// Initial integration at step `step` (already incremented) for the owned particles
    /// of `groupbit`: positions and velocities of the prescribed components set, the
    /// others given a half kick and a drift.
    pub(crate) fn initial_integrate(
        &self,
        p: &mut Particles,
        domain: &Domain,
        groupbit: u32,
        step: u64,
        dt: f64,
    ) {
        let id = match p.property(&self.property) {
            Some(id) => id,
            None => p
                .add_property(&self.property, WIDTH, &[0.0; WIDTH])
                .expect("a valid property"),
        };
        let t = step.saturating_sub(self.origin_step) as f64 * dt;
        let t_prev = step.saturating_sub(self.origin_step + 1) as f64 * dt;
        let prd = domain.prd();
        let set = self.prescribed();
        let dtf = 0.5 * dt;
        let n = p.nlocal();
        let Particles {
            x,
            v,
            omega,
            f,
            mask,
            rmass,
            image,
            props,
            ..
        } = p;
        let x0s = &mut props[id.0];
        for i in 0..n {
            if mask[i] & groupbit == 0 {
                continue;
            }
            let im = image[i].get();
            let shift = DVec3::new(
                im[0] as f64 * prd.x,
                im[1] as f64 * prd.y,
                im[2] as f64 * prd.z,
            );
            let rec = x0s.get_mut(i);
            if rec[3] == 0.0 {
                let x0 = self.original(x[i] + shift, t_prev);
                rec.copy_from_slice(&[x0.x, x0.y, x0.z, 1.0]);
            }
            let x0 = DVec3::new(rec[0], rec[1], rec[2]);
            let target = self.displaced(x0, t) - shift;
            for d in 0..3 {
                if !set[d] {
                    v[i][d] += dtf * f[i][d] / rmass[i];
                    x[i][d] += dt * v[i][d];
                }
            }
            match &self.style {
                MoveStyle::Linear { v: vel } => {
                    for d in (0..3).filter(|&d| set[d]) {
                        x[i][d] = target[d];
                        v[i][d] = vel[d].unwrap_or(0.0);
                    }
                }
                MoveStyle::Wiggle {
                    amplitude,
                    omega: w,
                } => {
                    let c = (w * t).cos();
                    for d in (0..3).filter(|&d| set[d]) {
                        x[i][d] = target[d];
                        v[i][d] = amplitude[d].unwrap_or(0.0) * w * c;
                    }
                }
                MoveStyle::Rotate {
                    point,
                    axis,
                    omega: w,
                } => {
                    x[i] = target;
                    let (c, _, _) = rotation_frame(target + shift, *point, *axis);
                    v[i] = *w * axis.cross(target + shift - c);
                    omega[i] = *w * *axis;
                }
                MoveStyle::Variable {
                    displacement,
                    velocity,
                    ..
                } => {
                    for d in 0..3 {
                        match (displacement[d], velocity[d]) {
                            (Some(_), vel) => {
                                x[i][d] = target[d];
                                if let Some(w) = vel {
                                    v[i][d] = w;
                                }
                            }
                            (None, Some(w)) => {
                                v[i][d] = w;
                                x[i][d] += dt * w;
                            }
                            (None, None) => {}
                        }
                    }
                }
            }
        }
    }

    /// Final integration: the half kick of the components that are not prescribed.
    pub(crate) fn final_integrate(&self, p: &mut Particles, groupbit: u32, dt: f64) {
        let set = self.prescribed();
        if set == [true; 3] {
            return;
        }
        let dtf = 0.5 * dt;
        for i in 0..p.nlocal() {
            if p.mask[i] & groupbit == 0 {
                continue;
            }
            for d in (0..3).filter(|&d| !set[d]) {
                p.v[i][d] += dtf * p.f[i][d] / p.rmass[i];
            }
        }
    }
}

/// The frame of a point `x` about the axis through `point` along the unit `axis`: the
/// foot `c` on the axis, the radial vector `a = x − c` and `b = axis × a`.
fn rotation_frame(x: DVec3, point: DVec3, axis: DVec3) -> (DVec3, DVec3, DVec3) {
    let d = x - point;
    let c = point + d.dot(axis) * axis;
    let a = x - c;
    (c, a, axis.cross(a))
}
