//! `fix ID group slowinit [xmax X] [reset N] [threshold T] [start_dt A] [end_dt B]`
//! (LIGGGHTS_CFDRC, elizabeth-suehr/LIGGGHTS_CFDRC; not in LIGGGHTS 3.8): relaxes a dense
//! packing inserted with overlaps before a sheared run. No manual exists; this is the
//! fork's behaviour as its code does it (`src/fix_init.cpp`, read, not copied):
//!
//! - **Integration**: the group moves by `fix nve/limit absolute X`
//!   ([`rdem::fix::integrate::NveLimit`]): translation only, the speed capped at X/dt.
//! - **At each run's set-up**: every velocity is zeroed (a rigid clump's velocity and
//!   angular momentum too), the timestep is set to A, and the restitution coefficient of
//!   every pair of types to 0.1.
//! - **Before each step**: the restitution of every pair of types is
//!   e = max over the fix's life of 0.1 + 0.9 / (1 + exp(−17.5 (m − 0.8))), m being the
//!   smallest ratio d / (r_i + r_j) over the pairs of the last step (1 when none touch;
//!   0.5 before the first step).
//! - **After each step**: the timestep of the next is min(A (9.9 B / A)^(s/9999), 10 B e)
//!   at step s < 10000 (10 000 log-spaced values from A to 9.9 B), 10 B e from then on;
//!   the mass-weighted mean velocity of the free spheres and the clumps is taken away.
//!   Every 1000 steps a line `pre-run, step: s, ke/mass=…, natoms=…, overlap=m, cor=e,
//!   dt=…` (and ` nbody: n` with clumps) is printed, and the kinetic energy per mass of
//!   the group (clumps by their bodies) is compared with T. Every N steps the velocities
//!   are zeroed again; if the last comparison found less than T, the timestep is set to
//!   B, the restitution coefficients back to the script's, and the run ends there (the
//!   script goes on with its next command).
//!
//! Defaults as in the fork: X 0.1, N 10, T 1e-6, A 1e-16, B 1e-10. The fork requires the
//! keywords in this order; rdem takes them in any. `f_ID` is the number of velocity
//! resets of the cap since the run's start. Time-dependent commands see the simulated
//! time as the sum of the changing timesteps.

use crate::error::Error;
use glam::DVec3;
use rdem::fix::integrate::NveLimit;
use rdem::{Fix, FixKind};

use super::engine::InEngine;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "slowinit",
    parse,
    Stages::ENGINE
        .and(Stages::PRE_STEP)
        .and(Stages::END_OF_STEP)
        .and(Stages::VALUES),
    "`[xmax X] [reset N] [threshold T] [start_dt A] [end_dt B]` (LIGGGHTS_CFDRC): relaxes an overlapped packing: nve/limit X, velocities zeroed every N steps, restitution and timestep (A to B) ramped with the smallest overlap ratio, the run ended once kinetic energy per mass < T",
)
.notes("the fork's keywords must come in this order; rdem takes any order");

/// Steps of the timestep table.
const TABLE: u64 = 10_000;
/// Steps between the progress lines and kinetic-energy checks.
const CHECK_EVERY: u64 = 1000;
/// The restitution coefficient at the start.
const COR_START: f64 = 0.1;

struct SlowInit {
    inner: InEngine,
    reset: u64,
    threshold: f64,
    start_dt: f64,
    end_dt: f64,
    /// The restitution coefficient reached (it never decreases).
    max_cor: f64,
    /// The coefficient in the pair table this step.
    cor: f64,
    /// The smallest d / (r_i + r_j) of the last step.
    ratio: f64,
    /// The last check found the kinetic energy per mass under the threshold.
    exit: bool,
    /// The script's restitution coefficients (put back when the run ends early).
    saved: Vec<f64>,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (mut xmax, mut reset, mut threshold) = (0.1, 10, 1e-6);
    let (mut start_dt, mut end_dt) = (1e-16, 1e-10);
    while !a.is_done() {
        match a.keyword(
            "fix slowinit keyword",
            &["xmax", "reset", "threshold", "start_dt", "end_dt"],
        )? {
            "xmax" => xmax = a.positive("xmax")?,
            "reset" => reset = a.count("reset")?,
            "threshold" => threshold = a.non_negative("threshold")?,
            "start_dt" => start_dt = a.positive("start_dt")?,
            _ => end_dt = a.positive("end_dt")?,
        }
    }
    sim.world_ref(a)?;
    let fix = Fix::new(
        &head.id,
        head.groupbit,
        FixKind::NveLimit(NveLimit::new(xmax, false)),
    )
    .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(SlowInit {
        inner: InEngine::new(fix),
        reset,
        threshold,
        start_dt,
        end_dt,
        max_cor: COR_START,
        cor: COR_START,
        ratio: 0.5,
        exit: false,
        saved: Vec::new(),
    }))
}

