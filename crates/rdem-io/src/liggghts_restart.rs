//! A reader of the binary restart files LIGGGHTS 3.8 writes (`write_restart`,
//! `restart N`), so that a study begun in LIGGGHTS can go on in rdem.
//!
//! The layout was learnt from files written by LIGGGHTS 3.8.0 (the Debian build) and
//! from the LAMMPS restart documentation; it is that of LAMMPS of 2013, on which
//! LIGGGHTS 3.8 is built. Every value is little-endian as written by an x86-64 build
//! (`int` 4 bytes, `bigint` 8, `double` 8); a string is an `int` length (NUL included)
//! and its bytes.
//!
//! ```text
//! header      (int flag, value)... until flag -1: version, integer sizes, units, step,
//!             dimension, processors, newton, periodicity and boundary per face,
//!             atom style, counts of atoms, types, bonds..., box, special factors
//! groups      int count, then (int length, name) per used slot of 32 (0 = empty slot)
//! type arrays (int flag, values)... until -1 (per-type mass; not written for granular)
//! force field (int flag, style, the style's own data)... until -1 (pair gran: an
//!             8-byte model hash code, then the pair_coeff flags of every type pair)
//! fixes       int count, then (id, style, int byte count, bytes) per fix with a state;
//!             int count, then (id, style, int largest per-atom length) per fix that
//!             stores values with each atom, in the order they follow each atom
//! atoms       per writing processor: int count of doubles, the doubles; per atom:
//!             length (this count of doubles), x y z, tag type mask image (integers
//!             stored bit for bit in a double), vx vy vz, radius, mass, density,
//!             omegax omegay omegaz, then each per-atom fix's values, led by their
//!             count (itself included)
//! ```
//!
//! The contact history fix (`contacthistory`, of `pair_style gran ... tangential
//! history`) stores with each atom its number of partners and, per partner, the
//! partner's tag and the history values: [`LiggghtsRestart::contact_history`] reads
//! them as `[tag i, tag j, values]` entries. Each pair is stored with both of its atoms
//! (LIGGGHTS uses `newton off` for granular pairs), the tangential values of the two
//! opposite in sign.
//!
//! Every damaged, truncated or foreign file is a [`LiggghtsRestartError`] naming the file,
//! the byte where reading stopped and what was expected there; no length read from the
//! file is trusted before the bytes it announces are known to be present.

use std::path::{Path, PathBuf};

use crate::atomic::IoError;

/// Why a LIGGGHTS restart file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum LiggghtsRestartError {
    /// The file could not be opened or read.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The file is damaged, truncated or holds something rdem does not read.
    #[error("'{path}' (a LIGGGHTS restart file): at byte {offset}: {what}")]
    Bad {
        /// The file.
        path: PathBuf,
        /// Where reading stopped.
        offset: usize,
        /// What is wrong.
        what: String,
    },
}

/// The pair style section of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct PairSection {
    /// The style (`gran`).
    pub style: String,
    /// LIGGGHTS' hash code of the contact model combination.
    pub model_hash: i64,
    /// `pair_coeff` set flags of the type pairs (i ≤ j, row by row).
    pub setflag: Vec<i32>,
}

/// A fix's global state.
#[derive(Debug, Clone, PartialEq)]
pub struct FixGlobal {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// The fix's own bytes.
    pub state: Vec<u8>,
}

/// Values a fix stores with every atom.
#[derive(Debug, Clone, PartialEq)]
pub struct PerAtomFix {
    /// Fix ID (`history_floor` for the wall history of fix `floor`, `contacthistory`
    /// for the pair contact history, the ID of a `fix property/atom`).
    pub id: String,
    /// Fix style.
    pub style: String,
    /// Largest number of values per atom (count included) at writing.
    pub maxsize: u32,
    /// Where each atom's values start in `values` (one more entry than atoms).
    pub start: Vec<usize>,
    /// The values of every atom, in atom order (the leading count left out).
    pub values: Vec<f64>,
}

impl PerAtomFix {
    /// The values of atom `k` (file order).
    pub fn of(&self, k: usize) -> &[f64] {
        &self.values[self.start[k]..self.start[k + 1]]
    }
}

