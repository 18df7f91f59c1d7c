//! `compute` and `uncompute`.

use crate::args::{id_help, suggest, Args, CmdResult};
use crate::computes::{self, Compute, ComputeHead};
use crate::sim::Sim;

pub(super) fn compute(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("compute ID")?.to_string();
    if sim.compute_index(&id).is_some() {
        return Err(a.error_prev(
            format!("compute ID '{id}' is already used"),
            Some("uncompute it first".into()),
        ));
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let style_word = a.word("compute style")?;
    let (style, parse) = computes::REGISTRY.lookup(a, style_word)?;
    // LIGGGHTS' general keyword, read right after the style and before the style's own
    // words. rdem evaluates a compute from the current state whenever it is asked, so
    // its value after a run is always current: `yes` is what rdem does anyway, and `no`
    // only loses LIGGGHTS' "not current" error.
    while a.peek() == Some("update_on_run_end") {
        a.word("update_on_run_end")?;
        a.yes_no("update_on_run_end value")?;
    }
    let imp = parse(sim, a)?;
    a.done()?;
    sim.defs.computes.push(Compute {
        head: ComputeHead { id, groupbit },
        style,
        imp,
    });
    Ok(())
}

/// `uncompute ID`.
pub(super) fn uncompute(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("compute ID")?;
    a.done()?;
    match sim.compute_index(id) {
        Some(k) => {
            sim.defs.computes.remove(k);
        }
        None => {
            let names: Vec<&str> = sim.defs.computes.iter().map(|c| c.id()).collect();
            return Err(a.error_prev(format!("no compute '{id}'"), Some(suggest(id, &names))));
        }
    }
    Ok(())
}

/// The generic `compute_modify` keywords (LAMMPS' `Compute::modify_params`): a style
/// that does not take one accepts it with a warning that it has no effect, as LIGGGHTS
/// 3.8 accepts it without acting. `extra/dof` and `dynamic/dof` are the names later
/// LAMMPS versions give `extra` and `dynamic` (LIGGGHTS 3.8 refuses them).
const MODIFY_KEYWORDS: [&str; 5] = ["extra", "extra/dof", "dynamic", "dynamic/dof", "thermo"];

/// `compute_modify ID keyword value ...`: `extra N`, `dynamic yes|no` for temperature
/// computes (`thermo_temp` included), `thermo yes|no`.
pub(super) fn compute_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("compute ID")?;
    let Some(k) = sim.compute_index(id) else {
        let names: Vec<&str> = sim.defs.computes.iter().map(|c| c.id()).collect();
        return Err(a.error_prev(
            format!("no compute '{id}'"),
            Some(id_help("compute", id, &names)),
        ));
    };
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "compute_modify: missing keyword",
            Some(format!("expected one of: {}", MODIFY_KEYWORDS.join(", "))),
        ));
    }
    // Each keyword applies as it is read: an error leaves the ones before it applied,
    // as in LIGGGHTS.
    while !a.is_done() {
        let kw = a.keyword("compute_modify keyword", &MODIFY_KEYWORDS)?;
        let c = &mut sim.defs.computes[k];
        if c.imp.modify(kw, a)? {
            continue;
        }
        let at = a.pos() - 1;
        let style = c.style;
        match kw {
            "extra" | "extra/dof" => {
                let w = a.word("number of extra degrees of freedom")?;
                if w.parse::<i64>().is_err() {
                    return Err(a.error_prev(format!("{kw} must be an integer, not '{w}'"), None));
                }
            }
            _ => {
                a.yes_no(kw)?;
            }
        }
        let why = if kw == "thermo" {
            "only compute pe adds the fixes' energy"
        } else {
            "it computes no temperature"
        };
        a.warn_at(
            at,
            &format!("compute_modify {kw} has no effect on compute {id} (style {style}): {why}"),
        );
    }
    Ok(())
}
