//! The contact-model words shared by `pair_style gran` and `fix wall/gran`: the
//! model-type/name pairs in LIGGGHTS' required order (`model`, `tangential`, `cohesion`,
//! `rolling_friction`, `surface`) and the switch keywords that may follow in any order.

use rdem::contact::names::{
    COHESION_MODELS, NORMAL_MODELS, ROLLING_MODELS, SURFACE_MODELS, TANGENTIAL_MODELS,
};
use rdem::{CohesionKind, ContactModel, NormalKind, RollingKind};

use crate::args::{names, suggest, Args, CmdResult};

/// Model types, in the order LIGGGHTS requires.
pub const ORDER: [&str; 5] = [
    "model",
    "tangential",
    "cohesion",
    "rolling_friction",
    "surface",
];

/// Switch keywords (after the model types, any order).
pub const SWITCHES: [&str; 5] = [
    "tangential_damping",
    "limitForce",
    "torsionTorque",
    "tangential_reduce",
    "absolute_damping",
];

/// Keywords of `cohesion bond` (LIGGGHTS-INL), switches like [`SWITCHES`].
pub const BOND_SWITCHES: [&str; 15] = [
    "stressBreak",
    "temperatureBreak",
    "tensionStress",
    "compressionStress",
    "shearStress",
    "normalTorqueStress",
    "shearTorqueStress",
    "createBondAlways",
    "dampingBond",
    "dampingBondSmooth",
    "dissipationBond",
    "druckerPrager",
    "ratioTensionCompression",
    "computeDissipatedEnergy",
    "computeElasticPotential",
];

/// Keywords of `cohesion bond/nonlinear` (LIGGGHTS-INL): those of `cohesion bond` without
/// dissipation, Drucker–Prager and the energy bookkeeping, and `ratioTensionCompressionBond`
/// for `ratioTensionCompression`.
pub const NONLINEAR_SWITCHES: [&str; 10] = [
    "stressBreak",
    "tensionStress",
    "compressionStress",
    "shearStress",
    "normalTorqueStress",
    "shearTorqueStress",
    "createBondAlways",
    "dampingBond",
    "dampingBondSmooth",
    "ratioTensionCompressionBond",
];

/// Reads the model-type/name pairs at the cursor (stops at the first other word).
pub fn parse_types(a: &mut Args) -> CmdResult<ContactModel> {
    // Without `tangential`, LIGGGHTS 3.8 (and LIGGGHTS_Flexible_Fibers, SEAICE, INL,
    // CFDRC) apply no tangential force; LIGGGHTS-PFM applies `no_history`.
    let mut m = ContactModel {
        tangential: rdem::TangentialKind::Off,
        ..ContactModel::hertz_history()
    };
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
                m.normal = a.choice("normal model", NORMAL_MODELS)?;
                m.flags.limit_force = m.normal.traits().limit_force;
            }
            1 => m.tangential = a.choice("tangential model", TANGENTIAL_MODELS)?,
            2 => {
                if let Some(w @ "washino/capillary/viscous") = a.peek() {
                    // LIGGGHTS 3.8 has this liquid-bridge model; rdem does not yet.
                    return Err(a.error_at(
                        a.pos(),
                        format!("cohesion {w} (liquid bridges) is not supported yet"),
                        Some(format!(
                            "supported cohesion models: {}",
                            names(COHESION_MODELS).join(", ")
                        )),
                    ));
                }
                m.cohesion = a.choice("cohesion model", COHESION_MODELS)?;
            }
            3 => m.rolling = a.choice("rolling friction model", ROLLING_MODELS)?,
            _ => m.surface = a.choice("surface model", SURFACE_MODELS)?,
        }
    }
    Ok(m)
}

/// True if the word at the cursor is a switch keyword.
pub fn at_switch(a: &Args) -> bool {
    a.peek().is_some_and(|w| {
        SWITCHES.contains(&w) || BOND_SWITCHES.contains(&w) || NONLINEAR_SWITCHES.contains(&w)
    })
}

/// Reads switch keywords at the cursor until the end of the command.
pub fn parse_switches(a: &mut Args, m: &mut ContactModel) -> CmdResult {
    parse_switches_while(a, m, |_| true)
}

/// Reads switch keywords at the cursor while there are some (`fix wall/gran` takes them
/// before its wall too, as LIGGGHTS-INL scripts write them).
pub fn parse_leading_switches(a: &mut Args, m: &mut ContactModel) -> CmdResult {
    parse_switches_while(a, m, at_switch)
}

