//! LAMMPS data files for `atom_style granular` (LIGGGHTS' name for `sphere`):
//! [`read_data`]/[`parse_data`] and [`write_data`]/[`format_data`].
//!
//! Layout (LIGGGHTS `read_data` page): the first line is a title and is skipped; then
//! header lines `N atoms`, `N atom types`, `lo hi xlo xhi` (and `ylo yhi`, `zlo zhi`;
//! default -0.5 0.5); then sections, each a keyword line, one skipped (empty) line and
//! one line per atom:
//!
//! * `Atoms`: `atom-ID atom-type diameter density x y z [ix iy iz]` (image flags on all
//!   lines or on none);
//! * `Velocities` (after `Atoms`): `atom-ID vx vy vz omegax omegay omegaz`.
//!
//! Under `atom_style hybrid` ([`AtomLayout::Hybrid`]) an atom line is
//! `atom-ID atom-type x y z` followed by each sub-style's own values in the order the
//! style names them (`granular`/`sphere`: `diameter density`; `bond/gran`: `molecule-ID`),
//! then optionally `ix iy iz`; a velocity line is `atom-ID vx vy vz` and, for
//! `granular`/`sphere`, `omegax omegay omegaz`. With `bond/gran` the header may give
//! `N bonds`, `N bond types` and `N extra bond per atom`, and a `Bonds` section (after
//! `Atoms`) lists `bond-ID bond-type atom-1 atom-2`, as LIGGGHTS-PFM,
//! LIGGGHTS_Flexible_Fibers and LIGGGHTS_SEAICE read them.
//!
//! `#` starts a comment anywhere; blank lines are skipped outside sections. Anything a
//! granular simulation cannot use (bonds without `bond/gran`, a triclinic tilt,
//! `Masses`, zero diameters) is refused with a [`DataError`] that gives the 1-based line and the byte range of the
//! offending word, so the front end can underline it. The reader never panics.
//!
//! The writer puts every number in the shortest form that reads back to the same `f64`
//! (Rust's `{}`, or `{:e}` for very large and very small magnitudes), so
//! `parse_data(format_data(f)) == f` exactly, and LIGGGHTS 3.8 reads the file.

use std::fmt::Write as _;
use std::ops::Range;
use std::path::{Path, PathBuf};

use rdem::{DVec3, Domain, NewParticle, Particles, Tag};

use crate::atomic::{write_atomic, IoError};

/// A sub-style of `atom_style hybrid`, which adds its own values to the data lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SubStyle {
    /// `granular` or `sphere`: `diameter density` on atom lines, `omegax omegay omegaz`
    /// on velocity lines.
    Sphere,
    /// `bond/gran`: `molecule-ID` on atom lines; bonds.
    BondGran,
}

/// The column layout of the `Atoms` and `Velocities` lines, which the atom style sets.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum AtomLayout {
    /// `atom_style granular` (or `sphere`): `atom-ID atom-type diameter density x y z`.
    #[default]
    Granular,
    /// `atom_style hybrid` of these sub-styles, in order (one of them [`SubStyle::Sphere`]).
    Hybrid(Vec<SubStyle>),
}

impl AtomLayout {
    /// True when the style holds bonds (a `bond/gran` sub-style).
    pub fn has_bonds(&self) -> bool {
        matches!(self, AtomLayout::Hybrid(s) if s.contains(&SubStyle::BondGran))
    }

    /// The atom style, as messages name it.
    fn style(&self) -> &'static str {
        match self {
            AtomLayout::Granular => "atom_style granular",
            AtomLayout::Hybrid(_) if self.has_bonds() => "atom_style hybrid granular bond/gran",
            AtomLayout::Hybrid(_) => "atom_style hybrid without bond/gran",
        }
    }

    /// The names of an atom line's values, without image flags.
    fn atom_names(&self) -> Vec<&'static str> {
        match self {
            AtomLayout::Granular => {
                vec!["atom-ID", "atom-type", "diameter", "density", "x", "y", "z"]
            }
            AtomLayout::Hybrid(s) => {
                let mut v = vec!["atom-ID", "atom-type", "x", "y", "z"];
                for k in s {
                    match k {
                        SubStyle::Sphere => v.extend(["diameter", "density"]),
                        SubStyle::BondGran => v.push("molecule-ID"),
                    }
                }
                v
            }
        }
    }

    /// The names of a velocity line's values.
    fn velocity_names(&self) -> Vec<&'static str> {
        let mut v = vec!["atom-ID", "vx", "vy", "vz"];
        let spheres = match self {
            AtomLayout::Granular => 1,
            AtomLayout::Hybrid(s) => s.iter().filter(|&&k| k == SubStyle::Sphere).count(),
        };
        for _ in 0..spheres {
            v.extend(["omegax", "omegay", "omegaz"]);
        }
        v
    }
}

