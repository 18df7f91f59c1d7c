//! `rdem -check SCRIPT`: reads the whole script and reports every line rdem cannot run,
//! instead of stopping at the first as a run does.
//!
//! The script is executed as usual — `include`, variables, `if`, `label`/`jump` loops,
//! the box and its particles, every fix, compute and dump are made — with these
//! differences:
//!
//! - **No step runs.** `run N` does everything its set-up does before the first step
//!   (materials from `fix property/global`, `pair_coeff` given, the wear constants, the
//!   timestep, `fix adapt`'s variables, the set-up forces, the thermo header and first
//!   row, so every `c_`/`f_`/`v_` in `thermo_style` is resolved) and then resolves the
//!   columns of every particle dump instead of writing it. It then moves the step counter
//!   on by N (so `run N upto`, `step` in variables and loops that count steps behave as in
//!   a run), but nothing moves and nothing is inserted.
//! - **No file is written.** Dumps, `write_dump`, `write_data`, `write_restart`,
//!   `print ... file|append`, `log FILE`, `fix print ... file|append` and `fix ave/time
//!   ... file` are checked but write nothing, and `rdem -check` opens no `log.liggghts`
//!   (whatever `-log` says): the script's folder stays as it was. `shell cd` and
//!   `shell putenv` act (they change what later lines mean); `shell mkdir|rm|rmdir|mv`
//!   and other shell commands do nothing.
//! - **An error does not stop the script.** Its report is kept and the next command
//!   runs. The same line failing again (a loop body on its next pass) is reported once.
//! - **No cascades.** When a line that defines something fails — a fix, compute, dump,
//!   region, group or variable ID, a `fix property/global` property, the box
//!   (`create_box`, `read_data`, `read_restart`) or the pair style — the errors of later
//!   lines that only say that this thing does not exist (`no fix 'heat'` from
//!   `unfix heat`, `no compute 'x'` from `c_x` in `thermo_style`, "before the simulation
//!   box is defined", "pair_coeff before pair_style", ...) are left out: the line that
//!   failed is the one to fix. So are the errors of later `run` lines with the same
//!   message as an earlier `run` line (a property missing for every run). The failed IDs are remembered and such messages are
//!   recognised by their "no ... 'ID'" wording; no placeholder is registered, because a
//!   placeholder fix or compute would have to pretend to give values. A note line says
//!   how many were left out.
//! - **Loops end.** A `jump` is followed as `next` and `if` allow. A loop whose end
//!   depends on what the steps compute (particle counts, positions, ...) would not end,
//!   since no step runs: each `jump` command is followed at most [`MAX_JUMPS`] times,
//!   then the script goes on past it, and a note line says so.
//! - **Formulas over no particles.** A formula that divides by zero while the box holds
//!   no particles (a count or a mass in a denominator, which a run would have filled)
//!   gives a note line, not a problem.

use crate::error::Error;
use std::collections::{BTreeMap, BTreeSet};

use crate::diagnostic::{RunError, ScriptReport};
use crate::input::Interpreter;
use crate::lexer::{self, Command};
use crate::sim::Sim;

/// How many times one `jump` command is followed before `rdem -check` goes on past it.
pub const MAX_JUMPS: usize = 1000;

/// One line rdem cannot run.
#[derive(Debug)]
pub struct Problem {
    /// The script file the line is in.
    pub file: String,
    /// 1-based line of the command's first character.
    pub line: usize,
    /// The command and, for styled commands, its style (`fix heat/gran`, `dump local`,
    /// `pair_style gran`, `modify_timing`).
    pub what: String,
    /// The usual report: message, file:line:col, the line with a caret, help.
    pub report: ScriptReport,
}

/// What `rdem -check` found.
#[derive(Debug, Default)]
pub struct Checked {
    /// Every line rdem cannot run, in the order they were met.
    pub problems: Vec<Problem>,
    /// Remarks (errors left out as follow-ons, loops cut short).
    pub notes: Vec<String>,
}