/// The atoms of the file, in file order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Atoms {
    /// Tags.
    pub tag: Vec<u64>,
    /// Types (1-based).
    pub ty: Vec<u32>,
    /// Group masks (bit k: group slot k).
    pub mask: Vec<u32>,
    /// Periodic image counts.
    pub image: Vec<[i32; 3]>,
    /// Positions.
    pub x: Vec<[f64; 3]>,
    /// Velocities.
    pub v: Vec<[f64; 3]>,
    /// Angular velocities.
    pub omega: Vec<[f64; 3]>,
    /// Radii.
    pub radius: Vec<f64>,
    /// Masses.
    pub rmass: Vec<f64>,
    /// Densities.
    pub density: Vec<f64>,
}

impl Atoms {
    /// Number of atoms.
    pub fn len(&self) -> usize {
        self.tag.len()
    }
    /// True without atoms.
    pub fn is_empty(&self) -> bool {
        self.tag.is_empty()
    }
}

/// Pair contact histories read from the contact history fix.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactHistory {
    /// History values per contact.
    pub width: usize,
    /// `[tag i, tag j, width values]` per contact as atom i stored it; every pair
    /// appears twice, once from each atom.
    pub entries: Vec<f64>,
}

/// Everything rdem reads from a LIGGGHTS 3.8 restart file.
#[derive(Debug, Clone, PartialEq)]
pub struct LiggghtsRestart {
    /// The version string of the LIGGGHTS that wrote it.
    pub version: String,
    /// `units` style.
    pub units: String,
    /// Step.
    pub step: u64,
    /// `dimension`.
    pub dimension: u32,
    /// Processors that wrote it.
    pub nprocs: u32,
    /// `newton` pair and bond settings.
    pub newton: [i32; 2],
    /// Boundary letters per face (`p`, `f`, `s`, `m`).
    pub boundary: [[char; 2]; 3],
    /// Atom style.
    pub atom_style: String,
    /// Atoms announced by the header.
    pub natoms: u64,
    /// Atom types.
    pub ntypes: u32,
    /// Box corners.
    pub boxlo: [f64; 3],
    /// Box corners.
    pub boxhi: [f64; 3],
    /// Tilt factors `xy xz yz` when the box is triclinic.
    pub tilt: Option<[f64; 3]>,
    /// Group names by bit (32 slots, slot 0 `all`).
    pub groups: Vec<Option<String>>,
    /// Per-type masses, when the atom style has them.
    pub masses: Option<Vec<f64>>,
    /// The pair style section.
    pub pair: Option<PairSection>,
    /// Fixes with a global state.
    pub fixes: Vec<FixGlobal>,
    /// Fixes that store values with every atom.
    pub peratom: Vec<PerAtomFix>,
    /// The atoms.
    pub atoms: Atoms,
}

/// True when `bytes` begin as a LIGGGHTS restart file: the version flag (0), the length
/// of the version string and `Version LIGGGHTS`.
pub fn is_liggghts_restart(bytes: &[u8]) -> bool {
    const SIG: &[u8] = b"Version LIGGGHTS";
    bytes.len() >= 8 + SIG.len() && bytes[..4] == [0, 0, 0, 0] && bytes[8..].starts_with(SIG)
}

/// Reads the LIGGGHTS restart file at `path`.
pub fn read_liggghts_restart(path: &Path) -> Result<LiggghtsRestart, LiggghtsRestartError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, "read", e))?;
    parse_liggghts_restart(path, &bytes)
}