/// One line of the `Bonds` section.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DataBond {
    /// Bond-ID.
    pub id: u64,
    /// Bond type (1..=`nbondtypes`).
    pub ty: u32,
    /// The two atoms' IDs.
    pub atoms: [Tag; 2],
}

/// One line of the `Atoms` section.
#[derive(Debug, Clone)]
pub struct DataAtom {
    /// Atom-ID (≥ 1).
    pub id: Tag,
    /// Atom type (1..=`ntypes`).
    pub ty: u32,
    /// Diameter (> 0).
    pub diameter: f64,
    /// Density (> 0).
    pub density: f64,
    /// Position.
    pub x: DVec3,
    /// Image flags (0 when the file has none).
    pub image: [i32; 3],
    /// Molecule-ID (`bond/gran`; 0 without).
    pub molecule: u64,
    /// 1-based line in the file (0 for atoms not read from a file); not compared by `==`.
    pub line: usize,
}

impl PartialEq for DataAtom {
    fn eq(&self, o: &Self) -> bool {
        // Bitwise float comparison, so that -0.0 and 0.0 differ and a round trip is exact.
        self.id == o.id
            && self.ty == o.ty
            && self.diameter.to_bits() == o.diameter.to_bits()
            && self.density.to_bits() == o.density.to_bits()
            && self.x.to_array().map(f64::to_bits) == o.x.to_array().map(f64::to_bits)
            && self.image == o.image
            && self.molecule == o.molecule
    }
}

/// One line of the `Velocities` section.
#[derive(Debug, Clone)]
pub struct DataVelocity {
    /// Atom-ID of an atom of the `Atoms` section.
    pub id: Tag,
    /// Velocity.
    pub v: DVec3,
    /// Angular velocity.
    pub omega: DVec3,
    /// 1-based line in the file (0 when not read from a file); not compared by `==`.
    pub line: usize,
}

impl PartialEq for DataVelocity {
    fn eq(&self, o: &Self) -> bool {
        self.id == o.id
            && self.v.to_array().map(f64::to_bits) == o.v.to_array().map(f64::to_bits)
            && self.omega.to_array().map(f64::to_bits) == o.omega.to_array().map(f64::to_bits)
    }
}

/// The contents of a data file.
#[derive(Debug, Clone, PartialEq)]
pub struct DataFile {
    /// The first line.
    pub title: String,
    /// `N atoms`.
    pub natoms: u64,
    /// `N atom types`.
    pub ntypes: u32,
    /// Lower box corner (`xlo`, `ylo`, `zlo`).
    pub lo: DVec3,
    /// Upper box corner.
    pub hi: DVec3,
    /// The `Atoms` section, in file order.
    pub atoms: Vec<DataAtom>,
    /// The `Velocities` section, in file order (empty without one).
    pub velocities: Vec<DataVelocity>,
    /// The column layout (the atom style).
    pub layout: AtomLayout,
    /// `N bond types` (0 without bonds).
    pub nbondtypes: u32,
    /// The `Bonds` section, in file order (empty without one).
    pub bonds: Vec<DataBond>,
}

/// A data file that cannot be used, with the place to point at.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("line {line}, column {}: {message}", col_range.start + 1)]
pub struct DataError {
    /// 1-based line number (one past the last line for a file that ends too early).
    pub line: usize,
    /// Byte range of the offending word within the line (empty at the end of a line).
    pub col_range: Range<usize>,
    /// What is wrong.
    pub message: String,
}

/// Failure of [`read_data`].
#[derive(Debug, thiserror::Error)]
pub enum ReadDataError {
    /// The file could not be read.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The file was read but is not a usable data file.
    #[error("{}: {error}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// Where and why.
        error: DataError,
    },
}

/// A word of a line and its byte range.
#[derive(Debug, Clone, Copy)]
struct Word<'a> {
    text: &'a str,
    start: usize,
}

impl Word<'_> {
    fn range(&self) -> Range<usize> {
        self.start..self.start + self.text.len()
    }
}

