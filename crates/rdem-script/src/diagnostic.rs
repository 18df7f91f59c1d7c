//! Script errors that point at the offending word: a byte span in the source file, a
//! message and the valid alternatives. [`ScriptError::in_file`] attaches the file so that
//! `miette` renders the line with a caret under the word.

use std::ops::Range;
use std::sync::Arc;

use miette::{Diagnostic, LabeledSpan, NamedSource, SourceCode, SourceSpan};

/// A script file: its name (for messages) and its text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceFile {
    /// The name as the user gave it (`in.script`, an `include`d file).
    pub name: Arc<str>,
    /// The text the spans point into.
    pub src: Arc<str>,
}

/// Where a word of a script stands: its file and byte range. Kept by the commands that
/// introduce a reference evaluated later (a thermo column, a dump column, a fix), so
/// that an error found during a run points at that word.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Origin {
    /// The file.
    pub file: SourceFile,
    /// Byte range of the word.
    pub span: Range<usize>,
}

impl Origin {
    /// 1-based line of the word.
    pub fn line(&self) -> usize {
        let at = self.span.start.min(self.file.src.len());
        1 + self.file.src.as_bytes()[..at]
            .iter()
            .filter(|&&c| c == b'\n')
            .count()
    }
}

/// An error at a place in a script.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct ScriptError {
    /// What is wrong.
    pub message: String,
    /// Byte range in the source file.
    pub span: Range<usize>,
    /// The valid alternatives or the fix, if any.
    pub help: Option<String>,
    /// The file the span points into, when it is not the file of the command that
    /// failed (an error found during a run, at the word that introduced it).
    pub file: Option<SourceFile>,
    /// A miette error code (`rdem::run::thermo`, ...), for errors found during a run.
    pub code: Option<&'static str>,
}

/// An error found during a run (or its set-up), with the word that introduced what
/// failed when it is known: a thermo column, a dump column, a fix. Without one it is
/// reported at the `run` command.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct RunError {
    /// What is wrong.
    pub message: String,
    /// The word that introduced it.
    pub origin: Option<Origin>,
    /// The error code: `rdem::run::thermo`, `rdem::run::dump`, `rdem::run::fix`,
    /// `rdem::run::engine`, `rdem::run`.
    pub code: &'static str,
}

impl RunError {
    /// An error of kind `code` at `origin` (if known).
    pub fn at(origin: Option<&Origin>, code: &'static str, message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            origin: origin.cloned(),
            code,
        }
    }
}

impl From<String> for RunError {
    fn from(message: String) -> Self {
        Self {
            message,
            origin: None,
            code: "rdem::run",
        }
    }
}

/// An error of the engine's step (lost or non-finite particles, ...).
impl From<rdem::Error> for RunError {
    fn from(e: rdem::Error) -> Self {
        RunError::at(None, "rdem::run::engine", e.to_string())
    }
}

/// An error below the command level, reported at the `run` command.
impl From<crate::error::Error> for RunError {
    fn from(e: crate::error::Error) -> Self {
        e.to_string().into()
    }
}

impl From<&str> for RunError {
    fn from(message: &str) -> Self {
        message.to_string().into()
    }
}

impl ScriptError {
    /// An error at the source bytes `span` of the file being read (see
    /// [`crate::lexer::Command::error`] for an error at the bytes of a command).
    pub fn spanned(span: Range<usize>, message: String, help: Option<String>) -> Self {
        Self {
            message,
            span,
            help,
            file: None,
            code: None,
        }
    }

    /// The error at `origin`, in its own file.
    pub fn at_origin(origin: &Origin, message: String, help: Option<String>) -> Self {
        Self {
            message,
            span: origin.span.clone(),
            help,
            file: Some(origin.file.clone()),
            code: None,
        }
    }

    /// The source span.
    pub fn span(&self) -> Range<usize> {
        self.span.clone()
    }