/// Header flags of LIGGGHTS 3.8 (LAMMPS 2013), in their numbering.
mod flag {
    pub const VERSION: i32 = 0;
    pub const SMALLINT: i32 = 1;
    pub const TAGINT: i32 = 2;
    pub const BIGINT: i32 = 3;
    pub const UNITS: i32 = 4;
    pub const NTIMESTEP: i32 = 5;
    pub const DIMENSION: i32 = 6;
    pub const NPROCS: i32 = 7;
    pub const NEWTON_PAIR: i32 = 11;
    pub const NEWTON_BOND: i32 = 12;
    pub const XPERIODIC: i32 = 13;
    pub const BOUNDARY_00: i32 = 16;
    pub const BOUNDARY_21: i32 = 21;
    pub const ATOM_STYLE: i32 = 22;
    pub const NATOMS: i32 = 23;
    pub const NTYPES: i32 = 24;
    pub const NBONDS: i32 = 25;
    pub const IMPROPER_PER_ATOM: i32 = 36;
    pub const BOXLO_0: i32 = 37;
    pub const BOXHI_2: i32 = 42;
    pub const SPECIAL_COUL_3: i32 = 48;
    pub const XY: i32 = 49;
    pub const YZ: i32 = 51;
}

/// Values per atom before the fixes' values in `atom_style granular` (the length
/// included).
const GRANULAR_VALUES: usize = 17;

/// Reads the file's bytes in order; every failure names the byte it stopped at.
struct Reader<'a> {
    path: &'a Path,
    buf: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn err(&self, offset: usize, what: impl Into<String>) -> LiggghtsRestartError {
        LiggghtsRestartError::Bad {
            path: self.path.to_path_buf(),
            offset,
            what: what.into(),
        }
    }
    fn left(&self) -> usize {
        self.buf.len() - self.at
    }
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], LiggghtsRestartError> {
        if n > self.left() {
            return Err(self.err(
                self.at,
                format!(
                    "the file ends ({} bytes) inside {what}, which needs {n} more bytes: it is truncated",
                    self.buf.len()
                ),
            ));
        }
        let s = &self.buf[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }
    fn int(&mut self, what: &str) -> Result<i32, LiggghtsRestartError> {
        Ok(i32::from_le_bytes(
            self.take(4, what)?.try_into().expect("4 bytes"),
        ))
    }
    /// An `int` in `lo..=hi`.
    fn int_in(&mut self, what: &str, lo: i32, hi: i32) -> Result<i32, LiggghtsRestartError> {
        let at = self.at;
        let v = self.int(what)?;
        if v < lo || v > hi {
            return Err(self.err(at, format!("{what} is {v}, not in {lo}..{hi}")));
        }
        Ok(v)
    }
    fn bigint(&mut self, what: &str) -> Result<i64, LiggghtsRestartError> {
        Ok(i64::from_le_bytes(
            self.take(8, what)?.try_into().expect("8 bytes"),
        ))
    }
    fn double(&mut self, what: &str) -> Result<f64, LiggghtsRestartError> {
        Ok(f64::from_le_bytes(
            self.take(8, what)?.try_into().expect("8 bytes"),
        ))
    }
    /// A string: `int` length with the NUL, the bytes.
    fn string(&mut self, what: &str) -> Result<String, LiggghtsRestartError> {
        let at = self.at;
        let n = self.int_in(&format!("the length of {what}"), 1, 4096)? as usize;
        let s = self.take(n, what)?;
        if s[n - 1] != 0 || s[..n - 1].contains(&0) {
            return Err(self.err(
                at,
                format!("{what} is not a string of {n} bytes ending in NUL"),
            ));
        }
        String::from_utf8(s[..n - 1].to_vec())
            .map_err(|_| self.err(at, format!("{what} is not text")))
    }
    fn doubles(&mut self, n: usize, what: &str) -> Result<Vec<f64>, LiggghtsRestartError> {
        let bytes = self.take(n.saturating_mul(8), what)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect())
    }
}

fn boundary_letter(code: i32) -> Option<char> {
    ['p', 'f', 's', 'm']
        .get(usize::try_from(code).ok()?)
        .copied()
}

