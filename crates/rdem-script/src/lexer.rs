//! The LIGGGHTS parsing rules (manual section 3.2), in three stages that keep every
//! character's place in the source file, so an error can point at the word it is about:
//!
//! 1. [`commands`]: a script becomes commands. A line whose last printable character is
//!    `&` continues on the next line, which takes the place of the `&` (as LIGGGHTS joins
//!    them: `a&` + `b` is `ab`, also inside quotes); everything from the first unquoted
//!    `#` on is a comment; blank commands are dropped.
//! 2. [`substitute`]: `$x`, `${name}` and `$(expression)` outside quotes are replaced by
//!    the text the caller's variable table gives; the replacement text points back at the
//!    `$…` it came from.
//! 3. [`words`]: the command is split into words at white space; single, double or
//!    triple (`"""`) quotes make one word of text with spaces and are removed.

use crate::error::Error;
use std::ops::Range;

use crate::diagnostic::ScriptError;

/// A command's text with, for every byte, the byte offset in the source file it came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Command {
    /// The command text (continuations joined, comment removed).
    pub text: String,
    /// Source offset of each byte of `text`.
    pub origin: Vec<usize>,
    /// 1-based line of the command's first character.
    pub line: usize,
}

/// One word of a command, quotes removed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Word {
    /// The word's text.
    pub text: String,
    /// Byte range in the source file (quotes included).
    pub span: Range<usize>,
}

/// Quote state while scanning: none, one of `'` `"`, or a triple `"""`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Quote {
    None,
    Single,
    Double,
    Triple,
}

/// Steps the quote state at byte `i` of `s`; returns how many bytes the quote mark
/// itself takes (0 if `s[i]` is not a quote mark that changes the state).
fn quote_step(s: &[u8], i: usize, q: &mut Quote) -> usize {
    let triple = s[i..].starts_with(b"\"\"\"");
    match (*q, s[i]) {
        (Quote::None, b'"') if triple => {
            *q = Quote::Triple;
            3
        }
        (Quote::None, b'"') => {
            *q = Quote::Double;
            1
        }
        (Quote::None, b'\'') => {
            *q = Quote::Single;
            1
        }
        (Quote::Triple, b'"') if triple => {
            *q = Quote::None;
            3
        }
        (Quote::Double, b'"') | (Quote::Single, b'\'') => {
            *q = Quote::None;
            1
        }
        _ => 0,
    }
}

/// Stage 1: splits `src` into commands (see the module doc).
pub fn commands(src: &str) -> Vec<Command> {
    let mut out = Vec::new();
    let mut cur = Command {
        text: String::new(),
        origin: Vec::new(),
        line: 1,
    };
    let mut line_no = 0;
    let mut offset = 0;
    // A line whose comment ends in '&' continues into the next line, which is then part
    // of the comment (LIGGGHTS joins lines before it cuts comments: checked on 3.8).
    let mut in_comment = false;
    for raw in src.split_inclusive('\n') {
        line_no += 1;
        let line = raw.trim_end_matches(['\n', '\r']);
        if cur.text.is_empty() && !in_comment {
            cur.line = line_no;
        }
        if in_comment {
            in_comment = line.trim_end().ends_with('&');
            if !in_comment {
                finish(&mut out, &mut cur, line_no);
            }
            offset += raw.len();
            continue;
        }
        // Cut the comment: the first '#' outside quotes (quotes may span continuations).
        let b = line.as_bytes();
        let mut q = cur_quote(&cur.text);
        let mut end = b.len();
        let mut i = 0;
        while i < b.len() {
            let n = quote_step(b, i, &mut q);
            if n > 0 {
                i += n;
                continue;
            }
            if q == Quote::None && b[i] == b'#' {
                end = i;
                break;
            }
            i += 1;
        }
        let kept = &line[..end];
        let trimmed = kept.trim_end();
        // As LIGGGHTS reads lines: a final '&' continues the command even inside quotes.
        let continues = end == b.len() && trimmed.ends_with('&');
        let body = if continues {
            &trimmed[..trimmed.len() - 1]
        } else {
            kept
        };
        cur.text.push_str(body);
        cur.origin.extend((0..body.len()).map(|k| offset + k));
        in_comment = end < b.len() && line.trim_end().ends_with('&');
        if !continues && !in_comment {
            finish(&mut out, &mut cur, line_no);
        }
        offset += raw.len();
    }
    if !cur.text.trim().is_empty() {
        out.push(cur);
    }
    out
}

