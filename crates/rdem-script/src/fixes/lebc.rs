//! `fix ID group lebc RATE [true|false] [gtemp G] [ave_reset N]` (LIGGGHTS_CFDRC,
//! elizabeth-suehr/LIGGGHTS_CFDRC; not in LIGGGHTS 3.8, which stops with "Invalid fix
//! style"): Lees–Edwards boundaries, a box in steady simple shear at rate RATE (γ̇, 1/time)
//! with the flow along x and the gradient along y. The engine's part (the sliding images,
//! the wrap through a y face, the ghosts) is [`rdem::shear`]; this fix adds what the
//! fork's fix does around it:
//!
//! - **At the set-up of the first run after the definition**, the velocities of the group
//!   are set to the shear profile γ̇ (y − y_c) along x (y_c the middle of the box) plus a
//!   normal scatter of standard deviation G γ̇ L_y on each component (`gtemp`, default
//!   1e-6), and the group's mass-weighted mean velocity is taken away. The scatter is
//!   drawn per particle from its tag, so it does not depend on the ranks or threads; the
//!   fork draws it from one fixed-seed generator in storage order, so the two agree in
//!   distribution, not particle for particle. The fork sets them at the set-up of every
//!   run (its `init`); rdem only once, so that `run 100` twice is `run 200` and a
//!   restart continues the run (the fix keeps that it has set them in restart files).
//! - **Every step**, the kinetic stress Σ m (v − v̄ − γ̇ (y − y_c) x̂) ⊗ (…) / V and the
//!   contact stress Σ_contacts r_ij ⊗ F_ij / V (both positive in compression) are
//!   averaged. Every 2500 steps a line `step count atom_count: N kxx kyy kxy cxx cyy
//!   cxy` is printed; every `ave_reset` steps (default 50000, the fork's fixed window)
//!   the line `stress: kxx kyy kxy cxx cyy cxy` goes to the screen and the log and the
//!   averages restart. `f_ID[1..6]` are the current averages in that order.
//! - `false` (the second word; also `no` or `0`) prints the stresses divided by ρ γ̇² d²
//!   (ρ the particles' mass per volume, d their mean diameter); `true` (`yes`, `1`), the
//!   default, as they are. The fork divides by 2500 · 100² · d², its particles' density
//!   and its examples' rate, fixed in its code: the two agree for those values. Its code
//!   reads any second word but `false` as `true`; scripts of its older versions give `1`.
//!
//! Rigid clumps (`fix multisphere`, as four of the fork's examples use) shear as the
//! fork's do: a clump in the group takes the profile and the scatter at its centre of
//! mass (its angular velocity kept), and counts in the kinetic stress and the mean
//! velocity by its centre of mass's velocity, translation only. The engine places a
//! clump's spheres on the sliding images ([`rdem::shear`]).
//!
//! The fork's own code requires the 7-word form `lebc RATE true gtemp G` and stops on
//! the 4-word form `lebc RATE` that its examples use; rdem takes both. Its README's
//! `body_data NAME N` (clump data written every N steps, in a layout the fork does not
//! document) is refused. Lees–Edwards needs `boundary p p p` and, with MPI, one
//! brick along x (`processors 1 * *`); both are checked when a run starts.

use glam::DVec3;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use rdem::shear::Shear;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "lebc",
    parse,
    Stages::PRE_STEP.and(Stages::END_OF_STEP).and(Stages::VALUES),
    "`RATE [true\\|false\\|1\\|0] [gtemp G] [ave_reset N]` (LIGGGHTS_CFDRC): Lees-Edwards shear at rate RATE, flow along x, gradient along y; velocities set to the profile (scatter G·RATE·Ly) at the first run's set-up; kinetic and contact stress averaged, `stress:` lines every N steps (50000)",
)
.notes("the fork resets the velocities at every run, rdem at the first only; needs boundary p p p, and one MPI brick along x; rigid clumps shear by their centres of mass (`body_data` is refused); the scatter is drawn per particle from its tag, not from the fork's single generator");

