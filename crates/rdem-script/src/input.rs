//! The script driver: reads files (and `include`d ones) command by command, substitutes
//! variables, echoes, handles flow control (`label`, `jump`, `next`, `if`, `include`),
//! `variable`, `print`, `log`, `echo`, and hands every other command to the command table.
//! An error stops the script and is reported with its file, line and a caret.

use std::sync::Arc;

use crate::args::{suggest, Args, CmdResult};
use crate::commands;
use crate::context;
use crate::diagnostic::ScriptReport;
use crate::error::Error;
use crate::lexer::{self, Command, Reference};
use crate::output::Echo;
use crate::sim::Sim;

/// A `jump` searching for its label, and the error to report if the file ends first.
struct SkipTo {
    label: String,
    missing: Box<ScriptReport>,
}

struct Frame {
    name: String,
    src: Arc<str>,
    cmds: Vec<Command>,
    pos: usize,
}

/// A script run: the simulation state and the stack of open script files.
pub struct Interpreter {
    /// The simulation.
    pub sim: Sim,
    frames: Vec<Frame>,
    /// Label being searched by `jump` (commands are skipped until it).
    skip_to: Option<SkipTo>,
    /// Set by `next` when a variable is exhausted: the next `jump` is skipped.
    skip_jump: bool,
    quit: bool,
    /// An error already reported in an included file, passed up through `include`.
    inner_report: Option<Box<ScriptReport>>,
    /// Number of MPI ranks running the script (1 without MPI).
    nprocs: usize,
    /// `rdem -check`: the errors so far (each is recorded and the script goes on).
    pub(crate) check: Option<crate::check::State>,
}

/// Every command name rdem knows (for suggestions).
pub fn all_commands() -> Vec<&'static str> {
    commands::REGISTRY.names()
}

const IF_USAGE: &str =
    "if \"condition\" then \"command\" ... [elif \"condition\" \"command\" ...] [else \"command\" ...]";

/// Replaces `$x`, `${name}` and `$(expression)` in `cmd` (see [`lexer::substitute`]); an
/// unknown variable's error suggests the defined ones.
pub(crate) fn substitute_vars(sim: &Sim, cmd: &Command) -> CmdResult<Command> {
    let mut help = None;
    let mut expr_span = None;
    lexer::substitute(cmd, |r| match r {
        Reference::Variable(name) => context::variable_text(sim, name).inspect_err(|_| {
            if sim.script.vars.get(name).is_none() {
                help = Some((name.clone(), unknown_variable_help(sim, name)));
            }
        }),
        Reference::Immediate(e) => context::eval_equal(sim, e)
            .map(|v| crate::variables::format_g(v, 20))
            .map_err(|e| {
                expr_span = Some(e.span);
                Error::Invalid(e.message)
            }),
    })
    .map_err(|mut e| {
        // An error in `$(formula)` points at its place inside the formula.
        if let Some(r) = expr_span.take() {
            if let Some(i) = cmd.origin.iter().position(|&o| o == e.span.start) {
                let (a, b) = (i + 2 + r.start, i + 2 + r.end);
                if b < cmd.text.len() {
                    e.span = lexer::span_of(cmd, a..b);
                }
            }
        }
        if e.help.is_none() {
            // `$nsteps` is `$n` followed by "steps": say so when `$n` is unknown.
            let braces = cmd
                .origin
                .iter()
                .position(|&o| o == e.span.start)
                .is_some_and(|i| cmd.text[i..].starts_with("${"));
            e.help = help.map(|(name, h): (String, String)| {
                if name.chars().count() == 1 && !braces {
                    format!("'${name}' is the one-letter variable '{name}': write ${{NAME}} with braces for longer names")
                } else {
                    h
                }
            });
        }
        e
    })
}

/// Help for `${name}` of a variable that does not exist.
fn unknown_variable_help(sim: &Sim, name: &str) -> String {
    let names = sim.script.vars.names();
    let define =
        format!("define it with 'variable {name} ...' (or -var {name} VALUE) before it is used");
    match crate::args::nearest(name, &names) {
        Some(n) => format!("did you mean '{n}'? Or {define}"),
        None => define[..1].to_uppercase() + &define[1..],
    }
}

