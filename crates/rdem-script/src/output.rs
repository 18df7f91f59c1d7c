//! Where messages go: the screen (standard output, a file, or nowhere) and the log file,
//! as LIGGGHTS' `-screen`, `-log` and `log` options choose, plus the `echo` setting.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::sync::{Arc, Mutex};

/// Warnings waiting to be printed: the output prints them before its next line (and at
/// [`Output::flush_warnings`]), so a command's reader can warn while the command runs.
pub type Warnings = Arc<Mutex<Vec<String>>>;

/// Which sinks echo each input command (`echo none|screen|log|both`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Echo {
    /// No echo.
    None,
    /// Screen only.
    Screen,
    /// Log only (LIGGGHTS' default).
    #[default]
    Log,
    /// Both.
    Both,
}

/// Screen and log sinks.
pub struct Output {
    screen: Option<Box<dyn Write + Send>>,
    log: Option<BufWriter<File>>,
    /// `thermo_log FILE`: the thermo header and rows also go there.
    thermo_log: Option<BufWriter<File>>,
    /// Command echo setting.
    pub echo: Echo,
    /// Everything written to the screen sink is also kept here when set (tests).
    pub captured: Option<String>,
    /// Warnings not yet printed.
    pending: Warnings,
}

impl Default for Output {
    fn default() -> Self {
        Self::stdout()
    }
}

impl Output {
    /// Screen on standard output, no log.
    pub fn stdout() -> Self {
        Self {
            screen: Some(Box::new(std::io::stdout())),
            log: None,
            thermo_log: None,
            echo: Echo::Log,
            captured: None,
            pending: Warnings::default(),
        }
    }

    /// No screen, no log; the screen text is captured in [`Output::captured`].
    pub fn captured() -> Self {
        Self {
            screen: None,
            log: None,
            thermo_log: None,
            echo: Echo::Log,
            captured: Some(String::new()),
            pending: Warnings::default(),
        }
    }

    /// Replaces the screen sink (`None`: no screen output).
    pub fn set_screen(&mut self, screen: Option<Box<dyn Write + Send>>) {
        self.screen = screen;
    }

    /// Opens (or appends to) the log file; `None` closes it.
    pub fn set_log(&mut self, path: Option<&str>, append: bool) -> std::io::Result<()> {
        reopen(&mut self.log, path, append)
    }

    /// Opens (or appends to) the thermo log file (`thermo_log`); `None` closes it.
    pub fn set_thermo_log(&mut self, path: Option<&str>, append: bool) -> std::io::Result<()> {
        reopen(&mut self.thermo_log, path, append)
    }

    /// Writes a thermo header or row to the screen, the log and the thermo log (flushed,
    /// so the file can be followed during a run).
    pub fn thermo_line(&mut self, text: &str) {
        self.line(text);
        if let Some(t) = &mut self.thermo_log {
            let _ = writeln!(t, "{text}");
            let _ = t.flush();
        }
    }

    /// Writes a line (a newline is added) to the screen and the log.
    pub fn line(&mut self, text: &str) {
        self.screen_line(text);
        self.log_line(text);
    }

    /// The queue of warnings that are printed before the next line.
    pub fn warnings(&self) -> Warnings {
        self.pending.clone()
    }

    /// Prints the queued warnings (`WARNING: ...`) on screen and in the log.
    pub fn flush_warnings(&mut self) {
        let pending = match self.pending.lock() {
            Ok(mut q) if !q.is_empty() => std::mem::take(&mut *q),
            _ => return,
        };
        for w in pending {
            self.warning(&w);
        }
    }

    /// Writes a line to the screen only.
    pub fn screen_line(&mut self, text: &str) {
        self.flush_warnings();
        if let Some(s) = &mut self.screen {
            let _ = writeln!(s, "{text}");
        }
        if let Some(c) = &mut self.captured {
            c.push_str(text);
            c.push('\n');
        }
    }

    /// Writes a line to the log only.
    pub fn log_line(&mut self, text: &str) {
        self.flush_warnings();
        if let Some(l) = &mut self.log {
            let _ = writeln!(l, "{text}");
        }
    }

    /// A warning, LIGGGHTS style (`WARNING: ...`), on screen and in the log.
    pub fn warning(&mut self, text: &str) {
        self.line(&format!("WARNING: {text}"));
    }

    /// Echoes an input command as the echo setting says.
    pub fn echo_command(&mut self, text: &str) {
        match self.echo {
            Echo::None => {}
            Echo::Screen => self.screen_line(text),
            Echo::Log => self.log_line(text),
            Echo::Both => self.line(text),
        }
    }

    /// True when the screen is the terminal's standard output (for progress lines).
    pub fn has_screen(&self) -> bool {
        self.screen.is_some()
    }

    /// Flushes both sinks.
    pub fn flush(&mut self) {
        if let Some(s) = &mut self.screen {
            let _ = s.flush();
        }
        if let Some(l) = &mut self.log {
            let _ = l.flush();
        }
    }
}

/// Flushes and closes the file in `slot`, then opens `path` there (truncated, or appended
/// to with `append`); `None` leaves it closed. The log and the thermo log use it.
fn reopen(
    slot: &mut Option<BufWriter<std::fs::File>>,
    path: Option<&str>,
    append: bool,
) -> std::io::Result<()> {
    if let Some(l) = slot {
        l.flush()?;
    }
    *slot = match path {
        None => None,
        Some(p) => Some(BufWriter::new(
            std::fs::OpenOptions::new()
                .create(true)
                .write(true)
                .append(append)
                .truncate(!append)
                .open(p)?,
        )),
    };
    Ok(())
}