/// Parses the bytes of a LIGGGHTS restart file read from `path`.
pub fn parse_liggghts_restart(
    path: &Path,
    bytes: &[u8],
) -> Result<LiggghtsRestart, LiggghtsRestartError> {
    let mut r = Reader {
        path,
        buf: bytes,
        at: 0,
    };
    if !is_liggghts_restart(bytes) {
        return Err(r.err(0, "it does not begin with LIGGGHTS' version string"));
    }
    let mut f = LiggghtsRestart {
        version: String::new(),
        units: String::new(),
        step: 0,
        dimension: 3,
        nprocs: 0,
        newton: [0, 0],
        boundary: [['p'; 2]; 3],
        atom_style: String::new(),
        natoms: 0,
        ntypes: 0,
        boxlo: [0.0; 3],
        boxhi: [0.0; 3],
        tilt: None,
        groups: vec![None; 32],
        masses: None,
        pair: None,
        fixes: Vec::new(),
        peratom: Vec::new(),
        atoms: Atoms::default(),
    };
    header(&mut r, &mut f)?;
    groups(&mut r, &mut f)?;
    type_arrays(&mut r, &mut f)?;
    force_fields(&mut r, &mut f)?;
    fixes(&mut r, &mut f)?;
    atoms(&mut r, &mut f)?;
    Ok(f)
}

fn header(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    let mut seen_style = false;
    let mut seen_box = 0;
    loop {
        let at = r.at;
        let fl = r.int("a header flag")?;
        if fl < 0 {
            break;
        }
        match fl {
            flag::VERSION => f.version = r.string("the version string")?,
            flag::SMALLINT | flag::TAGINT | flag::BIGINT => {
                let want = if fl == flag::BIGINT { 8 } else { 4 };
                let name = ["smallint", "tagint", "bigint"][(fl - 1) as usize];
                let v = r.int(name)?;
                if v != want {
                    return Err(r.err(
                        at,
                        format!("it was written with a {v}-byte {name}; rdem reads files of LIGGGHTS built with {want}-byte ones"),
                    ));
                }
            }
            flag::UNITS => f.units = r.string("the units")?,
            flag::NTIMESTEP => {
                let s = r.bigint("the step")?;
                f.step = u64::try_from(s).map_err(|_| r.err(at, format!("the step is {s}")))?;
            }
            flag::DIMENSION => f.dimension = r.int_in("the dimension", 2, 3)? as u32,
            flag::NPROCS => f.nprocs = r.int_in("the number of processors", 1, 1 << 24)? as u32,
            8..=10 => {
                r.int("the processor grid")?;
            }
            flag::NEWTON_PAIR | flag::NEWTON_BOND => {
                f.newton[(fl - flag::NEWTON_PAIR) as usize] = r.int("a newton setting")?
            }
            13..=15 => {
                let p = r.int_in("a periodicity flag", 0, 1)?;
                if p == 1 {
                    let d = (fl - flag::XPERIODIC) as usize;
                    f.boundary[d] = ['p', 'p'];
                }
            }
            flag::BOUNDARY_00..=flag::BOUNDARY_21 => {
                let k = (fl - flag::BOUNDARY_00) as usize;
                let c = r.int_in("a boundary code", 0, 3)?;
                f.boundary[k / 2][k % 2] = boundary_letter(c).expect("0..=3");
            }
            flag::ATOM_STYLE => {
                f.atom_style = r.string("the atom style")?;
                if f.atom_style == "hybrid" {
                    return Err(r.err(
                        at,
                        "its atom style is hybrid; rdem reads files of atom_style granular",
                    ));
                }
                seen_style = true;
            }
            flag::NATOMS => {
                let n = r.bigint("the number of atoms")?;
                f.natoms = u64::try_from(n).map_err(|_| r.err(at, format!("{n} atoms")))?;
            }
            flag::NTYPES => f.ntypes = r.int_in("the number of atom types", 1, 1 << 16)? as u32,
            flag::NBONDS..=flag::IMPROPER_PER_ATOM => {
                // Counts of bonds, angles, dihedrals, impropers (bigint), their types
                // and per-atom maxima (int): LIGGGHTS' granular files hold none.
                let big = matches!(fl, 25 | 28 | 31 | 34);
                let v = if big {
                    r.bigint("a topology count")?
                } else {
                    r.int("a topology count")? as i64
                };
                if v != 0 {
                    return Err(r.err(
                        at,
                        format!("it holds molecular topology (header item {fl} is {v}), which rdem does not read"),
                    ));
                }
            }
            flag::BOXLO_0..=flag::BOXHI_2 => {
                let k = (fl - flag::BOXLO_0) as usize;
                let v = r.double("a box bound")?;
                if !v.is_finite() {
                    return Err(r.err(at, format!("a box bound is {v}")));
                }
                if k % 2 == 0 {
                    f.boxlo[k / 2] = v;
                } else {
                    f.boxhi[k / 2] = v;
                }
                seen_box += 1;
            }
            43..=flag::SPECIAL_COUL_3 => {
                r.double("a special_bonds factor")?;
            }
            flag::XY..=flag::YZ => {
                let v = r.double("a tilt factor")?;
                f.tilt.get_or_insert([0.0; 3])[(fl - flag::XY) as usize] = v;
            }
            _ => {
                return Err(r.err(
                    at,
                    format!(
                        "header item {fl} is not one LIGGGHTS 3.8 writes (is the file damaged?)"
                    ),
                ))
            }
        }
    }
    if !seen_style || seen_box != 6 || f.ntypes == 0 || f.nprocs == 0 || f.units.is_empty() {
        return Err(r.err(
            r.at,
            "its header lacks the atom style, the box, the number of types, of processors or the units",
        ));
    }
    if f.atom_style != "granular" && f.atom_style != "sphere" {
        return Err(r.err(
            r.at,
            format!(
                "its atom style is '{}'; rdem reads files of atom_style granular (sphere)",
                f.atom_style
            ),
        ));
    }
    Ok(())
}