impl Checked {
    /// The one-line summary for the script `main`: `in.x: rdem can run every line`, or
    /// `in.x: 3 lines rdem cannot run: fix heat/gran (line 40), compute
    /// pair/gran/local (52), dump local (53)`. A line of another file (an `include`d one)
    /// names it: `fix heat/gran (in.models line 12)`.
    pub fn summary(&self, main: &str) -> String {
        if self.problems.is_empty() {
            return format!("{main}: rdem can run every line");
        }
        let n = self.problems.len();
        let list: Vec<String> = self
            .problems
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let at = if p.file != main {
                    format!("{} line {}", p.file, p.line)
                } else if k == 0 {
                    format!("line {}", p.line)
                } else {
                    p.line.to_string()
                };
                format!("{} ({at})", p.what)
            })
            .collect();
        format!(
            "{main}: {n} line{} rdem cannot run: {}",
            if n == 1 { "" } else { "s" },
            list.join(", ")
        )
    }
}

/// The state of a check while the script runs (kept by the [`Interpreter`]).
#[derive(Debug, Default)]
pub(crate) struct State {
    problems: Vec<Problem>,
    /// (file, line) of every failed command, reported or not.
    seen: BTreeSet<(String, usize)>,
    /// IDs and names that failing lines would have defined.
    failed_ids: BTreeSet<String>,
    /// `fix property/global` property names whose line failed.
    failed_properties: BTreeSet<String>,
    box_failed: bool,
    pair_failed: bool,
    /// Messages of the `run` lines reported so far.
    run_messages: BTreeSet<String>,
    /// Errors left out as follow-ons: (file, line, message).
    left_out: Vec<(String, usize, String)>,
    /// Times each `jump` command (file, line) was followed.
    jumps: BTreeMap<(String, usize), usize>,
    notes: Vec<String>,
}

impl State {
    /// Records the error `report` of command `cmd` in `file`.
    pub(crate) fn record(&mut self, sim: &Sim, file: &str, cmd: &Command, report: ScriptReport) {
        let words: Vec<String> = crate::input::substitute_vars(sim, cmd)
            .ok()
            .and_then(|c| lexer::words(&c).ok())
            .or_else(|| lexer::words(cmd).ok())
            .unwrap_or_default()
            .into_iter()
            .map(|w| w.text)
            .collect();
        let message = report.to_string();
        // A later `run` failing for the same reason (a property missing for every run)
        // has the same cause: the first is reported.
        let follow_on = self.follows_from_earlier(&message)
            || (words.first().map(String::as_str) == Some("run")
                && !self.run_messages.insert(message.clone()));
        self.remember_definitions(&words);
        if !self.seen.insert((file.to_string(), cmd.line)) {
            return;
        }
        if follow_on {
            self.left_out.push((file.to_string(), cmd.line, message));
            return;
        }
        // No step runs, so a box that a run would fill holds no particles here: a
        // formula over them (a count or a mass in a denominator) may divide by zero
        // where the run would not. That is a note, not a line rdem cannot run.
        if sim.world.is_some() && sim.natoms() == 0 && message.contains("divide by 0") {
            self.notes.push(format!(
                "{file}:{}: not checked: a formula divides by zero with no particles, which a run may not ({})",
                cmd.line,
                message.lines().next().unwrap_or("").trim()
            ));
            return;
        }
        self.problems.push(Problem {
            file: file.to_string(),
            line: cmd.line,
            what: describe(&words),
            report,
        });
    }

    /// Whether one more pass of the `jump` at `line` of `file` exceeds [`MAX_JUMPS`]
    /// (the jump is then not taken).
    pub(crate) fn jump_capped(&mut self, file: &str, line: usize, label: Option<&str>) -> bool {
        let n = self.jumps.entry((file.to_string(), line)).or_insert(0);
        *n += 1;
        if *n <= MAX_JUMPS {
            return false;
        }
        if *n == MAX_JUMPS + 1 {
            let to = label.map_or(String::new(), |l| format!(" (to label {l})"));
            self.notes.push(format!(
                "note: {file}:{line}: the jump{to} was followed {MAX_JUMPS} times; the check went on past it \
                 (no step runs, so a loop that waits for the particles to do something would not end)"
            ));
        }
        true
    }