/// The words of `line` before any `#`.
fn words(line: &str) -> Vec<Word<'_>> {
    let content = line.split('#').next().unwrap_or("");
    let mut out = Vec::new();
    let mut start = None;
    for (k, c) in content.char_indices() {
        match (c.is_whitespace(), start) {
            (true, Some(s)) => {
                out.push(Word {
                    text: &content[s..k],
                    start: s,
                });
                start = None;
            }
            (false, None) => start = Some(k),
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push(Word {
            text: &content[s..],
            start: s,
        });
    }
    out
}

struct Parser<'a> {
    lines: Vec<&'a str>,
    /// Index of the next line to read.
    next: usize,
    /// `N bonds` of the header.
    nbonds: u64,
}

fn err(line: usize, col_range: Range<usize>, message: impl Into<String>) -> DataError {
    DataError {
        line,
        col_range,
        message: message.into(),
    }
}

fn word_err(line: usize, w: &Word, message: impl Into<String>) -> DataError {
    err(line, w.range(), message)
}

fn parse_float(line: usize, w: &Word, what: &str) -> Result<f64, DataError> {
    let v: f64 = w.text.parse().map_err(|_| {
        word_err(
            line,
            w,
            format!("expected a number for {what}, found '{}'", w.text),
        )
    })?;
    if !v.is_finite() {
        return Err(word_err(line, w, format!("{what} must be finite")));
    }
    Ok(v)
}

fn parse_int<T: std::str::FromStr>(line: usize, w: &Word, what: &str) -> Result<T, DataError> {
    w.text.parse().map_err(|_| {
        word_err(
            line,
            w,
            format!("expected an integer for {what}, found '{}'", w.text),
        )
    })
}

/// Header keywords of LAMMPS data files that a granular simulation has no use for; a
/// zero count is accepted.
const UNUSED_COUNTS: [&str; 14] = [
    "bonds",
    "angles",
    "dihedrals",
    "impropers",
    "bond types",
    "angle types",
    "dihedral types",
    "improper types",
    "extra bond per atom",
    "extra angle per atom",
    "ellipsoids",
    "lines",
    "triangles",
    "bodies",
];

/// Section keywords of LAMMPS data files other than `Atoms` and `Velocities`.
const OTHER_SECTIONS: [&str; 24] = [
    "Masses",
    "Ellipsoids",
    "Lines",
    "Triangles",
    "Bodies",
    "Bonds",
    "Angles",
    "Dihedrals",
    "Impropers",
    "Pair Coeffs",
    "PairIJ Coeffs",
    "Bond Coeffs",
    "Angle Coeffs",
    "Dihedral Coeffs",
    "Improper Coeffs",
    "BondBond Coeffs",
    "BondAngle Coeffs",
    "MiddleBondTorsion Coeffs",
    "EndBondTorsion Coeffs",
    "AngleTorsion Coeffs",
    "AngleAngleTorsion Coeffs",
    "BondBond13 Coeffs",
    "AngleAngle Coeffs",
    "Molecules",
];

impl<'a> Parser<'a> {
    /// Line number (1-based) of the line at index `k`.
    fn lineno(k: usize) -> usize {
        k + 1
    }

