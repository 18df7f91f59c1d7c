//! The contact-model words shared by `pair_style gran` and `fix wall/gran`: the
//! model-type/name pairs in LIGGGHTS' required order (`model`, `tangential`, `cohesion`,
//! `rolling_friction`, `surface`) and the switch keywords that may follow in any order.

use rdem::{CohesionKind, ContactModel, NormalKind, RollingKind, TangentialKind};

use crate::args::{suggest, Args, CmdResult};
use crate::diagnostic::one_of;

/// Model types, in the order LIGGGHTS requires.
pub const ORDER: [&str; 5] = [
    "model",
    "tangential",
    "cohesion",
    "rolling_friction",
    "surface",
];

/// Switch keywords (after the model types, any order).
pub const SWITCHES: [&str; 4] = [
    "tangential_damping",
    "limitForce",
    "torsionTorque",
    "tangential_reduce",
];

/// Reads the model-type/name pairs at the cursor (stops at the first other word).
pub fn parse_types(a: &mut Args) -> CmdResult<ContactModel> {
    let mut m = ContactModel::hertz_history();
    let mut last: Option<usize> = None;
    while let Some(w) = a.peek() {
        let Some(k) = ORDER.iter().position(|o| *o == w) else {
            break;
        };
        if let Some(l) = last {
            if k <= l {
                return Err(a.error_at(
                    a.pos(),
                    format!(
                        "'{w}' {} '{}': the model types must come in the order {}",
                        if k == l {
                            "is given twice, after"
                        } else {
                            "must come before"
                        },
                        ORDER[l],
                        ORDER.join(", ")
                    ),
                    Some(format!(
                        "write: {}",
                        ORDER.map(|o| format!("{o} ...")).join(" ")
                    )),
                ));
            }
        }
        last = Some(k);
        a.seek(a.pos() + 1);
        match k {
            0 => {
                m.normal =
                    match a.keyword("normal model", &["hertz", "hooke", "hooke/hysteresis"])? {
                        "hertz" => NormalKind::Hertz,
                        "hooke" => NormalKind::Hooke,
                        _ => NormalKind::HookeHysteresis,
                    }
            }
            1 => {
                m.tangential = match a.keyword("tangential model", &["history", "no_history"])? {
                    "history" => TangentialKind::History,
                    _ => TangentialKind::NoHistory,
                }
            }
            2 => {
                if a.peek() == Some("bond") {
                    a.seek(a.pos() + 1);
                    return Err(a.error_prev(
                        "cohesion bond is not supported yet (bonded particles are a later rdem release)",
                        Some(format!("supported: {}", one_of(&["off", "sjkr", "sjkr2"]))),
                    ));
                }
                m.cohesion = match a.keyword("cohesion model", &["off", "sjkr", "sjkr2"])? {
                    "sjkr" => CohesionKind::Sjkr,
                    "sjkr2" => CohesionKind::Sjkr2,
                    _ => CohesionKind::Off,
                }
            }
            3 => {
                m.rolling =
                    match a.keyword("rolling friction model", &["off", "cdt", "epsd", "epsd2"])? {
                        "cdt" => RollingKind::Cdt,
                        "epsd" => RollingKind::Epsd,
                        "epsd2" => RollingKind::Epsd2,
                        _ => RollingKind::Off,
                    }
            }
            _ => {
                a.keyword("surface model", &["default"])?;
            }
        }
    }
    Ok(m)
}

/// True if the word at the cursor is a switch keyword.
pub fn at_switch(a: &Args) -> bool {
    a.peek().is_some_and(|w| SWITCHES.contains(&w))
}

/// Reads switch keywords at the cursor until the end of the command.
pub fn parse_switches(a: &mut Args, m: &mut ContactModel) -> CmdResult {
    while let Some(w) = a.peek() {
        if ORDER.contains(&w) {
            return Err(a.error_at(
                a.pos(),
                format!("model type '{w}' after a model keyword"),
                Some(format!(
                    "the model types ({}) come first, in that order, then the keywords ({})",
                    ORDER.join(", "),
                    SWITCHES.join(", ")
                )),
            ));
        }
        let k = a.keyword("model keyword", &SWITCHES)?;
        let on = matches!(
            a.keyword(&format!("{k} setting"), &["on", "off", "yes", "no"])?,
            "on" | "yes"
        );
        match k {
            "tangential_damping" => m.flags.tangential_damping = on,
            "limitForce" => m.flags.limit_force = on,
            "torsionTorque" => {
                if on && m.rolling == RollingKind::Off {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "torsionTorque needs a rolling friction model (rolling_friction cdt, epsd or epsd2)",
                        None,
                    ));
                }
                m.flags.torsion_torque = on
            }
            _ => {
                if on && m.cohesion == CohesionKind::Off {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "tangential_reduce needs a cohesion model (cohesion sjkr or sjkr2)",
                        None,
                    ));
                }
                m.flags.tangential_reduce = on
            }
        }
    }
    Ok(())
}

/// Error for an unknown word where a model type or keyword was expected.
pub fn unknown(a: &Args, k: usize, extra: &[&str]) -> crate::diagnostic::ScriptError {
    let w = &a.words()[k].text;
    // A model name without its type in front (`pair_style gran hertz ...`).
    let ty = match w.as_str() {
        "hertz" | "hooke" | "hooke/hysteresis" => Some("model"),
        "history" | "no_history" => Some("tangential"),
        "sjkr" | "sjkr2" => Some("cohesion"),
        "cdt" | "epsd" | "epsd2" => Some("rolling_friction"),
        _ => None,
    };
    if let Some(ty) = ty {
        return a.error_at(
            k,
            format!("model name '{w}' without its type"),
            Some(format!(
                "write '{ty} {w}'; the model types come in the order {}",
                ORDER.join(", ")
            )),
        );
    }
    let mut valid: Vec<&str> = ORDER.to_vec();
    valid.extend_from_slice(extra);
    valid.extend_from_slice(&SWITCHES);
    a.error_at(
        k,
        format!("unknown keyword '{w}'"),
        Some(suggest(w, &valid)),
    )
}
