//! Script errors that point at the offending word: a byte span in the source file, a
//! message and the valid alternatives. [`ScriptError::in_file`] attaches the file so that
//! `miette` renders the line with a caret under the word.

use std::ops::Range;
use std::sync::Arc;

use miette::{Diagnostic, NamedSource, SourceSpan};

use crate::lexer::{span_of, Command};

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
}

impl ScriptError {
    /// An error at the bytes `r` of command `cmd`.
    pub fn at(cmd: &Command, r: Range<usize>, message: String, help: Option<String>) -> Self {
        Self {
            message,
            span: span_of(cmd, r),
            help,
        }
    }

    /// The source span.
    pub fn span(&self) -> Range<usize> {
        self.span.clone()
    }

    /// Attaches the script's name and text for rendering.
    pub fn in_file(self, name: &str, source: Arc<str>) -> ScriptReport {
        let len = source.len();
        let start = self.span.start.min(len);
        let end = self.span.end.clamp(start, len);
        ScriptReport {
            message: self.message,
            help: self.help,
            src: Some(NamedSource::new(name, source)),
            span: Some((start, end - start).into()),
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
        }
    }
}

/// A [`ScriptError`] with its file, ready to render (`miette::Report::new(report)`).
#[derive(Debug, thiserror::Error, Diagnostic)]
#[error("{message}")]
pub struct ScriptReport {
    message: String,
    #[help]
    help: Option<String>,
    #[source_code]
    src: Option<NamedSource<Arc<str>>>,
    #[label("here")]
    span: Option<SourceSpan>,
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