    fn header(&mut self, f: &mut DataFile) -> Result<(), DataError> {
        let mut seen: Vec<&str> = Vec::new();
        while self.next < self.lines.len() {
            let ln = Self::lineno(self.next);
            let ws = words(self.lines[self.next]);
            let Some(first) = ws.first() else {
                self.next += 1;
                continue;
            };
            if first.text.parse::<f64>().is_err() {
                return Ok(()); // the body starts here
            }
            let nnum = ws
                .iter()
                .take_while(|w| w.text.parse::<f64>().is_ok())
                .count();
            if nnum == ws.len() {
                let end = ws[nnum - 1].range().end;
                return Err(err(ln, end..end, "header line without a keyword"));
            }
            let kw_words = &ws[nnum..];
            let keyword = kw_words
                .iter()
                .map(|w| w.text)
                .collect::<Vec<_>>()
                .join(" ");
            let kw_range = kw_words[0].start..kw_words[kw_words.len() - 1].range().end;
            let want = match keyword.as_str() {
                "xlo xhi" | "ylo yhi" | "zlo zhi" => 2,
                "xy xz yz" => {
                    return Err(err(
                        ln,
                        kw_range,
                        "triclinic boxes (xy xz yz) are not supported",
                    ))
                }
                "atoms" | "atom types" => 1,
                k if UNUSED_COUNTS.contains(&k) => 1,
                _ => {
                    return Err(err(
                        ln,
                        kw_range,
                        format!("unknown header keyword '{keyword}'"),
                    ))
                }
            };
            if nnum != want {
                let w = if nnum > want { &ws[want] } else { &kw_words[0] };
                return Err(word_err(
                    ln,
                    w,
                    format!("'{keyword}' takes {want} value(s), found {nnum}"),
                ));
            }
            if let Some(&prev) = seen.iter().find(|&&k| k == keyword) {
                return Err(err(ln, kw_range, format!("'{prev}' given twice")));
            }
            seen.push(match keyword.as_str() {
                "xlo xhi" => "xlo xhi",
                "ylo yhi" => "ylo yhi",
                "zlo zhi" => "zlo zhi",
                "atoms" => "atoms",
                "atom types" => "atom types",
                k => UNUSED_COUNTS
                    .iter()
                    .find(|&&u| u == k)
                    .copied()
                    .unwrap_or("?"),
            });
            match keyword.as_str() {
                "atoms" => f.natoms = parse_int(ln, &ws[0], "the number of atoms")?,
                "atom types" => {
                    f.ntypes = parse_int(ln, &ws[0], "the number of atom types")?;
                }
                "xlo xhi" | "ylo yhi" | "zlo zhi" => {
                    let a = match &keyword[..1] {
                        "x" => 0,
                        "y" => 1,
                        _ => 2,
                    };
                    let lo = parse_float(ln, &ws[0], "the lower box bound")?;
                    let hi = parse_float(ln, &ws[1], "the upper box bound")?;
                    if lo >= hi {
                        return Err(err(
                            ln,
                            ws[0].start..ws[1].range().end,
                            format!("the lower bound {lo} must be below the upper bound {hi}"),
                        ));
                    }
                    f.lo[a] = lo;
                    f.hi[a] = hi;
                }
                "bonds" if f.layout.has_bonds() => {
                    self.nbonds = parse_int(ln, &ws[0], "the number of bonds")?;
                }
                "bond types" if f.layout.has_bonds() => {
                    f.nbondtypes = parse_int(ln, &ws[0], "the number of bond types")?;
                }
                "extra bond per atom" if f.layout.has_bonds() => {
                    // Room for bonds made later: `bonds_per_atom` of the atom style.
                    let _: u64 = parse_int(ln, &ws[0], "the extra bonds per atom")?;
                }
                _ => {
                    let n: u64 = parse_int(ln, &ws[0], &format!("'{keyword}'"))?;
                    if n != 0 {
                        return Err(err(
                            ln,
                            kw_range,
                            format!("'{keyword}' is not supported by {}", f.layout.style()),
                        ));
                    }
                }
            }
            self.next += 1;
        }
        Ok(())
    }

    /// Opens section `name` (its keyword on line `ln`, at `range`): `after_atoms` false
    /// (a section that needs the atoms, before them) or `seen` (a second one) is an error;
    /// marks it seen and skips the empty line after the keyword.
    fn open_section(
        &mut self,
        name: &str,
        ln: usize,
        range: Range<usize>,
        after_atoms: bool,
        seen: &mut bool,
    ) -> Result<(), DataError> {
        if !after_atoms {
            return Err(err(
                ln,
                range,
                format!("'{name}' must come after the 'Atoms' section"),
            ));
        }
        if *seen {
            return Err(err(ln, range, format!("a second '{name}' section")));
        }
        *seen = true;
        self.skip_after_keyword(name)
    }

    /// After a section keyword at index `k`: skips the following line, which must be
    /// empty (LAMMPS skips it unread; a data line there would silently be lost).
    fn skip_after_keyword(&mut self, name: &str) -> Result<(), DataError> {
        let k = self.next;
        if let Some(line) = self.lines.get(k) {
            if let Some(w) = words(line).first() {
                return Err(word_err(
                    Self::lineno(k),
                    w,
                    format!("expected an empty line after '{name}'"),
                ));
            }
        }
        self.next += 1;
        Ok(())
    }

