//! `read_dump file Nstep field ... keyword value ...`: particles of one snapshot of a
//! native text dump file (as `dump custom` writes it) replace, are added to or trim the
//! current ones; the snapshot's step becomes the current step and, with `box yes`, its box
//! the simulation box.
//!
//! Checked on LIGGGHTS 3.8 (the runs are in tests/read_dump.rs):
//! - the fields are `x y z vx vy vz ix iy iz radius`, and `radius` must be one of them
//!   (`q` stops: granular particles carry no charge; `density`, `mass`, `omegax` are
//!   not read_dump fields and stop);
//! - a replaced particle keeps its type, density and mass (its mass is not recomputed
//!   from the new radius);
//! - an added particle gets the next free ID (as `create_atoms`; the dump's ID is not
//!   kept), the dump's type, density 1 and the mass of a sphere of radius 0.5 and
//!   density 1 (its read radius does not change its mass): use `set ... density` after;
//!   fields not read are 0;
//! - an added particle outside a fixed face of the box is dropped without a word;
//! - `purge yes` needs `replace no` (the default `replace yes` stops), `add keep` stops.

mod snapshot;

use crate::error::Error;
use std::collections::{HashMap, HashSet};

use glam::DVec3;

use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The fields LIGGGHTS 3.8's read_dump reads for granular particles.
const FIELDS: [&str; 11] = [
    "x", "y", "z", "vx", "vy", "vz", "q", "ix", "iy", "iz", "radius",
];

/// The keywords.
const KEYWORDS: [&str; 9] = [
    "box", "replace", "purge", "trim", "add", "label", "scaled", "wrapped", "format",
];

/// What the words ask.
struct Request {
    file: String,
    nstep: u64,
    /// Fields in order, with their word.
    fields: Vec<(&'static str, usize)>,
    box_: bool,
    replace: bool,
    purge: bool,
    trim: bool,
    add: bool,
    /// `label FIELD COLUMN`.
    labels: HashMap<&'static str, String>,
    scaled: bool,
    wrapped: bool,
}

fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Request> {
    let file = a.word("dump file")?.to_string();
    if file.ends_with(".gz") || file.ends_with(".bin") || file.contains('%') {
        return Err(a.error_prev(
            "gzipped, binary and per-processor dump files are not supported yet",
            None,
        ));
    }
    let nstep = a.u64("Nstep")?;
    let mut fields = Vec::new();
    while let Some(w) = a.peek() {
        if KEYWORDS.contains(&w) {
            break;
        }
        let k = a.pos();
        let f = a.keyword("read_dump field", &FIELDS)?;
        if f == "q" {
            return Err(a.error_at(k, "granular particles carry no charge (q)", None));
        }
        if sim.setup.dimension == 2 && matches!(f, "z" | "vz" | "iz") {
            return Err(a.error_at(k, format!("{f} cannot be read in a 2d simulation"), None));
        }
        if fields.iter().any(|(g, _)| *g == f) {
            return Err(a.error_at(k, format!("field {f} is listed twice"), None));
        }
        fields.push((f, k));
    }
    if fields.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "read_dump needs at least one field",
            Some(FIELDS.join(" ")),
        ));
    }
    if !fields.iter().any(|(f, _)| *f == "radius") {
        return Err(a.error_at(
            fields[0].1,
            "read_dump: the radius field is required to be read (as in LIGGGHTS 3.8)",
            None,
        ));
    }
    let mut r = Request {
        file,
        nstep,
        fields,
        box_: true,
        replace: true,
        purge: false,
        trim: false,
        add: false,
        labels: HashMap::new(),
        scaled: false,
        wrapped: true,
    };
    let mut purge_word = 0;
    while !a.is_done() {
        match a.keyword("read_dump keyword", &KEYWORDS)? {
            "box" => r.box_ = a.yes_no("box")?,
            "replace" => r.replace = a.yes_no("replace")?,
            "purge" => {
                purge_word = a.pos() - 1;
                r.purge = a.yes_no("purge")?;
            }
            "trim" => r.trim = a.yes_no("trim")?,
            "add" => r.add = a.yes_no("add")?,
            "scaled" => r.scaled = a.yes_no("scaled")?,
            "wrapped" => r.wrapped = a.yes_no("wrapped")?,
            "label" => {
                let mut valid = FIELDS.to_vec();
                valid.extend(["id", "type"]);
                let f = a.keyword("label field", &valid)?;
                r.labels.insert(f, a.word("column label")?.to_string());
            }
            _ => {
                let k = a.pos();
                if a.keyword("format", &["native", "xyz"])? == "xyz" {
                    return Err(a.error_at(k, "read_dump format xyz is not supported yet", None));
                }
                if !a.is_done() {
                    return Err(a.error_at(
                        a.pos(),
                        "format must be the last keyword of read_dump",
                        None,
                    ));
                }
            }
        }
    }
    if r.purge && (r.replace || r.trim) {
        return Err(a.error_at(
            purge_word,
            "if read_dump purges it cannot replace or trim",
            Some("add 'replace no' (replace is yes by default)".into()),
        ));
    }
    Ok(r)
}