/// Steps between the progress lines.
const PROGRESS_EVERY: u64 = 2500;
/// Seed of the velocity scatter (mixed with each particle's tag).
const SEED: u64 = 0x6c65_6263;
/// Seed of a rigid clump's velocity scatter (mixed with its body's tag).
const BODY_SEED: u64 = 0x6c65_6263_626f_6479;

/// The fix's settings and running averages.
struct Lebc {
    rate: f64,
    dimensional: bool,
    gtemp: f64,
    ave_reset: u64,
    avg: Averages,
    /// The velocities have been set (at the first run's set-up).
    started: bool,
}

/// Running means of the kinetic and contact stress (xx yy zz xy xz yz each) over `count`
/// steps; kept in restart files.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct Averages {
    kinetic: [f64; 6],
    contact: [f64; 6],
    count: u64,
}

/// What a restart file keeps: the images' offset and the averages.
#[derive(Serialize, Deserialize)]
struct LebcState {
    offset: f64,
    avg: Averages,
    started: bool,
}

fn parse(_sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let rate = a.f64("shear rate")?;
    let mut dimensional = true;
    // The flag as a word (`true`, `false`) or a number (`1`, `0`), which scripts of the
    // fork's older versions give (`lebc 100.0 1`).
    if let Some(w @ ("true" | "false" | "yes" | "no" | "1" | "0")) = a.peek() {
        dimensional = matches!(w, "true" | "yes" | "1");
        a.word("true or false")?;
    }
    let (mut gtemp, mut ave_reset) = (1e-6, 50000);
    while !a.is_done() {
        match a.keyword("fix lebc keyword", &["gtemp", "ave_reset", "body_data"])? {
            "gtemp" => gtemp = a.non_negative("gtemp")?,
            "ave_reset" => ave_reset = a.count("ave_reset")?,
            _ => {
                return Err(a.error_prev(
                    "fix lebc: body_data (the fork's file of clump data) is not supported",
                    Some("the keywords rdem takes are gtemp and ave_reset (the file's layout is not documented: compute multisphere gives the clumps' data for dump local)".into()),
                ))
            }
        }
    }
    Ok(Box::new(Lebc {
        rate,
        dimensional,
        gtemp,
        ave_reset,
        avg: Averages::default(),
        started: false,
    }))
}

/// Rigid clump `k`'s mass.
fn body_mass(w: &rdem::World, k: usize) -> Option<f64> {
    Some(w.multisphere.as_ref()?.bodies.get(k)?.mass)
}

impl Lebc {
    /// Sets the group's velocities to the shear profile plus the scatter, less the mean.
    /// A clump in the group (any of its spheres is) moves as one: its centre of mass
    /// takes the profile at its height and the scatter, as the fork sets its bodies'
    /// velocities, and its angular velocity is kept. The mean is mass-weighted over the
    /// free spheres and the clumps.
    fn set_velocities(&self, w: &mut rdem::World, groupbit: u32) {
        let (lo, prd) = (w.domain.boxlo, w.domain.prd());
        let yc = lo.y + 0.5 * prd.y;
        let sigma = self.gtemp * prd.y * self.rate.abs();
        let draw = |seed: u64, y: f64| {
            let mut rng = rdem::insert::rng(seed);
            let mut one = |mean: f64| match Normal::new(mean, sigma) {
                Ok(n) if sigma > 0.0 => n.sample(&mut rng),
                _ => mean,
            };
            let vx = one(self.rate * (y - yc));
            DVec3::new(vx, one(0.0), one(0.0))
        };
        let nbodies = w.multisphere.as_ref().map_or(0, |ms| ms.bodies.len());
        // Which clumps are in the group, over all ranks.
        let mut grouped = vec![0.0; nbodies];
        let clump: Vec<Option<usize>> = {
            let of = w.clump_of();
            (0..w.particles.nlocal()).map(&of).collect()
        };
        let p = &mut w.particles;
        let mut momentum = [0.0; 4];
        for (i, &c) in clump.iter().enumerate() {
            if p.mask[i] & groupbit == 0 {
                continue;
            }
            if let Some(k) = c {
                grouped[k] = 1.0;
                continue;
            }
            let v = draw(SEED ^ p.tag[i], p.x[i].y);
            p.v[i] = v;
            let m = p.rmass[i];
            momentum[0] += m * v.x;
            momentum[1] += m * v.y;
            momentum[2] += m * v.z;
            momentum[3] += m;
        }
        w.comm.sum_slice(&mut momentum);
        w.comm.sum_slice(&mut grouped);
        if let Some(ms) = w.multisphere.as_mut() {
            for k in (0..nbodies).filter(|&k| grouped[k] > 0.0) {
                let seed = BODY_SEED ^ ms.tags[k];
                let b = &mut ms.bodies[k];
                b.v = draw(seed, b.x.y);
            }
        }
        // Every rank holds every body: each adds them alike, after the reduction.
        for k in (0..nbodies).filter(|&k| grouped[k] > 0.0) {
            if let Some((m, (_, v))) = body_mass(w, k).zip(w.body_in_box(k)) {
                momentum[0] += m * v.x;
                momentum[1] += m * v.y;
                momentum[2] += m * v.z;
                momentum[3] += m;
            }
        }
        if momentum[3] > 0.0 {
            let mean = DVec3::new(momentum[0], momentum[1], momentum[2]) / momentum[3];
            let p = &mut w.particles;
            for (i, c) in clump.iter().enumerate() {
                if p.mask[i] & groupbit != 0 && c.is_none() {
                    p.v[i] -= mean;
                }
            }
            if let Some(ms) = w.multisphere.as_mut() {
                for k in (0..nbodies).filter(|&k| grouped[k] > 0.0) {
                    ms.bodies[k].v -= mean;
                }
            }
        }
        if nbodies > 0 {
            w.refresh_clump_velocities();
        }
    }

