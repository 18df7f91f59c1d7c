//! `dump custom` text snapshots, byte for byte as LIGGGHTS 3.8 writes them:
//!
//! ```text
//! ITEM: TIMESTEP
//! 10
//! ITEM: NUMBER OF ATOMS
//! 3
//! ITEM: BOX BOUNDS pp ff mm
//! 0 1
//! 0 1
//! 0 2
//! ITEM: ATOMS id type x y z vx radius
//! 1 1 0.2001 0.3 0.499995 0.1 0.05
//! ```
//!
//! The boundary letters are those of the lower and upper face of each axis; the box
//! bounds are written with `%g`; the header lists the column arguments as written (a
//! repeated argument is repeated); every value, and the header, is followed by one space.
//! Integer columns use `%d` and all others `%g` unless `dump_modify format` gave a format
//! per column ([`parse_line_format`]); `dump_modify sort` orders the lines ([`Sort`]).
//! With `*` in the file name each snapshot is its own file, otherwise the snapshots are
//! appended to one file (truncated when the dump is defined).

use std::path::PathBuf;

use rdem::{Boundary, Domain, Particles};

use crate::atomic::{write_atomic, AppendFile, IoError};
use crate::fields::Column;
use crate::filename::DumpFileName;
use crate::printf::{FormatError, Printf, Value};

/// Order of the particle lines in a snapshot (`dump_modify sort`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sort {
    /// `off`: the order of the selection (LIGGGHTS' default).
    #[default]
    Off,
    /// `id`: ascending particle tag.
    Id,
    /// `N`: ascending by the N-th column (1-based).
    Ascending(usize),
    /// `-N`: descending by the N-th column (1-based).
    Descending(usize),
}

/// Why a `dump_modify sort` argument is refused ([`Sort::parse`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SortError {
    /// Not `off`, `id`, N or -N.
    #[error("expected 'off', 'id', N or -N, found '{0}'")]
    Syntax(String),
    /// A column the dump does not have.
    #[error("sort column {n} does not exist (the dump has {ncolumns} columns)")]
    NoColumn {
        /// The column asked for (1-based).
        n: usize,
        /// The dump's columns.
        ncolumns: usize,
    },
}

impl Sort {
    /// Parses the `dump_modify sort` argument for a dump with `ncolumns` columns.
    pub fn parse(arg: &str, ncolumns: usize) -> Result<Sort, SortError> {
        match arg {
            "off" => return Ok(Sort::Off),
            "id" => return Ok(Sort::Id),
            _ => {}
        }
        let (desc, digits) = match arg.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, arg),
        };
        let n: usize = digits
            .parse()
            .map_err(|_| SortError::Syntax(arg.to_string()))?;
        if n == 0 || n > ncolumns {
            return Err(SortError::NoColumn { n, ncolumns });
        }
        Ok(if desc {
            Sort::Descending(n)
        } else {
            Sort::Ascending(n)
        })
    }

    /// Reorders `selection` (indices of owned particles) in place; ties keep their order.
    ///
    /// # Panics
    /// If a column sort names a column that `columns` does not have.
    pub fn apply(self, selection: &mut [usize], p: &Particles, d: &Domain, columns: &[Column]) {
        let key = |c: &Column, i: usize| match c.value(p, d, i) {
            Value::Int(v) => v as f64,
            Value::Float(v) => v,
        };
        match self {
            Sort::Off => {}
            Sort::Id => selection.sort_by_key(|&i| p.tag[i]),
            Sort::Ascending(n) => {
                let c = &columns[n - 1];
                selection.sort_by(|&a, &b| key(c, a).total_cmp(&key(c, b)));
            }
            Sort::Descending(n) => {
                let c = &columns[n - 1];
                selection.sort_by(|&a, &b| key(c, b).total_cmp(&key(c, a)));
            }
        }
    }
}

/// Per-dump settings of a text dump.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TextOptions {
    /// Line order.
    pub sort: Sort,
    /// Format per column; `None` (or a missing entry) means `%d`/`%g` by column kind.
    pub formats: Vec<Option<Printf>>,
}

