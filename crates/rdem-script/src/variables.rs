//! The `variable` command's table: styles `index`, `loop`, `file`, `universe`, `uloop`,
//! `string`, `getenv`, `equal` and `atom`, the redefinition rules of the LIGGGHTS manual
//! (an existing `index`, `loop`, `file`, `universe` or `uloop` variable is not redefined,
//! so `-var` on the command line wins; `string`, `getenv`, `equal`, `atom` are), `next`,
//! `delete`, and the text a `${name}` turns into (an `equal` variable prints as C's
//! `%.15g`).
//!
//! rdem runs one partition (no `-partition`), so `universe` and `uloop` variables step
//! through their values as `index` and `loop` do; each `next` of them prints
//! `Increment via next: value K on partition 0` as LIGGGHTS 3.8 does on one partition
//! (LIGGGHTS also keeps the shared count in a file `tmp.lammps.variable`, which rdem does
//! not write).

use crate::error::Error;
use crate::expr::{self, Context};
use crate::registry::{Registry, Row};

/// One variable.
#[derive(Debug, Clone, PartialEq)]
pub enum Variable {
    /// `index a b c`: the current string, and what follows.
    Index {
        /// All values.
        values: Vec<String>,
        /// Current position.
        pos: usize,
    },
    /// `loop N [pad]` / `loop N1 N2 [pad]`: integers as strings.
    Loop {
        /// All values.
        values: Vec<String>,
        /// Current position.
        pos: usize,
    },
    /// `file FILE`: the values of the file's lines (see [`file_values`]).
    File {
        /// All values.
        values: Vec<String>,
        /// Current position.
        pos: usize,
    },
    /// `universe v1 v2 ...` or `uloop N [pad]` on one partition.
    Universe {
        /// All values.
        values: Vec<String>,
        /// Current position.
        pos: usize,
    },
    /// `string text`.
    Str(String),
    /// `getenv NAME`.
    Getenv(String),
    /// `equal formula`, evaluated when used.
    Equal(String),
    /// `atom formula`, evaluated per particle by the commands that use it.
    Atom(String),
}

/// Every style word of `variable` (their definitions are read in
/// [`Variables::define`]), then LIGGGHTS styles rdem does not take yet.
pub static STYLES: Registry<()> = Registry {
    family: "variable style",
    readme_prefix: "variable ",
    rows: &[
        Row::runs("delete", (), "removes the variable"),
        Row::runs("index", (), "`v1 v2 ...`: the next one at each `next`"),
        Row::runs("loop", (), "`N`, `N1 N2`, `pad`: counts at each `next`"),
        Row::runs("file", (), "`FILE`: the next line's first word at each `next`")
            .notes("the file is read when the variable is defined; text from `#` on and blank lines are skipped; a value keeps the spaces before its word, as LIGGGHTS 3.8; no `next()` formula function"),
        Row::runs("universe", (), "`v1 v2 ...`: the next one at each `next` (one partition)")
            .notes("rdem runs one partition: as `index`, with LIGGGHTS' `Increment via next` line; no `tmp.lammps.variable` file"),
        Row::runs("uloop", (), "`N [pad]`: counts at each `next` (one partition)")
            .notes("as `universe`"),
        Row::runs("string", (), "one string"),
        Row::runs("getenv", (), "an environment variable"),
        Row::runs("equal", (), "a formula, evaluated when used")
            .notes("LIGGGHTS' formula grammar and precedence; math functions; group functions `count mass xcm vcm bound ke`; `random(lo,hi,seed)` (LIGGGHTS' RANMAR generator: the same numbers for the same seed; atom-style: not supported yet); `x[ID]`, `vx[ID]`, ...; `v_name[ID]`, atom ID's value of an atom-style variable; `c_ID[I]` / `f_ID[I]`, atom I's value of a per-atom vector compute or fix, and `c_ID[I][J]` / `f_ID[I][J]`, column J at atom I of a per-atom array, as LAMMPS reads them"),
        Row::runs("atom", (), "a formula evaluated per particle"),
        Row::not_yet("atomfile", ""),
        Row::not_yet("world", ""),
        Row::not_yet("format", ""),
        Row::not_yet("python", ""),
    ],
};

