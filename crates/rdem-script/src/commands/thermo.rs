//! `thermo`, `thermo_style`, `thermo_modify`: what the thermo table prints and when.

use rdem::LostPolicy;

use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;
use crate::thermo;

use super::id_help;

/// `thermo N`.
pub(super) fn thermo(sim: &mut Sim, a: &mut Args) -> CmdResult {
    sim.outputs.thermo.every = a.u64("thermo output interval")?;
    a.done()?;
    Ok(())
}

pub(super) fn thermo_style(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let style = a.keyword("thermo style", &["custom", "one", "multi"])?;
    let mut origins = Vec::new();
    let cols: Vec<String> = match style {
        "custom" => {
            let mut c = Vec::new();
            while let Some(w) = a.peek() {
                if !thermo::valid_column(w) {
                    return Err(a.error_at(
                        a.pos(),
                        format!("unknown thermo keyword '{w}'"),
                        Some(suggest(w, &thermo::KEYWORDS)),
                    ));
                }
                if let Some((kind, id, _)) = thermo::split_reference(w) {
                    let ok = match kind {
                        'c' => sim.compute_index(id).is_some(),
                        'f' => sim.fix_index(id).is_some(),
                        _ => true,
                    };
                    if !ok {
                        let what = if kind == 'c' { "compute" } else { "fix" };
                        let ids: Vec<&str> = if kind == 'c' {
                            sim.defs.computes.iter().map(|c| c.id()).collect()
                        } else {
                            sim.defs.fixes.iter().map(|f| f.id()).collect()
                        };
                        return Err(a.error_at(
                            a.pos(),
                            format!("'{w}': no {what} '{id}'"),
                            Some(id_help(what, id, &ids)),
                        ));
                    }
                }
                c.push(w.to_string());
                origins.push(sim.origin(a, a.pos()));
                a.seek(a.pos() + 1);
            }
            if c.is_empty() {
                return Err(a.error_at(
                    a.pos(),
                    "thermo_style custom needs at least one keyword",
                    Some(format!(
                        "e.g. step atoms ke; valid: {}",
                        thermo::KEYWORDS.join(" ")
                    )),
                ));
            }
            c
        }
        // `multi`: the items of `one` in the layout of `thermo_modify line multi` (LIGGGHTS
        // 3.8's manual; its screen compared in tests/thermo_multi.rs).
        _ => {
            origins = vec![None; 4];
            ["step", "atoms", "ke", "cpu"].map(String::from).to_vec()
        }
    };
    if sim.outputs.thermo.norm
        || !sim.outputs.thermo.col_format.is_empty()
        || sim.outputs.thermo.float_format.is_some()
        || sim.outputs.thermo.int_format.is_some()
        || sim.outputs.thermo.multi
    {
        sim.outputs
            .out
            .warning("New thermo_style command, previous thermo_modify settings will be lost");
    }
    sim.outputs.thermo.columns = cols;
    sim.outputs.thermo.origins = origins;
    sim.outputs.thermo.norm = false;
    sim.outputs.thermo.col_format.clear();
    sim.outputs.thermo.int_format = None;
    sim.outputs.thermo.float_format = None;
    sim.outputs.thermo.line_format = None;
    sim.outputs.thermo.multi = style == "multi";
    Ok(())
}

pub(super) fn thermo_modify(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "thermo_modify: missing keyword",
            Some("lost, norm, line, format, flush, every".into()),
        ));
    }
    while !a.is_done() {
        match a.keyword(
            "thermo_modify keyword",
            &["lost", "norm", "line", "format", "flush", "every"],
        )? {
            // LIGGGHTS 3.8 knows `one` and `multi` (`yaml` came to LAMMPS later: 3.8
            // stops with "Illegal thermo_modify command").
            "line" => {
                sim.outputs.thermo.multi = a.keyword("line style", &["one", "multi"])? == "multi"
            }
            "lost" => {
                let p = match a.keyword("lost setting", &["error", "warn", "ignore"])? {
                    "error" => LostPolicy::Error,
                    "warn" => LostPolicy::Warn,
                    _ => LostPolicy::Ignore,
                };
                sim.set_lost(p);
            }
            "norm" => sim.outputs.thermo.norm = a.yes_no("norm")?,
            "flush" => {
                a.yes_no("flush")?;
            }
            "every" => sim.outputs.thermo.every = a.u64("every")?,
            _ => {
                let which = a.word("format target (int, float, line or a column number)")?;
                let f = a.word("format string")?.to_string();
                let check = |s: &str| rdem_io::Printf::parse(s).map(|_| ());
                match which {
                    "int" => {
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.outputs.thermo.int_format = Some(f);
                    }
                    "float" => {
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.outputs.thermo.float_format = Some(f);
                    }
                    "line" => {
                        let parts: Vec<String> = f.split_whitespace().map(String::from).collect();
                        for p in &parts {
                            check(p).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        }
                        sim.outputs.thermo.line_format = Some(parts);
                    }
                    n => {
                        let k: usize = n
                            .parse()
                            .ok()
                            .filter(|&k| k >= 1 && k <= sim.outputs.thermo.columns.len())
                            .ok_or_else(|| {
                                a.error_at(
                                    a.pos() - 2,
                                    format!(
                                        "'{n}' is not int, float, line or a column number 1..{}",
                                        sim.outputs.thermo.columns.len()
                                    ),
                                    None,
                                )
                            })?;
                        check(&f).map_err(|e| a.error_prev(format!("bad format: {e}"), None))?;
                        sim.outputs.thermo.col_format.push((k, f));
                    }
                }
            }
        }
    }
    Ok(())
}

/// `thermo_log FILE [append]`, `thermo_log none`: thermo's header and rows also go to
/// FILE (truncated unless `append`) from the next run on, until another `thermo_log`.
/// LIGGGHTS 3.8 writes exactly the screen's thermo lines there (a header at each run);
/// `none` closes the file (LIGGGHTS 3.8 then writes none). Without a file name
/// LIGGGHTS 3.8 writes to a file named `log`; rdem asks for the name.
pub(super) fn thermo_log(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let file = a.word("thermo log file name or none")?.to_string();
    let append = !a.is_done() && a.keyword("thermo_log keyword", &["append"])? == "append";
    a.done()?;
    // Written by rank 0 only, and not under `rdem -check`.
    let write = file != "none" && !sim.script.check && rdem::comm::process_rank_size().0 == 0;
    sim.outputs
        .out
        .set_thermo_log(write.then_some(file.as_str()), append)
        .map_err(|e| {
            a.error_at(
                1,
                format!("cannot open thermo log file '{file}': {e}"),
                None,
            )
        })
}
