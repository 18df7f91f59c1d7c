//! `fix ID group check/timestep/bond N fraction [warn yes|no] [error yes|no]`
//! (LIGGGHTS_Flexible_Fibers): every N steps, the time step as a fraction of the
//! shortest bond time √(m*/K_n) ([`rdem::bond_gran::GranBonds::shortest_time`]); above
//! `fraction`, the fork's warning "time-step is P % of bond time" (or an error with
//! `error yes`). `f_ID`: the fraction.

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "check/timestep/bond",
    parse,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "`N fraction` (`warn`, `error`) (LIGGGHTS_Flexible_Fibers): the time step against the bond time √(m*/K_n)",
)
.notes("`f_ID`: dt over the shortest bond time");

/// `fix check/timestep/bond`.
struct CheckBond {
    every: u64,
    fraction: f64,
    warn: bool,
    error: bool,
    value: f64,
}

fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.count("nevery")?;
    let fraction = a.positive("fraction of the bond time")?;
    let (mut warn, mut error) = (true, false);
    while !a.is_done() {
        match a.keyword("check/timestep/bond keyword", &["warn", "error"])? {
            "warn" => warn = a.yes_no("warn")?,
            _ => error = a.yes_no("error")?,
        }
    }
    if sim.setup.bond_gran.is_none() {
        return Err(a.error_cmd(
            "fix check/timestep/bond needs an atom style with bonds",
            Some("atom_style hybrid granular bond/gran n_bondtypes N bonds_per_atom M".into()),
        ));
    }
    Ok(Box::new(CheckBond {
        every,
        fraction,
        warn,
        error,
        value: 0.0,
    }))
}

impl ScriptFix for CheckBond {
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(vec![self.value])
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup || ctx.step % self.every != 0 {
            return Ok(());
        }
        let w = ctx.world_ref();
        let t = w
            .bonds
            .as_ref()
            .and_then(|b| b.shortest_time(&w.particles))
            .unwrap_or(f64::INFINITY);
        let t = w.comm.min(t);
        if !t.is_finite() {
            return Ok(());
        }
        self.value = w.dt / t;
        if self.value > self.fraction {
            let msg = format!(
                "time-step is {:.6} % of bond time (fix {}: limit {:.2} %)",
                100.0 * self.value,
                head.id,
                100.0 * self.fraction
            );
            super::check_timestep_gran::report(ctx, msg, self.error, self.warn)?;
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
