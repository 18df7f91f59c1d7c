//! Smoothed particle hydrodynamics (SPH) as LIGGGHTS 3.8 runs it (`atom_style sph`,
//! `pair_style sph/artVisc/tensCorr`, `fix sph/density/continuity`,
//! `fix sph/density/corr shepard`, `fix sph/pressure`, `fix wall/sph`, `fix nve/sph`,
//! `fix nve/sph/stationary`): weakly compressible SPH after Monaghan (1992, 1994).
//!
//! Per particle: the density ρ, the pressure P, the density rate dρ/dt and the velocity
//! estimate v̂ that the pair and density passes read (named properties [`RHO`], [`PRESSURE`],
//! [`DRHO`], [`VEST`]); the mass is the particle's `rmass` (per type, `mass` command) and
//! its radius is set to its type's smoothing length `sl`, so that the neighbor list's
//! touching distance r_i + r_j is the kernel support 2h̄ with h̄ = (sl_i + sl_j)/2.
//!
//! # One timestep (where [`crate::step`] calls each part), as measured on LIGGGHTS 3.8
//!
//! - initial integrate (`nve/sph`): v̂ = v + Δt f/m, v += Δt/2 f/m, x += Δt v, ρ += Δt dρ/dt;
//!   (`nve/sph/stationary`): ρ += Δt dρ/dt only (v̂ stays as it was: 0 unless set);
//! - pre-force, the SPH fixes in definition order ([`World::sph_pre_force`]):
//!   `sph/density/continuity` dρ_a/dt = Σ_b m_b (v̂_a − v̂_b)·∇_a W_ab (Monaghan 1992
//!   eq. 2.11); `sph/density/summation` ρ_a = Σ_b m_b W_ab (b including a);
//!   `sph/density/corr shepard` on steps that are multiples of `every`:
//!   ρ_a = Σ_b m_b W_ab / Σ_b (m_b/ρ_b) W_ab, the sums including a itself (Shepard filter);
//!   `sph/pressure`: P from ρ ([`Eos`]);
//! - pair ([`SphPair`]): the momentum equation with artificial viscosity and tensile
//!   correction;
//! - post-force: `wall/sph`, `wall/region/sph` (with gravity, enforce2d, ... in definition
//!   order);
//! - final integrate (`nve/sph`): v += Δt/2 f/m.
//!
//! At a run's set-up the pre-force fixes do not act (P keeps its value), dρ/dt is zeroed
//! (the first step of every run keeps ρ) and the pair force is computed from the current
//! P, ρ and v̂ — zero at the first set-up, where P and v̂ are still 0; gravity and the
//! walls act as usual. (LIGGGHTS 3.8 does so; measured with three particles and two runs,
//! `in.three` of the CLI tests.)

pub mod kernel;
pub mod pair;
pub mod wall;

use crate::error::{Error, Result};
use crate::fix::FixKind;
use crate::particles::{Particles, PropId};
use crate::world::World;

pub use kernel::{Kernel, KernelKind};
pub use pair::SphPair;
pub use wall::{SphRegionWall, SphWall};

/// Per-particle density (`rho` in dumps, `set meso_rho`).
pub const RHO: &str = "sph_rho";
/// Per-particle pressure (`p` in dumps).
pub const PRESSURE: &str = "sph_p";
/// Per-particle density rate dρ/dt.
pub const DRHO: &str = "sph_drho";
/// Per-particle velocity estimate v̂ (3 values).
pub const VEST: &str = "sph_vest";

/// Handles of the SPH per-particle properties.
#[derive(Debug, Clone, Copy)]
pub struct SphProps {
    /// ρ
    pub rho: PropId,
    /// P
    pub p: PropId,
    /// dρ/dt
    pub drho: PropId,
    /// v̂
    pub vest: PropId,
}

impl SphProps {
    /// Adds the SPH properties (or finds them): ρ, P, dρ/dt zero and v̂ zero for new
    /// particles, as LIGGGHTS creates them; ρ and v̂ are forwarded to ghosts every step.
    pub fn add(p: &mut Particles) -> Result<Self> {
        let rho = p.add_property(RHO, 1, &[0.0])?;
        let pr = p.add_property(PRESSURE, 1, &[0.0])?;
        let drho = p.add_property(DRHO, 1, &[0.0])?;
        let vest = p.add_property(VEST, 3, &[0.0; 3])?;
        p.set_forward(rho);
        p.set_forward(vest);
        Ok(Self {
            rho,
            p: pr,
            drho,
            vest,
        })
    }

