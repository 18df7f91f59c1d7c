//! `pair_style gran` and `pair_coeff * *`: the particle–particle contact model.

use rdem::{CohesionKind, ContactModel, PairGran};

use crate::args::{suggest, Args, CmdResult};
use crate::models;
use crate::old_gran;
use crate::sim::Sim;

pub(super) fn pair_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.word("pair style")?;
    match style {
        // LIGGGHTS-PFM's OpenMP variant: the same model, on rdem's threads.
        "gran" | "gran/omp" => {}
        "none" => {
            a.done()?;
            let w = sim.world_mut(a)?;
            w.pair = None;
            w.sph = None;
            return Ok(());
        }
        "sph/artVisc/tensCorr" => return crate::sph::pair_style(sim, a),
        s if s.starts_with("gran/") => return old_pair_style(sim, a, s),
        s => {
            return Err(a.error_prev(
                format!("unknown pair style '{s}'"),
                Some(suggest(s, &["gran", "sph/artVisc/tensCorr", "none"])),
            ))
        }
    }
    let mut m: ContactModel = models::parse_types(a)?;
    if !a.is_done() && !models::at_switch(a) {
        return Err(models::unknown(a, a.pos(), &[]));
    }
    models::parse_switches(a, &mut m)?;
    crate::coarse_graining::check_model(sim, a, 1, &m)?;
    if sim.world.is_none() {
        // Before the box (LIGGGHTS 3.8 takes it there too): the box gets it.
        sim.setup.pair = Some(m);
        sim.defs.pair_coeff_set = false;
        return Ok(());
    }
    let w = sim.world_mut(a)?;
    w.pair = Some(PairGran::new(m));
    w.sph = None;
    if m.cohesion == CohesionKind::Easo {
        crate::fixes::liquid::define(sim);
    }
    sim.defs.pair_coeff_set = false;
    Ok(())
}

/// `pair_style gran/hertz/history ...` and the other pre-3.0 names (LIGGGHTS 1.x and
/// 2.x syntax, see [`old_gran`]): the 3.x model they mean, with a note line saying so.
fn old_pair_style(sim: &mut Sim, a: &mut Args, style: &str) -> CmdResult {
    let Some(mut m) = old_gran::base_model(&style["gran/".len()..]) else {
        let names = old_gran::old_names("gran/");
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        return Err(a.error_prev(
            format!("pair_style {style} is not a LIGGGHTS pair style rdem knows"),
            Some(format!(
                "write 'pair_style gran model hertz tangential history' (LIGGGHTS 3.x syntax); the pre-3.0 names rdem translates: {}",
                suggest(style, &names)
            )),
        ));
    };
    let form = old_gran::read_pair_words(a, &mut m)?;
    crate::coarse_graining::check_model(sim, a, 1, &m)?;
    let note = format!(
        "pair_style {} ({} syntax) runs as: pair_style gran {}",
        old_gran::text_from(a, 1),
        form.label(),
        old_gran::model_words(&m)
    );
    sim.world_mut(a)?.pair = Some(PairGran::new(m));
    sim.defs.pair_coeff_set = false;
    sim.outputs.out.line(&note);
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
            "granular and SPH pair styles take no coefficients: write 'pair_coeff * *'",
            None,
        ));
    }
    if sim.world.is_none() {
        return Err(a.error_cmd(
            "pair_coeff before the simulation box is defined",
            Some("use create_box or read_data first".into()),
        ));
    }
    if sim
        .world
        .as_ref()
        .is_none_or(|w| w.pair.is_none() && w.sph.is_none())
    {
        return Err(a.error_cmd(
            "pair_coeff before pair_style",
            Some("define 'pair_style gran ...' first".into()),
        ));
    }
    sim.defs.pair_coeff_set = true;
    Ok(())
}
