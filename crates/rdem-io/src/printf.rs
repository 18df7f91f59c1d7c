//! The subset of C `printf` that `dump_modify format` strings use: `%d %i %g %G %e %E %f
//! %F %s` (and `%u`, treated as `%d`) with the flags `- + space 0 #`, a width and a
//! precision, and `%%`. Length modifiers (`l`, `ll`, `h`, `L`, ...) are accepted and
//! ignored, since a value is converted to what the conversion asks for anyway.
//!
//! Hand-written because no formatting crate in reach reproduces C's output exactly (the
//! `%g` choice between fixed and exponent notation, trailing-zero removal, the two-digit
//! exponent `e+05`, `-0`, `inf`/`nan`), and LIGGGHTS users post-process dump files with
//! tools that expect it. Rounding uses Rust's exact decimal expansion, which rounds ties
//! to even on the exact binary value, as glibc does.
//!
//! Unlike C, a mismatched conversion is not undefined behaviour: an integer printed with
//! a float conversion is converted to `f64`, a float printed with `%d` is truncated toward
//! zero (saturating), and `%s` prints the value as `%g` (floats) or `%d` (integers) would.

use std::fmt::Write as _;

/// A value to format.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// An integer quantity (id, type, image flag).
    Int(i64),
    /// A floating-point quantity.
    Float(f64),
}

impl Value {
    fn as_f64(self) -> f64 {
        match self {
            Value::Int(i) => i as f64,
            Value::Float(f) => f,
        }
    }
    fn as_i64(self) -> i64 {
        match self {
            Value::Int(i) => i,
            // `as` truncates toward zero and saturates; NaN becomes 0.
            Value::Float(f) => f as i64,
        }
    }
}

/// A format string that could not be understood.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid format '{format}' at character {}: {message}", pos + 1)]
pub struct FormatError {
    /// The whole format string.
    pub format: String,
    /// 0-based byte offset of the problem.
    pub pos: usize,
    /// What is wrong.
    pub message: String,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Conv {
    Int,
    Fixed,
    Exp,
    General,
    Str,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Flags {
    left: bool,
    plus: bool,
    space: bool,
    zero: bool,
    alt: bool,
}

#[derive(Debug, Clone, PartialEq, Eq)]
struct Spec {
    flags: Flags,
    width: usize,
    precision: Option<usize>,
    conv: Conv,
    upper: bool,
}

/// A parsed format with at most one conversion, and literal text around it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Printf {
    source: String,
    prefix: String,
    spec: Option<Spec>,
    suffix: String,
}

impl Printf {
    /// `%d`, LAMMPS' default for integer columns.
    pub fn default_int() -> Self {
        Self::parse("%d").expect("valid")
    }
    /// `%g`, LAMMPS' default for float columns.
    pub fn default_float() -> Self {
        Self::parse("%g").expect("valid")
    }