    /// Line `done` (0-based) of the `n` lines of section `name`, with its line number.
    fn section_line(
        &mut self,
        name: &str,
        done: u64,
        n: u64,
    ) -> Result<(usize, Vec<Word<'a>>), DataError> {
        let Some(&line) = self.lines.get(self.next) else {
            return Err(err(
                Self::lineno(self.lines.len()),
                0..0,
                format!("the file ends after {done} of the {n} lines of '{name}'"),
            ));
        };
        let ln = Self::lineno(self.next);
        let ws = words(line);
        if ws.is_empty() {
            return Err(err(
                ln,
                0..line.len(),
                format!(
                    "'{name}' has {done} lines here, but the header announces {n} {}",
                    if name == "Bonds" { "bonds" } else { "atoms" }
                ),
            ));
        }
        self.next += 1;
        Ok((ln, ws))
    }

    fn atoms(&mut self, f: &mut DataFile) -> Result<(), DataError> {
        let mut ncols = None;
        let mut ids = std::collections::HashMap::new();
        let names = f.layout.atom_names();
        let nv = names.len();
        // Where each value sits on the line.
        let col = |name: &str| names.iter().position(|&n| n == name).unwrap_or(0);
        let (cd, cr, cx, cm) = (
            col("diameter"),
            col("density"),
            col("x"),
            col("molecule-ID"),
        );
        for done in 0..f.natoms {
            let (ln, ws) = self.section_line("Atoms", done, f.natoms)?;
            if ws.len() != nv && ws.len() != nv + 3 {
                let w = ws.get(nv).unwrap_or(&ws[ws.len() - 1]);
                return Err(word_err(
                    ln,
                    w,
                    format!(
                        "an atom line has {nv} values ({}) or {} (with ix iy iz), found {}",
                        names.join(" "),
                        nv + 3,
                        ws.len()
                    ),
                ));
            }
            match ncols {
                None => ncols = Some(ws.len()),
                Some(n) if n != ws.len() => {
                    let end = ws[ws.len() - 1].range().end;
                    return Err(err(
                        ln,
                        ws[0].start..end,
                        format!(
                            "{} values here but {n} on the first atom line: image flags must be \
                             given on all atom lines or on none",
                            ws.len()
                        ),
                    ));
                }
                _ => {}
            }
            let id: Tag = parse_int(ln, &ws[0], "the atom-ID")?;
            if id == 0 {
                return Err(word_err(ln, &ws[0], "atom-IDs must be >= 1"));
            }
            if let Some(prev) = ids.insert(id, ln) {
                return Err(word_err(
                    ln,
                    &ws[0],
                    format!("atom-ID {id} is used twice (first on line {prev})"),
                ));
            }
            let ty: u32 = parse_int(ln, &ws[1], "the atom type")?;
            if ty == 0 || ty > f.ntypes {
                return Err(word_err(
                    ln,
                    &ws[1],
                    format!(
                        "atom type {ty} is outside 1..{} (the header's 'atom types')",
                        f.ntypes
                    ),
                ));
            }
            let diameter = parse_float(ln, &ws[cd], "the diameter")?;
            if diameter <= 0.0 {
                return Err(word_err(
                    ln,
                    &ws[cd],
                    "the diameter must be > 0 (point particles are not supported)",
                ));
            }
            let density = parse_float(ln, &ws[cr], "the density")?;
            if density <= 0.0 {
                return Err(word_err(ln, &ws[cr], "the density must be > 0"));
            }
            let mut x = DVec3::ZERO;
            for a in 0..3 {
                x[a] = parse_float(ln, &ws[cx + a], ["x", "y", "z"][a])?;
            }
            let molecule = if f.layout.has_bonds() {
                parse_int(ln, &ws[cm], "the molecule-ID")?
            } else {
                0
            };
            let mut image = [0; 3];
            if ws.len() == nv + 3 {
                for a in 0..3 {
                    image[a] = parse_int(ln, &ws[nv + a], ["ix", "iy", "iz"][a])?;
                }
            }
            f.atoms.push(DataAtom {
                id,
                ty,
                diameter,
                density,
                x,
                image,
                molecule,
                line: ln,
            });
        }
        Ok(())
    }

