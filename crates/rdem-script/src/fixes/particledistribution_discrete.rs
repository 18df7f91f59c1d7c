//! `fix ID all particledistribution/discrete seed N template1 weight1 ...` (and its
//! `/massbased`, `/numberbased` forms): a weighted choice of particle templates.

use rdem::insert::{Distribution, Weighting};

use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "particledistribution/discrete",
    parse,
    Stages::NONE,
    "mass fractions",
)
.notes("weights are normalised with a warning")
.atoi();

/// The registry row of the mass-based form (the same as the plain one).
pub(super) const ROW_MASS: FixRow = style(
    "particledistribution/discrete/massbased",
    parse,
    Stages::NONE,
    "mass fractions",
);

/// The registry row of the number-based form.
pub(super) const ROW_NUMBER: FixRow = style(
    "particledistribution/discrete/numberbased",
    parse,
    Stages::NONE,
    "number fractions",
);

/// A defined distribution: it lives in `Sim::distributions` under the fix ID.
pub struct DistributionFix {
    parsed: Option<Distribution>,
}

impl ScriptFix for DistributionFix {
    fn install(&mut self, sim: &mut Sim, _a: &Args, head: &FixHead) -> CmdResult<()> {
        if let Some(d) = self.parsed.take() {
            if let Some(wm) = &d.warning {
                sim.outputs.out.warning(wm);
            }
            sim.defs.distributions.insert(head.id.clone(), d);
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        sim.defs.distributions.remove(&head.id);
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (id, style) = (head.id.as_str(), head.style);
    let seed = a.seed()?;
    let n = a.count("number of templates")?;
    let mut parts = Vec::new();
    for _ in 0..n {
        let tid = a.word("template ID")?;
        let t = sim.defs.templates.get(tid).cloned().ok_or_else(|| {
            let names: Vec<&str> = sim.defs.templates.keys().map(|s| s.as_str()).collect();
            a.error_prev(
                format!("no particle template '{tid}'"),
                Some(suggest(tid, &names)),
            )
        })?;
        let w = match a.peek().and_then(crate::args::parse_f64) {
            Some(_) => a.non_negative("template weight")?,
            // LIGGGHTS 3.8 reads a weight with C's atof: `1./6.` is 1 (with `5./6.` for
            // the other template the normalized weights are still 1/6 and 5/6).
            None => {
                let word = a.word("template weight")?;
                match crate::args::atof_prefix(word).filter(|v| *v >= 0.0) {
                    Some(v) => {
                        a.warn_at(
                            a.pos() - 1,
                            &format!(
                                "template weight '{word}' read as {v}, as LIGGGHTS reads it (C's atof stops at the first character that is not part of a number); weights are normalized to sum 1"
                            ),
                        );
                        v
                    }
                    None => {
                        return Err(a.error_prev(
                            format!("template weight must be a number, not '{word}'"),
                            None,
                        ))
                    }
                }
            }
        };
        parts.push((t, w));
    }
    a.done()?;
    let weighting = if style.ends_with("numberbased") {
        Weighting::Number
    } else {
        Weighting::Mass
    };
    let mut d = Distribution::new(id, seed, weighting, parts)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    // Inserted particles join the distribution's group too, as in LIGGGHTS 3.8.
    d.groupbit = head.groupbit;
    Ok(Box::new(DistributionFix { parsed: Some(d) }))
}