/// Ends the command being read after line `line_no`: kept if it has text.
fn finish(out: &mut Vec<Command>, cur: &mut Command, line_no: usize) {
    if !cur.text.trim().is_empty() {
        out.push(std::mem::replace(
            cur,
            Command {
                text: String::new(),
                origin: Vec::new(),
                line: line_no + 1,
            },
        ));
    } else {
        cur.text.clear();
        cur.origin.clear();
    }
}

/// The quote state at the end of `text` (for a command continued across lines).
fn cur_quote(text: &str) -> Quote {
    let b = text.as_bytes();
    let mut q = Quote::None;
    let mut i = 0;
    while i < b.len() {
        let n = quote_step(b, i, &mut q);
        i += n.max(1);
    }
    q
}

/// Index in `cmd.text` of the first byte outside quotes (quote marks excluded) whose
/// source offset satisfies `pred`.
pub fn first_unquoted(cmd: &Command, pred: impl Fn(usize) -> bool) -> Option<usize> {
    let b = cmd.text.as_bytes();
    let mut q = Quote::None;
    let mut i = 0;
    while i < b.len() {
        let n = quote_step(b, i, &mut q);
        if n > 0 {
            i += n;
            continue;
        }
        if q == Quote::None && pred(cmd.origin[i]) {
            return Some(i);
        }
        i += 1;
    }
    None
}

/// What a `$` refers to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reference {
    /// `$x` or `${name}`: a variable by name.
    Variable(String),
    /// `$(expression)`: an immediate equal-style expression.
    Immediate(String),
}

/// Stage 2: replaces every `$` reference outside quotes with `resolve(reference)`. The
/// error of `resolve` is reported at the reference's source span.
pub fn substitute(
    cmd: &Command,
    mut resolve: impl FnMut(&Reference) -> Result<String, Error>,
) -> Result<Command, ScriptError> {
    let b = cmd.text.as_bytes();
    let mut text = String::with_capacity(cmd.text.len());
    let mut origin = Vec::with_capacity(cmd.origin.len());
    let mut q = Quote::None;
    let mut i = 0;
    while i < b.len() {
        let n = quote_step(b, i, &mut q);
        if n > 0 {
            text.push_str(&cmd.text[i..i + n]);
            origin.extend_from_slice(&cmd.origin[i..i + n]);
            i += n;
            continue;
        }
        if q != Quote::None || b[i] != b'$' {
            let c = cmd.text[i..].chars().next().unwrap_or(' ');
            let len = c.len_utf8();
            text.push_str(&cmd.text[i..i + len]);
            origin.extend_from_slice(&cmd.origin[i..i + len]);
            i += len;
            continue;
        }
        let (reference, end) = parse_reference(&cmd.text, i)
            .map_err(|msg| cmd.error(i..(i + 2).min(b.len()), msg.to_string(), None))?;
        let value = resolve(&reference).map_err(|msg| cmd.error(i..end, msg.to_string(), None))?;
        text.push_str(&value);
        origin.extend(std::iter::repeat_n(cmd.origin[i], value.len()));
        i = end;
    }
    Ok(Command {
        text,
        origin,
        line: cmd.line,
    })
}

/// Parses the reference starting at the `$` at byte `i`; returns it and the byte after it.
fn parse_reference(s: &str, i: usize) -> Result<(Reference, usize), Error> {
    let rest = &s[i + 1..];
    match rest.chars().next() {
        Some('{') => match rest.find('}') {
            Some(e) => Ok((Reference::Variable(rest[1..e].to_string()), i + 1 + e + 1)),
            None => Err("'${' without a closing '}'".into()),
        },
        Some('(') => {
            let mut depth = 0usize;
            for (k, c) in rest.char_indices() {
                match c {
                    '(' => depth += 1,
                    ')' => {
                        depth -= 1;
                        if depth == 0 {
                            return Ok((
                                Reference::Immediate(rest[1..k].to_string()),
                                i + 1 + k + 1,
                            ));
                        }
                    }
                    _ => {}
                }
            }
            Err("'$(' without a closing ')'".into())
        }
        Some(c) if !c.is_whitespace() => {
            Ok((Reference::Variable(c.to_string()), i + 1 + c.len_utf8()))
        }
        _ => Err("'$' must be followed by a variable name, {name} or (expression)".into()),
    }
}