fn groups(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    let ngroup = r.int_in("the number of groups", 1, 32)? as usize;
    let mut count = 0;
    for slot in 0..32 {
        if count == ngroup {
            break;
        }
        let at = r.at;
        let n = r.int_in("the length of a group name", 0, 4096)?;
        if n > 0 {
            r.at = at;
            f.groups[slot] = Some(r.string("a group name")?);
            count += 1;
        }
    }
    if count != ngroup || f.groups[0].as_deref() != Some("all") {
        return Err(r.err(
            r.at,
            format!("its group table is damaged ({count} of {ngroup} groups found, or slot 0 is not 'all')"),
        ));
    }
    Ok(())
}

fn type_arrays(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    loop {
        let at = r.at;
        match r.int("a type array flag")? {
            -1 => return Ok(()),
            0 => f.masses = Some(r.doubles(f.ntypes as usize, "the per-type masses")?),
            fl => {
                return Err(r.err(
                    at,
                    format!("type array item {fl} is not one LIGGGHTS 3.8 writes"),
                ))
            }
        }
    }
}

fn force_fields(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    loop {
        let at = r.at;
        match r.int("a force field flag")? {
            -1 => return Ok(()),
            0 => {
                let style = r.string("the pair style")?;
                if !style.starts_with("gran") {
                    return Err(r.err(
                        at,
                        format!("its pair style is '{style}', whose restart data rdem does not know (it reads pair_style gran)"),
                    ));
                }
                let model_hash = r.bigint("the contact model code")?;
                let n = f.ntypes as usize;
                // No more room than the bytes present can hold (a flag is a 4-byte int).
                let mut setflag = Vec::with_capacity((n * (n + 1) / 2).min(r.left() / 4));
                for _ in 0..n * (n + 1) / 2 {
                    setflag.push(r.int_in("a pair_coeff flag", 0, 1)?);
                }
                f.pair = Some(PairSection {
                    style,
                    model_hash,
                    setflag,
                });
            }
            fl @ 1..=4 => {
                let what = ["bond", "angle", "dihedral", "improper"][(fl - 1) as usize];
                return Err(r.err(
                    at,
                    format!("it holds a {what} style, which rdem does not read"),
                ));
            }
            fl => {
                return Err(r.err(
                    at,
                    format!("force field item {fl} is not one LIGGGHTS 3.8 writes"),
                ))
            }
        }
    }
}

