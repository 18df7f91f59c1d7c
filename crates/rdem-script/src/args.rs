//! A cursor over a command's words with typed readers. Every reader's error points at the
//! word it is about (or just past the last word when one is missing) and, for keywords,
//! lists the valid ones and suggests the nearest.

use std::sync::Arc;

use crate::diagnostic::{one_of, ScriptError};
use crate::lexer::{Command, Word};
use crate::output::Warnings;

/// Where the readers' warnings go: the output's queue, and the script the command comes
/// from (for the line of the word).
#[derive(Clone)]
pub struct WarningSink {
    /// The output's warning queue ([`crate::output::Output::warnings`]).
    pub queue: Warnings,
    /// The script text the word spans point into.
    pub src: Arc<str>,
    /// The script's name when it is not the main script (an `include`d file).
    pub file: Option<String>,
}

/// Result of a command handler.
pub type CmdResult<T = ()> = Result<T, ScriptError>;

/// The words of one command and a read position (word 0 is the command name).
pub struct Args<'a> {
    cmd: &'a Command,
    words: &'a [Word],
    pos: usize,
    warnings: Option<WarningSink>,
    atoi: bool,
}

/// Levenshtein distance, for "did you mean" suggestions.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The valid word nearest to `word`, if it is close enough to be a likely typo.
pub fn nearest<'v>(word: &str, valid: &[&'v str]) -> Option<&'v str> {
    let lw = word.to_ascii_lowercase();
    valid
        .iter()
        .map(|v| (distance(&lw, &v.to_ascii_lowercase()), *v))
        .filter(|(d, v)| *d <= (v.len() / 3).max(2) && *d < v.len().max(word.len()))
        .min_by_key(|(d, _)| *d)
        .map(|(_, v)| v)
}

/// Help text for a word that is not one of `valid`: the nearest and the full list.
pub fn suggest(word: &str, valid: &[&str]) -> String {
    match nearest(word, valid) {
        Some(n) => format!("did you mean '{n}'? Valid: {}", one_of(valid)),
        None => format!("valid: {}", one_of(valid)),
    }
}

/// Help for an unknown compute/fix/dump ID: the nearest defined one, or how to define it
/// (when the only compute is the implicit `thermo_temp` and the ID is not near it, the
/// script has defined none).
pub fn id_help(what: &str, id: &str, ids: &[&str]) -> String {
    let implicit_only = what == "compute" && ids == ["thermo_temp"];
    if ids.is_empty() || (implicit_only && nearest(id, ids).is_none()) {
        format!("no {what} is defined yet; define '{id}' with '{what} {id} ...' first")
    } else {
        suggest(id, ids)
    }
}

/// Parses a number as C's `atof` would accept it in a script, but strictly: the whole word,
/// finite.
pub fn parse_f64(s: &str) -> Option<f64> {
    let v: f64 = s.parse().ok()?;
    (v.is_finite() && !s.to_ascii_lowercase().contains("inf")).then_some(v)
}

/// A number with one stray `.` after it (`0.5.`, `1e-3.`), which LIGGGHTS 3.8 reads as
/// the number before the dot (it checks the characters, then reads with `atof`).
pub fn number_with_trailing_dot(s: &str) -> Option<f64> {
    parse_f64(s.strip_suffix('.')?)
}

/// A whole number written with a decimal point and no fraction (`1.`, `12345.0`), which
/// LIGGGHTS 3.8 reads as that integer where it reads integers with `atoi`.
pub fn integer_with_point(s: &str) -> Option<u64> {
    let (int, frac) = s.split_once('.')?;
    let digits = int.strip_prefix('+').unwrap_or(int);
    (!digits.is_empty()
        && digits.bytes().all(|c| c.is_ascii_digit())
        && frac.bytes().all(|c| c == b'0'))
    .then(|| digits.parse().ok())
    .flatten()
}

