//! Fixes: per-step operations on a group, each declaring the stages it acts in. A fix is a
//! typed value built once from its command; the step calls it only in its stages.

pub mod integrate;

use glam::DVec3;

use crate::error::{check, Error, Result};
use crate::particles::Particles;
use crate::wall::PrimitiveWall;

/// What a fix does.
#[derive(Debug, Clone)]
pub enum FixKind {
    /// `fix nve/sphere`: velocity Verlet for translation and rotation.
    NveSphere,
    /// `fix gravity g vector x y z`: force m·g along the unit vector.
    Gravity {
        /// Acceleration vector (magnitude × unit direction).
        accel: DVec3,
    },
    /// `fix freeze`: zero force and torque.
    Freeze,
    /// `fix viscous gamma`: F −= γ v.
    Viscous {
        /// Damping coefficient (force/velocity).
        gamma: f64,
    },
    /// `fix addforce fx fy fz`: adds a constant force.
    AddForce {
        /// Force added to every particle of the group.
        force: DVec3,
    },
    /// `fix setforce fx fy fz` (NULL components are `None` and left alone).
    SetForce {
        /// Components to impose.
        force: [Option<f64>; 3],
    },
    /// `fix wall/gran ... primitive ...`.
    WallGran(Box<PrimitiveWall>),
}

/// A fix: an ID, a group (bit mask) and what it does.
#[derive(Debug, Clone)]
pub struct Fix {
    /// Fix ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
    /// Behaviour.
    pub kind: FixKind,
}

impl Fix {
    /// A fix with validation of its parameters.
    pub fn new(id: &str, groupbit: u32, kind: FixKind) -> Result<Self> {
        match &kind {
            FixKind::Gravity { accel } => {
                if !accel.is_finite() {
                    return Err(Error::Invalid {
                        what: "gravity",
                        reason: format!("{accel} is not finite"),
                    });
                }
            }
            FixKind::Viscous { gamma } => {
                check("viscous gamma", *gamma, *gamma >= 0.0, "must be >= 0")?;
            }
            FixKind::AddForce { force } => {
                if !force.is_finite() {
                    return Err(Error::Invalid {
                        what: "addforce",
                        reason: format!("{force} is not finite"),
                    });
                }
            }
            FixKind::SetForce { force } => {
                if force.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(Error::Invalid {
                        what: "setforce",
                        reason: "components must be finite or NULL".into(),
                    });
                }
            }
            FixKind::NveSphere | FixKind::Freeze | FixKind::WallGran(_) => {}
        }
        Ok(Self {
            id: id.to_string(),
            groupbit,
            kind,
        })
    }

    /// `fix ID group gravity magnitude vector x y z`.
    pub fn gravity(id: &str, groupbit: u32, magnitude: f64, dir: DVec3) -> Result<Self> {
        let len = dir.length();
        if len.is_nan() || len <= 0.0 || !dir.is_finite() {
            return Err(Error::Invalid {
                what: "gravity direction",
                reason: format!("{dir} has no direction"),
            });
        }
        check("gravity magnitude", magnitude, true, "must be finite")?;
        Self::new(
            id,
            groupbit,
            FixKind::Gravity {
                accel: magnitude * dir / len,
            },
        )
    }

    /// True if this fix integrates (acts in initial and final integrate).
    pub fn integrates(&self) -> bool {
        matches!(self.kind, FixKind::NveSphere)
    }

    /// True if this fix acts after the forces (post_force).
    pub fn post_force(&self) -> bool {
        matches!(
            self.kind,
            FixKind::Gravity { .. }
                | FixKind::Freeze
                | FixKind::Viscous { .. }
                | FixKind::AddForce { .. }
                | FixKind::SetForce { .. }
        )
    }

    /// The post-force action on the owned particles.
    pub fn apply_post_force(&self, p: &mut Particles) {
        let n = p.nlocal();
        let bit = self.groupbit;
        match &self.kind {
            FixKind::Gravity { accel } => {
                for i in 0..n {
                    if p.mask[i] & bit != 0 {
                        p.f[i] += p.rmass[i] * *accel;
                    }
                }
            }
            FixKind::Freeze => {
                for i in 0..n {
                    if p.mask[i] & bit != 0 {
                        p.f[i] = DVec3::ZERO;
                        p.torque[i] = DVec3::ZERO;
                    }
                }
            }
            FixKind::Viscous { gamma } => {
                for i in 0..n {
                    if p.mask[i] & bit != 0 {
                        p.f[i] -= *gamma * p.v[i];
                    }
                }
            }
            FixKind::AddForce { force } => {
                for i in 0..n {
                    if p.mask[i] & bit != 0 {
                        p.f[i] += *force;
                    }
                }
            }
            FixKind::SetForce { force } => {
                for i in 0..n {
                    if p.mask[i] & bit != 0 {
                        for (a, value) in force.iter().enumerate() {
                            if let Some(v) = value {
                                p.f[i][a] = *v;
                            }
                        }
                    }
                }
            }
            FixKind::NveSphere | FixKind::WallGran(_) => {}
        }
    }
}
