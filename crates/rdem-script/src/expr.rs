//! Equal-style variable formulas (LIGGGHTS `variable` doc page): numbers, the operators
//! `- ! ^ * / % + - < <= > >= == != && ||` with LIGGGHTS' precedence (unary minus and `!`
//! above `^`, so `-2^2` is 4; equal precedence evaluates left to right), parentheses, the
//! math functions, and names the caller resolves: thermo keywords (`step`, `xlo`, …),
//! references `v_name`, `c_ID`, `c_ID[i]`, `f_ID`, `f_ID[i]`, atom values `x[i]`, and
//! other functions (group functions such as `count(all)`, `random(…)`).
//!
//! Parsing gives an [`Expr`]; errors carry a byte range inside the formula so the caller
//! can point at the offending part of the script line.

use crate::error::Error;
use std::ops::Range;

/// A parse or evaluation error, with the byte range in the formula it is about.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct ExprError {
    /// What is wrong.
    pub message: String,
    /// Byte range in the formula.
    pub span: Range<usize>,
}

fn err<T>(message: impl Into<String>, span: Range<usize>) -> Result<T, ExprError> {
    Err(ExprError {
        message: message.into(),
        span,
    })
}

/// Binary operators, loosest first within the precedence table of [`precedence`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `||`
    Or,
    /// `&&`
    And,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `%`
    Mod,
    /// `^`
    Pow,
}

/// Binding strength of a binary operator (higher binds tighter).
fn precedence(op: BinOp) -> u8 {
    match op {
        BinOp::Or => 1,
        BinOp::And => 2,
        BinOp::Eq | BinOp::Ne => 3,
        BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => 4,
        BinOp::Add | BinOp::Sub => 5,
        BinOp::Mul | BinOp::Div | BinOp::Mod => 6,
        BinOp::Pow => 7,
    }
}

/// What a name refers to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Name {
    /// A thermo keyword or other bare word (`step`, `atoms`, `xlo`).
    Keyword(String),
    /// `v_name`.
    Variable(String),
    /// `v_name[i]`: atom `i`'s value (by atom ID) of an atom-style variable.
    VariableAt(String, u64),
    /// `c_ID` or `c_ID[i]`.
    Compute(String, Option<usize>),
    /// `f_ID` or `f_ID[i]`.
    Fix(String, Option<usize>),
    /// `c_ID[I][J]`: column `J` of the per-atom array of a compute, at atom ID `I`.
    ComputeAt(String, u64, usize),
    /// `f_ID[I][J]`: column `J` of the per-atom array of a fix, at atom ID `I`.
    FixAt(String, u64, usize),
    /// An atom value `x[i]`, `vx[i]`, `mass[i]`, … (the index is the atom ID).
    Atom(String, u64),
}

/// A parsed formula.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A number.
    Num(f64),
    /// A name resolved by the [`Context`]; the range is its place in the formula.
    Name(Name, Range<usize>),
    /// `-x`.
    Neg(Box<Expr>),
    /// `!x`.
    Not(Box<Expr>),
    /// `x op y`; the range is the operator's place.
    Bin(BinOp, Box<Expr>, Box<Expr>, Range<usize>),
    /// A function call; arguments are kept both parsed (when they parse) and as raw text
    /// (group IDs and dimensions such as `xcm(all,x)` are words, not formulas).
    Call {
        /// Function name.
        name: String,
        /// Raw argument texts.
        raw: Vec<String>,
        /// Parsed arguments (`None` where an argument is not a formula).
        args: Vec<Option<Expr>>,
        /// Place of the call in the formula.
        span: Range<usize>,
    },
}

/// What a formula needs from the simulation.
pub trait Context {
    /// Value of a name, or an error message (e.g. "unknown thermo keyword").
    fn name(&mut self, name: &Name) -> Result<f64, Error>;
    /// A function that is not plain math (group, region and special functions, random,
    /// ramp, …): `Ok(None)` if the name is not one.
    fn function(&mut self, name: &str, raw_args: &[String]) -> Result<Option<f64>, Error>;
}