    /// Parses a format with zero or one conversion.
    pub fn parse(format: &str) -> Result<Self, FormatError> {
        let err = |pos: usize, message: &str| FormatError {
            format: format.to_string(),
            pos,
            message: message.to_string(),
        };
        let bytes = format.as_bytes();
        let mut prefix = String::new();
        let mut suffix = String::new();
        let mut spec = None;
        let mut i = 0;
        let mut lit_start = 0;
        while i < bytes.len() {
            if bytes[i] != b'%' {
                i += 1;
                continue;
            }
            let start = i;
            let target = if spec.is_none() {
                &mut prefix
            } else {
                &mut suffix
            };
            target.push_str(&format[lit_start..start]);
            i += 1;
            if bytes.get(i) == Some(&b'%') {
                target.push('%');
                i += 1;
                lit_start = i;
                continue;
            }
            if spec.is_some() {
                return Err(err(start, "only one conversion per column is allowed"));
            }
            let mut flags = Flags::default();
            while let Some(&c) = bytes.get(i) {
                match c {
                    b'-' => flags.left = true,
                    b'+' => flags.plus = true,
                    b' ' => flags.space = true,
                    b'0' => flags.zero = true,
                    b'#' => flags.alt = true,
                    _ => break,
                }
                i += 1;
            }
            let digits = |i: &mut usize| -> Option<usize> {
                let s = *i;
                while bytes.get(*i).is_some_and(u8::is_ascii_digit) {
                    *i += 1;
                }
                (s < *i).then(|| format[s..*i].parse().unwrap_or(usize::MAX))
            };
            if bytes.get(i) == Some(&b'*') {
                return Err(err(i, "'*' width or precision is not supported"));
            }
            let width = digits(&mut i).unwrap_or(0);
            let mut precision = None;
            if bytes.get(i) == Some(&b'.') {
                i += 1;
                if bytes.get(i) == Some(&b'*') {
                    return Err(err(i, "'*' width or precision is not supported"));
                }
                precision = Some(digits(&mut i).unwrap_or(0));
            }
            if width > 1000 || precision.is_some_and(|p| p > 1000) {
                return Err(err(start, "width and precision must be at most 1000"));
            }
            while let Some(&c) = bytes.get(i) {
                if matches!(c, b'l' | b'h' | b'L' | b'q' | b'j' | b'z' | b't') {
                    i += 1;
                } else {
                    break;
                }
            }
            let Some(&c) = bytes.get(i) else {
                return Err(err(start, "incomplete conversion"));
            };
            let (conv, upper) = match c {
                b'd' | b'i' | b'u' => (Conv::Int, false),
                b'f' => (Conv::Fixed, false),
                b'F' => (Conv::Fixed, true),
                b'e' => (Conv::Exp, false),
                b'E' => (Conv::Exp, true),
                b'g' => (Conv::General, false),
                b'G' => (Conv::General, true),
                b's' => (Conv::Str, false),
                _ => {
                    let ch = format[i..].chars().next().unwrap_or('?');
                    return Err(err(
                        i,
                        &format!("unsupported conversion '%{ch}' (use %d %i %g %e %f %s)"),
                    ));
                }
            };
            i += 1;
            lit_start = i;
            spec = Some(Spec {
                flags,
                width,
                precision,
                conv,
                upper,
            });
        }
        if spec.is_none() {
            prefix.push_str(&format[lit_start..]);
        } else {
            suffix.push_str(&format[lit_start..]);
        }
        Ok(Self {
            source: format.to_string(),
            prefix,
            spec,
            suffix,
        })
    }

    /// The format as written.
    pub fn as_str(&self) -> &str {
        &self.source
    }

    /// Appends `value` formatted to `out`.
    pub fn write(&self, out: &mut String, value: Value) {
        out.push_str(&self.prefix);
        if let Some(spec) = &self.spec {
            format_one(out, spec, value);
        }
        out.push_str(&self.suffix);
    }

    /// `value` formatted.
    pub fn format(&self, value: Value) -> String {
        let mut s = String::new();
        self.write(&mut s, value);
        s
    }
}

fn sign_of(negative: bool, flags: Flags) -> &'static str {
    if negative {
        "-"
    } else if flags.plus {
        "+"
    } else if flags.space {
        " "
    } else {
        ""
    }
}

/// Pads `sign + body` to the width: left-justified, zero-padded after the sign, or
/// right-justified with spaces.
fn pad(out: &mut String, sign: &str, body: &str, width: usize, left: bool, zero: bool) {
    let len = sign.len() + body.len();
    let fill = width.saturating_sub(len);
    if left {
        out.push_str(sign);
        out.push_str(body);
        out.extend(std::iter::repeat_n(' ', fill));
    } else if zero {
        out.push_str(sign);
        out.extend(std::iter::repeat_n('0', fill));
        out.push_str(body);
    } else {
        out.extend(std::iter::repeat_n(' ', fill));
        out.push_str(sign);
        out.push_str(body);
    }
}