    /// The IDs a failing command would have defined: later errors that only say they do
    /// not exist are follow-ons.
    fn remember_definitions(&mut self, w: &[String]) {
        let Some(name) = w.first() else { return };
        match name.as_str() {
            "fix" | "compute" | "dump" | "region" | "group" | "variable" => {
                if let Some(id) = w.get(1) {
                    self.failed_ids.insert(id.clone());
                }
                if name == "fix" && w.get(3).map(String::as_str) == Some("property/global") {
                    if let Some(p) = w.get(4) {
                        self.failed_properties.insert(p.clone());
                    }
                }
            }
            "create_box" | "read_data" | "read_restart" => self.box_failed = true,
            "pair_style" => self.pair_failed = true,
            _ => {}
        }
    }

    /// Whether `message` only says that something a failed line defines does not exist.
    fn follows_from_earlier(&self, message: &str) -> bool {
        if self.box_failed
            && (message.contains("before the simulation box is defined")
                || message.contains("simulation box is not defined"))
        {
            return true;
        }
        if self.pair_failed
            && (message.contains("pair_coeff before pair_style")
                || message.contains("pair coefficients are not set")
                || message.contains("needs a granular pair style"))
        {
            return true;
        }
        if self
            .failed_properties
            .iter()
            .any(|p| contains_word(message, p))
        {
            return true;
        }
        self.failed_ids.iter().any(|id| names_missing(message, id))
    }

    /// The outcome.
    fn finish(mut self) -> Checked {
        if !self.left_out.is_empty() {
            let n = self.left_out.len();
            let lines: Vec<String> = self
                .left_out
                .iter()
                .map(|(f, l, m)| format!("{f}:{l} ({m})"))
                .collect();
            self.notes.push(format!(
                "note: {n} more error{} left out: {} only about what a failing line above would have defined: {}",
                if n == 1 { "" } else { "s" },
                if n == 1 { "it is" } else { "they are" },
                lines.join("; ")
            ));
        }
        Checked {
            problems: self.problems,
            notes: self.notes,
        }
    }
}

/// Whether `message` says that `id` does not exist: `no fix 'heat'`, `no fix mesh/surface
/// 'cad'`, `'c_x': no compute 'x'`, `in variable 'a': no variable 'b'`.
fn names_missing(message: &str, id: &str) -> bool {
    let quoted = format!("'{id}'");
    message.match_indices(&quoted).any(|(k, _)| {
        // The clause before the quoted ID starts with "no".
        let before = &message[..k];
        let clause = before.rsplit([':', ',', ';', '(']).next().unwrap_or(before);
        clause.trim_start().starts_with("no ")
    })
}

/// Whether `word` appears in `text` as a whole word.
fn contains_word(text: &str, word: &str) -> bool {
    text.split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .any(|w| w == word)
}

/// `fix heat/gran`, `compute pair/gran/local`, `pair_style gran`, `region cone`, or the
/// command name alone.
fn describe(w: &[String]) -> String {
    let Some(name) = w.first() else {
        return "(unreadable command)".into();
    };
    let style = match name.as_str() {
        "fix" | "compute" | "dump" => w.get(3),
        "region" => w.get(2),
        n if n.ends_with("_style") => w.get(1),
        _ => None,
    };
    match style {
        Some(s) => format!("{name} {s}"),
        None => name.clone(),
    }
}

/// The end of `run`'s set-up in check mode (from [`crate::run::steps`], where the first
/// step would start): resolves the columns of every particle dump instead of writing it,
/// and moves the step counter on by `nsteps`.
pub(crate) fn after_setup(sim: &mut Sim, nsteps: u64) -> Result<(), RunError> {
    for k in 0..sim.outputs.dumps.len() {
        let d = &sim.outputs.dumps[k];
        dump_columns(sim, k).map_err(|m| {
            RunError::at(
                d.origin.as_ref(),
                "rdem::run::dump",
                format!("dump {}: {m}", d.id()),
            )
        })?;
    }
    if let Some(w) = &mut sim.world {
        w.step += nsteps;
    }
    Ok(())
}