/// `x` as C's `%.3e` writes it (`9.736e-01`).
fn sci3(x: f64) -> String {
    let s = format!("{x:.3e}");
    match s.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = e.strip_prefix('-').map_or(("+", e), |d| ("-", d));
            format!("{m}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

impl SlowInit {
    /// The restitution coefficient for the overlap ratio `m` (and the new maximum).
    fn variable_cor(&mut self, m: f64) -> f64 {
        let e = 0.9 / (1.0 + (-17.5 * (m - 0.8)).exp()) + 0.1;
        self.max_cor = self.max_cor.max(e);
        self.max_cor
    }

    /// The timestep after step `step`.
    fn next_dt(&self, step: u64, cor: f64) -> f64 {
        let cap = self.end_dt * 10.0 * cor;
        if step >= TABLE {
            return cap;
        }
        let (a, b) = (self.start_dt.ln(), (9.9 * self.end_dt).ln());
        let t = (a + (b - a) * step as f64 / (TABLE - 1) as f64).exp();
        t.min(cap)
    }
}

/// Every pair of types' restitution coefficient set to `e` (the pair's table mixed again).
fn set_restitution(w: &mut rdem::World, e: &[f64]) -> Result<(), Error> {
    let r = &mut w.materials.restitution;
    if e.len() == 1 {
        r.iter_mut().for_each(|v| *v = e[0]);
    } else {
        r.copy_from_slice(e);
    }
    w.refresh_pair_table()?;
    Ok(())
}

/// Zeroes the velocities: the free spheres' (spins kept, as the fork), the clumps'
/// velocities and angular momenta.
fn zero_velocities(w: &mut rdem::World) {
    let clump: Vec<bool> = {
        let of = w.clump_of();
        (0..w.particles.nlocal()).map(|i| of(i).is_some()).collect()
    };
    for (v, _) in w.particles.v.iter_mut().zip(&clump).filter(|(_, &c)| !c) {
        *v = DVec3::ZERO;
    }
    if let Some(ms) = w.multisphere.as_mut() {
        for b in &mut ms.bodies {
            b.v = DVec3::ZERO;
            b.angmom = DVec3::ZERO;
        }
        w.refresh_clump_velocities();
    }
}

/// Takes the mass-weighted mean velocity of the free spheres and the clumps away.
fn remove_mean(w: &mut rdem::World) {
    let clump: Vec<bool> = {
        let of = w.clump_of();
        (0..w.particles.nlocal()).map(|i| of(i).is_some()).collect()
    };
    let p = &w.particles;
    let mut s = [0.0; 4];
    for i in (0..p.nlocal()).filter(|&i| !clump[i]) {
        let m = p.rmass[i];
        s[0] += m * p.v[i].x;
        s[1] += m * p.v[i].y;
        s[2] += m * p.v[i].z;
        s[3] += m;
    }
    w.comm.sum_slice(&mut s);
    let bodies = w.multisphere.as_ref().map_or(&[][..], |ms| &ms.bodies[..]);
    for b in bodies {
        s[0] += b.mass * b.v.x;
        s[1] += b.mass * b.v.y;
        s[2] += b.mass * b.v.z;
        s[3] += b.mass;
    }
    if s[3] <= 0.0 {
        return;
    }
    let mean = DVec3::new(s[0], s[1], s[2]) / s[3];
    let p = &mut w.particles;
    for i in (0..p.nlocal()).filter(|&i| !clump[i]) {
        p.v[i] -= mean;
    }
    if let Some(ms) = w.multisphere.as_mut() {
        for b in &mut ms.bodies {
            b.v -= mean;
        }
        w.refresh_clump_velocities();
    }
}

/// The smallest d / (r_i + r_j) over the listed pairs (1 when none is closer), over all
/// ranks.
fn overlap_ratio(w: &rdem::World) -> f64 {
    let p = &w.particles;
    let list = &w.neighbor.list;
    let mut m: f64 = 1.0;
    for i in 0..p.nlocal() {
        for &j in list.partners(i) {
            let j = j as usize;
            let d = p.x[i].distance(p.x[j]);
            m = m.min(d / (p.radius[i] + p.radius[j]));
        }
    }
    w.comm.min(m)
}

/// Kinetic energy per mass of the group: free spheres by their velocities, clumps by
/// their bodies (translation and rotation).
fn ke_per_mass(w: &rdem::World, groupbit: u32) -> f64 {
    let clump = w.clump_of();
    let p = &w.particles;
    let mut s = [0.0; 2];
    for i in (0..p.nlocal()).filter(|&i| p.mask[i] & groupbit != 0 && clump(i).is_none()) {
        s[0] += 0.5 * p.rmass[i] * p.v[i].length_squared();
        s[1] += p.rmass[i];
    }
    w.comm.sum_slice(&mut s);
    for b in w.multisphere.as_ref().map_or(&[][..], |ms| &ms.bodies[..]) {
        let (t, r) = b.kinetic_energy();
        s[0] += t + r;
        s[1] += b.mass;
    }
    if s[1] > 0.0 {
        s[0] / s[1]
    } else {
        0.0
    }
}

impl ScriptFix for SlowInit {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        self.inner.values(sim, head)
    }

    fn pre_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            let w = ctx.world();
            zero_velocities(w);
            self.saved = w.materials.restitution.clone();
            self.ratio = 0.5;
            self.exit = false;
            self.cor = COR_START;
            set_restitution(w, &[COR_START])?;
            ctx.set_timestep(self.start_dt)?;
            return Ok(());
        }
        let e = self.variable_cor(self.ratio);
        if e != self.cor {
            self.cor = e;
            set_restitution(ctx.world(), &[e])?;
        }
        Ok(())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        let step = ctx.step;
        self.ratio = overlap_ratio(ctx.world_ref());
        let e = self.variable_cor(self.ratio);
        ctx.set_timestep(self.next_dt(step, e))?;
        if step % CHECK_EVERY == 0 {
            let w = ctx.world_ref();
            let ke = ke_per_mass(w, head.groupbit);
            let natoms = w.comm.sum_count(w.particles.nlocal() as u64);
            let nbody = w
                .multisphere
                .as_ref()
                .map(|ms| format!(" nbody: {} ", ms.bodies.len()))
                .unwrap_or_default();
            let line = format!(
                "pre-run, step: {step}, ke/mass={}, natoms={natoms}, overlap={}, cor={}, dt={}{nbody}",
                sci3(ke),
                sci3(self.ratio),
                sci3(self.cor),
                sci3(w.dt)
            );
            ctx.line(&line);
            self.exit = ke < self.threshold;
        }
        if step % self.reset == 0 {
            zero_velocities(ctx.world());
            if self.exit {
                ctx.set_timestep(self.end_dt)?;
                let saved = std::mem::take(&mut self.saved);
                set_restitution(ctx.world(), &saved)?;
                ctx.end_run();
                return Ok(());
            }
        }
        remove_mean(ctx.world());
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_as_c_does() {
        assert_eq!(sci3(0.9736), "9.736e-01");
        assert_eq!(sci3(3.4674e-9), "3.467e-09");
        assert_eq!(sci3(0.0), "0.000e+00");
        assert_eq!(sci3(7090.0), "7.090e+03");
    }
}