impl Interpreter {
    /// An interpreter over `sim`.
    pub fn new(sim: Sim) -> Self {
        Self {
            sim,
            frames: Vec::new(),
            skip_to: None,
            skip_jump: false,
            quit: false,
            inner_report: None,
            nprocs: rdem::comm::process_rank_size().1,
            check: None,
        }
    }

    /// Runs the script `src` named `name` (a file name for messages).
    pub fn run_source(&mut self, name: &str, src: &str) -> Result<(), Box<ScriptReport>> {
        self.run_bytes(name, src.as_bytes())
    }

    /// Runs the script bytes `bytes` named `name`, read as LIGGGHTS reads a script file
    /// (see [`crate::source`]: any encoding in comments and quotes, CRLF as LF).
    pub fn run_bytes(&mut self, name: &str, bytes: &[u8]) -> Result<(), Box<ScriptReport>> {
        let (src, cmds) = crate::source::load(name, bytes)?;
        self.frames.push(Frame {
            name: name.to_string(),
            cmds,
            src,
            pos: 0,
        });
        let depth = self.frames.len();
        let r = self.drive(depth);
        self.sim.outputs.out.flush();
        r
    }

    /// A frame for the script file `file` named by word 1 of `a` (`include`, `jump`). A
    /// file that cannot be read is an error at the word; a non-UTF-8 byte outside
    /// comments and quotes is reported in that file.
    fn open_frame(&mut self, a: &Args, file: &str) -> CmdResult<Frame> {
        let bytes = std::fs::read(file)
            .map_err(|e| a.error_at(1, format!("cannot open '{file}': {e}"), None))?;
        let (src, cmds) = crate::source::load(file, &bytes).map_err(|report| {
            self.inner_report = Some(report);
            a.error_at(1, "error in included file", None)
        })?;
        Ok(Frame {
            name: file.to_string(),
            cmds,
            src,
            pos: 0,
        })
    }

    /// Where the current command's warnings go (see [`crate::args::WarningSink`]).
    fn warning_sink(&self) -> crate::args::WarningSink {
        let f = self.frames.last().expect("a command runs in a script");
        crate::args::WarningSink {
            queue: self.sim.outputs.out.warnings(),
            src: f.src.clone(),
            file: (self.frames.len() > 1).then(|| f.name.clone()),
        }
    }

    /// Runs the script file `path`.
    pub fn run_file(&mut self, path: &str) -> Result<(), Box<ScriptReport>> {
        match std::fs::read(path) {
            Ok(s) => self.run_bytes(path, &s),
            Err(e) => Err(Box::new(ScriptReport::without_source(
                format!("cannot open input script '{path}': {e}"),
                None,
            ))),
        }
    }