/// Splits a `dump_modify format` line into one format per column, as LIGGGHTS does
/// (whitespace-separated words; extra words are ignored, too few are an error).
pub fn parse_line_format(line: &str, ncolumns: usize) -> Result<Vec<Option<Printf>>, FormatError> {
    let words: Vec<&str> = line.split_whitespace().collect();
    if words.len() < ncolumns {
        return Err(FormatError {
            format: line.to_string(),
            pos: line.len(),
            message: format!("{} formats given for {ncolumns} columns", words.len()),
        });
    }
    words[..ncolumns]
        .iter()
        .map(|w| Printf::parse(w).map(Some))
        .collect()
}

fn letter(b: Boundary) -> char {
    match b {
        Boundary::Periodic => 'p',
        Boundary::Fixed => 'f',
        Boundary::Shrink => 's',
        Boundary::ShrinkMin => 'm',
    }
}

/// Appends one snapshot of the particles `selection` (indices of owned particles, written
/// in this order unless `options.sort` says otherwise) to `out`.
///
/// # Panics
/// If a custom column has fewer values than a selected index needs, or the sort column
/// does not exist.
pub fn format_text_snapshot(
    out: &mut String,
    step: u64,
    p: &Particles,
    d: &Domain,
    selection: &[usize],
    columns: &[Column],
    options: &TextOptions,
) {
    use std::fmt::Write as _;
    let g = Printf::default_float();
    let int = Printf::default_int();
    let _ = write!(
        out,
        "ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS",
        selection.len()
    );
    for faces in d.boundary {
        let _ = write!(out, " {}{}", letter(faces[0]), letter(faces[1]));
    }
    out.push('\n');
    for a in 0..3 {
        g.write(out, Value::Float(d.boxlo[a]));
        out.push(' ');
        g.write(out, Value::Float(d.boxhi[a]));
        out.push('\n');
    }
    out.push_str("ITEM: ATOMS ");
    for c in columns {
        out.push_str(c.label());
        out.push(' ');
    }
    out.push('\n');
    let formats: Vec<&Printf> = columns
        .iter()
        .enumerate()
        .map(|(k, c)| match options.formats.get(k) {
            Some(Some(f)) => f,
            _ if c.is_integer() => &int,
            _ => &g,
        })
        .collect();
    let mut order = selection.to_vec();
    options.sort.apply(&mut order, p, d, columns);
    for i in order {
        for (c, f) in columns.iter().zip(&formats) {
            f.write(out, c.value(p, d, i));
            out.push(' ');
        }
        out.push('\n');
    }
}

/// A `dump custom` text dump: file name rules, options, and the open file of a
/// single-file dump.
#[derive(Debug)]
pub struct TextDump {
    name: DumpFileName,
    /// Sort order and column formats.
    pub options: TextOptions,
    /// Rank substituted for `%`.
    pub rank: usize,
    single: Option<AppendFile>,
}

impl TextDump {
    /// A dump writing to `name` with `options`, as rank 0.
    pub fn new(name: DumpFileName, options: TextOptions) -> Self {
        Self {
            name,
            options,
            rank: 0,
            single: None,
        }
    }