fn parse_switches_while(
    a: &mut Args,
    m: &mut ContactModel,
    more: impl Fn(&Args) -> bool,
) -> CmdResult {
    while let Some(w) = a.peek() {
        if !more(a) {
            return Ok(());
        }
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
        let bond_words: &[&str] = match m.cohesion {
            CohesionKind::Bond => &BOND_SWITCHES,
            CohesionKind::BondNonlinear => &NONLINEAR_SWITCHES,
            _ => &[],
        };
        if !bond_words.contains(&w) {
            let model = match (BOND_SWITCHES.contains(&w), NONLINEAR_SWITCHES.contains(&w)) {
                (true, true) => Some("'cohesion bond' or 'cohesion bond/nonlinear'"),
                (true, false) => Some("'cohesion bond'"),
                (false, true) => Some("'cohesion bond/nonlinear'"),
                _ => None,
            };
            if let Some(model) = model {
                return Err(a.error_at(
                    a.pos(),
                    format!("'{w}' is not a keyword of the bond model given"),
                    Some(format!("it is a keyword of {model}")),
                ));
            }
        }
        let valid: Vec<&str> = SWITCHES.iter().chain(bond_words).copied().collect();
        let k = a.keyword("model keyword", &valid)?;
        let on = matches!(
            a.keyword(&format!("{k} setting"), &["on", "off", "yes", "no"])?,
            "on" | "yes"
        );
        let b = &mut m.bond;
        match k {
            "stressBreak" => b.stress_break = on,
            "tensionStress" => b.tension = on,
            "compressionStress" => b.compression = on,
            "shearStress" => b.shear = on,
            "normalTorqueStress" => b.normal_torque = on,
            "shearTorqueStress" => b.shear_torque = on,
            "createBondAlways" => b.create_always = on,
            "dampingBond" => b.damping = on,
            "dampingBondSmooth" => b.damping_smooth = on,
            "dissipationBond" => b.dissipation = on,
            "druckerPrager" => b.drucker_prager = on,
            "ratioTensionCompression" | "ratioTensionCompressionBond" => b.ratio_tc = on,
            "temperatureBreak" | "computeDissipatedEnergy" | "computeElasticPotential" => {
                if on {
                    let why = if k == "temperatureBreak" {
                        "bond breakage by temperature is not supported (LIGGGHTS-INL does not implement it either)"
                    } else {
                        "the bond energy bookkeeping (fix calculate/dissipated_energy) is not supported"
                    };
                    return Err(a.error_prev(
                        format!("{k} on: {why}"),
                        Some(format!("write '{k} off' or leave it out")),
                    ));
                }
            }
            "tangential_damping" => m.flags.tangential_damping = on,
            "limitForce" => m.flags.limit_force = on,
            "absolute_damping" => {
                // LIGGGHTS 3.8 knows the keyword only in hooke/stiffness (for hertz/stiffness
                // and the others it stops with "Unknown argument or wrong keyword order").
                if m.normal != NormalKind::HookeStiffness {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "absolute_damping is a keyword of model hooke/stiffness only",
                        Some("write 'model hooke/stiffness' or leave the keyword out".into()),
                    ));
                }
                m.flags.absolute_damping = on
            }
            "torsionTorque" => {
                if on && m.rolling == RollingKind::Off {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "torsionTorque needs a rolling friction model (rolling_friction cdt, cdtnonlinear2, epsd, epsd2 or epsd3)",
                        None,
                    ));
                }
                m.flags.torsion_torque = on
            }
            _ => {
                if on
                    && !matches!(
                        m.cohesion,
                        CohesionKind::Sjkr | CohesionKind::Sjkr2 | CohesionKind::Easo
                    )
                {
                    return Err(a.error_at(
                        a.pos() - 2,
                        "tangential_reduce needs a contact cohesion model (cohesion sjkr, sjkr2 or easo/capillary/viscous)",
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
    let w_ = w.as_str();
    let has = |names: Vec<&str>| names.contains(&w_) && w_ != "off" && w_ != "default";
    let ty = if has(names(NORMAL_MODELS)) {
        Some("model")
    } else if has(names(TANGENTIAL_MODELS)) {
        Some("tangential")
    } else if has(names(COHESION_MODELS)) {
        Some("cohesion")
    } else if has(names(ROLLING_MODELS)) {
        Some("rolling_friction")
    } else if has(names(SURFACE_MODELS)) {
        Some("surface")
    } else {
        None
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
    valid.extend_from_slice(&BOND_SWITCHES);
    a.error_at(
        k,
        format!("unknown keyword '{w}'"),
        Some(suggest(w, &valid)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The help line of `pair_style` (docs/commands.md, `rdem -check`) lists each model
    /// vocabulary exactly as its table does, in order.
    #[test]
    fn pair_style_help_lists_the_tables() {
        let help = crate::commands::REGISTRY
            .row("pair_style")
            .expect("pair_style is a command")
            .help;
        for (word, table) in [
            ("model", names(NORMAL_MODELS)),
            ("tangential", names(TANGENTIAL_MODELS)),
            ("cohesion", names(COHESION_MODELS)),
            ("rolling_friction", names(ROLLING_MODELS)),
            ("surface", names(SURFACE_MODELS)),
        ] {
            let want = format!("`{word} {}`", table.join("\\|"));
            assert!(help.contains(&want), "the pair_style help lacks {want}");
        }
    }
}