    /// Executes frames until the stack is back below `depth`.
    fn drive(&mut self, depth: usize) -> Result<(), Box<ScriptReport>> {
        while self.frames.len() >= depth && !self.quit {
            let top = self.frames.len() - 1;
            let f = &mut self.frames[top];
            if f.pos >= f.cmds.len() {
                if let Some(skip) = self.skip_to.take() {
                    // The file ended before the label of a `jump` (LIGGGHTS: "Label
                    // wasn't found in input script").
                    self.frames.truncate(depth - 1);
                    return Err(skip.missing);
                }
                self.frames.pop();
                continue;
            }
            let cmd = f.cmds[f.pos].clone();
            f.pos += 1;
            // The file of the command, for the words that later errors point at.
            if self
                .sim
                .script
                .here
                .as_ref()
                .is_none_or(|h| *h.name != *f.name)
            {
                self.sim.script.here = Some(crate::diagnostic::SourceFile {
                    name: f.name.as_str().into(),
                    src: f.src.clone(),
                });
            }
            let mut result = self.execute(&cmd);
            self.sim.outputs.out.flush_warnings();
            if self.nprocs > 1 {
                // Every rank runs every command: they stop together when any fails, and
                // the report (printed by rank 0) is the lowest failing rank's.
                let failed = result.as_ref().err().map(|e| e.message.clone());
                if let Some((rank, message)) = rdem::comm::agree_on_failure(failed.as_deref()) {
                    if result.is_ok() {
                        let end = cmd.text.find(char::is_whitespace).unwrap_or(cmd.text.len());
                        result =
                            Err(cmd.error(0..end, format!("on MPI rank {rank}: {message}"), None));
                    }
                }
            }
            if let Err(e) = result {
                if let Some(inner) = self.inner_report.take() {
                    self.frames.truncate(depth - 1);
                    return Err(inner);
                }
                // The error belongs to the file the command came from (the top frame
                // when it ran; an `include` may have pushed more frames meanwhile).
                let f = &self.frames[top.min(self.frames.len() - 1)];
                let report = e.in_file(&f.name, f.src.clone());
                if let Some(c) = &mut self.check {
                    c.record(&self.sim, &f.name, &cmd, report);
                    continue;
                }
                self.frames.truncate(depth - 1);
                return Err(Box::new(report));
            }
        }
        Ok(())
    }