/// The column of each field and of `id`, `type`, and whether the coordinates are scaled
/// and wrapped.
struct Columns {
    id: usize,
    ty: Option<usize>,
    fields: Vec<(&'static str, usize)>,
    scaled: bool,
    wrapped: bool,
}

fn columns(r: &Request, s: &snapshot::Snapshot) -> Result<Columns, Error> {
    let find = |f: &str, default: &str| -> Result<usize, Error> {
        let label = r.labels.get(f).map_or(default, |s| s.as_str());
        s.column(label).ok_or_else(|| {
            Error::invalid(format!(
                "the snapshot has no column '{label}' (its columns: {})",
                s.labels.join(" ")
            ))
        })
    };
    let id = find("id", "id")?;
    let ty = if r.add {
        Some(find("type", "type")?)
    } else {
        None
    };
    let mut fields = Vec::new();
    let mut kind: Option<(bool, bool)> = None;
    for &(f, _) in &r.fields {
        let (col, k) = if let (true, Some(label)) = (matches!(f, "x" | "y" | "z"), r.labels.get(f))
        {
            let c = s
                .column(label)
                .ok_or_else(|| format!("the snapshot has no column '{label}'"))?;
            (c, (r.scaled, r.wrapped))
        } else if matches!(f, "x" | "y" | "z") {
            let found = ["", "s", "u", "su"].iter().find_map(|suffix| {
                s.column(&format!("{f}{suffix}"))
                    .map(|c| (c, (suffix.contains('s'), !suffix.contains('u'))))
            });
            found.ok_or_else(|| format!("the snapshot has no column {f}, {f}s, {f}u or {f}su"))?
        } else {
            (find(f, f)?, (false, true))
        };
        if matches!(f, "x" | "y" | "z") {
            if kind.is_some_and(|kk| kk != k) {
                return Err("the x, y, z columns must all be scaled or unscaled, wrapped or unwrapped alike".into());
            }
            kind = Some(k);
        }
        fields.push((f, col));
    }
    let (scaled, wrapped) = kind.unwrap_or((false, true));
    Ok(Columns {
        id,
        ty,
        fields,
        scaled,
        wrapped,
    })
}

/// The command.
pub(super) fn read_dump(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let r = parse(sim, a)?;
    if sim.script.check {
        return Ok(());
    }
    let text = std::fs::read_to_string(&r.file)
        .map_err(|e| a.error_at(1, format!("{}: {e}", r.file), None))?;
    sim.world_ref(a)?;
    sim.outputs.out.line("Scanning dump file ...");
    let snap = snapshot::find(&text, r.nstep).map_err(|e| a.error_at(2, e, None))?;
    let cols = columns(&r, &snap).map_err(|e| a.error_at(1, e, None))?;
    sim.outputs.out.line("Reading snapshot from dump file ...");
    let w = sim.world.as_mut().expect("checked");
    let (slo, shi) = (DVec3::from(snap.lo), DVec3::from(snap.hi));
    if r.box_ {
        w.domain.boxlo = slo;
        w.domain.boxhi = shi;
        w.domain.initial_lo = slo;
        w.domain.initial_hi = shi;
        w.domain.update_subdomain();
    }
    let d = &w.domain;
    let g = crate::variables::g;
    let box_line = format!(
        "  orthogonal box = ({} {} {}) to ({} {} {})",
        g(d.boxlo.x),
        g(d.boxlo.y),
        g(d.boxlo.z),
        g(d.boxhi.x),
        g(d.boxhi.y),
        g(d.boxhi.z)
    );
    let before = w.natoms();
    w.neighbor.save_history(&w.particles);
    w.particles.clear_ghosts();
    let mut purged = 0;
    if r.purge {
        let n = w.particles.nlocal();
        purged = w
            .comm
            .sum_count(w.particles.remove_locals(&vec![true; n]) as u64);
    }
    let tags: HashMap<u64, usize> = (0..w.particles.nlocal())
        .map(|i| (w.particles.tag[i], i))
        .collect();
    let mine: Vec<f64> = tags.keys().map(|&t| t as f64).collect();
    let everywhere: HashSet<u64> = w.comm.all_gather(&mine).iter().map(|&t| t as u64).collect();
    // The value of one particle's coordinate `axis` read from the dump.
    let coord = |row: &[f64], col: usize, axis: usize| {
        let v = row[col];
        if cols.scaled {
            slo[axis] + v * (shi[axis] - slo[axis])
        } else {
            v
        }
    };
    let mut replaced = 0;
    let mut in_dump = HashSet::new();
    let mut new = Vec::new();
    for row in &snap.rows {
        let tag = row[cols.id] as u64;
        in_dump.insert(tag);
        let p = &mut w.particles;
        let i = match tags.get(&tag) {
            Some(&i) if r.replace => i,
            Some(_) => continue,
            None if r.add && !everywhere.contains(&tag) => {
                new.push(row);
                continue;
            }
            None => continue,
        };
        replaced += 1;
        if !cols.wrapped {
            p.image[i] = Default::default();
        }
        for &(f, c) in &cols.fields {
            set_field(p, i, f, row, c, &coord);
        }
        let (mut x, mut im) = (p.x[i], p.image[i].get());
        w.domain.remap(&mut x, &mut im);
        (p.x[i], p.image[i]) = (x, im.into());
    }
    let mut trimmed = 0;
    if r.trim {
        let p = &w.particles;
        let remove: Vec<bool> = (0..p.nlocal())
            .map(|i| !in_dump.contains(&p.tag[i]))
            .collect();
        trimmed = w.particles.remove_locals(&remove) as u64;
    }
    let mut added = 0;
    for row in new {
        let ty = row[cols.ty.expect("add reads types")] as u32;
        let mut np = super::create::new_default(DVec3::ZERO, ty);
        np.mask = 1;
        let mut radius = 0.5;
        let mut image = [0; 3];
        for &(f, c) in &cols.fields {
            let v = row[c];
            match f {
                "x" => np.x.x = coord(row, c, 0),
                "y" => np.x.y = coord(row, c, 1),
                "z" => np.x.z = coord(row, c, 2),
                "vx" => np.v.x = v,
                "vy" => np.v.y = v,
                "vz" => np.v.z = v,
                "ix" => image[0] = v as i32,
                "iy" => image[1] = v as i32,
                "iz" => image[2] = v as i32,
                _ => radius = v,
            }
        }
        if !cols.wrapped {
            image = [0; 3];
        }
        w.domain.remap(&mut np.x, &mut image);
        added += 1;
        if w.domain.check_inside_fixed(np.x).is_err() || !w.owns_point(np.x) {
            continue;
        }
        let i = w
            .add_particle(&np)
            .map_err(|e| a.error_cmd(e.to_string(), None))?;
        w.particles.image[i] = image.into();
        w.particles.radius[i] = radius;
    }
    w.extend_tags();
    let replaced = w.comm.sum_count(replaced);
    let trimmed = w.comm.sum_count(trimmed);
    let after = before - purged - trimmed + added;
    let out = &mut sim.outputs.out;
    out.line(&box_line);
    out.line(&format!("  {before} atoms before read"));
    out.line(&format!("  {} atoms in snapshot", snap.rows.len()));
    out.line(&format!("  {purged} atoms purged"));
    out.line(&format!("  {replaced} atoms replaced"));
    out.line(&format!("  {trimmed} atoms trimmed"));
    out.line(&format!("  {added} atoms added"));
    out.line(&format!("  {after} atoms after read"));
    let w = sim.world.as_mut().expect("checked");
    w.step = r.nstep;
    Ok(())
}

/// Sets field `f` of particle `i` from `row[c]` (coordinates through `coord`); the mass
/// stays (LIGGGHTS 3.8 does not recompute it from a read radius).
fn set_field(
    p: &mut rdem::Particles,
    i: usize,
    f: &str,
    row: &[f64],
    c: usize,
    coord: &dyn Fn(&[f64], usize, usize) -> f64,
) {
    let v = row[c];
    match f {
        "x" => p.x[i].x = coord(row, c, 0),
        "y" => p.x[i].y = coord(row, c, 1),
        "z" => p.x[i].z = coord(row, c, 2),
        "vx" => p.v[i].x = v,
        "vy" => p.v[i].y = v,
        "vz" => p.v[i].z = v,
        "ix" | "iy" | "iz" => {
            let mut im = p.image[i].get();
            im[(f.as_bytes()[1] - b'x') as usize] = v as i32;
            p.image[i] = im.into();
        }
        _ => p.radius[i] = v,
    }
}