/// What a `next` command did.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Next {
    /// A variable ran out of values: the next `jump` is skipped.
    pub exhausted: bool,
    /// The line to print (`universe` and `uloop` variables).
    pub message: Option<String>,
}

/// The values of a `file` variable's file, one per line that is not blank once the text
/// from `#` on is removed. As LIGGGHTS 3.8 reads them (checked: the lines `alpha beta #
/// c`, `  2.5e3`, `\tt1 x`, ` x#y` gave `alpha`, `  2.5e3`, `\tt1`, ` x`), a value is its
/// line up to the end of the first word: the white space before the word is kept.
pub fn file_values(text: &str) -> Vec<String> {
    text.lines()
        .filter_map(|line| {
            let line = line.split('#').next().unwrap_or("");
            let start = line.find(|c: char| !c.is_ascii_whitespace())?;
            let end = line[start..]
                .find(|c: char| c.is_ascii_whitespace())
                .map_or(line.len(), |k| start + k);
            Some(line[..end].to_string())
        })
        .collect()
}

/// A definition error: the message and which argument (0 = the style word) it is about.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DefineError {
    /// What is wrong.
    pub message: String,
    /// Index of the offending argument after the name (0 = style).
    pub arg: usize,
    /// Valid alternatives, if any.
    pub help: Option<String>,
}

fn derr<T>(message: impl Into<String>, arg: usize, help: Option<String>) -> Result<T, DefineError> {
    Err(DefineError {
        message: message.into(),
        arg,
        help,
    })
}

/// The variables of a run, in definition order.
#[derive(Debug, Clone, Default)]
pub struct Variables {
    vars: Vec<(String, Variable)>,
    /// Where each variable's definition stands (its formula or first value), for errors
    /// found while it is evaluated during a run.
    origins: Vec<(String, crate::diagnostic::Origin)>,
}