/// True if `n` is prime (Miller–Rabin with the bases that decide every `u64`).
pub fn is_prime(n: u64) -> bool {
    const BASES: [u64; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    if n < 2 {
        return false;
    }
    for p in BASES {
        if n % p == 0 {
            return n == p;
        }
    }
    let mul = |a: u64, b: u64| ((a as u128 * b as u128) % n as u128) as u64;
    let pow = |mut b: u64, mut e: u64| {
        let mut r = 1;
        while e > 0 {
            if e & 1 == 1 {
                r = mul(r, b);
            }
            b = mul(b, b);
            e >>= 1;
        }
        r
    };
    let (mut d, mut s) = (n - 1, 0);
    while d % 2 == 0 {
        d /= 2;
        s += 1;
    }
    BASES.iter().all(|&a| {
        let mut x = pow(a, d);
        if x == 1 || x == n - 1 {
            return true;
        }
        (1..s).any(|_| {
            x = mul(x, x);
            x == n - 1
        })
    })
}

/// What C's `atoi` reads from the start of `s` (sign and digits), if it starts so.
fn atoi_prefix(s: &str) -> Option<i64> {
    let body = s.strip_prefix(['+', '-']).unwrap_or(s);
    let n = body.bytes().take_while(|c| c.is_ascii_digit()).count();
    let v: i64 = body[..n].parse().ok()?;
    Some(if s.starts_with('-') { -v } else { v })
}

/// C's `atof` on `s`: the number at the start of `s` (`1./6.` gives 1), `None` when
/// `s` does not start with one.
pub fn atof_prefix(s: &str) -> Option<f64> {
    let b = s.as_bytes();
    let mut k = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let digits = |k: &mut usize| {
        let start = *k;
        while b.get(*k).is_some_and(u8::is_ascii_digit) {
            *k += 1;
        }
        *k - start
    };
    let mut n = digits(&mut k);
    if b.get(k) == Some(&b'.') {
        k += 1;
        n += digits(&mut k);
    }
    if n == 0 {
        return None;
    }
    let mantissa = k;
    if matches!(b.get(k), Some(b'e' | b'E')) {
        let mut e = k + 1 + usize::from(matches!(b.get(k + 1), Some(b'+' | b'-')));
        if digits(&mut e) > 0 {
            k = e;
        }
    }
    s[..k].parse().ok().or_else(|| s[..mantissa].parse().ok())
}

impl<'a> Args<'a> {
    /// A cursor after the command name.
    pub fn new(cmd: &'a Command, words: &'a [Word]) -> Self {
        Self {
            cmd,
            words,
            pos: 1,
            warnings: None,
            atoi: false,
        }
    }

    /// Sends the readers' warnings (numbers read as LIGGGHTS reads them) to `sink`;
    /// without a sink they are dropped.
    pub fn warn_into(mut self, sink: WarningSink) -> Self {
        self.warnings = Some(sink);
        self
    }

    /// Queues a warning about word `k`, prefixed with its line (and file if included).
    pub fn warn_at(&self, k: usize, message: &str) {
        let (Some(sink), Some(w)) = (&self.warnings, self.words.get(k)) else {
            return;
        };
        let at = w.span.start.min(sink.src.len());
        let line = 1 + sink.src.as_bytes()[..at]
            .iter()
            .filter(|&&c| c == b'\n')
            .count();
        let place = match &sink.file {
            Some(f) => format!("{f} line {line}"),
            None => format!("line {line}"),
        };
        if let Ok(mut q) = sink.queue.lock() {
            q.push(format!("{place}: {message}"));
        }
    }

    /// Reads this command's integers as LIGGGHTS does where it uses C's `atoi` (`1.`
    /// read as 1, with a warning): set by the commands and styles whose registry rows say
    /// so (`run`, `reset_timestep`, [`crate::fixes::FixStyle::atoi`]).
    pub fn read_integers_with_atoi(&mut self) {
        self.atoi = true;
    }

    /// True where LIGGGHTS reads this command's integers with C's `atoi`.
    fn reads_integers_with_atoi(&self) -> bool {
        self.atoi
    }

    /// Word `k` as a finite number; a number with a stray trailing `.` is read as
    /// LIGGGHTS reads it (`0.5.` is 0.5), with a warning.
    pub fn f64_at(&self, k: usize) -> Option<f64> {
        let w = &self.words.get(k)?.text;
        parse_f64(w).or_else(|| {
            let v = number_with_trailing_dot(w)?;
            self.warn_at(k, &format!("'{w}' read as {v} (LIGGGHTS reads it so)"));
            Some(v)
        })
    }

    /// The command (for spans).
    pub fn command(&self) -> &'a Command {
        self.cmd
    }

    /// All words.
    pub fn words(&self) -> &'a [Word] {
        self.words
    }

    /// The command name.
    pub fn name(&self) -> &'a str {
        &self.words[0].text
    }

    /// Index of the next word.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// Moves the cursor to word `pos`.
    pub fn seek(&mut self, pos: usize) {
        self.pos = pos.min(self.words.len());
    }

    /// Words left.
    pub fn remaining(&self) -> usize {
        self.words.len() - self.pos
    }

    /// True if no words are left.
    pub fn is_done(&self) -> bool {
        self.pos >= self.words.len()
    }

    /// The next word without consuming it.
    pub fn peek(&self) -> Option<&'a str> {
        self.words.get(self.pos).map(|w| w.text.as_str())
    }

    /// An error at word `k`.
    pub fn error_at(
        &self,
        k: usize,
        message: impl Into<String>,
        help: Option<String>,
    ) -> ScriptError {
        let span = match self.words.get(k) {
            Some(w) => w.span.clone(),
            None => {
                let end = self.words.last().map(|w| w.span.end).unwrap_or(0);
                end..end + 1
            }
        };
        ScriptError {
            message: message.into(),
            span,
            help,
            file: None,
            code: None,
        }
    }

    /// An error at the word just read.
    pub fn error_prev(&self, message: impl Into<String>, help: Option<String>) -> ScriptError {
        self.error_at(self.pos.saturating_sub(1), message, help)
    }

    /// An error at the whole command name.
    pub fn error_cmd(&self, message: impl Into<String>, help: Option<String>) -> ScriptError {
        self.error_at(0, message, help)
    }

    /// The command name with its style once the style has been read (`fix wall/gran`,
    /// `region block`, `compute reduce`), for "missing ..." messages.
    pub fn context(&self) -> String {
        let style_at = match self.name() {
            "fix" | "compute" | "dump" => 3,
            "region" => 2,
            "pair_style" => 1,
            _ => 0,
        };
        match self.words.get(style_at) {
            Some(w) if style_at > 0 && self.pos > style_at => format!("{} {}", self.name(), w.text),
            _ => self.name().to_string(),
        }
    }

    /// The next word, or an error "missing `what`".
    pub fn word(&mut self, what: &str) -> CmdResult<&'a str> {
        match self.words.get(self.pos) {
            Some(w) => {
                self.pos += 1;
                Ok(&w.text)
            }
            None => Err(self.error_at(
                self.pos,
                format!("{}: missing {what}", self.context()),
                None,
            )),
        }
    }

    /// The next word as a finite number.
    pub fn f64(&mut self, what: &str) -> CmdResult<f64> {
        let w = self.word(what)?;
        self.f64_at(self.pos - 1)
            .ok_or_else(|| self.error_prev(format!("{what} must be a number, not '{w}'"), None))
    }

    /// The next word as a number > 0.
    pub fn positive(&mut self, what: &str) -> CmdResult<f64> {
        let v = self.f64(what)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.error_prev(format!("{what} must be > 0, got {v}"), None))
        }
    }

    /// The next word as a number >= 0.
    pub fn non_negative(&mut self, what: &str) -> CmdResult<f64> {
        let v = self.f64(what)?;
        if v >= 0.0 {
            Ok(v)
        } else {
            Err(self.error_prev(format!("{what} must be >= 0, got {v}"), None))
        }
    }

    /// The next word as a non-negative integer.
    pub fn u64(&mut self, what: &str) -> CmdResult<u64> {
        let w = self.word(what)?;
        if let Ok(v) = w.parse::<u64>() {
            return Ok(v);
        }
        let atoi = self.reads_integers_with_atoi();
        if let Some(v) = integer_with_point(w).filter(|_| atoi) {
            self.warn_at(
                self.pos - 1,
                &format!("'{w}' read as the integer {v} (LIGGGHTS reads it so)"),
            );
            return Ok(v);
        }
        // LIGGGHTS would cut `1.5` to 1 and `1e4` to 1 here: rdem asks for the number.
        let help = atoi_prefix(w)
            .filter(|_| atoi)
            .map(|v| format!("LIGGGHTS would read '{w}' as {v}; write the whole number you mean"));
        Err(self.error_prev(
            format!("{what} must be a non-negative integer, not '{w}'"),
            help,
        ))
    }

    /// `text` (word `k` or a part of it, as either side of `a:b`) as a non-negative
    /// integer; where this command reads integers with `atoi`, `1.` is 1, with a warning.
    pub fn integer_in(&self, k: usize, text: &str) -> Option<u64> {
        if let Ok(v) = text.parse::<u64>() {
            return Some(v);
        }
        let v = integer_with_point(text).filter(|_| self.reads_integers_with_atoi())?;
        self.warn_at(
            k,
            &format!("'{text}' read as the integer {v} (LIGGGHTS reads it so)"),
        );
        Some(v)
    }

    /// The next word as an integer >= 1.
    pub fn count(&mut self, what: &str) -> CmdResult<u64> {
        let v = self.u64(what)?;
        if v == 0 {
            return Err(self.error_prev(format!("{what} must be >= 1"), None));
        }
        Ok(v)
    }

    /// The next word as a random seed (an integer >= 1). LIGGGHTS 3.8 refuses a seed of
    /// the insertion fixes, `particletemplate/*` and `particledistribution/*` that is not a
    /// prime > 10000 ("It is required that the random seed value is > 10000 and a prime
    /// number", checked with seed 12345 in each); rdem takes any, with a warning naming
    /// the line.
    pub fn seed(&mut self) -> CmdResult<u64> {
        let v = self.u64("seed")?;
        if v == 0 {
            return Err(self.error_prev(
                "seed must be a positive integer, not 0",
                Some("LIGGGHTS 3.8 asks for a prime > 10000, e.g. 32452843".into()),
            ));
        }
        if v <= 10000 || !is_prime(v) {
            self.warn_at(
                self.pos - 1,
                &format!("seed {v} is not a prime > 10000: LIGGGHTS 3.8 refuses it, rdem takes it"),
            );
        }
        Ok(v)
    }

    /// The next word, which must be one of `valid`.
    pub fn keyword(&mut self, what: &str, valid: &[&'static str]) -> CmdResult<&'static str> {
        let w = match self.words.get(self.pos) {
            Some(w) => &w.text,
            None => {
                return Err(self.error_at(
                    self.pos,
                    format!("{}: missing {what}", self.context()),
                    Some(format!("expected {}", one_of(valid))),
                ))
            }
        };
        self.pos += 1;
        valid.iter().copied().find(|v| v == w).ok_or_else(|| {
            self.error_prev(format!("unknown {what} '{w}'"), Some(suggest(w, valid)))
        })
    }

    /// One of the names of `table` (name, value); gives its value. The error lists the
    /// names, as [`Args::keyword`].
    pub fn choice<K: Copy>(&mut self, what: &str, table: &[(&'static str, K)]) -> CmdResult<K> {
        let names = names(table);
        let w = self.keyword(what, &names)?;
        Ok(table
            .iter()
            .find(|(n, _)| *n == w)
            .expect("a name of the table")
            .1)
    }

    /// `yes`/`no` (also `on`/`off`).
    pub fn yes_no(&mut self, what: &str) -> CmdResult<bool> {
        Ok(matches!(
            self.keyword(what, &["yes", "no", "on", "off"])?,
            "yes" | "on"
        ))
    }

    /// Three numbers.
    pub fn vec3(&mut self, what: &str) -> CmdResult<glam::DVec3> {
        Ok(glam::DVec3::new(
            self.f64(&format!("{what} x"))?,
            self.f64(&format!("{what} y"))?,
            self.f64(&format!("{what} z"))?,
        ))
    }

    /// A value word that may also be `NULL` or a `v_name` variable reference, as `accept`
    /// says; anything else must be a number ("`what` must be a number, not 'zero'", with
    /// the forms accepted in the help line).
    pub fn num_or_var(&mut self, what: &str, accept: Accept) -> CmdResult<NumOrVar> {
        let (null, var, forms) = match accept {
            Accept::Null => (true, false, "a number or NULL"),
            Accept::Var => (false, true, "a number or v_name"),
            Accept::NullOrVar => (true, true, "a number, NULL or v_name"),
        };
        match self.peek() {
            Some("NULL") if null => {
                self.pos += 1;
                Ok(NumOrVar::Null)
            }
            Some(w) if var && w.len() > 2 && w.starts_with("v_") => {
                self.pos += 1;
                Ok(NumOrVar::Var(w[2..].to_string()))
            }
            _ => {
                let w = self.word(what)?;
                self.f64_at(self.pos - 1).map(NumOrVar::Num).ok_or_else(|| {
                    self.error_prev(
                        format!("{what} must be a number, not '{w}'"),
                        Some(format!("give {forms}")),
                    )
                })
            }
        }
    }

    /// Errors if words are left.
    pub fn done(&self) -> CmdResult {
        if self.pos < self.words.len() {
            return Err(self.error_at(
                self.pos,
                format!(
                    "{}: unexpected extra argument '{}'",
                    self.context(),
                    self.words[self.pos].text
                ),
                None,
            ));
        }
        Ok(())
    }
}

/// The forms a value word may take besides a number ([`Args::num_or_var`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Accept {
    /// A number or `NULL`.
    Null,
    /// A number or `v_name`.
    Var,
    /// A number, `NULL` or `v_name`.
    NullOrVar,
}

/// A value word read by [`Args::num_or_var`].
#[derive(Clone, Debug, PartialEq)]
pub enum NumOrVar {
    /// A number.
    Num(f64),
    /// `NULL`: the component is left alone.
    Null,
    /// `v_name`: the variable `name`, evaluated when the value is used.
    Var(String),
}

impl NumOrVar {
    /// The number, `None` for `NULL` or a variable.
    pub fn num(&self) -> Option<f64> {
        match self {
            Self::Num(v) => Some(*v),
            _ => None,
        }
    }

    /// The variable's name, if this is one.
    pub fn var(&self) -> Option<&str> {
        match self {
            Self::Var(name) => Some(name),
            _ => None,
        }
    }
}

/// The names of a (name, value) table, in its order.
pub fn names<K>(table: &[(&'static str, K)]) -> Vec<&'static str> {
    table.iter().map(|(n, _)| *n).collect()
}

#[cfg(test)]
mod tests {
    use super::atof_prefix;

    /// C's atof: LIGGGHTS 3.8 read `1./6.` and `5./6.` as 1 and 5 (its printed mass
    /// shares 16.67 % and 83.33 % after normalizing).
    #[test]
    fn atof_reads_the_leading_number() {
        assert_eq!(atof_prefix("1./6."), Some(1.0));
        assert_eq!(atof_prefix("5./6."), Some(5.0));
        assert_eq!(atof_prefix("-2.5e3x"), Some(-2500.0));
        assert_eq!(atof_prefix("3e"), Some(3.0));
        assert_eq!(atof_prefix(".5/2"), Some(0.5));
        assert_eq!(atof_prefix("x1"), None);
        assert_eq!(atof_prefix("."), None);
    }

    use super::*;

    #[test]
    fn suggestions_pick_the_nearest() {
        assert_eq!(
            nearest("tangental", &["tangential", "model"]),
            Some("tangential")
        );
        assert_eq!(nearest("xyz", &["tangential", "model"]), None);
        assert_eq!(nearest("Hertz", &["hertz", "hooke"]), Some("hertz"));
    }

    #[test]
    fn numbers_as_liggghts_reads_them() {
        assert_eq!(number_with_trailing_dot("0.5."), Some(0.5));
        assert_eq!(number_with_trailing_dot("1e-3."), Some(1e-3));
        assert_eq!(number_with_trailing_dot("0.4.5"), None);
        assert_eq!(number_with_trailing_dot("1e-5x"), None);
        assert_eq!(number_with_trailing_dot("0.5"), None);
        assert_eq!(integer_with_point("1."), Some(1));
        assert_eq!(integer_with_point("12345.00"), Some(12345));
        assert_eq!(integer_with_point("1.5"), None);
        assert_eq!(integer_with_point(".0"), None);
        assert_eq!(integer_with_point("-1."), None);
        assert_eq!(atoi_prefix("1.5"), Some(1));
        assert_eq!(atoi_prefix("1e4"), Some(1));
        assert_eq!(atoi_prefix("-7x"), Some(-7));
        assert_eq!(atoi_prefix("x7"), None);
    }

    #[test]
    fn primes() {
        let slow = |n: u64| n >= 2 && (2..n).take_while(|d| d * d <= n).all(|d| n % d != 0);
        for n in 0..20_000 {
            assert_eq!(is_prime(n), slow(n), "{n}");
        }
        for n in [15485863, 32452843, 32452867, 86028121, 18446744073709551557] {
            assert!(is_prime(n), "{n}");
        }
        for n in [12345, 15485865, 3215031751, 18446744073709551555] {
            assert!(!is_prime(n), "{n}");
        }
    }

    #[test]
    fn numbers_like_atof_but_strict() {
        assert_eq!(parse_f64("5.e6"), Some(5e6));
        assert_eq!(parse_f64("+0.05"), Some(0.05));
        assert_eq!(parse_f64(".5"), Some(0.5));
        assert_eq!(parse_f64("inf"), None);
        assert_eq!(parse_f64("nan"), None);
        assert_eq!(parse_f64("1.0x"), None);
    }
}