    /// The handles, if the properties exist.
    pub fn find(p: &Particles) -> Option<Self> {
        Some(Self {
            rho: p.property(RHO)?,
            p: p.property(PRESSURE)?,
            drho: p.property(DRHO)?,
            vest: p.property(VEST)?,
        })
    }
}

/// `fix sph/pressure` equations of state (Monaghan 1994 for Tait's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Eos {
    /// `absolut B`: P = B² ρ (the LIGGGHTS manual's formula).
    Absolut {
        /// B
        b: f64,
    },
    /// `relativ B ρ0`: P = B (ρ − ρ0).
    Relativ {
        /// B
        b: f64,
        /// ρ0
        rho0: f64,
    },
    /// `Tait B ρ0 γ`: P = B ((ρ/ρ0)^γ − 1).
    Tait {
        /// B
        b: f64,
        /// ρ0
        rho0: f64,
        /// γ
        gamma: f64,
    },
}

impl Eos {
    /// P(ρ).
    #[inline]
    pub fn pressure(&self, rho: f64) -> f64 {
        match *self {
            Eos::Absolut { b } => b * b * rho,
            Eos::Relativ { b, rho0 } => b * (rho - rho0),
            Eos::Tait { b, rho0, gamma } => b * ((rho / rho0).powf(gamma) - 1.0),
        }
    }
}

/// The SPH fixes of [`FixKind`].
#[derive(Debug, Clone, PartialEq)]
pub enum SphFix {
    /// `sph/density/continuity` (its kernel: `set ... sphkernel`).
    Continuity {
        /// Kernel, once set.
        kernel: Option<KernelKind>,
    },
    /// `sph/density/summation`: ρ_a = Σ_b m_b W_ab, the sum including a itself.
    Summation {
        /// Kernel, once set.
        kernel: Option<KernelKind>,
    },
    /// `sph/density/corr shepard every N`.
    Shepard {
        /// Every this many steps (step multiple of N).
        every: u64,
        /// Kernel, once set.
        kernel: Option<KernelKind>,
    },
    /// `sph/pressure`.
    Pressure(Eos),
    /// `nve/sph`.
    Nve,
    /// `nve/sph/stationary`.
    NveStationary,
}

impl SphFix {
    /// The kernel slot of a fix that has one (`set sphkernel` fills the empty ones).
    pub fn kernel_slot(&mut self) -> Option<&mut Option<KernelKind>> {
        match self {
            SphFix::Continuity { kernel }
            | SphFix::Summation { kernel }
            | SphFix::Shepard { kernel, .. } => Some(kernel),
            _ => None,
        }
    }
}

/// Sets the kernel of every SPH fix that has none yet (`set group all sphkernel K`, as
/// LIGGGHTS 3.8: "Setting undefined fix_sph kernel IDs"); returns how many were set.
pub fn set_undefined_kernels(fixes: &mut [crate::fix::Fix], k: KernelKind) -> usize {
    let mut n = 0;
    for f in fixes {
        let slot = match &mut f.kind {
            FixKind::Sph(s) => s.kernel_slot(),
            FixKind::WallSph(w) => Some(&mut w.kernel),
            FixKind::WallRegionSph(w) => Some(&mut w.kernel),
            _ => None,
        };
        if let Some(slot) = slot {
            if slot.is_none() {
                *slot = Some(k);
                n += 1;
            }
        }
    }
    n
}

/// Initial integration of `nve/sph` (`moving`) or `nve/sph/stationary` for the owned
/// particles of `groupbit`.
pub fn initial_integrate(p: &mut Particles, props: SphProps, groupbit: u32, dt: f64, moving: bool) {
    let n = p.nlocal();
    let [rho, drho, vest] = props_mut(&mut p.props, [props.rho, props.drho, props.vest]);
    for i in 0..n {
        if p.mask[i] & groupbit == 0 {
            continue;
        }
        if moving {
            let inv = 1.0 / p.rmass[i];
            let ve = p.v[i] + dt * inv * p.f[i];
            vest[3 * i..3 * i + 3].copy_from_slice(&ve.to_array());
            p.v[i] += 0.5 * dt * inv * p.f[i];
            p.x[i] += dt * p.v[i];
        }
        rho[i] += dt * drho[i];
    }
}

/// Final integration of `nve/sph`: v += Δt/2 f/m.
pub fn final_integrate(p: &mut Particles, groupbit: u32, dt: f64) {
    for i in 0..p.nlocal() {
        if p.mask[i] & groupbit != 0 {
            p.v[i] += 0.5 * dt / p.rmass[i] * p.f[i];
        }
    }
}