    fn velocities(&mut self, f: &mut DataFile) -> Result<(), DataError> {
        let ids: std::collections::HashSet<Tag> = f.atoms.iter().map(|a| a.id).collect();
        let mut seen = std::collections::HashMap::new();
        let names = f.layout.velocity_names();
        let nv = names.len();
        for done in 0..f.natoms {
            let (ln, ws) = self.section_line("Velocities", done, f.natoms)?;
            if ws.len() != nv {
                let w = ws.get(nv).unwrap_or(&ws[ws.len() - 1]);
                return Err(word_err(
                    ln,
                    w,
                    format!(
                        "a velocity line has {nv} values ({}), found {}",
                        names.join(" "),
                        ws.len()
                    ),
                ));
            }
            let id: Tag = parse_int(ln, &ws[0], "the atom-ID")?;
            if !ids.contains(&id) {
                return Err(word_err(
                    ln,
                    &ws[0],
                    format!("atom-ID {id} is not in the Atoms section"),
                ));
            }
            if let Some(prev) = seen.insert(id, ln) {
                return Err(word_err(
                    ln,
                    &ws[0],
                    format!("atom-ID {id} has a second velocity (first on line {prev})"),
                ));
            }
            let mut vals = [0.0; 6];
            for k in 0..nv - 1 {
                vals[k] = parse_float(ln, &ws[1 + k], names[1 + k])?;
            }
            f.velocities.push(DataVelocity {
                id,
                v: DVec3::new(vals[0], vals[1], vals[2]),
                omega: DVec3::new(vals[3], vals[4], vals[5]),
                line: ln,
            });
        }
        Ok(())
    }

    fn bonds(&mut self, f: &mut DataFile) -> Result<(), DataError> {
        let ids: std::collections::HashSet<Tag> = f.atoms.iter().map(|a| a.id).collect();
        for done in 0..self.nbonds {
            let (ln, ws) = self.section_line("Bonds", done, self.nbonds)?;
            if ws.len() != 4 {
                let w = ws.get(4).unwrap_or(&ws[ws.len() - 1]);
                return Err(word_err(
                    ln,
                    w,
                    format!(
                        "a bond line has 4 values (bond-ID bond-type atom-1 atom-2), found {}",
                        ws.len()
                    ),
                ));
            }
            let id: u64 = parse_int(ln, &ws[0], "the bond-ID")?;
            let ty: u32 = parse_int(ln, &ws[1], "the bond type")?;
            if ty == 0 || ty > f.nbondtypes {
                return Err(word_err(
                    ln,
                    &ws[1],
                    format!(
                        "bond type {ty} is outside 1..{} (the header's 'bond types')",
                        f.nbondtypes
                    ),
                ));
            }
            let mut atoms = [0; 2];
            for k in 0..2 {
                let t: Tag = parse_int(ln, &ws[2 + k], "an atom-ID")?;
                if !ids.contains(&t) {
                    return Err(word_err(
                        ln,
                        &ws[2 + k],
                        format!("atom-ID {t} is not in the Atoms section"),
                    ));
                }
                atoms[k] = t;
            }
            if atoms[0] == atoms[1] {
                return Err(word_err(
                    ln,
                    &ws[3],
                    format!("a bond of atom {} to itself", atoms[0]),
                ));
            }
            f.bonds.push(DataBond { id, ty, atoms });
        }
        Ok(())
    }

    fn body(&mut self, f: &mut DataFile) -> Result<(), DataError> {
        let mut have_atoms = false;
        let mut have_vel = false;
        let mut have_bonds = false;
        while self.next < self.lines.len() {
            let ln = Self::lineno(self.next);
            let ws = words(self.lines[self.next]);
            if ws.is_empty() {
                self.next += 1;
                continue;
            }
            let keyword = ws.iter().map(|w| w.text).collect::<Vec<_>>().join(" ");
            let range = ws[0].start..ws[ws.len() - 1].range().end;
            self.next += 1;
            match keyword.as_str() {
                "Atoms" => {
                    self.open_section("Atoms", ln, range, true, &mut have_atoms)?;
                    self.atoms(f)?;
                }
                "Velocities" => {
                    self.open_section("Velocities", ln, range, have_atoms, &mut have_vel)?;
                    self.velocities(f)?;
                }
                "Bonds" if f.layout.has_bonds() => {
                    self.open_section("Bonds", ln, range, have_atoms, &mut have_bonds)?;
                    self.bonds(f)?;
                }
                "Masses" => {
                    return Err(err(
                        ln,
                        range,
                        "'Masses' cannot be used with atom_style granular: masses follow from \
                         diameter and density",
                    ))
                }
                k if OTHER_SECTIONS.contains(&k) => {
                    return Err(err(
                        ln,
                        range,
                        format!("section '{k}' is not supported by {}", f.layout.style()),
                    ));
                }
                _ if ws[0].text.parse::<f64>().is_ok() => {
                    return Err(err(
                        ln,
                        range,
                        "header line after the first section (or a data line without a \
                         section keyword)",
                    ))
                }
                _ => {
                    return Err(err(
                        ln,
                        range,
                        format!(
                            "unknown section keyword '{keyword}' (expected 'Atoms' or \
                             'Velocities')"
                        ),
                    ))
                }
            }
        }
        if self.nbonds > 0 && !have_bonds {
            return Err(err(
                Self::lineno(self.lines.len()),
                0..0,
                format!(
                    "the header announces {} bonds but there is no 'Bonds' section",
                    self.nbonds
                ),
            ));
        }
        if f.natoms > 0 && !have_atoms {
            return Err(err(
                Self::lineno(self.lines.len()),
                0..0,
                format!(
                    "the header announces {} atoms but there is no 'Atoms' section",
                    f.natoms
                ),
            ));
        }
        Ok(())
    }
}