    /// The file name pattern (mutable for `dump_modify pad`).
    pub fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.name
    }

    /// Writes one snapshot and returns the file written: a new file when the name has
    /// `*`, otherwise appended to the dump's single file (created by the first snapshot).
    pub fn write(
        &mut self,
        step: u64,
        p: &Particles,
        d: &Domain,
        selection: &[usize],
        columns: &[Column],
    ) -> Result<PathBuf, IoError> {
        let mut text = String::new();
        format_text_snapshot(&mut text, step, p, d, selection, columns, &self.options);
        let path = self.name.path(step, self.rank);
        if self.name.per_step() {
            write_atomic(&path, text.as_bytes())?;
        } else {
            self.single
                .get_or_insert_with(|| AppendFile::new(&path))
                .append(text.as_bytes())?;
        }
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fields::tests::sample;
    use crate::fields::Field;

    fn cols(names: &[&str]) -> Vec<Column> {
        names.iter().map(|n| Column::field(n).unwrap()).collect()
    }

    #[test]
    fn layout_matches_liggghts() {
        let (mut p, d) = sample();
        p.x[0].z = 0.499995095;
        let mut s = String::new();
        let c = cols(&["id", "type", "x", "z", "vx", "ix", "radius", "type"]);
        format_text_snapshot(&mut s, 10, &p, &d, &[0, 1], &c, &TextOptions::default());
        let want = "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff mm\n\
                    0 2\n-1 1\n0 4\nITEM: ATOMS id type x z vx ix radius type \n\
                    7 2 0.5 0.499995 1 -1 0.1 2 \n3 1 1.5 3 0 0 0.05 1 \n";
        assert_eq!(s, want);
    }

    #[test]
    fn sorting() {
        let (p, d) = sample();
        let c = cols(&["id", "x"]);
        let run = |sort| {
            let mut s = String::new();
            let o = TextOptions {
                sort,
                formats: vec![],
            };
            format_text_snapshot(&mut s, 0, &p, &d, &[0, 1], &c, &o);
            s.lines().skip(9).map(String::from).collect::<Vec<_>>()
        };
        assert_eq!(run(Sort::Off), ["7 0.5 ", "3 1.5 "]);
        assert_eq!(run(Sort::Id), ["3 1.5 ", "7 0.5 "]);
        assert_eq!(run(Sort::Ascending(2)), ["7 0.5 ", "3 1.5 "]);
        assert_eq!(run(Sort::Descending(2)), ["3 1.5 ", "7 0.5 "]);
        assert_eq!(Sort::parse("id", 2), Ok(Sort::Id));
        assert_eq!(Sort::parse("off", 2), Ok(Sort::Off));
        assert_eq!(Sort::parse("-2", 2), Ok(Sort::Descending(2)));
        assert_eq!(Sort::parse("1", 2), Ok(Sort::Ascending(1)));
        assert!(Sort::parse("3", 2)
            .unwrap_err()
            .to_string()
            .contains("2 columns"));
        assert!(Sort::parse("0", 2).is_err());
        assert!(Sort::parse("x", 2).is_err());
    }

    #[test]
    fn user_formats() {
        // The exact line LIGGGHTS 3.8 wrote for
        // dump_modify b format "%5d %-3i %12.4e %+d %10.3f" (atom 3 of the sample run).
        let (mut p, d) = sample();
        p.tag[0] = 3;
        p.ty[0] = 1;
        p.x[0].x = 0.21002;
        p.image[0] = [1, 0, 0].into();
        p.v[0].x = 0.02;
        let c = cols(&["id", "type", "x", "ix", "vx"]);
        let formats = parse_line_format("%5d %-3i %12.4e %+d %10.3f extra", 5).unwrap();
        let o = TextOptions {
            sort: Sort::Off,
            formats,
        };
        let mut s = String::new();
        format_text_snapshot(&mut s, 0, &p, &d, &[0], &c, &o);
        assert_eq!(
            s.lines().last().unwrap(),
            "    3 1     2.1002e-01 +1      0.020 "
        );
        let e = parse_line_format("%d %g", 3).unwrap_err();
        assert!(e.message.contains("2 formats given for 3 columns"));
        assert!(parse_line_format("%d %q", 2).is_err());
    }

    #[test]
    fn custom_columns_and_empty_selection() {
        let (p, d) = sample();
        let c = vec![
            Column::Field(Field::Id),
            Column::Custom {
                name: "c_pa[2]".into(),
                values: vec![-0.0, 1.63625e-05],
            },
            Column::Custom {
                name: "v_ke".into(),
                values: vec![0.25, 1e7],
            },
        ];
        let mut s = String::new();
        format_text_snapshot(&mut s, 3, &p, &d, &[0, 1], &c, &TextOptions::default());
        assert!(s.contains("ITEM: ATOMS id c_pa[2] v_ke \n7 -0 0.25 \n3 1.63625e-05 1e+07 \n"));
        let mut s = String::new();
        format_text_snapshot(&mut s, 3, &p, &d, &[], &c, &TextOptions::default());
        assert!(s.contains("ITEM: NUMBER OF ATOMS\n0\n"));
        assert!(s.ends_with("ITEM: ATOMS id c_pa[2] v_ke \n"));
    }
}
