//! The parser error suite: every fixture in `tests/data/errors/*.in` is a small script
//! whose last command is wrong. Its header comments give the expected report:
//!
//! ```text
//! # expect-line: 7
//! # expect-col: 12
//! # expect-message: unknown fix style 'gravty'
//! # expect-help: did you mean 'gravity'
//! # expect-file: tests/data/errors/included/x.inc   (optional: the error is in another file)
//! ```
//!
//! Each fixture runs through the [`Interpreter`] as `in.<file stem>`; it must stop with an
//! error (never run through, never panic) whose rendered report names `file:line:col`,
//! carries the message and the help, and puts the caret under column `col` of the line.
//! All failures are reported together. `RDEM_SHOW_ERRORS=1` prints every rendered report.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use crate::common;
use common::render;

const DIR: &str = "tests/data/errors";

#[derive(Debug, Default)]
struct Expect {
    line: usize,
    col: usize,
    message: String,
    help: Option<String>,
    file: Option<String>,
}

fn header(src: &str) -> Result<Expect, String> {
    let mut e = Expect::default();
    let (mut line, mut col) = (None, None);
    for l in src.lines().take_while(|l| l.starts_with('#')) {
        let Some((key, value)) = l.trim_start_matches('#').trim().split_once(':') else {
            continue;
        };
        let value = value.trim().to_string();
        match key.trim() {
            "expect-line" => line = value.parse().ok(),
            "expect-col" => col = value.parse().ok(),
            "expect-message" => e.message = value,
            "expect-help" => e.help = Some(value),
            "expect-file" => e.file = Some(value),
            _ => {}
        }
    }
    e.line = line.ok_or("header has no valid '# expect-line: N'")?;
    e.col = col.ok_or("header has no valid '# expect-col: N'")?;
    if e.message.is_empty() {
        return Err("header has no '# expect-message: ...'".into());
    }
    Ok(e)
}

/// Column (1-based) of the caret under source line `line`, read off the rendering: the
/// underline row follows the source row, and both share the gutter width.
fn caret_column(text: &str, line: usize) -> Option<usize> {
    let rows: Vec<&str> = text.lines().collect();
    let prefix = format!("{line} │");
    let k = rows
        .iter()
        .position(|r| r.trim_start().starts_with(&prefix))?;
    let code: Vec<char> = rows[k].chars().collect();
    let under: Vec<char> = rows.get(k + 1)?.chars().collect();
    let gutter = code.iter().position(|&c| c == '│')?;
    if under.get(gutter) != Some(&'·') {
        return None;
    }
    let first = under
        .iter()
        .skip(gutter + 1)
        .position(|&c| c == '─' || c == '┬')?;
    // The code starts two characters after the gutter bar ("│ "), so `first` (counted
    // from the character after the bar) is the 1-based column.
    Some(first)
}

fn check(path: &Path) -> Result<String, String> {
    let src = std::fs::read_to_string(path).map_err(|e| format!("cannot read: {e}"))?;
    let want = header(&src)?;
    let stem = path.file_stem().unwrap().to_string_lossy();
    let name = format!("in.{stem}");
    let result = catch_unwind(AssertUnwindSafe(|| {
        let mut interp = common::interpreter();
        interp.run_source(&name, &src)
    }));
    let report = match result {
        Err(_) => return Err("PANICKED".into()),
        Ok(Ok(())) => return Err("ran to the end without an error".into()),
        Ok(Err(r)) => r,
    };
    let text = render(&report);
    let mut problems = Vec::new();
    let file = want.file.clone().unwrap_or(name);
    let loc = format!("{file}:{}:{}", want.line, want.col);
    if !text.contains(&loc) {
        problems.push(format!("expected location {loc}"));
    }
    let message = text.lines().find(|l| l.contains('×')).unwrap_or("");
    if !message.contains(&want.message) {
        problems.push(format!("expected message containing: {}", want.message));
    }
    if let Some(h) = &want.help {
        let help = text.lines().find(|l| l.trim_start().starts_with("help:"));
        if !help.is_some_and(|l| l.contains(h.as_str())) {
            problems.push(format!("expected help containing: {h}"));
        }
    }
    match caret_column(&text, want.line) {
        Some(c) if c == want.col => {}
        Some(c) => problems.push(format!("caret at column {c}, expected column {}", want.col)),
        None => problems.push(format!("no caret under line {}", want.line)),
    }
    if text.contains("panicked") {
        problems.push("the report mentions a panic".into());
    }
    if problems.is_empty() {
        Ok(text)
    } else {
        Err(format!("{}\n--- rendered ---\n{text}", problems.join("\n")))
    }
}

fn fixtures() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(DIR)
        .expect("fixture directory")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "in"))
        .collect();
    v.sort();
    v
}

#[test]
fn every_bad_form_stops_with_file_line_caret_and_help() {
    let all = fixtures();
    assert!(
        all.len() >= 60,
        "at least 60 error fixtures expected, found {}",
        all.len()
    );
    let show = std::env::var_os("RDEM_SHOW_ERRORS").is_some();
    let mut failures = Vec::new();
    for p in &all {
        match check(p) {
            Ok(text) if show => println!("===== {}\n{text}", p.display()),
            Ok(_) => {}
            Err(e) => failures.push(format!("===== {}\n{e}", p.display())),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} error fixtures failed:\n\n{}",
        failures.len(),
        all.len(),
        failures.join("\n\n")
    );
}

#[test]
fn fixture_headers_parse() {
    let h = header(
        "# expect-line: 7\n# expect-col: 12\n# expect-message: unknown fix style 'gravty'\n# expect-help: did you mean 'gravity'\nunits si\n",
    )
    .unwrap();
    assert_eq!((h.line, h.col), (7, 12));
    assert_eq!(h.message, "unknown fix style 'gravty'");
    assert_eq!(h.help.as_deref(), Some("did you mean 'gravity'"));
    assert!(header("# expect-line: 1\nunits si\n").is_err());
}

/// Every fixture's bad command cut short after each of its words, or with one word left
/// out, still gives a result or an error, never a panic.
#[test]
fn shortened_bad_commands_never_panic() {
    let mut panics = Vec::new();
    let mut runs = 0;
    for p in fixtures() {
        let src = std::fs::read_to_string(&p).unwrap();
        let want = header(&src).unwrap();
        if want.file.is_some() {
            continue;
        }
        let lines: Vec<&str> = src.lines().collect();
        let bad = lines[want.line - 1];
        let words: Vec<&str> = bad.split_whitespace().collect();
        // `jump SELF` without its label loops for ever, as in LIGGGHTS.
        if words.first() == Some(&"jump") {
            continue;
        }
        let mut variants = Vec::new();
        for k in 1..words.len() {
            variants.push(words[..k].join(" "));
            let mut dropped = words.clone();
            dropped.remove(k);
            variants.push(dropped.join(" "));
        }
        for v in variants {
            let mut text: Vec<&str> = lines.clone();
            text[want.line - 1] = &v;
            let text = text.join("\n");
            runs += 1;
            let r = catch_unwind(AssertUnwindSafe(|| {
                let mut interp = common::interpreter();
                let _ = interp.run_source("in.variant", &text);
            }));
            if r.is_err() {
                panics.push(format!("{}: '{v}'", p.display()));
            }
        }
    }
    assert!(runs > 500, "only {runs} variants ran");
    assert!(panics.is_empty(), "panics:\n{}", panics.join("\n"));
}