    /// This step's kinetic and contact stress (xx yy zz xy xz yz, over all ranks). The
    /// kinetic part counts a free sphere by its velocity and a rigid clump by its centre
    /// of mass's (translation only, as the fork counts its bodies), each less the mean
    /// velocity and the profile at its height.
    fn stresses(&self, w: &rdem::World, virial: &[[f64; 6]]) -> ([f64; 6], [f64; 6]) {
        let (lo, prd) = (w.domain.boxlo, w.domain.prd());
        let yc = lo.y + 0.5 * prd.y;
        let volume = w.domain.volume();
        let p = &w.particles;
        let n = p.nlocal();
        let clump = w.clump_of();
        let nbodies = w.multisphere.as_ref().map_or(0, |ms| ms.bodies.len());
        let bodies: Vec<(f64, DVec3, DVec3)> = (0..nbodies)
            .filter_map(|k| Some((body_mass(w, k)?, w.body_in_box(k)?)))
            .map(|(m, (x, v))| (m, x, v))
            .collect();
        let mut mean = [0.0; 4];
        for i in (0..n).filter(|&i| clump(i).is_none()) {
            let (m, v) = (p.rmass[i], p.v[i]);
            mean[0] += m * v.x;
            mean[1] += m * v.y;
            mean[2] += m * v.z;
            mean[3] += m;
        }
        w.comm.sum_slice(&mut mean);
        for &(m, _, v) in &bodies {
            mean[0] += m * v.x;
            mean[1] += m * v.y;
            mean[2] += m * v.z;
            mean[3] += m;
        }
        let vbar = DVec3::new(mean[0], mean[1], mean[2]) / mean[3].max(f64::MIN_POSITIVE);
        let kinetic_of = |m: f64, v: DVec3, y: f64, s: &mut [f64]| {
            let mut u = v - vbar;
            u.x -= self.rate * (y - yc);
            let t = [
                u.x * u.x,
                u.y * u.y,
                u.z * u.z,
                u.x * u.y,
                u.x * u.z,
                u.y * u.z,
            ];
            for k in 0..6 {
                s[k] += m * t[k];
            }
        };
        // Kinetic then contact, 12 sums reduced at once.
        let mut s = [0.0; 12];
        for (i, w) in virial[..n].iter().enumerate() {
            if clump(i).is_none() {
                kinetic_of(p.rmass[i], p.v[i], p.x[i].y, &mut s);
            }
            for k in 0..6 {
                s[6 + k] += w[k];
            }
        }
        w.comm.sum_slice(&mut s);
        for &(m, x, v) in &bodies {
            kinetic_of(m, v, x.y, &mut s);
        }
        let mut kinetic = [0.0; 6];
        let mut contact = [0.0; 6];
        for k in 0..6 {
            kinetic[k] = s[k] / volume;
            contact[k] = s[6 + k] / volume;
        }
        (kinetic, contact)
    }

