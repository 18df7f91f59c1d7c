//! `fix ID group print N "text" [file F | append F] [screen yes|no] [title T]`: the text,
//! its variables substituted afresh, at every step that is a multiple of N.
//!
//! As LIGGGHTS 3.8 does it (checked with `liggghts -in in.fp -log log.x`, recorded in
//! `tests/fix_print.rs`):
//! - the text is printed after the steps whose number is a multiple of N (before that
//!   step's thermo row), never at a run's set-up, so a run starting at a multiple of N
//!   does not print it again;
//! - `$x`, `${name}` and `$(formula)` inside quotes are left alone when the line is read
//!   and substituted at each print (rdem's reader leaves quoted text alone too);
//! - `file` truncates the file and `append` appends to it when the fix is defined; both
//!   write the title first (`# Fix print output for fix ID` unless `title T`; `title none`
//!   writes none), then one line per print, flushed;
//! - `screen no` prints neither on the screen nor in the log file.
//!
//! rdem differs in one point: a missing parent folder of the file is made (as for every
//! file rdem writes), where LIGGGHTS stops with "Cannot open fix print file". Only MPI
//! rank 0 writes the file; `rdem -check` writes none and substitutes the text once at the
//! set-up of each run, so a variable it names that does not exist is reported.

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::lexer::Command;
use crate::sim::Sim;
use rdem_io::atomic::AppendFile;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "print",
    parse,
    Stages::END_OF_STEP,
    "`N \"text\"` with `$x`, `${name}`, `$(formula)` substituted at each print; `file`, `append`, `screen yes\\|no`, `title`",
)
.notes("prints after the steps that are multiples of N, never at a run's set-up, as LIGGGHTS 3.8; a missing folder of the file is made (LIGGGHTS stops)");

/// Where the file goes.
enum Target {
    /// `file F`: truncated when the fix is defined.
    File(String),
    /// `append F`: appended to.
    Append(String),
}

/// `fix print`.
pub struct FixPrint {
    /// Print every N steps.
    every: u64,
    /// The text as written (quotes removed), with its source places.
    text: Command,
    /// `screen yes|no`.
    screen: bool,
    /// `file` or `append`.
    target: Option<Target>,
    /// `title T`; `None` for `title none`.
    title: Option<String>,
    /// The open file (rank 0, not under `rdem -check`).
    file: Option<AppendFile>,
}

fn parse(_sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.count("N (print every N steps)")?;
    let k = a.pos();
    a.word("text")?;
    let text = crate::lexer::word_commands(a.command())?.swap_remove(k);
    let (mut screen, mut target, mut title) = (
        true,
        None,
        Some(format!("# Fix print output for fix {}", head.id)),
    );
    while !a.is_done() {
        match a.keyword("fix print keyword", &["file", "append", "screen", "title"])? {
            "file" => target = Some(Target::File(a.word("file name")?.to_string())),
            "append" => target = Some(Target::Append(a.word("file name")?.to_string())),
            "screen" => screen = a.yes_no("screen")?,
            _ => {
                let t = a.word("title text (or none)")?;
                title = (t != "none").then(|| t.to_string());
            }
        }
    }
    Ok(Box::new(FixPrint {
        every,
        text,
        screen,
        target,
        title,
        file: None,
    }))
}

impl FixPrint {
    /// Writes one line to the file, if there is one.
    fn write(&mut self, line: &str) -> Result<(), Error> {
        if let Some(f) = &mut self.file {
            f.append(format!("{line}\n").as_bytes())?;
        }
        Ok(())
    }
}

impl ScriptFix for FixPrint {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let rank0 = rdem::comm::process_rank_size().0 == 0;
        let Some(target) = self.target.as_ref().filter(|_| rank0 && !sim.script.check) else {
            return Ok(());
        };
        // The file name is the word after `file`/`append`.
        let at = a
            .words()
            .iter()
            .rposition(|w| w.text == "file" || w.text == "append")
            .map_or(a.words().len(), |k| k + 1);
        let mut f = match target {
            Target::File(p) => AppendFile::new(p),
            Target::Append(p) => {
                AppendFile::appending(p).map_err(|e| a.error_at(at, e.to_string(), None))?
            }
        };
        // `file` is created (empty with `title none`) when the fix is defined.
        let title = self
            .title
            .as_ref()
            .map_or(String::new(), |t| format!("{t}\n"));
        if matches!(target, Target::File(_)) || !title.is_empty() {
            f.append(title.as_bytes())
                .map_err(|e| a.error_at(at, e.to_string(), None))?;
        }
        self.file = Some(f);
        Ok(())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let setup = ctx.setup;
        let check_setup = setup && ctx.checking();
        if (setup || step % self.every != 0) && !check_setup {
            return Ok(());
        }
        let line = crate::input::substitute_vars(ctx.view(), &self.text)
            .map_err(|e| e.message)?
            .text;
        if check_setup {
            return Ok(());
        }
        if self.screen {
            ctx.line(&line);
        }
        let wrote = self.write(&line);
        ctx.agree_write("fix print", wrote)
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