fn format_one(out: &mut String, spec: &Spec, value: Value) {
    let f = spec.flags;
    match spec.conv {
        Conv::Int => {
            let v = value.as_i64();
            let mut body = v.unsigned_abs().to_string();
            if let Some(p) = spec.precision {
                if p == 0 && v == 0 {
                    body.clear();
                } else if body.len() < p {
                    body = "0".repeat(p - body.len()) + &body;
                }
            }
            let zero = f.zero && !f.left && spec.precision.is_none();
            pad(out, sign_of(v < 0, f), &body, spec.width, f.left, zero);
        }
        Conv::Str => {
            let s = match value {
                Value::Int(i) => i.to_string(),
                Value::Float(x) => Printf::default_float().format(Value::Float(x)),
            };
            let s = match spec.precision {
                Some(p) => s.chars().take(p).collect(),
                None => s,
            };
            pad(out, "", &s, spec.width, f.left, false);
        }
        Conv::Fixed | Conv::Exp | Conv::General => {
            let x = value.as_f64();
            let sign = sign_of(x.is_sign_negative(), f);
            if !x.is_finite() {
                let body = match (x.is_nan(), spec.upper) {
                    (true, false) => "nan",
                    (true, true) => "NAN",
                    (false, false) => "inf",
                    (false, true) => "INF",
                };
                pad(out, sign, body, spec.width, f.left, false);
                return;
            }
            let a = x.abs();
            let prec = spec.precision.unwrap_or(6);
            let mut body = match spec.conv {
                Conv::Fixed => fixed(a, prec, f.alt),
                Conv::Exp => exp(a, prec, f.alt),
                _ => general(a, prec, f.alt),
            };
            if spec.upper {
                body.make_ascii_uppercase();
            }
            pad(out, sign, &body, spec.width, f.left, f.zero && !f.left);
        }
    }
}

/// `%.{prec}f` of a non-negative finite value.
fn fixed(a: f64, prec: usize, alt: bool) -> String {
    let mut s = format!("{a:.prec$}");
    if alt && prec == 0 {
        s.push('.');
    }
    s
}

/// Mantissa digits and decimal exponent of `a` rounded to `prec` digits after the point.
fn exp_parts(a: f64, prec: usize) -> (String, i32) {
    let s = format!("{a:.prec$e}");
    let (m, e) = s.split_once('e').expect("exponent");
    (m.to_string(), e.parse().expect("exponent"))
}

fn exp_string(mut mantissa: String, e: i32, alt: bool) -> String {
    if alt && !mantissa.contains('.') {
        mantissa.push('.');
    }
    let _ = write!(
        mantissa,
        "e{}{:02}",
        if e < 0 { '-' } else { '+' },
        e.unsigned_abs()
    );
    mantissa
}

/// `%.{prec}e` of a non-negative finite value.
fn exp(a: f64, prec: usize, alt: bool) -> String {
    let (m, e) = exp_parts(a, prec);
    exp_string(m, e, alt)
}

fn strip_zeros(s: &mut String) {
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
}

