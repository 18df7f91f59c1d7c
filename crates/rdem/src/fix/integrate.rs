//! `fix nve/sphere`: velocity Verlet for translation and rotation of solid spheres.
//! Initial half step: v += dt/2 · f/m, x += dt · v, ω += dt/2 · τ/(0.4 m r²);
//! final half step: v += dt/2 · f/m, ω += dt/2 · τ/(0.4 m r²).

use crate::particles::{Particles, INERTIA_SPHERE};

/// First half of the velocity Verlet step for the owned particles of `groupbit`.
pub fn initial_integrate(p: &mut Particles, groupbit: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let n = p.nlocal();
    for i in 0..n {
        if p.mask[i] & groupbit == 0 {
            continue;
        }
        let m = p.rmass[i];
        let r = p.radius[i];
        p.v[i] += (dtf / m) * p.f[i];
        p.x[i] += dt * p.v[i];
        p.omega[i] += (dtf / (INERTIA_SPHERE * m * r * r)) * p.torque[i];
    }
}

/// Second half of the velocity Verlet step.
pub fn final_integrate(p: &mut Particles, groupbit: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let n = p.nlocal();
    for i in 0..n {
        if p.mask[i] & groupbit == 0 {
            continue;
        }
        let m = p.rmass[i];
        let r = p.radius[i];
        p.v[i] += (dtf / m) * p.f[i];
        p.omega[i] += (dtf / (INERTIA_SPHERE * m * r * r)) * p.torque[i];
    }
}