/// Stage 3: splits a command into words at white space outside quotes, removing the
/// quotes. An unterminated quote is an error at the opening quote.
pub fn words(cmd: &Command) -> Result<Vec<Word>, ScriptError> {
    Ok(split_words(cmd)?.into_iter().map(|(w, _)| w).collect())
}

/// Like [`words`], but each word as a command of its own whose bytes keep their source
/// offsets (quotes removed), for text that is substituted again when it runs (`print`,
/// `if`).
pub fn word_commands(cmd: &Command) -> Result<Vec<Command>, ScriptError> {
    Ok(split_words(cmd)?
        .into_iter()
        .map(|(w, origin)| Command {
            text: w.text,
            origin,
            line: cmd.line,
        })
        .collect())
}

/// The words and, for every byte of each word's text, its source offset.
fn split_words(cmd: &Command) -> Result<Vec<(Word, Vec<usize>)>, ScriptError> {
    let b = cmd.text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        let mut text = String::new();
        let mut origin = Vec::new();
        let mut q = Quote::None;
        let mut opened_at = 0;
        while i < b.len() && (q != Quote::None || !b[i].is_ascii_whitespace()) {
            let before = q;
            let n = quote_step(b, i, &mut q);
            if n > 0 {
                if before == Quote::None {
                    opened_at = i;
                }
                i += n;
                continue;
            }
            let c = cmd.text[i..].chars().next().unwrap_or(' ');
            text.push(c);
            origin.extend_from_slice(&cmd.origin[i..i + c.len_utf8()]);
            i += c.len_utf8();
        }
        if q != Quote::None {
            let mark = match q {
                Quote::Single => "'",
                Quote::Triple => "\"\"\"",
                _ => "\"",
            };
            return Err(cmd.error(
                opened_at..b.len(),
                "this quote is never closed".into(),
                Some(format!(
                    "close it with {mark} before the end of the command"
                )),
            ));
        }
        out.push((
            Word {
                text,
                span: span_of(cmd, start..i),
            },
            origin,
        ));
    }
    Ok(out)
}

impl Command {
    /// An error at the command's bytes `r` (the span in the source file follows the
    /// command's origin map through continuation lines).
    pub fn error(&self, r: Range<usize>, message: String, help: Option<String>) -> ScriptError {
        ScriptError::spanned(span_of(self, r), message, help)
    }
}

