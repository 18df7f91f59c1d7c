//! The typed errors below the command level: what evaluating a reference or a formula,
//! writing an output file, reading a restart file or running a fix's stage can fail
//! with. A command turns one into a located [`crate::diagnostic::ScriptError`] (file,
//! line and caret), a run into a [`crate::diagnostic::RunError`] at the word that
//! introduced what failed; the text the user reads is the error's `Display`.
//!
//! The kinds a caller may act on (no box yet, a name not defined, a reference loop, a
//! failed file operation, the engine's error, a write that failed on MPI rank 0) are
//! variants of their own; the rest are rules of one command or format, carried as their
//! message ([`Error::Invalid`]).

use std::sync::Arc;

use crate::expr::ExprError;

/// An error below the command level (see the module documentation).
#[derive(Debug, Clone, thiserror::Error)]
pub enum Error {
    /// Something needs the simulation box, and there is none yet.
    #[error("the simulation box is not defined yet")]
    NoBox,
    /// `who` needs the simulation box, and there is none yet.
    #[error("{0} needs a simulation box")]
    NeedsBox(String),
    /// A reference to a name that is not defined: `no compute 'c1'`.
    #[error("no {kind} '{id}'")]
    Undefined {
        /// What the name was to be: "variable", "compute", "fix", "group", "region".
        kind: &'static str,
        /// The name.
        id: String,
    },
    /// Definitions that refer to each other in a loop (`what`: "variables", ...).
    #[error("{0} refer to each other in a loop")]
    Loop(&'static str),
    /// A formula that does not parse or evaluate, in variable `name`.
    #[error("in variable '{name}': {source}")]
    InVariable {
        /// The variable.
        name: String,
        /// The formula's error.
        #[source]
        source: ExprError,
    },
    /// A file operation that failed.
    #[error(transparent)]
    File(Arc<rdem_io::IoError>),
    /// An rdem restart file that cannot be read.
    #[error(transparent)]
    RestartFile(Arc<rdem_io::restart_file::RestartFileError>),
    /// The engine's error (a lost particle, a bad value, ...).
    #[error(transparent)]
    Engine(#[from] rdem::Error),
    /// Writing `what` failed on MPI rank 0 (this rank stops with it; rank 0 reports why).
    #[error("{0}: writing failed on rank 0")]
    FailedOnRankZero(String),
    /// Bytes (a restart file's block, a fix's saved state) that do not decode.
    #[error("{0}")]
    Decode(String),
    /// `source`, in the part named `what` (`dump d1: ...`).
    #[error("{what}: {source}")]
    In {
        /// Where it happened.
        what: String,
        /// What happened.
        #[source]
        source: Box<Error>,
    },
    /// A rule of one command or format, as its message.
    #[error("{0}")]
    Invalid(String),
}

/// The result of an operation that fails with an [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// A rule of one command or format: `message` as the user reads it.
    pub fn invalid(message: impl Into<String>) -> Self {
        Error::Invalid(message.into())
    }

    /// `no {kind} '{id}'`.
    pub fn undefined(kind: &'static str, id: impl Into<String>) -> Self {
        Error::Undefined {
            kind,
            id: id.into(),
        }
    }

    /// This error inside `what`: reads "{what}: {self}".
    pub fn within(self, what: impl Into<String>) -> Self {
        Error::In {
            what: what.into(),
            source: Box::new(self),
        }
    }

    /// The innermost error, past every [`Error::In`].
    pub fn root(&self) -> &Error {
        match self {
            Error::In { source, .. } => source.root(),
            e => e,
        }
    }
}

impl From<rdem_io::IoError> for Error {
    fn from(e: rdem_io::IoError) -> Self {
        Error::File(Arc::new(e))
    }
}

impl From<rdem_io::restart_file::RestartFileError> for Error {
    fn from(e: rdem_io::restart_file::RestartFileError) -> Self {
        Error::RestartFile(Arc::new(e))
    }
}

/// The message as the user reads it (for a located [`crate::diagnostic::ScriptError`]).
impl From<Error> for String {
    fn from(e: Error) -> Self {
        e.to_string()
    }
}

impl From<String> for Error {
    fn from(message: String) -> Self {
        Error::Invalid(message)
    }
}

impl From<&str> for Error {
    fn from(message: &str) -> Self {
        Error::Invalid(message.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_read_as_before() {
        assert_eq!(
            Error::undefined("compute", "c1").to_string(),
            "no compute 'c1'"
        );
        assert_eq!(
            Error::NoBox.to_string(),
            "the simulation box is not defined yet"
        );
        let e = Error::undefined("fix", "f").within("dump d1");
        assert_eq!(e.to_string(), "dump d1: no fix 'f'");
        assert!(matches!(e.root(), Error::Undefined { kind: "fix", .. }));
        assert_eq!(
            Error::Loop("variables").to_string(),
            "variables refer to each other in a loop"
        );
    }
}
