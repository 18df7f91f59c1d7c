//! The granular model syntax of LIGGGHTS before 3.0, which LIGGGHTS 3.8 refuses:
//! `pair_style gran/hertz/history`, `gran/hooke/history`, `gran/hooke` and the wall fixes
//! of the same names, with their model words in either old form:
//!
//! - LIGGGHTS 1.x: two flags, `dampflag cohesionflag` (0 or 1 each): tangential damping
//!   off/on, the linear cohesion model (force = k × contact area, k the
//!   `cohesionEnergyDensity`, which is 3.x's `cohesion sjkr`) off/on;
//! - LIGGGHTS 2.x: keyword/value pairs in any order, `tangential_damping on|off`
//!   (default on), `cohesion off|sjkr`, `rolling_friction off|cdt`, and `viscous off`
//!   (the Stokes-number damping of 2.x hooke, which rdem does not have).
//!
//! Each is read into the 3.x [`ContactModel`] it means (`gran/hertz/history` is
//! `model hertz tangential history`, `gran/hooke` is `model hooke tangential
//! no_history`), and [`model_words`] writes that model as 3.x words for the note line that
//! tells the user what the old command became.

use rdem::{CohesionKind, ContactModel, NormalKind, RollingKind, TangentialKind};

use crate::args::{suggest, Args, CmdResult};

/// The old model names (after `gran/` or `wall/gran/`), the 3.x normal and tangential
/// models they mean.
const OLD_MODELS: [(&str, NormalKind, TangentialKind); 3] = [
    ("hertz/history", NormalKind::Hertz, TangentialKind::History),
    ("hooke/history", NormalKind::Hooke, TangentialKind::History),
    ("hooke", NormalKind::Hooke, TangentialKind::NoHistory),
];

/// The cohesion models of the 2.x form.
const COHESION: &[(&str, CohesionKind)] =
    &[("off", CohesionKind::Off), ("sjkr", CohesionKind::Sjkr)];

/// The rolling friction models of the 2.x form.
const ROLLING: &[(&str, RollingKind)] = &[("off", RollingKind::Off), ("cdt", RollingKind::Cdt)];

/// The keywords of the 2.x form.
pub const KEYWORDS: [&str; 4] = [
    "tangential_damping",
    "cohesion",
    "rolling_friction",
    "viscous",
];

/// The 3.x model of an old model name (`hertz/history`, `hooke/history`, `hooke`), with
/// LIGGGHTS' defaults (tangential damping on, no cohesion, no rolling friction).
pub fn base_model(name: &str) -> Option<ContactModel> {
    OLD_MODELS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, normal, tangential)| ContactModel {
            normal,
            tangential,
            ..ContactModel::hertz_history()
        })
}

/// The old model names, for error help.
pub fn old_names(prefix: &str) -> Vec<String> {
    OLD_MODELS
        .iter()
        .map(|(n, _, _)| format!("{prefix}{n}"))
        .collect()
}

/// Which old form a command was written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// LIGGGHTS 1.x: `dampflag cohesionflag`.
    V1,
    /// LIGGGHTS 2.x: keywords (or no model words at all).
    V2,
}

impl Form {
    /// "LIGGGHTS 1.x", "LIGGGHTS 2.x".
    pub fn label(self) -> &'static str {
        match self {
            Form::V1 => "LIGGGHTS 1.x",
            Form::V2 => "LIGGGHTS 2.x",
        }
    }
}

/// True if the word at the cursor is a number (the 1.x flags come first).
pub fn at_flags(a: &Args) -> bool {
    a.peek()
        .is_some_and(|w| crate::args::parse_f64(w).is_some())
}

