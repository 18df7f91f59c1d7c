//! `fix nve/sphere`: velocity Verlet for translation and rotation of solid spheres; and
//! `fix nve/limit` ([`NveLimit`]), translation only with a cap on the speed.
//! Initial half step: v += dt/2 · f/m, x += dt · v, ω += dt/2 · τ/(0.4 m r²);
//! final half step: v += dt/2 · f/m, ω += dt/2 · τ/(0.4 m r²).
//!
//! Each particle is updated on its own, so the loops run in parallel over chunks of the
//! owned particles (see [`crate::par`]) with results independent of the thread count.

use glam::DVec3;
use rayon::prelude::*;

use crate::par::{parallel, CHUNK};
use crate::particles::{Particles, INERTIA_SPHERE};

/// Read-only per-particle inputs of the update, from particle `lo` on.
#[derive(Clone, Copy)]
struct Inputs<'a> {
    f: &'a [DVec3],
    torque: &'a [DVec3],
    mask: &'a [u32],
    rmass: &'a [f64],
    radius: &'a [f64],
}

impl Inputs<'_> {
    /// The half kick of particle `k` (relative to the slices' start): Δv and Δω, or
    /// `None` when it is not in the group.
    #[inline(always)]
    fn kick(&self, k: usize, groupbit: u32, dtf: f64) -> Option<(DVec3, DVec3)> {
        if self.mask[k] & groupbit == 0 {
            return None;
        }
        let m = self.rmass[k];
        let r = self.radius[k];
        Some((
            (dtf / m) * self.f[k],
            (dtf / (INERTIA_SPHERE * m * r * r)) * self.torque[k],
        ))
    }

    fn at(&self, lo: usize, hi: usize) -> Self {
        Inputs {
            f: &self.f[lo..hi],
            torque: &self.torque[lo..hi],
            mask: &self.mask[lo..hi],
            rmass: &self.rmass[lo..hi],
            radius: &self.radius[lo..hi],
        }
    }
}

/// First half of the velocity Verlet step for the owned particles of `groupbit`.
pub fn initial_integrate(p: &mut Particles, groupbit: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let n = p.nlocal();
    let Particles {
        x,
        v,
        omega,
        f,
        torque,
        mask,
        rmass,
        radius,
        ..
    } = p;
    let inp = Inputs {
        f,
        torque,
        mask,
        rmass,
        radius,
    };
    let run = |inp: Inputs, x: &mut [DVec3], v: &mut [DVec3], omega: &mut [DVec3]| {
        for k in 0..x.len() {
            if let Some((dv, dw)) = inp.kick(k, groupbit, dtf) {
                v[k] += dv;
                x[k] += dt * v[k];
                omega[k] += dw;
            }
        }
    };
    let (x, v, omega) = (&mut x[..n], &mut v[..n], &mut omega[..n]);
    if !parallel(n) {
        run(inp.at(0, n), x, v, omega);
        return;
    }
    x.par_chunks_mut(CHUNK)
        .zip(v.par_chunks_mut(CHUNK))
        .zip(omega.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, ((x, v), omega))| {
            let lo = c * CHUNK;
            run(inp.at(lo, lo + x.len()), x, v, omega);
        });
}

/// Second half of the velocity Verlet step.
pub fn final_integrate(p: &mut Particles, groupbit: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let n = p.nlocal();
    let Particles {
        v,
        omega,
        f,
        torque,
        mask,
        rmass,
        radius,
        ..
    } = p;
    let inp = Inputs {
        f,
        torque,
        mask,
        rmass,
        radius,
    };
    let run = |inp: Inputs, v: &mut [DVec3], omega: &mut [DVec3]| {
        for k in 0..v.len() {
            if let Some((dv, dw)) = inp.kick(k, groupbit, dtf) {
                v[k] += dv;
                omega[k] += dw;
            }
        }
    };
    let (v, omega) = (&mut v[..n], &mut omega[..n]);
    if !parallel(n) {
        run(inp.at(0, n), v, omega);
        return;
    }
    v.par_chunks_mut(CHUNK)
        .zip(omega.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, (v, omega))| {
            let lo = c * CHUNK;
            run(inp.at(lo, lo + v.len()), v, omega);
        });
}

/// `fix nve/limit absolute|radius_ratio xmax` (LIGGGHTS 3.8, from LAMMPS): velocity Verlet
/// for translation only (the angular velocity is left as it is), with the speed capped
/// after each half kick so that no particle moves more than `xmax` in one step (`xmax`
/// times its radius with `radius_ratio`): a velocity faster than xmax/dt is scaled down
/// to it, and each such reset is counted. The loops are serial: the fix relaxes
/// overlapped packings and is not on any hot path.
#[derive(Debug, Clone, PartialEq)]
pub struct NveLimit {
    /// The largest displacement per step (a length, or a multiple of the radius).
    pub xmax: f64,
    /// `radius_ratio`: `xmax` is relative to each particle's radius.
    pub radius_ratio: bool,
    /// The velocity resets on this rank since the run's set-up (the fix's scalar, summed
    /// over the ranks).
    pub resets: u64,
}

impl NveLimit {
    /// A fix with no resets counted yet.
    pub fn new(xmax: f64, radius_ratio: bool) -> Self {
        Self {
            xmax,
            radius_ratio,
            resets: 0,
        }
    }

    /// Half a kick of the group's velocities with the cap; with `drift`, then the
    /// positions' full step.
    pub fn integrate(&mut self, p: &mut Particles, groupbit: u32, dt: f64, drift: bool) {
        let dtf = 0.5 * dt;
        let vmax = self.xmax / dt;
        for i in 0..p.nlocal() {
            if p.mask[i] & groupbit == 0 {
                continue;
            }
            let mut v = p.v[i] + (dtf / p.rmass[i]) * p.f[i];
            let limit = if self.radius_ratio {
                vmax * p.radius[i]
            } else {
                vmax
            };
            let vsq = v.length_squared();
            if vsq > limit * limit {
                self.resets += 1;
                v *= (limit * limit / vsq).sqrt();
            }
            p.v[i] = v;
            if drift {
                p.x[i] += dt * v;
            }
        }
    }
}