fn valid_name(n: &str) -> bool {
    !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

impl Variables {
    /// No variables.
    pub fn new() -> Self {
        Self::default()
    }

    /// The variable `name`.
    pub fn get(&self, name: &str) -> Option<&Variable> {
        self.vars.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    /// Where variable `name` was defined (its formula or first value), if known.
    pub fn origin(&self, name: &str) -> Option<&crate::diagnostic::Origin> {
        self.origins.iter().find(|(n, _)| n == name).map(|(_, o)| o)
    }

    /// Records where variable `name` was defined.
    pub fn set_origin(&mut self, name: &str, origin: Option<crate::diagnostic::Origin>) {
        self.origins.retain(|(n, _)| n != name);
        if let Some(o) = origin {
            self.origins.push((name.to_string(), o));
        }
    }

    /// Names of all variables, in definition order.
    pub fn names(&self) -> Vec<&str> {
        self.vars.iter().map(|(n, _)| n.as_str()).collect()
    }

    fn set(&mut self, name: &str, v: Variable) {
        match self.vars.iter_mut().find(|(n, _)| n == name) {
            Some(slot) => slot.1 = v,
            None => self.vars.push((name.to_string(), v)),
        }
    }

    /// `variable name style args…`. Returns false when the definition was ignored
    /// (an `index` or `loop` variable that already exists).
    pub fn define(
        &mut self,
        name: &str,
        style: &str,
        args: &[String],
    ) -> Result<bool, DefineError> {
        if !valid_name(name) {
            return Err(DefineError {
                message: format!("variable name '{name}' may only use letters, digits and '_'"),
                arg: usize::MAX,
                help: None,
            });
        }
        let exists = self.get(name).is_some();
        let one = |what: &str| -> Result<String, DefineError> {
            match args {
                [a] => Ok(a.clone()),
                [] => derr(format!("style {style} needs {what}"), 0, None),
                _ => derr(
                    format!("style {style} takes one argument ({what}); quote text with spaces"),
                    2,
                    None,
                ),
            }
        };
        let v = match style {
            "delete" => {
                if !args.is_empty() {
                    return derr("style delete takes no arguments", 1, None);
                }
                self.vars.retain(|(n, _)| n != name);
                self.origins.retain(|(n, _)| n != name);
                return Ok(true);
            }
            "index" => {
                if args.is_empty() {
                    return derr("style index needs at least one value", 0, None);
                }
                if exists {
                    return Ok(false);
                }
                Variable::Index {
                    values: args.to_vec(),
                    pos: 0,
                }
            }
            "loop" => {
                let pad = args.last().map(|a| a == "pad").unwrap_or(false);
                let nums = &args[..args.len() - pad as usize];
                let parse = |k: usize| -> Result<i64, DefineError> {
                    nums[k]
                        .parse::<i64>()
                        .or_else(|_| derr(format!("'{}' is not an integer", nums[k]), k + 1, None))
                };
                let (lo, hi) = match nums.len() {
                    1 => (1, parse(0)?),
                    2 => (parse(0)?, parse(1)?),
                    _ => {
                        return derr(
                            "style loop takes N, or N1 N2, optionally followed by pad",
                            0,
                            None,
                        )
                    }
                };
                if hi < lo || hi < 1 {
                    return derr(format!("loop from {lo} to {hi} is empty"), nums.len(), None);
                }
                if exists {
                    return Ok(false);
                }
                let width = hi.to_string().len();
                let values = (lo..=hi)
                    .map(|k| {
                        if pad {
                            format!("{k:0width$}")
                        } else {
                            k.to_string()
                        }
                    })
                    .collect();
                Variable::Loop { values, pos: 0 }
            }
            "file" => {
                let file = one("a file name")?;
                if exists {
                    return Ok(false);
                }
                let text = std::fs::read(&file).or_else(|e| {
                    derr(
                        format!("cannot open file variable file '{file}': {e}"),
                        1,
                        None,
                    )
                })?;
                let values = file_values(&String::from_utf8_lossy(&text));
                if values.is_empty() {
                    return derr(
                        format!("file variable could not read a value: '{file}' has no line that is not blank or a comment"),
                        1,
                        None,
                    );
                }
                Variable::File { values, pos: 0 }
            }
            "universe" | "uloop" => {
                let values = if style == "universe" {
                    if args.is_empty() {
                        return derr("style universe needs at least one value", 0, None);
                    }
                    args.to_vec()
                } else {
                    let pad = args.len() == 2 && args[1] == "pad";
                    if args.len() != 1 && !pad {
                        return derr("style uloop takes N, optionally followed by pad", 0, None);
                    }
                    let n: i64 = args[0]
                        .parse()
                        .or_else(|_| derr(format!("'{}' is not an integer", args[0]), 1, None))?;
                    if n < 1 {
                        return derr(format!("uloop {n} has no value (N >= 1)"), 1, None);
                    }
                    let width = n.to_string().len();
                    (1..=n)
                        .map(|k| {
                            if pad {
                                format!("{k:0width$}")
                            } else {
                                k.to_string()
                            }
                        })
                        .collect()
                };
                if exists {
                    return Ok(false);
                }
                // LIGGGHTS: "All universe/uloop variables must have same # of values".
                if let Some((other, Variable::Universe { values: v, .. })) = self
                    .vars
                    .iter()
                    .find(|(_, v)| matches!(v, Variable::Universe { .. }))
                {
                    if v.len() != values.len() {
                        return derr(
                            format!(
                                "all universe and uloop variables must have the same number of values: '{other}' has {}, this one {}",
                                v.len(),
                                values.len()
                            ),
                            1,
                            None,
                        );
                    }
                }
                Variable::Universe { values, pos: 0 }
            }
            "string" => Variable::Str(one("one string")?),
            "getenv" => Variable::Getenv(one("the name of an environment variable")?),
            "equal" => Variable::Equal(self.formula(style, args)?),
            "atom" => Variable::Atom(self.formula(style, args)?),
            _ => {
                let message = match STYLES.row(style) {
                    Some(_) => format!("variable style '{style}' is not supported by rdem yet"),
                    None => format!("unknown variable style '{style}'"),
                };
                let valid = crate::diagnostic::one_of(&STYLES.names());
                return derr(message, 0, Some(format!("use {valid}")));
            }
        };
        self.set(name, v);
        Ok(true)
    }

    fn formula(&self, style: &str, args: &[String]) -> Result<String, DefineError> {
        match args {
            [f] => {
                if let Err(e) = expr::parse(f) {
                    return derr(format!("in formula '{f}': {}", e.message), 1, None);
                }
                Ok(f.clone())
            }
            [] => derr(format!("style {style} needs a formula"), 0, None),
            _ => derr(
                format!("style {style} takes one formula; put it in quotes if it has spaces"),
                2,
                None,
            ),
        }
    }

    /// `next name…`: advances `index`, `loop`, `file`, `universe` and `uloop` variables,
    /// which must all be of one style (`universe` and `uloop` count as one). Returns
    /// whether one of them was exhausted (they are then deleted, and the `jump` that
    /// follows is skipped) and, for `universe`/`uloop`, the line LIGGGHTS prints.
    pub fn next(&mut self, names: &[String]) -> Result<Next, Error> {
        let mut kind = None;
        for name in names {
            let k = match self.get(name) {
                Some(Variable::Index { .. }) => "index",
                Some(Variable::Loop { .. }) => "loop",
                Some(Variable::File { .. }) => "file",
                Some(Variable::Universe { .. }) => "universe",
                Some(_) => {
                    return Err(format!(
                        "variable '{name}' is not an index, loop, file, universe or uloop variable"
                    )
                    .into())
                }
                None => return Err(Error::undefined("variable", name)),
            };
            match kind {
                Some(first) if first != k => {
                    return Err(format!(
                        "all variables of one next command must be of the same style ('{name}' is {k}, '{}' is {first})",
                        names[0]
                    ).into())
                }
                _ => kind = Some(k),
            }
        }
        let mut out = Next::default();
        for name in names {
            if let Some((
                _,
                Variable::Index { values, pos }
                | Variable::Loop { values, pos }
                | Variable::File { values, pos }
                | Variable::Universe { values, pos },
            )) = self.vars.iter_mut().find(|(n, _)| n == name)
            {
                *pos += 1;
                if *pos >= values.len() {
                    out.exhausted = true;
                }
                if kind == Some("universe") {
                    out.message = Some(format!(
                        "Increment via next: value {} on partition 0",
                        *pos + 1
                    ));
                }
            }
        }
        if out.exhausted {
            self.vars.retain(|(n, _)| !names.contains(n));
        }
        Ok(out)
    }

    /// The text `${name}` is replaced by. `equal` variables are evaluated with `ctx`
    /// (which resolves `v_` references, usually through this table again).
    pub fn text(&self, name: &str, ctx: &mut dyn Context) -> Result<String, Error> {
        match self.get(name) {
            None => Err(Error::undefined("variable", name)),
            Some(
                Variable::Index { values, pos }
                | Variable::Loop { values, pos }
                | Variable::File { values, pos }
                | Variable::Universe { values, pos },
            ) => Ok(values[*pos].clone()),
            Some(Variable::Str(s)) => Ok(s.clone()),
            Some(Variable::Getenv(v)) => Ok(std::env::var(v).unwrap_or_default()),
            Some(Variable::Equal(f)) => {
                let e = expr::parse(f).map_err(|e| e.message)?;
                let v = expr::eval(&e, ctx).map_err(|e| Error::InVariable {
                    name: name.to_string(),
                    source: e,
                })?;
                Ok(format_g(v, 15))
            }
            Some(Variable::Atom(_)) => {
                Err(format!("atom-style variable '{name}' has no single value").into())
            }
        }
    }
}

/// C's `%.{prec}g`.
pub fn format_g(v: f64, prec: usize) -> String {
    if v == 0.0 {
        return if v.is_sign_negative() {
            "-0".into()
        } else {
            "0".into()
        };
    }
    if !v.is_finite() {
        return if v.is_nan() {
            "nan".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let p = prec.max(1);
    let sci = format!("{:.*e}", p - 1, v);
    let (mant, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let strip = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if exp < -4 || exp >= p as i32 {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", strip(mant), exp.abs())
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        strip(&format!("{v:.decimals$}"))
    }
}

/// `%e` as C prints it (`1.500000e-01`).
pub fn format_e(v: f64) -> String {
    let s = format!("{v:.6e}");
    // Rust writes 1.5e-1; C writes 1.500000e-01.
    match s.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

/// A number in a message, as `%g` prints it.
pub fn g(v: f64) -> String {
    format_g(v, 6)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::Name;

    /// Resolves `v_` references through a variable table, like the real front end.
    struct Ctx<'a>(&'a Variables);
    impl Context for Ctx<'_> {
        fn name(&mut self, n: &Name) -> Result<f64, Error> {
            match n {
                Name::Variable(v) => {
                    let t = self.0.text(v, &mut Ctx(self.0))?;
                    t.parse()
                        .map_err(|_| format!("variable '{v}' is not a number: '{t}'").into())
                }
                Name::Keyword(k) if k == "PI" => Ok(std::f64::consts::PI),
                other => Err(format!("unknown {other:?}").into()),
            }
        }
        fn function(&mut self, _: &str, _: &[String]) -> Result<Option<f64>, Error> {
            Ok(None)
        }
    }

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    /// The printed forms of 1/3, 2^60 (and below 1e-5, 100/3, `loop 8 10 pad`) are the ones
    /// LIGGGHTS 3.8 prints for `print "${a}"` with the same definitions.
    #[test]
    fn styles_and_text() {
        let mut t = Variables::new();
        t.define("r", "equal", &s(&["0.5*3"])).unwrap();
        t.define("two", "equal", &s(&["v_r/0.75"])).unwrap();
        t.define("name", "string", &s(&["hello"])).unwrap();
        t.define("third", "equal", &s(&["1/3"])).unwrap();
        t.define("big", "equal", &s(&["2^60"])).unwrap();
        let text = |t: &Variables, n: &str| t.text(n, &mut Ctx(t)).unwrap();
        assert_eq!(text(&t, "r"), "1.5");
        assert_eq!(text(&t, "two"), "2");
        assert_eq!(text(&t, "name"), "hello");
        assert_eq!(text(&t, "third"), "0.333333333333333");
        assert_eq!(text(&t, "big"), "1.15292150460685e+18");
        // equal and string are redefined, index is not.
        t.define("r", "equal", &s(&["4"])).unwrap();
        assert_eq!(text(&t, "r"), "4");
        t.define("i", "index", &s(&["a", "b"])).unwrap();
        assert!(!t.define("i", "index", &s(&["z"])).unwrap());
        assert_eq!(text(&t, "i"), "a");
    }

    #[test]
    fn loops_and_next() {
        let mut t = Variables::new();
        t.define("k", "loop", &s(&["8", "10", "pad"])).unwrap();
        let mut seen = Vec::new();
        loop {
            seen.push(t.text("k", &mut Ctx(&Variables::new())).unwrap());
            if t.next(&s(&["k"])).unwrap().exhausted {
                break;
            }
        }
        assert_eq!(seen, vec!["08", "09", "10"]);
        assert!(
            t.get("k").is_none(),
            "an exhausted loop variable is deleted"
        );
        assert!(t.next(&s(&["k"])).is_err());
    }

    #[test]
    fn bad_definitions_say_which_argument() {
        let mut t = Variables::new();
        let e = t.define("x", "equl", &s(&["1"])).unwrap_err();
        assert_eq!(e.arg, 0);
        assert!(e.help.unwrap().contains("'equal'"));
        assert_eq!(t.define("x", "loop", &s(&["a"])).unwrap_err().arg, 1);
        assert_eq!(t.define("x", "loop", &s(&["3", "1"])).unwrap_err().arg, 2);
        assert_eq!(t.define("x", "equal", &s(&["1+"])).unwrap_err().arg, 1);
        assert_eq!(t.define("x", "equal", &s(&["1", "+2"])).unwrap_err().arg, 2);
        assert!(t.define("x-y", "string", &s(&["a"])).is_err());
        assert!(t.define("x", "index", &[]).is_err());
        assert!(t.text("nope", &mut Ctx(&Variables::new())).is_err());
    }

    #[test]
    fn percent_g_like_c() {
        for (v, want) in [
            (1.0, "1"),
            (0.1, "0.1"),
            (1e-5, "1e-05"),
            (123456.0, "123456"),
            (1e15, "1e+15"),
            (-2.5e-7, "-2.5e-07"),
            (0.0001, "0.0001"),
            (100.0 / 3.0, "33.3333333333333"),
        ] {
            assert_eq!(format_g(v, 15), want, "{v}");
        }
    }
}