/// Parses `src` as a formula.
pub fn parse(src: &str) -> Result<Expr, ExprError> {
    let mut p = Parser { s: src, i: 0 };
    let e = p.expr(0)?;
    p.skip_ws();
    if p.i < src.len() {
        return err(
            format!("unexpected '{}' in formula", &src[p.i..]),
            p.i..src.len(),
        );
    }
    Ok(e)
}

struct Parser<'a> {
    s: &'a str,
    i: usize,
}

impl Parser<'_> {
    fn skip_ws(&mut self) {
        while self.s[self.i..].starts_with([' ', '\t']) {
            self.i += 1;
        }
    }

    fn peek_op(&mut self) -> Option<(BinOp, usize)> {
        self.skip_ws();
        let r = &self.s[self.i..];
        let two = [
            ("||", BinOp::Or),
            ("&&", BinOp::And),
            ("==", BinOp::Eq),
            ("!=", BinOp::Ne),
            ("<=", BinOp::Le),
            (">=", BinOp::Ge),
        ];
        for (t, op) in two {
            if r.starts_with(t) {
                return Some((op, 2));
            }
        }
        let op = match r.chars().next()? {
            '<' => BinOp::Lt,
            '>' => BinOp::Gt,
            '+' => BinOp::Add,
            '-' => BinOp::Sub,
            '*' => BinOp::Mul,
            '/' => BinOp::Div,
            '%' => BinOp::Mod,
            '^' => BinOp::Pow,
            _ => return None,
        };
        Some((op, 1))
    }

    /// Precedence climbing; all binary operators are left-associative, as in LIGGGHTS.
    fn expr(&mut self, min: u8) -> Result<Expr, ExprError> {
        let mut lhs = self.unary()?;
        while let Some((op, len)) = self.peek_op() {
            let p = precedence(op);
            if p <= min {
                break;
            }
            let at = self.i..self.i + len;
            self.i += len;
            let rhs = self.expr(p)?;
            lhs = Expr::Bin(op, Box::new(lhs), Box::new(rhs), at);
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<Expr, ExprError> {
        self.skip_ws();
        let r = &self.s[self.i..];
        if r.starts_with('-') {
            self.i += 1;
            return Ok(Expr::Neg(Box::new(self.unary()?)));
        }
        if r.starts_with('!') && !r.starts_with("!=") {
            self.i += 1;
            return Ok(Expr::Not(Box::new(self.unary()?)));
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<Expr, ExprError> {
        self.skip_ws();
        let start = self.i;
        let r = &self.s[start..];
        let Some(c) = r.chars().next() else {
            return err("formula ends where a value was expected", start..start);
        };
        if c == '(' {
            self.i += 1;
            let e = self.expr(0)?;
            self.skip_ws();
            if !self.s[self.i..].starts_with(')') {
                return err("'(' without a matching ')'", start..start + 1);
            }
            self.i += 1;
            return Ok(e);
        }
        if c.is_ascii_digit() || c == '.' {
            return self.number();
        }
        if c.is_ascii_alphabetic() || c == '_' {
            let end = start
                + r.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(r.len());
            let word = &self.s[start..end];
            self.i = end;
            if self.s[end..].starts_with('(') {
                return self.call(word, start);
            }
            let index = self.bracket()?;
            let second = match index {
                Some(_) if word.starts_with("c_") || word.starts_with("f_") => self.bracket()?,
                _ => None,
            };
            let span = start..self.i;
            let name = if let (Some(i), Some(j)) = (index, second) {
                let j = j as usize;
                match word.split_at(2) {
                    ("c_", id) => Name::ComputeAt(id.to_string(), i, j),
                    (_, id) => Name::FixAt(id.to_string(), i, j),
                }
            } else if let Some(rest) = word.strip_prefix("v_") {
                match index {
                    Some(k) => Name::VariableAt(rest.to_string(), k),
                    None => Name::Variable(rest.to_string()),
                }
            } else if let Some(rest) = word.strip_prefix("c_") {
                Name::Compute(rest.to_string(), index.map(|k| k as usize))
            } else if let Some(rest) = word.strip_prefix("f_") {
                Name::Fix(rest.to_string(), index.map(|k| k as usize))
            } else if let Some(k) = index {
                Name::Atom(word.to_string(), k)
            } else {
                Name::Keyword(word.to_string())
            };
            return Ok(Expr::Name(name, span));
        }
        err(
            format!("unexpected '{c}' in formula"),
            start..start + c.len_utf8(),
        )
    }

    /// An index `[k]` at the cursor (a non-negative integer), if one is there.
    fn bracket(&mut self) -> Result<Option<u64>, ExprError> {
        let at = self.i;
        if !self.s[at..].starts_with('[') {
            return Ok(None);
        }
        let close = match self.s[at..].find(']') {
            Some(k) => at + k,
            None => return err("'[' without a matching ']'", at..at + 1),
        };
        let text = self.s[at + 1..close].trim();
        let Ok(k) = text.parse::<u64>() else {
            return err(
                format!("index '{text}' must be a positive integer"),
                at..close + 1,
            );
        };
        self.i = close + 1;
        Ok(Some(k))
    }

    fn number(&mut self) -> Result<Expr, ExprError> {
        let start = self.i;
        let b = self.s.as_bytes();
        let mut i = start;
        while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
            i += 1;
        }
        if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
            let mut k = i + 1;
            if k < b.len() && (b[k] == b'+' || b[k] == b'-') {
                k += 1;
            }
            if k < b.len() && b[k].is_ascii_digit() {
                while k < b.len() && b[k].is_ascii_digit() {
                    k += 1;
                }
                i = k;
            }
        }
        self.i = i;
        match self.s[start..i].parse::<f64>() {
            Ok(v) => Ok(Expr::Num(v)),
            Err(_) => err(format!("'{}' is not a number", &self.s[start..i]), start..i),
        }
    }

    fn call(&mut self, name: &str, start: usize) -> Result<Expr, ExprError> {
        // Split the arguments at top-level commas.
        let open = self.i;
        let mut depth = 0usize;
        let mut pieces = Vec::new();
        let mut piece_start = open + 1;
        let mut close = None;
        for (k, c) in self.s[open..].char_indices() {
            let at = open + k;
            match c {
                '(' => depth += 1,
                ')' => {
                    depth -= 1;
                    if depth == 0 {
                        pieces.push(piece_start..at);
                        close = Some(at);
                        break;
                    }
                }
                ',' if depth == 1 => {
                    pieces.push(piece_start..at);
                    piece_start = at + 1;
                }
                _ => {}
            }
        }
        let Some(close) = close else {
            return err(format!("'{name}(' without a matching ')'"), start..open + 1);
        };
        self.i = close + 1;
        let raw: Vec<String> = pieces
            .iter()
            .map(|r| self.s[r.clone()].trim().to_string())
            .collect();
        let args = pieces
            .iter()
            .map(|r| parse(&self.s[r.clone()]).ok())
            .collect();
        Ok(Expr::Call {
            name: name.to_string(),
            raw,
            args,
            span: start..self.i,
        })
    }
}

fn truth(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// `x op y`; the message where LIGGGHTS stops (a division by 0, 0 to a negative power).
pub fn binary(op: BinOp, x: f64, y: f64) -> Result<f64, &'static str> {
    Ok(match op {
        BinOp::Or => truth(x != 0.0 || y != 0.0),
        BinOp::And => truth(x != 0.0 && y != 0.0),
        BinOp::Eq => truth(x == y),
        BinOp::Ne => truth(x != y),
        BinOp::Lt => truth(x < y),
        BinOp::Le => truth(x <= y),
        BinOp::Gt => truth(x > y),
        BinOp::Ge => truth(x >= y),
        BinOp::Add => x + y,
        BinOp::Sub => x - y,
        BinOp::Mul => x * y,
        BinOp::Div | BinOp::Mod if y == 0.0 => return Err("divide by 0 in formula"),
        BinOp::Div => x / y,
        BinOp::Mod => x % y,
        BinOp::Pow if x == 0.0 && y < 0.0 => return Err("0 raised to a negative power in formula"),
        BinOp::Pow => x.powf(y),
    })
}

/// Evaluates `e` with `ctx` resolving names and non-math functions.
pub fn eval(e: &Expr, ctx: &mut dyn Context) -> Result<f64, ExprError> {
    Ok(match e {
        Expr::Num(v) => *v,
        Expr::Name(Name::Keyword(k), _) if k == "PI" => std::f64::consts::PI,
        Expr::Name(n, span) => ctx.name(n).or_else(|m| err(m, span.clone()))?,
        Expr::Neg(x) => -eval(x, ctx)?,
        Expr::Not(x) => truth(eval(x, ctx)? == 0.0),
        Expr::Bin(op, a, b, span) => {
            let (x, y) = (eval(a, ctx)?, eval(b, ctx)?);
            binary(*op, x, y).or_else(|m| err(m, span.clone()))?
        }
        Expr::Call {
            name,
            raw,
            args,
            span,
        } => {
            let span = span.clone();
            let math = |k: usize| -> Option<&Expr> { args.get(k).and_then(|a| a.as_ref()) };
            let arity = match name.as_str() {
                "sqrt" | "exp" | "ln" | "log" | "abs" | "sin" | "cos" | "tan" | "asin" | "acos"
                | "atan" | "ceil" | "floor" | "round" => Some(1),
                "atan2" => Some(2),
                _ => None,
            };
            match arity {
                Some(n) => {
                    if args.len() != n {
                        return err(
                            format!("{name}() takes {n} argument(s), got {}", args.len()),
                            span,
                        );
                    }
                    let mut v = [0.0; 2];
                    for (k, slot) in v.iter_mut().enumerate().take(n) {
                        match math(k) {
                            Some(a) => *slot = eval(a, ctx)?,
                            None => {
                                return err(
                                    format!("argument '{}' of {name}() is not a formula", raw[k]),
                                    span,
                                )
                            }
                        }
                    }
                    let x = v[0];
                    match name.as_str() {
                        "sqrt" if x < 0.0 => {
                            return err("sqrt of a negative value in formula", span)
                        }
                        "ln" | "log" if x <= 0.0 => {
                            return err(format!("{name} of a value <= 0 in formula"), span)
                        }
                        "asin" | "acos" if !(-1.0..=1.0).contains(&x) => {
                            return err(
                                format!("{name} of a value outside [-1, 1] in formula"),
                                span,
                            )
                        }
                        _ => {}
                    }
                    match name.as_str() {
                        "sqrt" => x.sqrt(),
                        "exp" => x.exp(),
                        "ln" => x.ln(),
                        "log" => x.log10(),
                        "abs" => x.abs(),
                        "sin" => x.sin(),
                        "cos" => x.cos(),
                        "tan" => x.tan(),
                        "asin" => x.asin(),
                        "acos" => x.acos(),
                        "atan" => x.atan(),
                        "ceil" => x.ceil(),
                        "floor" => x.floor(),
                        "round" => x.round(),
                        _ => x.atan2(v[1]),
                    }
                }
                None => match ctx.function(name, raw).or_else(|m| err(m, span.clone()))? {
                    Some(v) => v,
                    None => {
                        const KNOWN: [&str; 22] = [
                            "sqrt", "exp", "ln", "log", "abs", "sin", "cos", "tan", "asin", "acos",
                            "atan", "atan2", "ceil", "floor", "round", "count", "mass", "xcm",
                            "vcm", "bound", "ke", "random",
                        ];
                        let hint = crate::args::nearest(name, &KNOWN)
                            .map(|n| format!(" (did you mean '{n}'?)"))
                            .unwrap_or_default();
                        return err(format!("unknown function '{name}' in formula{hint}"), span);
                    }
                },
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Ctx;
    impl Context for Ctx {
        fn name(&mut self, n: &Name) -> Result<f64, Error> {
            match n {
                Name::Keyword(k) if k == "step" => Ok(100.0),
                Name::Variable(v) if v == "r" => Ok(0.5),
                Name::Compute(c, Some(2)) if c == "bc" => Ok(7.0),
                Name::Atom(a, 3) if a == "x" => Ok(-1.25),
                other => Err(format!("unknown {other:?}").into()),
            }
        }
        fn function(&mut self, name: &str, raw: &[String]) -> Result<Option<f64>, Error> {
            Ok(match (name, raw) {
                ("count", [g]) if g == "all" => Some(42.0),
                ("xcm", [g, d]) if g == "all" && d == "z" => Some(0.125),
                _ => None,
            })
        }
    }

    fn ev(s: &str) -> f64 {
        eval(&parse(s).unwrap(), &mut Ctx).unwrap()
    }

    /// The first four were checked on LIGGGHTS 3.8 (`variable a equal -2^2` etc. and
    /// `print`): it prints 4, 64, 3 for `7%4`, and 1 for `round(2.5)+floor(-1.5)`.
    #[test]
    fn precedence_as_liggghts() {
        assert_eq!(ev("round(2.5)+floor(-1.5)"), 1.0);
        assert_eq!(ev("-2^2"), 4.0); // unary minus binds tighter than ^
        assert_eq!(ev("-(2^2)"), -4.0);
        assert_eq!(ev("2^3^2"), 64.0); // left to right
        assert_eq!(ev("1+2*3"), 7.0);
        assert_eq!(ev("10-4-3"), 3.0);
        assert_eq!(ev("8/2/2"), 2.0);
        assert_eq!(ev("7%4"), 3.0);
        assert_eq!(ev("1 < 2 == 1"), 1.0);
        assert_eq!(ev("0 || 1 && 0"), 0.0);
        assert_eq!(ev("!0 + !3"), 1.0);
        assert_eq!(ev("2 != 3"), 1.0);
        assert_eq!(ev("1.5e-3*2e3"), 3.0);
        assert_eq!(ev("PI"), std::f64::consts::PI);
    }

    #[test]
    fn functions_and_names() {
        assert!((ev("sqrt(2)^2") - 2.0).abs() < 1e-15);
        assert!((ev("atan2(1,1)") - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert_eq!(ev("log(1000)"), 3.0);
        assert_eq!(ev("floor(-1.5)+ceil(1.2)+round(2.5)+abs(-1)"), 4.0); // -2 + 2 + 3 + 1
        assert_eq!(ev("step*v_r + c_bc[2] + x[3]"), 55.75);
        assert_eq!(ev("count(all) + xcm(all,z)*8"), 43.0);
        assert_eq!(ev("(xcm(all,z) > 0.1) * 5"), 5.0);
    }

    #[test]
    fn errors_point_into_the_formula() {
        let e = parse("1 + (2 * 3").unwrap_err();
        assert_eq!(e.span, 4..5);
        let e = parse("1 + * 2").unwrap_err();
        assert_eq!(e.span, 4..5);
        let e = parse("2 3").unwrap_err();
        assert_eq!(e.span, 2..3);
        let e = eval(&parse("1 + v_nope").unwrap(), &mut Ctx).unwrap_err();
        assert_eq!(e.span, 4..10);
        let e = eval(&parse("1/(2-2)").unwrap(), &mut Ctx).unwrap_err();
        assert!(e.message.contains("divide by 0"));
        for bad in [
            "sqrt(-1)",
            "ln(0)",
            "asin(2)",
            "frobnicate(1)",
            "sqrt(1,2)",
            "0^-1",
        ] {
            assert!(eval(&parse(bad).unwrap(), &mut Ctx).is_err(), "{bad}");
        }
    }
}