    /// The factor the stresses are printed with: 1, or 1/(ρ γ̇² d²) with `false`.
    fn scale(&self, w: &rdem::World) -> f64 {
        if self.dimensional {
            return 1.0;
        }
        let p = &w.particles;
        let mut s = [0.0; 3];
        for i in 0..p.nlocal() {
            let r = p.radius[i];
            s[0] += p.rmass[i];
            s[1] += 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
            s[2] += r;
        }
        let count = w.comm.sum_count(p.nlocal() as u64).max(1) as f64;
        w.comm.sum_slice(&mut s);
        let (rho, d) = (s[0] / s[1], 2.0 * s[2] / count);
        1.0 / (rho * self.rate * self.rate * d * d)
    }

    /// kxx kyy kxy cxx cyy cxy, scaled.
    fn printed(&self, scale: f64) -> [f64; 6] {
        let (k, c) = (&self.avg.kinetic, &self.avg.contact);
        [k[0], k[1], k[3], c[0], c[1], c[3]].map(|v| v * scale)
    }
}

impl ScriptFix for Lebc {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        w.domain.shear = Some(Shear::new(self.rate));
        Ok(())
    }

    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no box")?;
        Ok(self.printed(self.scale(w)).to_vec())
    }

    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup && !self.started {
            self.set_velocities(ctx.world(), head.groupbit);
            self.started = true;
        }
        Ok(())
    }

    fn wants_virial(&self, _step: u64, setup: bool) -> bool {
        !setup
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        let step = ctx.step;
        let w = ctx.world_ref();
        let virial = w.current_virial().ok_or_else(|| {
            format!(
                "fix {} (lebc): the contact virial of step {step} was not computed",
                head.id
            )
        })?;
        let (kinetic, contact) = self.stresses(w, virial);
        let n = self.avg.count as f64;
        for k in 0..6 {
            self.avg.kinetic[k] = (self.avg.kinetic[k] * n + kinetic[k]) / (n + 1.0);
            self.avg.contact[k] = (self.avg.contact[k] * n + contact[k]) / (n + 1.0);
        }
        self.avg.count += 1;
        let progress = self.avg.count % PROGRESS_EVERY == 0;
        let window = self.avg.count == self.ave_reset;
        if !(progress || window) {
            return Ok(());
        }
        // Only on the steps that print (every rank alike: the reductions are collective).
        let natoms = w.comm.sum_count(w.particles.nlocal() as u64);
        let v = self.printed(self.scale(w));
        if progress {
            let show = v.map(|x| format!("{x}")).join(" ");
            ctx.line(&format!(
                "{step} {} atom_count: {natoms} {show}",
                self.avg.count
            ));
        }
        if window {
            // The fork writes the window's line with printf's %f.
            let fixed = v.map(|x| format!("{x:.6}")).join(" ");
            ctx.line(&format!("stress: {fixed}"));
            self.avg = Averages::default();
        }
        Ok(())
    }

    fn save_state(&self, sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let offset = sim.world.as_ref()?.domain.shear?.offset;
        postcard::to_stdvec(&LebcState {
            offset,
            avg: self.avg.clone(),
            started: self.started,
        })
        .ok()
    }

    fn restore_state(&mut self, sim: &mut Sim, _head: &FixHead, state: &[u8]) -> Result<(), Error> {
        let st: LebcState =
            postcard::from_bytes(state).map_err(|e| format!("fix lebc state: {e}"))?;
        self.avg = st.avg;
        self.started = st.started;
        if let Some(s) = sim.world.as_mut().and_then(|w| w.domain.shear.as_mut()) {
            s.offset = st.offset;
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = sim.world.as_mut() {
            w.domain.shear = None;
        }
    }
}