    /// Executes one command (substitution, echo, dispatch).
    fn execute(&mut self, raw: &Command) -> CmdResult {
        if let Some(skip) = &self.skip_to {
            let w = lexer::words(raw)?;
            if w.len() >= 2 && w[0].text == "label" && w[1].text == skip.label {
                self.skip_to = None;
            }
            return Ok(());
        }
        let cmd = substitute_vars(&self.sim, raw)?;
        let words = lexer::words(&cmd)?;
        if words.is_empty() {
            return Ok(());
        }
        self.sim.outputs.out.echo_command(&cmd.text);
        let mut a = Args::new(&cmd, &words).warn_into(self.warning_sink());
        match a.name() {
            "include" => {
                let file = a.word("file name")?.to_string();
                a.done()?;
                let frame = self.open_frame(&a, &file)?;
                self.frames.push(frame);
                let depth = self.frames.len();
                // Run the included file to its end; its errors are reported in it.
                if let Err(report) = self.drive(depth) {
                    self.inner_report = Some(report);
                    return Err(a.error_at(1, "error in included file", None));
                }
            }
            "label" => {
                a.word("label ID")?;
                a.done()?;
            }
            "jump" => {
                let file = a.word("file name or SELF")?.to_string();
                let label = a.peek().map(String::from);
                if label.is_some() {
                    a.seek(a.pos() + 1);
                }
                a.done()?;
                if self.skip_jump {
                    self.skip_jump = false;
                    return Ok(());
                }
                let top = self.frames.len() - 1;
                if let Some(c) = &mut self.check {
                    if c.jump_capped(&self.frames[top].name, raw.line, label.as_deref()) {
                        return Ok(());
                    }
                }
                let target = if file == "SELF" || file == self.frames[top].name {
                    None
                } else {
                    Some(self.open_frame(&a, &file)?)
                };
                if let Some(label) = label {
                    let cmds = target.as_ref().map_or(&self.frames[top].cmds, |f| &f.cmds);
                    let labels: Vec<String> = cmds
                        .iter()
                        .filter_map(|c| {
                            let mut w = c.text.split_whitespace();
                            (w.next() == Some("label"))
                                .then(|| w.next().map(String::from))
                                .flatten()
                        })
                        .collect();
                    let labels: Vec<&str> = labels.iter().map(|l| l.as_str()).collect();
                    let name = if file == "SELF" {
                        self.frames[top].name.clone()
                    } else {
                        file.clone()
                    };
                    let help = if labels.is_empty() {
                        format!("{name} has no 'label' command")
                    } else {
                        suggest(&label, &labels)
                    };
                    let here = &self.frames[top];
                    let missing = a.error_at(
                        2,
                        format!("label '{label}' not found in {name}"),
                        Some(help),
                    );
                    if self.check.is_some() && !labels.contains(&label.as_str()) {
                        return Err(missing);
                    }
                    let missing = missing.in_file(&here.name, here.src.clone());
                    self.skip_to = Some(SkipTo {
                        label,
                        missing: Box::new(missing),
                    });
                }
                match target {
                    Some(f) => self.frames[top] = f,
                    None => self.frames[top].pos = 0,
                }
            }
            "next" => {
                let mut names = Vec::new();
                while !a.is_done() {
                    names.push(a.word("variable name")?.to_string());
                }
                if names.is_empty() {
                    return Err(a.error_at(1, "next: missing variable name", None));
                }
                let next = self
                    .sim
                    .script
                    .vars
                    .next(&names)
                    .map_err(|m| a.error_at(1, m, None))?;
                if let Some(line) = &next.message {
                    self.sim.outputs.out.line(line);
                }
                if next.exhausted {
                    self.skip_jump = true;
                }
            }
            "variable" => {
                let name = a.word("variable name")?.to_string();
                let style = a.word("variable style")?.to_string();
                let rest: Vec<String> = words[3..].iter().map(|w| w.text.clone()).collect();
                let defined = self
                    .sim
                    .script
                    .vars
                    .define(&name, &style, &rest)
                    .map_err(|e| {
                        let k = if e.arg == usize::MAX { 1 } else { e.arg + 2 };
                        let help = e.help.clone().or_else(|| {
                            (e.arg == 0).then(|| crate::variables::STYLES.suggest(&style))
                        });
                        a.error_at(k.min(words.len()), e.message, help)
                    })?;
                if defined && style != "delete" {
                    // The formula (or first value): errors of its evaluation during a
                    // run point at it.
                    let origin = self.sim.origin(&a, 3.min(words.len() - 1));
                    self.sim.script.vars.set_origin(&name, origin);
                }
            }
            "print" => self.print(&mut a, &cmd)?,
            "log" => {
                let file = a.word("log file name or none")?.to_string();
                let mut append = false;
                while !a.is_done() {
                    a.keyword("log keyword", &["append"])?;
                    append = true;
                }
                let path = (file != "none" && self.check.is_none()).then_some(file.as_str());
                self.sim.outputs.out.set_log(path, append).map_err(|e| {
                    a.error_at(1, format!("cannot open log file '{file}': {e}"), None)
                })?;
            }
            "echo" => {
                self.sim.outputs.out.echo =
                    match a.keyword("echo setting", &["none", "screen", "log", "both"])? {
                        "none" => Echo::None,
                        "screen" => Echo::Screen,
                        "log" => Echo::Log,
                        _ => Echo::Both,
                    };
                a.done()?;
            }
            "if" => self.if_command(&mut a, &cmd)?,
            "run" => self.run_command(&mut a, &cmd)?,
            "quit" => self.quit = true,
            name => {
                if commands::REGISTRY.row(name).is_none() {
                    return Err(a.error_cmd(
                        format!("unknown command '{name}'"),
                        Some(commands::unknown_command_help(name, &all_commands())),
                    ));
                }
                commands::execute(&mut self.sim, &mut a)?;
            }
        }
        Ok(())
    }

    fn print(&mut self, a: &mut Args, cmd: &Command) -> CmdResult {
        let k = a.pos();
        a.word("text")?;
        let text = self.resubstitute(cmd, k)?;
        let (mut file, mut screen) = (None, true);
        while !a.is_done() {
            match a.keyword("print keyword", &["file", "append", "screen"])? {
                "file" | "append" => {
                    let append = a.words()[a.pos() - 1].text == "append";
                    let f = a.word("file name")?.to_string();
                    file = Some((f, append));
                }
                _ => screen = a.yes_no("screen")?,
            }
        }
        if screen {
            self.sim.outputs.out.line(&text);
        } else {
            self.sim.outputs.out.log_line(&text);
        }
        if let Some((f, append)) = file.filter(|_| self.check.is_none()) {
            use std::io::Write;
            let mut h = std::fs::OpenOptions::new()
                .create(true)
                .write(true)
                .append(append)
                .truncate(!append)
                .open(&f)
                .map_err(|e| a.error_prev(format!("cannot open '{f}': {e}"), None))?;
            writeln!(h, "{text}")
                .map_err(|e| a.error_prev(format!("cannot write '{f}': {e}"), None))?;
        }
        Ok(())
    }