/// The kernel of an SPH fix, or the error saying how to set it.
fn kernel_of(id: &str, k: Option<KernelKind>) -> Result<KernelKind> {
    k.ok_or_else(|| Error::Invalid {
        what: "SPH kernel",
        reason: format!(
            "fix {id} has no kernel: add 'set group all sphkernel NAME' after the SPH fixes"
        ),
    })
}

impl World {
    /// Set-up of SPH (set-up 2 of [`crate::step`]): the SPH fixes need
    /// `pair_style sph/artVisc/tensCorr` and a kernel; radii become the types' smoothing
    /// lengths; dρ/dt is zeroed.
    pub(crate) fn setup_sph(&mut self) -> Result<()> {
        let Some(pair) = &mut self.sph else {
            if let Some(f) = self.fixes.iter().find(|f| {
                matches!(
                    &f.kind,
                    FixKind::Sph(_) | FixKind::WallSph(_) | FixKind::WallRegionSph(_)
                )
            }) {
                return Err(Error::Invalid {
                    what: "SPH fix",
                    reason: format!(
                        "fix {} needs pair_style sph/artVisc/tensCorr (its smoothing lengths)",
                        f.id
                    ),
                });
            }
            return Ok(());
        };
        for f in &self.fixes {
            match &f.kind {
                FixKind::Sph(s) => {
                    if let Some(k) = s.clone().kernel_slot() {
                        kernel_of(&f.id, *k)?;
                    }
                }
                FixKind::WallSph(w) => {
                    kernel_of(&f.id, w.kernel)?;
                }
                FixKind::WallRegionSph(w) => {
                    kernel_of(&f.id, w.kernel)?;
                }
                _ => {}
            }
        }
        for f in &mut self.fixes {
            if let FixKind::WallRegionSph(w) = &mut f.kind {
                w.sl.clone_from(&pair.sl);
            }
        }
        pair.prepare();
        let props = SphProps::add(&mut self.particles)?;
        let n = self.particles.nlocal();
        for i in 0..n {
            let ty = self.particles.ty[i] as usize;
            let h = pair.sl.get(ty).copied().ok_or(Error::TypeOutOfRange {
                ty: ty as u32,
                ntypes: pair.sl.len().saturating_sub(1) as u32,
            })?;
            self.particles.radius[i] = h;
        }
        self.particles.props[props.drho.0].data.fill(0.0);
        Ok(())
    }

    /// Pre-force of the SPH fixes (step 6b of [`crate::step`]), in definition order:
    /// density rate, Shepard filter, pressure. Not at a run's set-up.
    pub(crate) fn sph_pre_force(&mut self) {
        let Some(pair) = &mut self.sph else { return };
        let Some(props) = SphProps::find(&self.particles) else {
            return;
        };
        for f in &self.fixes {
            let FixKind::Sph(s) = &f.kind else { continue };
            match s {
                SphFix::Continuity { kernel: Some(k) } => {
                    pair.density_rate(
                        *k,
                        &mut self.particles,
                        props,
                        &self.neighbor.list,
                        f.groupbit,
                        &*self.comm,
                    );
                }
                SphFix::Summation { kernel: Some(k) } => {
                    pair.summation(
                        *k,
                        &mut self.particles,
                        props,
                        &self.neighbor.list,
                        f.groupbit,
                        &*self.comm,
                    );
                    self.comm.forward(&mut self.particles, &self.domain);
                }
                SphFix::Shepard {
                    every,
                    kernel: Some(k),
                } if *every > 0 && self.step % every == 0 => {
                    pair.shepard(
                        *k,
                        &mut self.particles,
                        props,
                        &self.neighbor.list,
                        f.groupbit,
                        &*self.comm,
                    );
                    self.comm.forward(&mut self.particles, &self.domain);
                }
                SphFix::Pressure(eos) => {
                    let p = &mut self.particles;
                    let [rho, pr] = props_mut(&mut p.props, [props.rho, props.p]);
                    // Ghosts too: the pair pass reads their pressure.
                    for i in 0..p.mask.len() {
                        if p.mask[i] & f.groupbit != 0 {
                            pr[i] = eos.pressure(rho[i]);
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

/// The values of several distinct properties at once (in the order of `ids`).
pub(crate) fn props_mut<const N: usize>(
    props: &mut [crate::particles::Property],
    ids: [PropId; N],
) -> [&mut Vec<f64>; N] {
    let mut out: [Option<&mut Vec<f64>>; N] = [const { None }; N];
    for (k, p) in props.iter_mut().enumerate() {
        if let Some(slot) = ids.iter().position(|id| id.0 == k) {
            out[slot] = Some(&mut p.data);
        }
    }
    out.map(|o| o.expect("distinct SPH properties"))
}
