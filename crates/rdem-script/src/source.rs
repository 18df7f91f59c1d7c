//! Script files as LIGGGHTS reads them: bytes, not UTF-8. LIGGGHTS 3.8 reads a script in
//! any encoding (it prints a Latin-1 `µ` inside a quoted `print` string back byte for
//! byte); rdem keeps valid UTF-8 as it is and reads every byte that is not part of valid
//! UTF-8 as the Latin-1 character of the same value (0xB5 is `µ`), so that comments and
//! quoted text in Latin-1, CP1252 or another 8-bit encoding are read. Outside comments
//! and quotes such a byte is an error at its line and column: command words, keywords,
//! numbers and variable names are ASCII or UTF-8.
//!
//! Line ends: CRLF is read as LF (also before a `&` continuation), and so is a CR that
//! ends the last line.

use std::sync::Arc;

use crate::diagnostic::{ScriptError, ScriptReport};
use crate::lexer::{self, Command};

/// A script decoded to text, with the places of the bytes that were not UTF-8.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Source {
    /// The text (CRLF read as LF; each non-UTF-8 byte as its Latin-1 character).
    pub text: String,
    /// Byte offsets in `text` of the characters that were non-UTF-8 bytes, ascending.
    pub foreign: Vec<usize>,
}

/// Decodes script bytes (see the module doc).
pub fn decode(bytes: &[u8]) -> Source {
    // CRLF and a final lone CR read as LF.
    let mut b = Vec::with_capacity(bytes.len());
    for (i, &c) in bytes.iter().enumerate() {
        if c == b'\r' && (bytes.get(i + 1) == Some(&b'\n') || i + 1 == bytes.len()) {
            continue;
        }
        b.push(c);
    }
    let mut text = String::with_capacity(b.len());
    let mut foreign = Vec::new();
    for chunk in b.utf8_chunks() {
        text.push_str(chunk.valid());
        for &c in chunk.invalid() {
            foreign.push(text.len());
            text.push(char::from(c));
        }
    }
    Source { text, foreign }
}

/// Help for a non-UTF-8 byte outside comments and quotes.
pub const FOREIGN_HELP: &str = "only comments and quoted text may use other encodings than UTF-8 (Latin-1, CP1252, ...); write commands, keywords, numbers and names in ASCII or UTF-8";

/// The first non-UTF-8 byte of `src` outside comments and quotes, as an error at it.
pub fn check(src: &Source, cmds: &[Command]) -> Result<(), ScriptError> {
    if src.foreign.is_empty() {
        return Ok(());
    }
    for cmd in cmds {
        let hit = lexer::first_unquoted(cmd, |o| src.foreign.binary_search(&o).is_ok());
        if let Some(i) = hit {
            let c = cmd.text[i..].chars().next().unwrap_or(' ');
            return Err(cmd.error(
                i..i + c.len_utf8(),
                format!("non-UTF-8 byte 0x{:02X} in a command word", c as u32),
                Some(FOREIGN_HELP.into()),
            ));
        }
    }
    Ok(())
}

/// A script file ready to run: its name, text and commands; or the report of a non-UTF-8
/// byte outside comments and quotes, located in it.
pub fn load(name: &str, bytes: &[u8]) -> Result<(Arc<str>, Vec<Command>), Box<ScriptReport>> {
    let src = decode(bytes);
    let cmds = lexer::commands(&src.text);
    let text: Arc<str> = src.text.as_str().into();
    match check(&src, &cmds) {
        Ok(()) => Ok((text, cmds)),
        Err(e) => Err(Box::new(e.in_file(name, text))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_bytes_read_as_latin1_and_are_remembered() {
        let s = decode(b"# 5 \xb5m\nprint \"\xe9t\xe9 \xc2\xb5\"\n");
        assert_eq!(s.text, "# 5 µm\nprint \"été µ\"\n");
        // The two 0xE9 and the 0xB5, not the UTF-8 µ (C2 B5).
        assert_eq!(s.foreign, vec![4, 15, 18]);
        let cmds = lexer::commands(&s.text);
        assert_eq!(check(&s, &cmds), Ok(()));
    }

    #[test]
    fn crlf_and_a_final_cr_read_as_lf() {
        assert_eq!(decode(b"a\r\nb &\r\n c\r").text, "a\nb &\n c");
        // A CR inside a line stays (it is white space between words).
        assert_eq!(decode(b"a\rb\n").text, "a\rb\n");
    }

    #[test]
    fn a_foreign_byte_in_a_word_is_an_error_at_it() {
        let s = decode(b"# \xb5\nfix 1 all \"\xb5\" gr\xb5v\n");
        let cmds = lexer::commands(&s.text);
        let e = check(&s, &cmds).unwrap_err();
        assert_eq!(e.message, "non-UTF-8 byte 0xB5 in a command word");
        assert_eq!(&s.text[e.span()], "µ");
        assert_eq!(e.span().start, s.text.find("gr").unwrap() + 2);
    }
}
