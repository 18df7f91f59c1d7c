//! `fix adapt N atom diameter v_name [reset yes|no]`: every N steps (and before a run's
//! set-up forces) the particles of the group take the diameter an atom-style variable
//! gives; the mass follows at constant density. With `reset yes` the radii return to
//! their values of the run's start when the run ends.

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::context;
use crate::error::Error;
use crate::sim::Sim;
use crate::variables::Variable;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "adapt",
    parse,
    Stages::PRE_STEP.and(Stages::END_OF_RUN),
    "`N atom diameter v_name` (`reset`)",
)
.notes("the mass follows at constant density; the growth counts against the neighbor skin, so no contact is missed");

/// `fix adapt N atom diameter v_name`.
pub struct Adapt {
    /// Every this many steps.
    pub every: u64,
    /// Atom-style variable giving the new diameter.
    pub var: String,
    /// `reset yes`: radii restored when the run ends.
    pub reset: bool,
    /// Radii at the start of the run (for reset).
    pub saved: Option<Vec<(u64, f64)>>,
}

fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    if sim.setup.dimension == 2 {
        return Err(a.error_at(
            super::STYLE_WORD,
            "fix adapt in a 2d simulation is not supported yet",
            Some("2d particles have disc masses, which fix adapt does not keep yet".into()),
        ));
    }
    let every = a.count("N (adapt every N steps)")?;
    match a.keyword("adapt attribute", &["atom", "pair"])? {
        "atom" => {}
        _ => return Err(a.error_prev(
            "fix adapt pair is not supported (granular pair styles have no per-pair parameters)",
            Some("use 'atom diameter v_name'".into()),
        )),
    }
    a.keyword("atom attribute", &["diameter"])?;
    let v = a.word("variable (v_name)")?;
    let Some(var) = v.strip_prefix("v_") else {
        return Err(a.error_prev(
            format!("expected v_name, got '{v}'"),
            Some("give an atom-style variable: 'variable d atom ...' then 'v_d'".into()),
        ));
    };
    // A variable defined later is checked when the run starts, as LIGGGHTS does.
    match sim.script.vars.get(var) {
        Some(crate::variables::Variable::Atom(_)) | None => {}
        Some(_) => {
            return Err(a.error_prev(
                format!("fix adapt: variable '{var}' is not atom-style"),
                Some(format!(
                    "the new diameters come per particle: define 'variable {var} atom FORMULA'"
                )),
            ))
        }
    }
    let var = var.to_string();
    let mut reset = false;
    while !a.is_done() {
        match a.keyword("adapt keyword", &["reset", "scale"])? {
            "reset" => reset = a.yes_no("reset")?,
            _ => {
                if a.yes_no("scale")? {
                    return Err(a.error_prev("scale yes applies to pair parameters only", None));
                }
            }
        }
    }
    Ok(Box::new(Adapt {
        every,
        var,
        reset,
        saved: None,
    }))
}

impl ScriptFix for Adapt {
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if !ctx.setup && ctx.step % self.every != 0 {
            return Ok(());
        }
        let var = &self.var;
        let formula = match ctx.view().script.vars.get(var) {
            Some(Variable::Atom(f)) => f.clone(),
            Some(_) => return Err(format!("fix adapt: variable '{var}' is not atom-style").into()),
            None => return Err(Error::undefined("variable", var).within("fix adapt")),
        };
        let d = context::eval_atom(ctx.view(), &formula)?;
        let w = ctx.world();
        let p = &w.particles;
        if self.reset && self.saved.is_none() {
            self.saved = Some((0..p.nlocal()).map(|i| (p.tag[i], p.radius[i])).collect());
        }
        let radii: Vec<f64> = (0..p.nlocal())
            .map(|i| {
                if p.mask[i] & head.groupbit != 0 {
                    0.5 * d[i]
                } else {
                    p.radius[i]
                }
            })
            .collect();
        w.set_radii(&radii)
            .map_err(|e| Error::invalid(format!("fix {}: {e}", head.id)))
    }

    fn end_of_run(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if let Some(saved) = self.saved.take() {
            let w = ctx.world();
            let p = &w.particles;
            let saved: std::collections::HashMap<_, _> = saved.into_iter().collect();
            let mut r: Vec<f64> = p.radius[..p.nlocal()].to_vec();
            for (i, ri) in r.iter_mut().enumerate() {
                if let Some(&r0) = saved.get(&p.tag[i]) {
                    *ri = r0;
                }
            }
            w.set_radii(&r)?;
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