    /// Attaches the script's name and text for rendering.
    /// An error that carries its own file ([`ScriptError::file`]) keeps it.
    pub fn in_file(self, name: &str, source: Arc<str>) -> ScriptReport {
        let (name, source) = match &self.file {
            Some(f) => (f.name.to_string(), f.src.clone()),
            None => (name.to_string(), source),
        };
        let len = source.len();
        let start = self.span.start.min(len);
        let end = self.span.end.clamp(start, len);
        ScriptReport {
            message: self.message,
            help: self.help,
            src: Some(NamedSource::new(name, source)),
            span: Some((start, end - start).into()),
            code: self.code,
        }
    }
}

impl ScriptReport {
    /// A report that belongs to no place in a script (e.g. the script file cannot be
    /// read): the message and help only.
    pub fn without_source(message: String, help: Option<String>) -> Self {
        Self {
            message,
            help,
            src: None,
            span: None,
            code: None,
        }
    }
}

/// A [`ScriptError`] with its file, ready to render (`miette::Report::new(report)`).
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub struct ScriptReport {
    message: String,
    help: Option<String>,
    src: Option<NamedSource<Arc<str>>>,
    span: Option<SourceSpan>,
    code: Option<&'static str>,
}

impl ScriptReport {
    /// The error code, if it has one (errors found during a run).
    pub fn code(&self) -> Option<&'static str> {
        self.code
    }

    /// The message (without the source excerpt and the help).
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The file, and the 1-based line and column (in characters) of the word the report
    /// points at; `None` when it points at no source.
    pub fn location(&self) -> Option<(String, usize, usize)> {
        let (src, span) = (self.src.as_ref()?, self.span?);
        let text: &str = src.inner();
        let mut off = span.offset().min(text.len());
        while !text.is_char_boundary(off) {
            off -= 1;
        }
        let before = &text[..off];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        Some((src.name().to_string(), line, col))
    }
}

impl Diagnostic for ScriptReport {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.code.map(|c| Box::new(c) as Box<dyn std::fmt::Display>)
    }

    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.help
            .as_ref()
            .map(|h| Box::new(h) as Box<dyn std::fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn SourceCode> {
        self.src.as_ref().map(|s| s as &dyn SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        self.span.map(|s| {
            Box::new(std::iter::once(LabeledSpan::new_with_span(
                Some("here".into()),
                s,
            ))) as Box<dyn Iterator<Item = LabeledSpan>>
        })
    }
}

/// "one of a, b or c" for help texts listing valid keywords.
pub fn one_of(valid: &[&str]) -> String {
    match valid {
        [] => String::new(),
        [a] => format!("'{a}'"),
        [init @ .., last] => format!(
            "one of {} or '{last}'",
            init.iter()
                .map(|v| format!("'{v}'"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::{commands, words};

    fn render(r: ScriptReport) -> String {
        let mut out = String::new();
        miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .render_report(&mut out, &r)
            .unwrap();
        out
    }

    #[test]
    fn errors_show_file_line_and_caret_under_the_word() {
        let src: Arc<str> = "units si\nboundary m m q\n".into();
        let c = &commands(&src)[1];
        let w = words(c).unwrap();
        let e = ScriptError {
            message: format!("unknown boundary '{}'", w[3].text),
            span: w[3].span.clone(),
            help: Some(format!("use {}", one_of(&["p", "f", "s", "m"]))),
            file: None,
            code: None,
        };
        let text = render(e.in_file("in.test", src.clone()));
        assert!(text.contains("unknown boundary 'q'"), "{text}");
        assert!(text.contains("in.test:2:14"), "{text}");
        assert!(text.contains("boundary m m q"), "{text}");
        assert!(text.contains("use one of 'p', 'f', 's' or 'm'"), "{text}");
        // The caret line marks column 14 (under 'q').
        let line = text
            .lines()
            .find(|l| l.contains('┬') || l.contains('^'))
            .unwrap();
        let marker = line.find(['┬', '^']).unwrap();
        let code = text.lines().find(|l| l.contains("boundary m m q")).unwrap();
        assert_eq!(
            line[..marker].chars().count(),
            code[..code.find('q').unwrap()].chars().count(),
            "{text}"
        );
    }

    #[test]
    fn one_of_lists() {
        assert_eq!(one_of(&["a"]), "'a'");
        assert_eq!(one_of(&["a", "b"]), "one of 'a' or 'b'");
    }
}