/// Reads the 1.x flags `dampflag cohesionflag` into `m`.
pub fn read_flags(a: &mut Args, m: &mut ContactModel) -> CmdResult {
    for what in ["dampflag", "cohesionflag"] {
        let w = a.word(&format!("{what} (0 or 1)"))?;
        let on = match w {
            "0" => false,
            "1" => true,
            _ => {
                return Err(a.error_prev(
                    format!("{what} must be 0 or 1, not '{w}'"),
                    Some(
                        "the LIGGGHTS 1.x form is 'dampflag cohesionflag', e.g. '1 0'; \
                         LAMMPS' 'Kn Kt gamma_n gamma_t xmu dampflag' form is not supported \
                         (rdem derives the stiffness from the material properties)"
                            .into(),
                    ),
                ))
            }
        };
        if what == "dampflag" {
            m.flags.tangential_damping = on;
        } else if on {
            m.cohesion = CohesionKind::Sjkr;
        }
    }
    Ok(())
}

/// True if the word at the cursor is a 2.x model keyword.
pub fn at_keyword(a: &Args) -> bool {
    a.peek().is_some_and(|w| KEYWORDS.contains(&w))
}

/// Reads one 2.x keyword and its value (the cursor is at the keyword) into `m`.
pub fn read_keyword(a: &mut Args, m: &mut ContactModel) -> CmdResult {
    let k = a.keyword("model keyword", &KEYWORDS)?;
    match k {
        "tangential_damping" => {
            m.flags.tangential_damping =
                a.keyword("tangential_damping setting", &["on", "off"])? == "on";
        }
        "cohesion" => {
            m.cohesion = a.choice("cohesion model", COHESION)?;
        }
        "rolling_friction" => {
            m.rolling = a.choice("rolling friction model", ROLLING)?;
        }
        _ => {
            if a.keyword("viscous setting", &["off", "on", "stokes"])? != "off" {
                return Err(a.error_prev(
                    "viscous damping (the Stokes-number restitution of LIGGGHTS 2.x) has no \
                     LIGGGHTS 3.x model in rdem: it is not supported",
                    Some("write 'viscous off' or leave it out".into()),
                ));
            }
        }
    }
    Ok(())
}

/// Reads the model words of `pair_style gran/...` after the style: the 1.x flags, or 2.x
/// keywords to the end of the command.
pub fn read_pair_words(a: &mut Args, m: &mut ContactModel) -> CmdResult<Form> {
    if at_flags(a) {
        read_flags(a, m)?;
        if !a.is_done() {
            return Err(a.error_at(
                a.pos(),
                format!(
                    "{}: unexpected extra argument '{}'",
                    a.context(),
                    a.words()[a.pos()].text
                ),
                Some(
                    "the LIGGGHTS 1.x form is 'dampflag cohesionflag'; LAMMPS' 'Kn Kt gamma_n \
                     gamma_t xmu dampflag' form is not supported (rdem derives the stiffness \
                     from the material properties)"
                        .into(),
                ),
            ));
        }
        return Ok(Form::V1);
    }
    while let Some(w) = a.peek() {
        if !KEYWORDS.contains(&w) {
            return Err(a.error_at(
                a.pos(),
                format!("unknown keyword '{w}' of the LIGGGHTS 2.x pair style"),
                Some(suggest(w, &KEYWORDS)),
            ));
        }
        read_keyword(a, m)?;
    }
    Ok(Form::V2)
}

/// `m` as the model words of `pair_style gran` (3.x): the model types, then the switches
/// that differ from their defaults.
pub fn model_words(m: &ContactModel) -> String {
    // The 3.x names, from the 3.x tables.
    let mut s = format!(
        "model {} tangential {}",
        rdem::contact::names::name_of(rdem::contact::names::NORMAL_MODELS, m.normal),
        rdem::contact::names::name_of(rdem::contact::names::TANGENTIAL_MODELS, m.tangential)
    );
    if m.cohesion == CohesionKind::Sjkr {
        s.push_str(" cohesion sjkr");
    }
    if m.rolling == RollingKind::Cdt {
        s.push_str(" rolling_friction cdt");
    }
    if !m.flags.tangential_damping {
        s.push_str(" tangential_damping off");
    }
    s
}

/// The command's words from `from` on, joined by spaces (for note lines).
pub fn text_from(a: &Args, from: usize) -> String {
    a.words()[from.min(a.words().len())..]
        .iter()
        .map(|w| w.text.as_str())
        .collect::<Vec<_>>()
        .join(" ")
}
