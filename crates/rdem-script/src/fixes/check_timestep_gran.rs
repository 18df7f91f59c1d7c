//! `fix check/timestep/gran N fraction_r fraction_h`: every N steps, the time step as a
//! fraction of the Rayleigh time and of the Hertz time of the fastest collision; a warning
//! (or an error) above the limits; `f_ID[1]`, `f_ID[2]`.

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "check/timestep/gran",
    parse,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "`N fraction_r fraction_h` (`warn`, `error`, `vmax`)",
)
.notes("`f_ID[1]`, `f_ID[2]`: dt over the Rayleigh and Hertz times")
.atoi();

/// `fix check/timestep/gran`.
pub struct CheckTimestep {
    /// Every this many steps.
    pub every: u64,
    /// Warn above this fraction of the Rayleigh time.
    pub fraction_r: f64,
    /// Warn above this fraction of the Hertz time.
    pub fraction_h: f64,
    /// `warn yes`.
    pub warn: bool,
    /// `error yes`.
    pub error: bool,
    /// `vmax`: least velocity for the Hertz estimate.
    pub vmax: f64,
    /// Last values: dt / Rayleigh time, dt / Hertz time.
    pub values: [f64; 2],
}

fn parse(_sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.count("nevery")?;
    let fraction_r = a.positive("fraction of the Rayleigh time")?;
    let fraction_h = a.positive("fraction of the Hertz time")?;
    let (mut warn, mut error, mut vmax) = (true, false, 0.0);
    while !a.is_done() {
        match a.keyword("check/timestep/gran keyword", &["warn", "error", "vmax"])? {
            "warn" => warn = a.yes_no("warn")?,
            "error" => error = a.yes_no("error")?,
            _ => vmax = a.non_negative("vmax")?,
        }
    }
    Ok(Box::new(CheckTimestep {
        every,
        fraction_r,
        fraction_h,
        warn,
        error,
        vmax,
        values: [0.0; 2],
    }))
}

/// Rayleigh and Hertz times of the current state (LIGGGHTS' check/timestep/gran
/// estimates): the smallest Rayleigh time π r √(ρ/G)/(0.1631 ν + 0.8766) over particles,
/// and the Hertz time 2.87 (m²/(r E*² v))^(1/5) per particle, with E* = E/(2(1−ν²)), the
/// particle's mass m = ρ 4/3 π r³ (ρ: a clump's sphere, its template's density) and radius
/// r, and v the largest
/// particle speed (at least `vmax`)
/// — the value LIGGGHTS 3.8 reports (checked against it, tests/liggghts_parity.rs).
pub fn timestep_limits(sim: &Sim, vmax: f64) -> Option<(f64, f64)> {
    let w = sim.world.as_ref()?;
    let p = &w.particles;
    let e = sim.defs.properties.get("youngsModulus")?;
    let nu = sim.defs.properties.get("poissonsRatio")?;
    let (mut t_r, mut t_h) = (f64::MAX, f64::MAX);
    let mut v: f64 = 0.0;
    for i in 0..p.nlocal() {
        v = v.max(p.v[i].length());
    }
    let v = w.comm.max(v).max(vmax);
    // A clump's sphere: its template's density, and the mass of a sphere of that density,
    // as LIGGGHTS 3.8 has them (tutorial multisphere_stone_restitution: 0.039839044 of
    // the Rayleigh time on every seed, the value of density 2500 and the smallest sphere;
    // neither the sphere's share of its body's mass nor the body's mass, which its dump
    // `mass` shows, gives LIGGGHTS' Hertz fractions).
    let clump_of = w.clump_of();
    let density = |i: usize| match (clump_of(i), &w.multisphere) {
        (Some(k), Some(ms)) => ms.info[k].density,
        _ => p.density[i],
    };
    for i in 0..p.nlocal() {
        let t = p.ty[i] as usize - 1;
        let (ei, ni) = (*e.values.get(t)?, *nu.values.get(t)?);
        let g = ei / (2.0 * (1.0 + ni));
        let r = p.radius[i];
        t_r = t_r.min(std::f64::consts::PI * r * (density(i) / g).sqrt() / (0.1631 * ni + 0.8766));
        if v > 0.0 {
            let e_star = ei / (2.0 * (1.0 - ni * ni));
            let m = density(i) * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
            t_h = t_h.min(2.87 * (m * m / (r * e_star * e_star * v)).powf(0.2));
        }
    }
    Some((w.comm.min(t_r), w.comm.min(t_h)))
}

/// A time step over its limit: the error (`error yes`), else the warning once (`warn
/// yes`), else nothing.
pub(super) fn report(
    ctx: &mut StageCtx,
    msg: String,
    error: bool,
    warn: bool,
) -> Result<(), Error> {
    if error {
        return Err(Error::Invalid(msg));
    }
    if warn {
        ctx.warn_once(&msg);
    }
    Ok(())
}

impl ScriptFix for CheckTimestep {
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(self.values.to_vec())
    }

    /// LIGGGHTS 3.8 divides the two fractions by the atom count under
    /// `thermo_modify norm yes` (observed; tests/liggghts_parity.rs).
    fn extensive(&self) -> bool {
        true
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let setup = ctx.setup;
        if setup || step % self.every != 0 {
            return Ok(());
        }
        let Some((tr, th)) = timestep_limits(ctx.view(), self.vmax) else {
            return Ok(());
        };
        let dt = ctx.world_ref().dt;
        let vals = [dt / tr, if th < f64::MAX { dt / th } else { 0.0 }];
        self.values = vals;
        for (v, f, what) in [
            (vals[0], self.fraction_r, "Rayleigh"),
            (vals[1], self.fraction_h, "Hertz"),
        ] {
            if v > f {
                let msg = format!(
                    "time-step is {:.2} % of {what} time (fix {}: limit {:.2} %)",
                    100.0 * v,
                    head.id,
                    100.0 * f
                );
                report(ctx, msg, self.error, self.warn)?;
            }
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
