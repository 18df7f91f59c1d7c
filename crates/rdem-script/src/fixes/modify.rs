//! `fix_modify ID keyword value ...`: a fix style's own keywords first
//! ([`ScriptFix::modify`]), then LIGGGHTS 3.8's generic ones.
//!
//! LIGGGHTS 3.8 (checked with `fix_modify` on `gravity`, `wall/gran`, `nve/sphere`):
//! - `energy yes|no` is accepted on every fix. Among rdem's styles only `gravity` and
//!   `addforce` have an energy (their manuals); LIGGGHTS 3.8 adds it to the potential
//!   energy that `compute pe` reports, and to nothing else: it has no thermo `pe` keyword,
//!   and its granular fixes (walls, integrators, insertion) tally none. rdem keeps the
//!   flag in [`super::FixEntry::energy`]; its thermo `pe` is 0 whatever the flag, and for
//!   `gravity`/`addforce` with `energy yes` it warns that their energy is not added.
//! - `temp ID` and `press ID` stop LIGGGHTS 3.8 ("Illegal fix_modify command") on every
//!   granular fix, as none computes a temperature or a pressure: rdem stops too, saying so.
//! - `virial` is not a fix_modify keyword of LIGGGHTS 3.8 (it stops): rdem stops too.

use crate::args::{id_help, Args, CmdResult};
use crate::sim::Sim;

/// The keywords `fix_modify` knows besides a style's own.
const KEYWORDS: [&str; 4] = ["energy", "temp", "press", "virial"];

/// Styles with an energy for `fix_modify energy yes` (LIGGGHTS 3.8 manuals).
const WITH_ENERGY: [&str; 2] = ["gravity", "addforce"];

/// `fix_modify ID keyword value ...`.
pub fn fix_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("fix ID")?;
    let Some(k) = sim.fix_index(id) else {
        let names: Vec<&str> = sim.defs.fixes.iter().map(|f| f.id()).collect();
        return Err(a.error_prev(format!("no fix '{id}'"), Some(id_help("fix", id, &names))));
    };
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "fix_modify: missing keyword",
            Some(format!("expected one of: {}", KEYWORDS.join(", "))),
        ));
    }
    let style = sim.defs.fixes[k].head.style;
    while !a.is_done() {
        let kw = a.word("fix_modify keyword")?;
        let own = super::with_fix(sim, k, |f, sim, head| f.modify(sim, head, kw, a))?;
        if own {
            continue;
        }
        match kw {
            "energy" => {
                let on = a.yes_no("energy")?;
                sim.defs.fixes[k].energy = on;
                if on && WITH_ENERGY.contains(&style) {
                    a.warn_at(
                        a.pos() - 2,
                        &format!(
                            "fix_modify energy yes: rdem does not add the energy of fix {id} \
                             ({style}) to the potential energy (LIGGGHTS 3.8 adds it to compute pe)"
                        ),
                    );
                }
            }
            "temp" | "press" => {
                let what = if kw == "temp" {
                    "temperature"
                } else {
                    "pressure"
                };
                return Err(a.error_prev(
                    format!(
                        "fix {id} ({style}) computes no {what}: fix_modify {kw} does not apply"
                    ),
                    Some("LIGGGHTS 3.8 stops here too (Illegal fix_modify command)".into()),
                ));
            }
            "virial" => {
                return Err(a.error_prev(
                    "fix_modify virial is not a LIGGGHTS 3.8 keyword",
                    Some(format!(
                        "LIGGGHTS 3.8 knows {} (and a style's own keywords)",
                        KEYWORDS[..3].join(", ")
                    )),
                ))
            }
            _ => {
                return Err(a.error_prev(
                    format!("unknown fix_modify keyword '{kw}' for fix {id} ({style})"),
                    Some(crate::args::suggest(kw, &KEYWORDS[..3])),
                ))
            }
        }
    }
    Ok(())
}