/// Parses the text of a data file of `atom_style granular`.
pub fn parse_data(text: &str) -> Result<DataFile, DataError> {
    parse_data_as(text, &AtomLayout::Granular)
}

/// Parses the text of a data file whose lines have the columns of `layout`.
pub fn parse_data_as(text: &str, layout: &AtomLayout) -> Result<DataFile, DataError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut f = DataFile {
        title: lines
            .first()
            .map(|s| s.trim_end().to_string())
            .unwrap_or_default(),
        natoms: 0,
        ntypes: 0,
        lo: DVec3::splat(-0.5),
        hi: DVec3::splat(0.5),
        atoms: Vec::new(),
        velocities: Vec::new(),
        layout: layout.clone(),
        nbondtypes: 0,
        bonds: Vec::new(),
    };
    if lines.is_empty() {
        return Err(err(1, 0..0, "the data file is empty"));
    }
    let mut p = Parser {
        lines,
        next: 1,
        nbonds: 0,
    };
    p.header(&mut f)?;
    if f.natoms > 0 && f.ntypes == 0 {
        let ln = Parser::lineno(p.next);
        return Err(err(
            ln,
            0..0,
            "the header has atoms but no 'atom types' line",
        ));
    }
    p.body(&mut f)?;
    Ok(f)
}

/// Reads and parses a data file of `atom_style granular` (`read_data`).
pub fn read_data(path: &Path) -> Result<DataFile, ReadDataError> {
    read_data_as(path, &AtomLayout::Granular)
}

/// Reads and parses a data file whose lines have the columns of `layout` (`read_data`).
/// Gzipped files are not supported.
pub fn read_data_as(path: &Path, layout: &AtomLayout) -> Result<DataFile, ReadDataError> {
    if path.extension().is_some_and(|e| e == "gz") {
        return Err(IoError::new(
            path,
            "read",
            std::io::Error::new(
                std::io::ErrorKind::Unsupported,
                "gzip-compressed data files are not supported; gunzip it first",
            ),
        )
        .into());
    }
    let text = std::fs::read_to_string(path).map_err(|e| IoError::new(path, "read", e))?;
    parse_data_as(&text, layout).map_err(|error| ReadDataError::Parse {
        path: path.to_path_buf(),
        error,
    })
}

/// Shortest text that reads back as exactly `v`, in plain notation for ordinary
/// magnitudes and exponent notation otherwise (C's `atof` reads both).
fn num(out: &mut String, v: f64) {
    let a = v.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) || !v.is_finite() {
        let _ = write!(out, "{v}");
    } else {
        let _ = write!(out, "{v:e}");
    }
}

impl DataFile {
    /// The owned particles of `p` (sorted by tag), the box of `d` and `ntypes` atom types.
    pub fn from_particles(p: &Particles, d: &Domain, ntypes: u32, title: &str) -> DataFile {
        let mut order: Vec<usize> = (0..p.nlocal()).collect();
        order.sort_by_key(|&i| p.tag[i]);
        DataFile {
            title: title.to_string(),
            natoms: order.len() as u64,
            ntypes,
            lo: d.boxlo,
            hi: d.boxhi,
            atoms: order
                .iter()
                .map(|&i| DataAtom {
                    id: p.tag[i],
                    ty: p.ty[i],
                    diameter: 2.0 * p.radius[i],
                    density: p.density[i],
                    x: p.x[i],
                    image: p.image[i].get(),
                    molecule: 0,
                    line: 0,
                })
                .collect(),
            velocities: order
                .iter()
                .map(|&i| DataVelocity {
                    id: p.tag[i],
                    v: p.v[i],
                    omega: p.omega[i],
                    line: 0,
                })
                .collect(),
            layout: AtomLayout::Granular,
            nbondtypes: 0,
            bonds: Vec::new(),
        }
    }