/// `%.{prec}g` of a non-negative finite value.
fn general(a: f64, prec: usize, alt: bool) -> String {
    let p = prec.max(1);
    let (m, x) = if a == 0.0 {
        (String::new(), 0)
    } else {
        exp_parts(a, p - 1)
    };
    if x >= -4 && (x as i64) < p as i64 {
        let mut s = format!("{a:.*}", (p as i64 - 1 - x as i64) as usize);
        if alt {
            if !s.contains('.') {
                s.push('.');
            }
        } else {
            strip_zeros(&mut s);
        }
        s
    } else {
        let mut m = m;
        if !alt {
            strip_zeros(&mut m);
        }
        exp_string(m, x, alt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(fmt: &str, v: f64) -> String {
        Printf::parse(fmt).unwrap().format(Value::Float(v))
    }
    fn d(fmt: &str, v: i64) -> String {
        Printf::parse(fmt).unwrap().format(Value::Int(v))
    }

    /// Expected strings produced by glibc's printf (see `printf_fixture.c` in
    /// tests/data for the program that printed them).
    const GLIBC: &[(&str, f64, &str)] = &[
        ("%g", 0.0, "0"),
        ("%g", -0.0, "-0"),
        ("%g", 1.0, "1"),
        ("%g", 0.1, "0.1"),
        ("%g", 1.308996938995747, "1.309"),
        ("%g", 2.352424579, "2.35242"),
        ("%g", 100000.0, "100000"),
        ("%g", 1000000.0, "1e+06"),
        ("%g", 999999.5, "1e+06"),
        ("%g", 0.0001, "0.0001"),
        ("%g", 0.00001, "1e-05"),
        ("%g", 0.000123456789, "0.000123457"),
        ("%g", -12.841259972, "-12.8413"),
        ("%g", 1.5e300, "1.5e+300"),
        ("%g", 5e-324, "4.94066e-324"),
        ("%g", 123456789.0, "1.23457e+08"),
        ("%.11g", -12.84125997234, "-12.841259972"),
        ("%.11g", 1.308996938995747, "1.308996939"),
        ("%.11g", 0.01308996939, "0.01308996939"),
        ("%.0g", 0.5, "0.5"),
        ("%.0g", 2.5, "2"),
        ("%#g", 1.0, "1.00000"),
        ("%#.3g", 100.0, "100."),
        ("%G", 1e-10, "1E-10"),
        ("%e", 0.0, "0.000000e+00"),
        ("%e", 123.456, "1.234560e+02"),
        ("%.3e", 0.125, "1.250e-01"),
        ("%12.4e", 0.21, "  2.1000e-01"),
        ("%-12.4e|", -0.21, "-2.1000e-01 |"),
        ("%E", 1e100, "1.000000E+100"),
        ("%.0e", 12345.0, "1e+04"),
        ("%#.0e", 12345.0, "1.e+04"),
        ("%f", 0.1, "0.100000"),
        ("%.2f", 0.125, "0.12"),
        ("%.2f", 0.375, "0.38"),
        ("%.0f", 0.5, "0"),
        ("%.0f", 1.5, "2"),
        ("%.0f", 2.5, "2"),
        ("%#.0f", 3.0, "3."),
        ("%10.3f", 0.09, "     0.090"),
        ("%010.3f", -0.09, "-00000.090"),
        ("%+.3f", 0.09, "+0.090"),
        ("% .3f", 0.09, " 0.090"),
        ("%+g", -0.0, "-0"),
        ("%f", 1e20, "100000000000000000000.000000"),
        ("%8.3lf", 2.0, "   2.000"),
        ("%g", f64::INFINITY, "inf"),
        ("%g", f64::NEG_INFINITY, "-inf"),
        ("%08.2f", f64::INFINITY, "     inf"),
        ("%E", f64::NAN, "NAN"),
        ("x=%g;", 2.0, "x=2;"),
        ("%g%%", 50.0, "50%"),
    ];

    #[test]
    fn floats_match_glibc() {
        for &(fmt, v, want) in GLIBC {
            assert_eq!(f(fmt, v), want, "format {fmt} of {v:e}");
        }
    }

    #[test]
    fn integers_match_glibc() {
        let cases: &[(&str, i64, &str)] = &[
            ("%d", 0, "0"),
            ("%d", -42, "-42"),
            ("%i", 7, "7"),
            ("%5d", 3, "    3"),
            ("%-5d|", 3, "3    |"),
            ("%05d", -3, "-0003"),
            ("%+d", 0, "+0"),
            ("% d", 5, " 5"),
            ("%.3d", 7, "007"),
            ("%08.3d", 7, "     007"),
            ("%.0d", 0, ""),
            ("%ld", 9_007_199_254_740_993, "9007199254740993"),
            ("%d", i64::MIN, "-9223372036854775808"),
            ("%s", 12, "12"),
            ("%4s|", 12, "  12|"),
        ];
        for &(fmt, v, want) in cases {
            assert_eq!(d(fmt, v), want, "format {fmt} of {v}");
        }
    }

    #[test]
    fn mismatched_conversions_convert() {
        assert_eq!(d("%g", 3), "3");
        assert_eq!(d("%.2f", -3), "-3.00");
        assert_eq!(f("%d", 2.9), "2");
        assert_eq!(f("%d", -2.9), "-2");
        assert_eq!(f("%d", f64::NAN), "0");
        assert_eq!(f("%s", 0.1), "0.1");
        assert_eq!(f("%.2s", 0.125), "0.");
        // No conversion: the literal text only.
        assert_eq!(f("abc", 1.0), "abc");
    }

    #[test]
    fn bad_formats_are_rejected_with_position() {
        let e = Printf::parse("%d%d").unwrap_err();
        assert_eq!(e.pos, 2);
        let e = Printf::parse("ab%y").unwrap_err();
        assert_eq!(e.pos, 3);
        assert!(e.message.contains("%y"), "{}", e.message);
        let e = Printf::parse("%*d").unwrap_err();
        assert_eq!(e.pos, 1);
        assert!(Printf::parse("%5.").is_err());
        assert!(Printf::parse("%99999d").is_err());
        assert!(e.to_string().contains("'%*d'"));
        assert_eq!(Printf::parse("%%").unwrap().format(Value::Int(1)), "%");
        assert_eq!(Printf::parse("%10.4e").unwrap().as_str(), "%10.4e");
    }
}