/// Resolves the columns of dump `k` (the `c_`, `f_` and `v_` references) without writing.
pub(crate) fn dump_columns(sim: &Sim, k: usize) -> Result<(), Error> {
    let d = &sim.outputs.dumps[k];
    d.style.resolve(sim, &d.columns)
}

impl Interpreter {
    /// `rdem -check`: runs the script file `path` in check mode (see the module doc) and
    /// returns every line rdem cannot run.
    pub fn check_file(&mut self, path: &str) -> Checked {
        match std::fs::read(path) {
            Ok(s) => self.check_bytes(path, &s),
            Err(e) => {
                let report = ScriptReport::without_source(
                    format!("cannot open input script '{path}': {e}"),
                    None,
                );
                Checked {
                    problems: vec![Problem {
                        file: path.to_string(),
                        line: 0,
                        what: "the script file".into(),
                        report,
                    }],
                    notes: Vec::new(),
                }
            }
        }
    }

    /// [`Interpreter::check_file`] on the script text `src` named `name`.
    pub fn check_source(&mut self, name: &str, src: &str) -> Checked {
        self.check_bytes(name, src.as_bytes())
    }

    /// `rdem -check` on the script bytes `bytes` named `name`, read as a run reads them
    /// (any encoding in comments and quotes, CRLF as LF).
    pub fn check_bytes(&mut self, name: &str, bytes: &[u8]) -> Checked {
        self.sim.script.check = true;
        self.check = Some(State::default());
        let r = self.run_bytes(name, bytes);
        let mut state = self.check.take().unwrap_or_default();
        if let Err(report) = r {
            // Not expected: every error is recorded where it happens.
            state.problems.push(Problem {
                file: name.to_string(),
                line: 0,
                what: "the script".into(),
                report: *report,
            });
        }
        state.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Output;

    fn check(src: &str) -> Checked {
        let mut i = Interpreter::new(Sim::new(Output::captured()));
        i.check_source("in.t", src)
    }

    #[test]
    fn missing_names_are_recognised() {
        assert!(names_missing("no fix 'heat'", "heat"));
        assert!(names_missing("'c_x': no compute 'x'", "x"));
        assert!(names_missing("no fix mesh/surface 'cad' here", "cad"));
        assert!(!names_missing("bad atom type '1'", "1"));
        assert!(!names_missing("no fix 'heat2'", "heat"));
    }

    #[test]
    fn every_error_is_reported_once_and_follow_ons_are_left_out() {
        let c = check(
            "units si\n\
             region box block 0 1 0 1 0 1 units box\n\
             create_box 1 box\n\
             fix heat all ave/histo 1 1 1 0 1 10 x\n\
             unfix heat\n\
             bogus_command 1\n\
             variable i loop 3\n\
             label again\n\
             create_bonds many all all 1 0.0 0.1\n\
             next i\n\
             jump SELF again\n",
        );
        let lines: Vec<usize> = c.problems.iter().map(|p| p.line).collect();
        assert_eq!(lines, vec![4, 6, 9], "{c:?}");
        assert_eq!(
            c.summary("in.t"),
            "in.t: 3 lines rdem cannot run: fix ave/histo (line 4), bogus_command (6), create_bonds (9)"
        );
        assert_eq!(c.notes.len(), 1, "{:?}", c.notes);
    }

    #[test]
    fn loops_that_wait_for_steps_are_cut() {
        let c = check(
            "units si\n\
             region box block 0 1 0 1 0 1 units box\n\
             create_box 1 box\n\
             label l\n\
             run 0\n\
             if \"$(atoms) < 10\" then \"jump SELF l\"\n",
        );
        assert!(c.problems.is_empty(), "{c:?}");
        assert_eq!(c.notes.len(), 1, "{:?}", c.notes);
        assert_eq!(
            check("units si\n").summary("in.t"),
            "in.t: rdem can run every line"
        );
    }
}
