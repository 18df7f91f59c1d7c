//! Registries: every name rdem knows in one family (commands, fix styles, compute styles,
//! dump styles, region styles, variable styles), each in one table of rows. A row names a
//! command or style, says whether rdem runs it (with its handler) or what it is when it
//! does not, and carries one line of help and the notes of the command table of docs/commands.md.
//!
//! The unknown-name error, its "did you mean", the list of valid names and the tables of
//! docs/commands.md all read these tables (`tests/readme_registry.rs` fails when that file and the
//! registries disagree), so a style is added by adding its row and nothing else.

use crate::args::{nearest, Args};
use crate::diagnostic::{one_of, ScriptError};

/// Whether rdem runs a name.
#[derive(Clone, Copy)]
pub enum Support<H: 'static> {
    /// It runs, with this handler.
    Runs(H),
    /// A LIGGGHTS name that rdem does not run (yet): what it is, for the error
    /// ("fix heat/gran (heat conduction) is not supported by rdem yet").
    Not(&'static str),
    /// Another name of a row rdem runs (LIGGGHTS-PFM's `/omp` variants): it runs as
    /// that row, under that row's name.
    Alias(&'static str),
}

/// One row of a registry.
#[derive(Clone, Copy)]
pub struct Row<H: 'static> {
    /// The command or style name, as written in scripts.
    pub name: &'static str,
    /// The handler, or why there is none.
    pub support: Support<H>,
    /// One line: what rdem supports of it (the docs/commands.md table's second column).
    pub help: &'static str,
    /// Differences and limits worth knowing (the docs/commands.md table's third column).
    pub notes: &'static str,
}

impl<H> Row<H> {
    /// A row rdem runs.
    pub const fn runs(name: &'static str, handler: H, help: &'static str) -> Self {
        Self {
            name,
            support: Support::Runs(handler),
            help,
            notes: "",
        }
    }

    /// A LIGGGHTS name rdem does not run: `what` says what it is.
    pub const fn not_yet(name: &'static str, what: &'static str) -> Self {
        Self {
            name,
            support: Support::Not(what),
            help: "",
            notes: "",
        }
    }

    /// Another name of the row `base`, which it runs as (`help` says what it is).
    pub const fn alias(name: &'static str, base: &'static str, help: &'static str) -> Self {
        Self {
            name,
            support: Support::Alias(base),
            help,
            notes: "",
        }
    }

    /// Whether rdem runs it (itself or as the row it is another name of).
    pub fn runs_here(&self) -> bool {
        !matches!(self.support, Support::Not(_))
    }

    /// The same row with notes (docs/commands.md).
    pub const fn notes(mut self, notes: &'static str) -> Self {
        self.notes = notes;
        self
    }

    /// The handler, if rdem runs it.
    pub fn handler(&self) -> Option<&H> {
        match &self.support {
            Support::Runs(h) => Some(h),
            Support::Not(_) | Support::Alias(_) => None,
        }
    }
}

/// One family of names.
pub struct Registry<H: 'static> {
    /// What a name of this family is called in messages: "command", "fix style", ...
    pub family: &'static str,
    /// How docs/commands.md writes a name of this family: "" for commands, "fix " for
    /// fix styles (`fix wall/gran`), ...
    pub readme_prefix: &'static str,
    /// The rows, in the order of docs/commands.md.
    pub rows: &'static [Row<H>],
}

impl<H> Registry<H> {
    /// The row of `name`, supported or not.
    pub fn row(&self, name: &str) -> Option<&'static Row<H>> {
        self.rows.iter().find(|r| r.name == name)
    }

    /// The names rdem runs, in table order.
    pub fn names(&self) -> Vec<&'static str> {
        self.rows
            .iter()
            .filter(|r| r.runs_here())
            .map(|r| r.name)
            .collect()
    }

    /// The handler of `name`, or the error for the word just read by `a` (an unknown
    /// name with the nearest valid one, or a known one that rdem does not run).
    pub fn lookup(&self, a: &Args, name: &str) -> Result<(&'static str, &'static H), ScriptError> {
        let k = a.pos().saturating_sub(1);
        self.lookup_at(a, k, name)
    }

    /// As [`Registry::lookup`], for the word at position `k`.
    pub fn lookup_at(
        &self,
        a: &Args,
        k: usize,
        name: &str,
    ) -> Result<(&'static str, &'static H), ScriptError> {
        match self.row(name) {
            Some(Row {
                name,
                support: Support::Runs(h),
                ..
            }) => Ok((name, h)),
            Some(Row {
                support: Support::Alias(base),
                ..
            }) => self.lookup_at(a, k, base),
            Some(Row {
                support: Support::Not(what),
                ..
            }) => Err(a.error_at(k, self.not_supported(name, what), Some(self.valid()))),
            None => Err(a.error_at(k, self.unknown(name), Some(self.suggest(name)))),
        }
    }

    /// "fix heat/gran (heat conduction) is not supported by rdem yet".
    pub fn not_supported(&self, name: &str, what: &str) -> String {
        let prefix = self.readme_prefix;
        if what.is_empty() {
            format!("{prefix}{name} is not supported by rdem yet")
        } else {
            format!("{prefix}{name} ({what}) is not supported by rdem yet")
        }
    }

    /// "unknown fix style 'foo'".
    pub fn unknown(&self, name: &str) -> String {
        format!("unknown {} '{name}'", self.family)
    }

    /// "supported fix styles: a, b, c".
    pub fn valid(&self) -> String {
        format!("supported {}s: {}", self.family, self.names().join(", "))
    }

    /// The nearest name rdem runs and the valid ones.
    pub fn suggest(&self, name: &str) -> String {
        let names = self.names();
        match nearest(name, &names) {
            Some(n) => format!("did you mean '{n}'? Valid: {}", one_of(&names)),
            None => format!("valid: {}", one_of(&names)),
        }
    }

    /// The docs/commands.md table rows of this family: `| name | help | notes |`, one per name rdem
    /// runs.
    pub fn readme_rows(&self) -> Vec<String> {
        self.rows
            .iter()
            .filter(|r| r.runs_here())
            .map(|r| {
                format!(
                    "| `{}{}` | {} | {} |",
                    self.readme_prefix, r.name, r.help, r.notes
                )
            })
            .collect()
    }
}
