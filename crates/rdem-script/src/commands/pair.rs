//! `pair_style gran` and `pair_coeff * *`: the particle–particle contact model.

use rdem::{CohesionKind, ContactModel, PairGran};

use crate::args::{suggest, Args, CmdResult};
use crate::models;
use crate::sim::Sim;

pub(super) fn pair_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.word("pair style")?;
    match style {
        "gran" => {}
        "none" => {
            a.done()?;
            sim.world_mut(a)?.pair = None;
            return Ok(());
        }
        s if s.starts_with("gran/") => {
            return Err(a.error_prev(
                format!("pair_style {s} is the pre-3.0 syntax, which rdem does not take"),
                Some(
                    "write 'pair_style gran model hertz tangential history' (LIGGGHTS 3.x syntax)"
                        .into(),
                ),
            ))
        }
        s => {
            return Err(a.error_prev(
                format!("unknown pair style '{s}'"),
                Some(suggest(s, &["gran", "none"])),
            ))
        }
    }
    let mut m: ContactModel = models::parse_types(a)?;
    if !a.is_done() && !models::at_switch(a) {
        return Err(models::unknown(a, a.pos(), &[]));
    }
    models::parse_switches(a, &mut m)?;
    sim.world_mut(a)?.pair = Some(PairGran::new(m));
    if m.cohesion == CohesionKind::Easo {
        crate::fixes::liquid::define(sim);
    }
    sim.defs.pair_coeff_set = false;
    Ok(())
}

/// `pair_coeff * *` (granular pair styles take no coefficients).
pub(super) fn pair_coeff(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let t1 = a.word("type I")?;
    let t2 = a.word("type J")?;
    for (t, k) in [(t1, 1), (t2, 2)] {
        if t != "*"
            && t.parse::<usize>()
                .map_or(true, |v| v == 0 || v > sim.ntypes().max(1))
        {
            return Err(a.error_at(
                k,
                format!("bad atom type '{t}'"),
                Some(format!("use * or 1..{}", sim.ntypes())),
            ));
        }
    }
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "granular pair styles take no coefficients: write 'pair_coeff * *'",
            None,
        ));
    }
    if sim.world.as_ref().and_then(|w| w.pair.as_ref()).is_none() {
        return Err(a.error_cmd(
            "pair_coeff before pair_style",
            Some("define 'pair_style gran ...' first".into()),
        ));
    }
    sim.defs.pair_coeff_set = true;
    Ok(())
}
