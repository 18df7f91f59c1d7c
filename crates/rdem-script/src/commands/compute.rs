//! `compute` and `uncompute`.

use crate::args::{suggest, Args, CmdResult};
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