/// Source span of the command bytes `r`.
pub fn span_of(cmd: &Command, r: Range<usize>) -> Range<usize> {
    if cmd.origin.is_empty() {
        return 0..0;
    }
    let a = cmd.origin[r.start.min(cmd.origin.len() - 1)];
    let last = cmd.origin[(r.end.max(r.start + 1) - 1).min(cmd.origin.len() - 1)];
    a..(last + 1).max(a + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(src: &str) -> Vec<String> {
        commands(src).into_iter().map(|c| c.text).collect()
    }

    #[test]
    fn comments_continuations_and_blank_lines() {
        let src = "atom_style granular # a comment\n\n  # only a comment\nregion reg block -1 1 &\n   -1 1 0 2 units box\nprint \"a # b\" # c\n";
        assert_eq!(
            texts(src),
            vec![
                "atom_style granular ",
                "region reg block -1 1    -1 1 0 2 units box",
                "print \"a # b\" ",
            ]
        );
        let cmds = commands(src);
        assert_eq!(cmds[0].line, 1);
        assert_eq!(cmds[1].line, 4);
        assert_eq!(cmds[2].line, 6);
        // The continuation keeps the source offsets of the second line.
        let c = &cmds[1];
        let k = c.text.find("units").unwrap();
        assert_eq!(&src[c.origin[k]..c.origin[k] + 5], "units");
    }

    /// LIGGGHTS 3.8 prints `B: ab` for `print "B: a&` + `b"`, and `C: one   two # not a
    /// comment` for `print "C: one &` + `  two # not a comment"`: the next line takes the
    /// place of the '&', and a '#' inside the quotes is text.
    #[test]
    fn continuation_joins_in_place_also_inside_quotes() {
        let src = "print \"B: a&\nb\"\nprint \"C: one &\n  two # not a comment\"\n";
        assert_eq!(
            texts(src),
            vec!["print \"B: ab\"", "print \"C: one   two # not a comment\""]
        );
        let c = &commands(src)[0];
        let w = words(c).unwrap();
        assert_eq!(w[1].text, "B: ab");
        // The word runs from the quote on line 1 to the quote on line 2.
        assert_eq!(&src[w[1].span.clone()], "\"B: a&\nb\"");
    }

    #[test]
    fn a_comment_after_the_ampersand_ends_the_command() {
        assert_eq!(
            texts("fix 1 all &  # no continuation\nnve\n"),
            vec!["fix 1 all &  ", "nve"]
        );
    }

    /// LIGGGHTS 3.8 prints `a`, `c`, `e` for `print "a" # c &` / `print "b"` /
    /// `print "c" #x &` / `  more &` / `print "d"` / `print "e"`: a comment that ends in
    /// '&' takes the next line into the comment.
    #[test]
    fn a_comment_ending_in_an_ampersand_swallows_the_next_line() {
        let src = "print \"a\" # c &\nprint \"b\"\nprint \"c\" #x &\n  more &\nprint \"d\"\nprint \"e\"\n";
        assert_eq!(
            texts(src),
            vec!["print \"a\" ", "print \"c\" ", "print \"e\""]
        );
        let lines: Vec<usize> = commands(src).iter().map(|c| c.line).collect();
        assert_eq!(lines, vec![1, 3, 6]);
        // A commented-out command continued over two lines is gone whole.
        assert_eq!(
            texts("#fix a all remove &\n  seed 1\nrun 1\n"),
            vec!["run 1"]
        );
    }

    #[test]
    fn words_remove_quotes_and_keep_spans() {
        let src = "print 'x  y' \"a\"b \"\"\"it's \"q\" here\"\"\" end";
        let c = &commands(src)[0];
        let w = words(c).unwrap();
        let t: Vec<&str> = w.iter().map(|w| w.text.as_str()).collect();
        assert_eq!(t, vec!["print", "x  y", "ab", "it's \"q\" here", "end"]);
        assert_eq!(&src[w[1].span.clone()], "'x  y'");
        assert_eq!(&src[w[4].span.clone()], "end");
    }

    #[test]
    fn unterminated_quote_is_an_error_at_the_quote() {
        let src = "print \"abc";
        let c = &commands(src)[0];
        let e = words(c).unwrap_err();
        assert_eq!(e.span(), 6..10);
    }

    #[test]
    fn substitution_outside_quotes_only() {
        let src = "region r block ${lo} $x $(2*3) 'v$x'\n";
        let c = &commands(src)[0];
        let s = substitute(c, |r| match r {
            Reference::Variable(n) if n == "lo" => Ok("-1.5".into()),
            Reference::Variable(n) if n == "x" => Ok("7".into()),
            Reference::Immediate(e) => Ok(format!("<{e}>")),
            Reference::Variable(n) => Err(format!("no variable {n}").into()),
        })
        .unwrap();
        assert_eq!(s.text, "region r block -1.5 7 <2*3> 'v$x'");
        let w = words(&s).unwrap();
        // The substituted word points at its reference in the source.
        assert_eq!(&src[w[3].span.clone()], "$");
        assert_eq!(w[6].text, "v$x");
        let bad = substitute(c, |_| Err("no such variable".into())).unwrap_err();
        assert_eq!(&src[bad.span()], "${lo}");
    }

    #[test]
    fn bad_references_are_errors() {
        for src in ["print ${x", "print $(1+2", "print $ x"] {
            let c = &commands(src)[0];
            assert!(substitute(c, |_| Ok(String::new())).is_err(), "{src}");
        }
    }
}