fn fixes(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    let n = r.int_in("the number of fixes with a state", 0, 100_000)?;
    for _ in 0..n {
        let id = r.string("a fix ID")?;
        let style = r.string("a fix style")?;
        let len = r.int_in(&format!("the state length of fix {id}"), 0, i32::MAX)? as usize;
        let state = r.take(len, &format!("the state of fix {id}"))?.to_vec();
        f.fixes.push(FixGlobal { id, style, state });
    }
    let n = r.int_in("the number of fixes with per-atom values", 0, 100_000)?;
    for _ in 0..n {
        let id = r.string("a fix ID")?;
        let style = r.string("a fix style")?;
        let maxsize = r.int_in(&format!("the per-atom size of fix {id}"), 0, i32::MAX)? as u32;
        f.peratom.push(PerAtomFix {
            id,
            style,
            maxsize,
            start: vec![0],
            values: Vec::new(),
        });
    }
    Ok(())
}

/// An integer stored bit for bit in a double (LIGGGHTS' `ubuf`).
fn ubuf(v: f64) -> i64 {
    v.to_bits() as i64
}

/// A count stored as a double value.
fn count(v: f64) -> Option<usize> {
    (v.fract() == 0.0 && (1.0..1e9).contains(&v)).then_some(v as usize)
}

fn atoms(r: &mut Reader, f: &mut LiggghtsRestart) -> Result<(), LiggghtsRestartError> {
    // No more room than the bytes present can hold.
    let cap = (f.natoms as usize).min(r.left() / (8 * GRANULAR_VALUES));
    let a = &mut f.atoms;
    *a = Atoms {
        tag: Vec::with_capacity(cap),
        ty: Vec::with_capacity(cap),
        mask: Vec::with_capacity(cap),
        image: Vec::with_capacity(cap),
        x: Vec::with_capacity(cap),
        v: Vec::with_capacity(cap),
        omega: Vec::with_capacity(cap),
        radius: Vec::with_capacity(cap),
        rmass: Vec::with_capacity(cap),
        density: Vec::with_capacity(cap),
    };
    for chunk in 0..f.nprocs {
        let n = r.int_in(
            &format!("the length of processor {chunk}'s atoms"),
            0,
            i32::MAX,
        )? as usize;
        let base = r.at;
        let d = r.doubles(n, &format!("processor {chunk}'s atoms"))?;
        let mut m = 0;
        while m < n {
            let at = base + 8 * m;
            let bad = |what: String| r.err(at, format!("atom {} of the file: {what}", a.len() + 1));
            let size = count(d[m])
                .filter(|&s| s >= GRANULAR_VALUES && m + s <= n)
                .ok_or_else(|| {
                    bad(format!(
                        "its length {} is not a whole number of values from {GRANULAR_VALUES} to the {} left in its block",
                        d[m],
                        n - m
                    ))
                })?;
            let rec = &d[m..m + size];
            let tag = ubuf(rec[4]);
            let ty = ubuf(rec[5]);
            let mask = ubuf(rec[6]);
            let image = ubuf(rec[7]);
            if tag <= 0 || tag > i64::from(i32::MAX) {
                return Err(bad(format!("its tag is {tag}")));
            }
            if ty < 1 || ty > i64::from(f.ntypes) {
                return Err(bad(format!(
                    "its type is {ty}, the file has {} types",
                    f.ntypes
                )));
            }
            let mask = u32::try_from(mask).map_err(|_| bad(format!("its group mask is {mask}")))?;
            let image =
                u32::try_from(image).map_err(|_| bad(format!("its image flags are {image}")))?;
            let finite = rec[1..GRANULAR_VALUES].iter().all(|v| v.is_finite());
            if !finite || rec[11] <= 0.0 || rec[12] <= 0.0 {
                return Err(bad(
                    "it has a value that is not finite, or a radius or mass that is not positive"
                        .into(),
                ));
            }
            // Image counts: 10 bits per axis, offset by 512 (LIGGGHTS' 4-byte imageint).
            let img = |k: u32| ((image >> (10 * k)) & 1023) as i32 - 512;
            a.x.push([rec[1], rec[2], rec[3]]);
            a.tag.push(tag as u64);
            a.ty.push(ty as u32);
            a.mask.push(mask);
            a.image.push([img(0), img(1), img(2)]);
            a.v.push([rec[8], rec[9], rec[10]]);
            a.radius.push(rec[11]);
            a.rmass.push(rec[12]);
            a.density.push(rec[13]);
            a.omega.push([rec[14], rec[15], rec[16]]);
            // The fixes' values: each led by its count (itself included).
            let mut k = GRANULAR_VALUES;
            for p in f.peratom.iter_mut() {
                let len = rec
                    .get(k)
                    .and_then(|&v| count(v))
                    .filter(|&l| k + l <= size)
                    .ok_or_else(|| {
                        r.err(
                            at,
                            format!(
                                "atom {} of the file: the values of fix {} do not fit in its length {size}",
                                a.len(),
                                p.id
                            ),
                        )
                    })?;
                p.values.extend_from_slice(&rec[k + 1..k + len]);
                p.start.push(p.values.len());
                k += len;
            }
            if k != size {
                return Err(r.err(
                    at,
                    format!(
                        "atom {} of the file: its length is {size}, its values {k}",
                        a.len()
                    ),
                ));
            }
            m += size;
        }
    }
    if r.left() != 0 {
        return Err(r.err(
            r.at,
            format!("{} bytes follow the last processor's atoms", r.left()),
        ));
    }
    if a.len() as u64 != f.natoms {
        return Err(r.err(
            r.at,
            format!(
                "the header announces {} atoms, the file holds {}",
                f.natoms,
                a.len()
            ),
        ));
    }
    Ok(())
}

