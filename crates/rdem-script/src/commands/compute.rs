//! `compute` and `uncompute`.

use crate::args::{suggest, Args, CmdResult};
use crate::computes::{self, Compute, ComputeKind, ReduceInput};
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
    let Some(style) = computes::STYLES.iter().copied().find(|s| *s == style_word) else {
        let later = [
            "pair/gran/local",
            "wall/gran/local",
            "bond/counter",
            "com",
            "msd",
            "rdf",
        ];
        if later.contains(&style_word) {
            return Err(a.error_prev(
                format!("compute {style_word} is not supported by this rdem release yet"),
                Some(format!("supported: {}", computes::STYLES.join(", "))),
            ));
        }
        return Err(a.error_prev(
            format!("unknown compute style '{style_word}'"),
            Some(suggest(style_word, &computes::STYLES)),
        ));
    };
    let kind = match style {
        "erotate/sphere" => ComputeKind::ERotateSphere,
        "ke" => ComputeKind::Ke,
        "contact/atom" => ComputeKind::ContactAtom,
        "nbond/atom" => ComputeKind::NBondAtom,
        "bond/counter" => {
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
            ComputeKind::BondCounter(Default::default())
        }
        "stress/atom" => {
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
            ComputeKind::StressAtom { ke, pair }
        }
        "property/atom" => {
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
            ComputeKind::PropertyAtom(f)
        }
        _ => {
            let mode = a
                .keyword("reduce mode", &computes::REDUCE_MODES)?
                .to_string();
            let mut inputs = Vec::new();
            while let Some(w) = a.peek() {
                if w == "replace" {
                    return Err(a.error_at(
                        a.pos(),
                        "compute reduce replace is not supported",
                        None,
                    ));
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
                                let ids: Vec<&str> =
                                    sim.computes.iter().map(|c| c.id.as_str()).collect();
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
            ComputeKind::Reduce { mode, inputs }
        }
    };
    if !matches!(
        kind,
        ComputeKind::PropertyAtom(_) | ComputeKind::Reduce { .. }
    ) {
        a.done()?;
    }
    sim.computes.push(Compute { id, groupbit, kind });
    Ok(())
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