    /// Substitutes variables in a quoted word (quotes stop substitution when the command
    /// is read; `print` and `if` substitute their text when they run, as LIGGGHTS).
    fn resubstitute(&self, cmd: &Command, k: usize) -> CmdResult<String> {
        let inner = &lexer::word_commands(cmd)?[k];
        Ok(substitute_vars(&self.sim, inner)?.text)
    }

    fn if_command(&mut self, a: &mut Args, cmd: &Command) -> CmdResult {
        // if "cond" then "c1" "c2" ... [elif "cond" "c" ...] [else "c" ...]
        let words = a.words().to_vec();
        let mut k = 1;
        loop {
            if k >= words.len() {
                return Err(a.error_at(k, "if: missing condition", Some(IF_USAGE.into())));
            }
            let cond = self.resubstitute(cmd, k)?;
            let value = context::eval_equal(&self.sim, &cond).map_err(|e| {
                a.error_at(k, format!("if condition '{cond}': {}", e.message), None)
            })?;
            k += 1;
            if k == 2 {
                match words.get(k).map(|w| w.text.as_str()) {
                    Some("then") => k += 1,
                    _ => {
                        return Err(a.error_at(
                            k,
                            "if: expected 'then' after the condition",
                            Some(IF_USAGE.into()),
                        ))
                    }
                }
            }
            let start = k;
            while k < words.len() && words[k].text != "elif" && words[k].text != "else" {
                k += 1;
            }
            if value != 0.0 {
                return self.run_inline(cmd, start..k);
            }
            match words.get(k).map(|w| w.text.as_str()) {
                Some("elif") => k += 1,
                Some("else") => return self.run_inline(cmd, k + 1..words.len()),
                _ => return Ok(()),
            }
        }
    }

    /// `run N ... [every M c1 c2 ...]`: with `every`, the run in chunks of M steps (the
    /// last one shorter) with the commands after each, as LAMMPS' `run`: the first chunk
    /// always sets up, the last always prints the full summary, and a run of 0 steps
    /// still runs the commands once. LIGGGHTS 3.8 reads the integers with `atoi`. Under
    /// `rdem -check` the steps are one checked run and the commands run once after it.
    fn run_command(&mut self, a: &mut Args, cmd: &Command) -> CmdResult {
        a.read_integers_with_atoi();
        let plan = crate::run::parse(&self.sim, a)?;
        let Some((m, range)) = plan.every.clone() else {
            return crate::run::run_plan(&mut self.sim, a, &plan);
        };
        if self.check.is_some() {
            crate::run::run_plan(&mut self.sim, a, &plan)?;
            return self.run_inline(cmd, range);
        }
        let mut left = plan.nsteps;
        let mut first = true;
        while (left > 0 || first) && !self.quit {
            let n = left.min(m);
            let step = self.sim.world_ref(a)?.step;
            let chunk = plan.chunk(step, n, first, left <= n);
            crate::run::run_chunk(&mut self.sim, a, chunk)?;
            if self.sim.script.halted {
                break;
            }
            self.run_inline(cmd, range.clone())?;
            left -= n;
            first = false;
        }
        Ok(())
    }

    /// Runs words `range` of `cmd` as commands (the branches of `if`, `run every`).
    fn run_inline(&mut self, cmd: &Command, range: std::ops::Range<usize>) -> CmdResult {
        let inner = lexer::word_commands(cmd)?;
        for c in &inner[range] {
            self.execute(c)?;
        }
        Ok(())
    }
}