    /// The atoms as particles to add (in group `all` only), with velocities from the
    /// `Velocities` section (zero for atoms it does not list) and their image flags.
    pub fn new_particles(&self) -> Vec<(NewParticle, [i32; 3])> {
        let vel: std::collections::HashMap<Tag, &DataVelocity> =
            self.velocities.iter().map(|v| (v.id, v)).collect();
        self.atoms
            .iter()
            .map(|a| {
                let mut p = NewParticle::at(a.x, 0.5 * a.diameter, a.density)
                    .with_tag(a.id)
                    .with_type(a.ty);
                if let Some(v) = vel.get(&a.id) {
                    p = p.with_v(v.v).with_omega(v.omega);
                }
                (p, a.image)
            })
            .collect()
    }
}

/// The text of a data file that LIGGGHTS' `read_data` and [`parse_data_as`] (with the
/// file's layout) read back. The `Velocities` section is written only when the file has
/// one; bond counts and the `Bonds` section only under a layout with bonds.
pub fn format_data(f: &DataFile) -> String {
    let mut s = String::new();
    s.push_str(f.title.lines().next().unwrap_or(""));
    let _ = write!(s, "\n\n{} atoms\n{} atom types\n", f.natoms, f.ntypes);
    if f.layout.has_bonds() {
        let _ = write!(s, "{} bonds\n{} bond types\n", f.bonds.len(), f.nbondtypes);
    }
    s.push('\n');
    for (a, kw) in ["xlo xhi", "ylo yhi", "zlo zhi"].iter().enumerate() {
        num(&mut s, f.lo[a]);
        s.push(' ');
        num(&mut s, f.hi[a]);
        let _ = writeln!(s, " {kw}");
    }
    if !f.atoms.is_empty() {
        s.push_str("\nAtoms\n\n");
        for a in &f.atoms {
            let _ = write!(s, "{} {} ", a.id, a.ty);
            match &f.layout {
                AtomLayout::Granular => {
                    for v in [a.diameter, a.density, a.x.x, a.x.y, a.x.z] {
                        num(&mut s, v);
                        s.push(' ');
                    }
                }
                AtomLayout::Hybrid(subs) => {
                    for v in a.x.to_array() {
                        num(&mut s, v);
                        s.push(' ');
                    }
                    for k in subs {
                        match k {
                            SubStyle::Sphere => {
                                for v in [a.diameter, a.density] {
                                    num(&mut s, v);
                                    s.push(' ');
                                }
                            }
                            SubStyle::BondGran => {
                                let _ = write!(s, "{} ", a.molecule);
                            }
                        }
                    }
                }
            }
            let _ = writeln!(s, "{} {} {}", a.image[0], a.image[1], a.image[2]);
        }
    }
    if !f.velocities.is_empty() {
        s.push_str("\nVelocities\n\n");
        for v in &f.velocities {
            let _ = write!(s, "{}", v.id);
            for x in v.v.to_array().into_iter().chain(v.omega.to_array()) {
                s.push(' ');
                num(&mut s, x);
            }
            s.push('\n');
        }
    }
    if f.layout.has_bonds() && !f.bonds.is_empty() {
        s.push_str("\nBonds\n\n");
        for b in &f.bonds {
            let _ = writeln!(s, "{} {} {} {}", b.id, b.ty, b.atoms[0], b.atoms[1]);
        }
    }
    s
}

/// `write_data`: writes the owned particles of `p` and the box of `d` to `path`
/// (atomically, creating parent directories).
pub fn write_data(
    path: &Path,
    p: &Particles,
    d: &Domain,
    ntypes: u32,
    step: u64,
) -> Result<(), IoError> {
    let title = format!("LAMMPS data file via rdem write_data, timestep = {step}");
    let f = DataFile::from_particles(p, d, ntypes, &title);
    write_atomic(path, format_data(&f).as_bytes())
}

#[cfg(test)]
mod tests;
