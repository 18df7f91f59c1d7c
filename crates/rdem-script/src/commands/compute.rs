//! `compute` and `uncompute`.

use crate::args::{suggest, Args, CmdResult};
use crate::computes::{self, Compute, ComputeKind, ReduceInput};
use crate::registry::{Registry, Row};
use crate::sim::Sim;
use crate::thermo;

use super::id_help;

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
    let (_, parse) = STYLES.lookup(a, style_word)?;
    let kind = parse(sim, a)?;
    if !matches!(
        kind,
        ComputeKind::PropertyAtom(_) | ComputeKind::Reduce { .. }
    ) {
        a.done()?;
    }
    sim.computes.push(Compute { id, groupbit, kind });
    Ok(())
}

/// A compute style's parser: reads the words after `compute ID group style`.
pub type ComputeParse = fn(&Sim, &mut Args) -> CmdResult<ComputeKind>;

/// Every compute style: those rdem runs, then LIGGGHTS styles it does not run yet.
pub static STYLES: Registry<ComputeParse> = Registry {
    family: "compute style",
    readme_prefix: "compute ",
    rows: &[
        Row::runs("erotate/sphere", (|_, _| Ok(ComputeKind::ERotateSphere)) as ComputeParse, "rotational kinetic energy of the group"),
        Row::runs("ke", (|_, _| Ok(ComputeKind::Ke)) as ComputeParse, "translational kinetic energy of the group"),
        Row::runs("reduce", reduce as ComputeParse, "`sum\\|min\\|max\\|ave\\|sumsq\\|avesq` of per-atom properties, `c_ID`, `c_ID[i]`, `v_name`"),
        Row::runs("property/atom", property_atom as ComputeParse, "per-atom properties"),
        Row::runs("contact/atom", (|_, _| Ok(ComputeKind::ContactAtom)) as ComputeParse, "number of particle contacts per particle"),
        Row::runs("stress/atom", stress_atom as ComputeParse, "stress × volume, 6 columns; `ke`, `pair`, `virial`")
            .notes("wall contacts do not count, as in LIGGGHTS"),
        Row::runs("bond/counter", bond_counter as ComputeParse, "bonds created, broken and intact, for pairs and walls (LIGGGHTS-INL)")
            .notes("one per script"),
        Row::runs("nbond/atom", (|_, _| Ok(ComputeKind::NBondAtom)) as ComputeParse, "intact bonds per particle")
            .notes("an rdem addition"),
        Row::not_yet("pair/gran/local", "contact output"),
        Row::not_yet("wall/gran/local", "contact output"),
        Row::not_yet("com", ""),
        Row::not_yet("msd", ""),
        Row::not_yet("rdf", ""),
    ],
};

/// `compute ID all bond/counter` (one per script).
fn bond_counter(sim: &Sim, a: &mut Args) -> CmdResult<ComputeKind> {
    if let Some(other) = sim
        .computes
        .iter()
        .find(|c| matches!(c.kind, ComputeKind::BondCounter(_)))
    {
        return Err(a.error_at(
            3,
            format!(
                "only one compute bond/counter is allowed (compute {} is one)",
                other.id
            ),
            Some(format!("use c_{}[1..6]", other.id)),
        ));
    }
    Ok(ComputeKind::BondCounter(Default::default()))
}

/// `compute ID group stress/atom [ke pair virial ...]`.
fn stress_atom(_sim: &Sim, a: &mut Args) -> CmdResult<ComputeKind> {
    // No keyword: every term; otherwise only the listed ones (`virial`: all but ke).
    let (mut ke, mut pair, mut any) = (false, false, false);
    while !a.is_done() {
        match a.keyword("stress/atom keyword", &computes::STRESS_KEYWORDS)? {
            "ke" => ke = true,
            "pair" | "virial" => pair = true,
            _ => {}
        }
        any = true;
    }
    if !any {
        (ke, pair) = (true, true);
    }
    Ok(ComputeKind::StressAtom { ke, pair })
}

/// `compute ID group property/atom field ...`.
fn property_atom(_sim: &Sim, a: &mut Args) -> CmdResult<ComputeKind> {
    let mut f = Vec::new();
    while let Some(w) = a.peek() {
        if !crate::atom_fields::is_field(w) {
            return Err(a.error_at(
                a.pos(),
                format!("unknown per-atom property '{w}'"),
                Some(suggest(w, &crate::atom_fields::NAMES)),
            ));
        }
        f.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if f.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "compute property/atom needs at least one property",
            Some(format!(
                "e.g. radius; valid: {}",
                crate::atom_fields::NAMES.join(" ")
            )),
        ));
    }
    Ok(ComputeKind::PropertyAtom(f))
}

/// `compute ID group reduce mode input ...`.
fn reduce(sim: &Sim, a: &mut Args) -> CmdResult<ComputeKind> {
    let mode = a
        .keyword("reduce mode", &computes::REDUCE_MODES)?
        .to_string();
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        if w == "replace" {
            return Err(a.error_at(a.pos(), "compute reduce replace is not supported", None));
        }
        let input = if crate::atom_fields::is_field(w) {
            ReduceInput::Field(w.to_string())
        } else {
            match thermo::split_reference(w) {
                Some(('c', cid, col)) => match sim.computes.iter().find(|c| c.id == cid) {
                    Some(c) if c.is_peratom() => ReduceInput::Compute(cid.to_string(), col),
                    Some(_) => {
                        return Err(a.error_at(
                            a.pos(),
                            format!("compute {cid} is not per-atom"),
                            None,
                        ))
                    }
                    None => {
                        let ids: Vec<&str> = sim.computes.iter().map(|c| c.id.as_str()).collect();
                        return Err(a.error_at(
                            a.pos(),
                            format!("no compute '{cid}'"),
                            Some(id_help("compute", cid, &ids)),
                        ));
                    }
                },
                Some(('v', v, None)) => ReduceInput::Variable(v.to_string()),
                _ => {
                    return Err(a.error_at(
                        a.pos(),
                        format!("unknown reduce input '{w}'"),
                        Some(format!(
                            "a per-atom property ({}), c_ID, c_ID[N] or v_name",
                            crate::atom_fields::NAMES.join(" ")
                        )),
                    ))
                }
            }
        };
        inputs.push(input);
        a.seek(a.pos() + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(a.pos(), "compute reduce needs at least one input", None));
    }
    Ok(ComputeKind::Reduce { mode, inputs })
}

/// `uncompute ID`.
pub(super) fn uncompute(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("compute ID")?;
    a.done()?;
    match sim.compute_index(id) {
        Some(k) => {
            sim.computes.remove(k);
        }
        None => {
            let names: Vec<&str> = sim.computes.iter().map(|c| c.id.as_str()).collect();
            return Err(a.error_prev(format!("no compute '{id}'"), Some(suggest(id, &names))));
        }
    }
    Ok(())
}