impl LiggghtsRestart {
    /// The pair contact histories of the contact history fix (`contacthistory`), if
    /// the file has one: per atom, the number of partners, then per partner its tag
    /// and the history values.
    pub fn contact_history(&self) -> Option<Result<ContactHistory, ContactHistoryError>> {
        let fix = self.peratom.iter().find(|p| p.style == "contacthistory")?;
        Some(read_contacts(fix, &self.atoms.tag))
    }
}

/// What is wrong with the contact history of atom `tag` in a LIGGGHTS restart file
/// ([`LiggghtsRestart::contact_history`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("the contact history of atom {tag}: {what}")]
pub struct ContactHistoryError {
    /// The atom's tag.
    pub tag: u64,
    /// What is wrong.
    pub what: BadContacts,
}

/// The fault of a [`ContactHistoryError`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BadContacts {
    /// The atom's values are empty.
    #[error("no partner count")]
    NoCount,
    /// The partner count is negative.
    #[error("a negative partner count")]
    NegativeCount,
    /// The values do not split into the partners.
    #[error("{values} values for {partners} partners")]
    Split {
        /// Values after the count.
        values: usize,
        /// Partners.
        partners: usize,
    },
    /// Another number of values per contact than the atoms before.
    #[error("{width} values per contact, other atoms {other}")]
    Width {
        /// This atom's.
        width: usize,
        /// The atoms' before.
        other: usize,
    },
    /// A partner tag that is not positive.
    #[error("partner tag {0}")]
    PartnerTag(i64),
}

fn read_contacts(fix: &PerAtomFix, tags: &[u64]) -> Result<ContactHistory, ContactHistoryError> {
    let mut width: Option<usize> = None;
    let mut entries = Vec::new();
    for (k, &tag) in tags.iter().enumerate() {
        let v = fix.of(k);
        let bad = |what: BadContacts| ContactHistoryError { tag, what };
        let np = v
            .first()
            .map(|&x| ubuf(x))
            .ok_or_else(|| bad(BadContacts::NoCount))?;
        let np = usize::try_from(np).map_err(|_| bad(BadContacts::NegativeCount))?;
        if np == 0 {
            continue;
        }
        let rest = v.len() - 1;
        if rest % np != 0 || rest / np < 2 {
            return Err(bad(BadContacts::Split {
                values: rest,
                partners: np,
            }));
        }
        let w = rest / np - 1;
        if *width.get_or_insert(w) != w {
            return Err(bad(BadContacts::Width {
                width: w,
                other: width.unwrap_or(0),
            }));
        }
        for c in v[1..].chunks_exact(w + 1) {
            let j = ubuf(c[0]);
            if j <= 0 {
                return Err(bad(BadContacts::PartnerTag(j)));
            }
            entries.push(tag as f64);
            entries.push(j as f64);
            entries.extend_from_slice(&c[1..]);
        }
    }
    Ok(ContactHistory {
        width: width.unwrap_or(0),
        entries,
    })
}
