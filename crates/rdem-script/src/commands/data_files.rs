//! `read_data`, `write_data`: particles and box from and to LAMMPS data files;
//! `read_restart`, `write_restart`: the whole state from and to rdem's restart files
//! ([`crate::restart_state`]).

use crate::error::Error;
use rdem::{Domain, World};

use crate::args::{Args, CmdResult};
use crate::dumps;
use crate::sim::Sim;

use super::create::decompose;

pub(super) fn read_data(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let file = a.word("data file")?;
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "read_data keywords (add, offset, ...) are not supported yet",
            None,
        ));
    }
    if sim.world.is_some() {
        return Err(a.error_cmd("read_data: the simulation box is already defined", None));
    }
    let boundary = super::settings::box_boundary(sim, a, 0)?;
    let Some(layout) = sim.setup.data_layout.clone() else {
        return Err(a.error_cmd(
            "read_data under atom_style bond/gran: its atom lines (atom-ID molecule-ID atom-type x y z) give no diameter or density",
            Some("use atom_style hybrid granular bond/gran ..., whose lines are atom-ID atom-type x y z diameter density molecule-ID".into()),
        ));
    };
    let data = rdem_io::read_data_as(std::path::Path::new(file), &layout)
        .map_err(|e| a.error_at(1, e.to_string(), None))?;
    if let Some((nbt, per_atom, _)) = sim.setup.bond_gran {
        check_data_bonds(&data, nbt, per_atom)
            .map_err(|m| a.error_at(1, format!("{file}: {m}"), None))?;
    }
    let domain = Domain::with_faces(data.lo, data.hi, boundary)
        .map_err(|e| a.error_at(1, format!("{file}: {e}"), None))?;
    sim.outputs.out.line(&format!(
        "Created orthogonal box = ({} {} {}) to ({} {} {})",
        crate::variables::g(data.lo.x),
        crate::variables::g(data.lo.y),
        crate::variables::g(data.lo.z),
        crate::variables::g(data.hi.x),
        crate::variables::g(data.hi.y),
        crate::variables::g(data.hi.z)
    ));
    let mut w = World::new(domain);
    decompose(sim, &mut w, a, 1)?;
    w.set_timestep(sim.setup.dt)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    for (mut p, image) in data.new_particles() {
        p.mask = 1;
        if !w.owns_point(p.x) {
            continue;
        }
        let i = w
            .add_particle(&p)
            .map_err(|e| a.error_at(1, format!("{file}: {e}"), None))?;
        w.particles.image[i] = image.into();
    }
    sim.outputs
        .out
        .line(&format!("  {} atoms", data.atoms.len()));
    if !data.velocities.is_empty() {
        sim.outputs
            .out
            .line(&format!("  {} velocities", data.velocities.len()));
    }
    w.materials.ntypes = data.ntypes as usize;
    sim.install_world(w);
    if data.layout.has_bonds() {
        data_bonds(sim, &data).map_err(|m| a.error_at(1, format!("{file}: {m}"), None))?;
        sim.outputs
            .out
            .line(&format!("  {} bonds", data.bonds.len()));
    }
    super::settings::disc_masses(sim);
    Ok(())
}

/// The bonds of a data file fit the atom style: bond types within `n_bondtypes`, at
/// most `bonds_per_atom` per atom.
fn check_data_bonds(data: &rdem_io::DataFile, nbt: usize, per_atom: usize) -> Result<(), String> {
    let mut count: std::collections::HashMap<rdem::Tag, usize> = Default::default();
    for b in &data.bonds {
        if b.ty as usize > nbt {
            return Err(format!(
                "bond {} has type {}, beyond the atom style's n_bondtypes {nbt}",
                b.id, b.ty
            ));
        }
        for t in b.atoms {
            let c = count.entry(t).or_default();
            *c += 1;
            if *c > per_atom {
                return Err(format!(
                    "atom {t} has more than the atom style's bonds_per_atom = {per_atom} bonds"
                ));
            }
        }
    }
    Ok(())
}

/// The molecule IDs and bonds of a data file (`atom_style hybrid granular bond/gran`)
/// given to the particles this rank owns: each bond is held by both of its spheres.
fn data_bonds(sim: &mut Sim, data: &rdem_io::DataFile) -> Result<(), String> {
    let w = sim.world.as_mut().ok_or("no simulation box")?;
    let Some(bonds) = w.bonds.as_mut() else {
        return Ok(());
    };
    let p = &mut w.particles;
    let local: std::collections::HashMap<rdem::Tag, usize> =
        (0..p.nlocal()).map(|i| (p.tag[i], i)).collect();
    if let Some(m) = bonds.molecule_id() {
        for a in &data.atoms {
            if let Some(&i) = local.get(&a.id) {
                p.props[m.0].data[i] = a.molecule as f64;
            }
        }
    }
    for b in &data.bonds {
        for (me, other) in [(b.atoms[0], b.atoms[1]), (b.atoms[1], b.atoms[0])] {
            if let Some(&i) = local.get(&me) {
                bonds.add_pending(i, other, b.ty);
            }
        }
    }
    bonds.make_pending(p).map_err(|e| e.to_string())
}

/// `write_data FILE [nocoeff] [nofix]`: the particles and the box (and the step, in the
/// title line) as a LAMMPS data file.
pub(super) fn write_data(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let f = a.word("file name")?;
    while !a.is_done() {
        a.keyword("write_data keyword", &["nocoeff", "nofix"])?;
    }
    let step = sim.world_ref(a)?.step;
    let f = f.replace('*', &step.to_string());
    write_data_file(sim, &f).map_err(|m| a.error_at(1, m, None))
}

/// `write_restart FILE`: the whole state as an rdem restart file (`*` in the name is
/// the step).
pub(super) fn write_restart(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let f = a.word("file name")?;
    while !a.is_done() {
        a.keyword("write_restart keyword", &[])?;
    }
    let step = sim.world_ref(a)?.step;
    let f = f.replace('*', &step.to_string());
    crate::restart_state::write(sim, &f).map_err(|m| a.error_at(1, m, None))
}

/// `read_restart FILE`: the box, particles, contact histories, groups, step, time and
/// timestep of a restart file, in place of `create_box`; a LIGGGHTS 3.8 restart file
/// gives its box, particles and histories ([`crate::liggghts_restart`]).
pub(super) fn read_restart(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let file = a.word("restart file")?;
    a.done()?;
    if sim.world.is_some() {
        return Err(a.error_cmd(
            "read_restart: the simulation box is already defined",
            Some(
                "read_restart takes the place of create_box, read_data or an earlier read_restart"
                    .into(),
            ),
        ));
    }
    if file.contains(['*', '%']) {
        return Err(a.error_at(
            1,
            "read_restart: the '*' (latest step) and '%' (one file per processor) wildcards are not supported yet",
            Some("name one restart file".into()),
        ));
    }
    if is_liggghts(file) {
        return read_liggghts_restart(sim, a, file);
    }
    let c = crate::restart_state::read(file).map_err(|m| a.error_at(1, m, None))?;
    let h = &c.head;
    sim.outputs.out.line(&format!(
        "Reading restart file ...\n  written by {} on {} rank(s) at step {}\n  orthogonal box = ({} {} {}) to ({} {} {})",
        h.program,
        h.nranks,
        h.world.step,
        crate::variables::g(h.boxlo[0]),
        crate::variables::g(h.boxlo[1]),
        crate::variables::g(h.boxlo[2]),
        crate::variables::g(h.boxhi[0]),
        crate::variables::g(h.boxhi[1]),
        crate::variables::g(h.boxhi[2])
    ));
    let natoms = h.natoms;
    crate::restart_state::restore(sim, c, |sim, w| {
        decompose(sim, w, a, 1).map_err(|e| Error::Invalid(e.message))
    })
    .map_err(|m| a.error_at(1, format!("{file}: {m}"), None))?;
    sim.outputs.out.line(&format!("  {natoms} atoms"));
    Ok(())
}

/// True when `file` begins as a LIGGGHTS binary restart file (an unreadable file is
/// left to the rdem reader, which names the failure).
fn is_liggghts(file: &str) -> bool {
    use std::io::Read;
    let mut head = Vec::with_capacity(32);
    std::fs::File::open(file)
        .and_then(|f| f.take(32).read_to_end(&mut head))
        .is_ok_and(|_| rdem_io::liggghts_restart::is_liggghts_restart(&head))
}

/// `read_restart` of a LIGGGHTS restart file: what was read is printed, what the file
/// holds that rdem does not take is one warning.
fn read_liggghts_restart(sim: &mut Sim, a: &mut Args, file: &str) -> CmdResult {
    let f = rdem_io::liggghts_restart::read_liggghts_restart(std::path::Path::new(file))
        .map_err(|e| a.error_at(1, e.to_string(), None))?;
    let g = crate::variables::g;
    sim.outputs.out.line(&format!(
        "Reading LIGGGHTS restart file ...\n  written by {} on {} processor(s) at step {}\n  orthogonal box = ({} {} {}) to ({} {} {})",
        f.version.strip_prefix("Version ").unwrap_or(&f.version),
        f.nprocs,
        f.step,
        g(f.boxlo[0]),
        g(f.boxlo[1]),
        g(f.boxlo[2]),
        g(f.boxhi[0]),
        g(f.boxhi[1]),
        g(f.boxhi[2])
    ));
    let taken = crate::liggghts_restart::restore(sim, &f, |sim, w| {
        decompose(sim, w, a, 1).map_err(|e| Error::Invalid(e.message))
    })
    .map_err(|m| a.error_at(1, format!("{file}: {m}"), None))?;
    let out = &mut sim.outputs.out;
    out.line(&format!("  {} atoms", f.natoms));
    out.line(&format!(
        "  {} pair contact histories, wall histories of {} fix(es){}{}",
        taken.contacts,
        taken.walls.len(),
        if taken.walls.is_empty() { "" } else { ": " },
        taken.walls.join(" ")
    ));
    if !taken.kept.is_empty() {
        out.line(&format!(
            "  per-particle values of fix(es) {} kept for fix property/atom defined again with that ID",
            taken.kept.join(" ")
        ));
    }
    let mut skipped = Vec::new();
    if let Some(p) = &f.pair {
        skipped.push(format!(
            "pair style {} and its coefficients (define them again after read_restart)",
            p.style
        ));
    }
    skipped.extend(taken.not_taken);
    if skipped.is_empty() {
        return Ok(());
    }
    sim.warn_once(&format!(
        "read_restart: {file} is a LIGGGHTS restart file; not taken from it: {}",
        skipped.join("; ")
    ));
    Ok(())
}

/// Writes the particles and the box (and the step, in the title line) to `path` as a
/// data file, which `read_data` reads, in the columns of the atom style (under
/// `hybrid granular bond/gran`, with the molecule IDs and the intact bonds that are
/// turned on; their lengths and loads are not kept, as in LAMMPS' data files). Every
/// rank sends its owned particles; rank 0 writes them all, sorted by tag, under a
/// temporary name renamed to `path` when complete (`rdem_io`'s atomic writes). Under
/// `rdem -check` nothing is written.
pub(crate) fn write_data_file(sim: &Sim, path: &str) -> Result<(), Error> {
    if sim.script.check {
        return Ok(());
    }
    let ntypes = sim.ntypes() as u32;
    let w = sim.world.as_ref().ok_or("no simulation box")?;
    let nl = w.particles.nlocal();
    let all: Vec<usize> = (0..nl).collect();
    let layout = sim
        .setup
        .data_layout
        .clone()
        .unwrap_or(rdem_io::AtomLayout::Granular);
    // Under bond/gran: the molecule ID, then (partner tag, type) per bond slot.
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let bonds = w.bonds.as_ref().filter(|_| layout.has_bonds());
    if let Some(b) = bonds {
        let per = b.per_atom;
        columns = vec![vec![0.0; nl]; 1 + 2 * per];
        if let Some(m) = b.molecule_id() {
            columns[0].copy_from_slice(&w.particles.props[m.0].data[..nl]);
        }
        for i in 0..nl {
            for (s, (tag, ty)) in b.intact(&w.particles, i).into_iter().enumerate() {
                let (tags, types) = columns[1 + 2 * s..].split_at_mut(1);
                tags[0][i] = tag as f64;
                types[0][i] = f64::from(ty);
            }
        }
    }
    let custom: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
    let Some(g) = dumps::gather_owned(&*w.comm, &w.particles, &all, &custom) else {
        return Ok(());
    };
    let title = format!(
        "LAMMPS data file via rdem write_data, timestep = {}",
        w.step
    );
    let mut f = rdem_io::DataFile::from_particles(&g.particles, &w.domain, ntypes, &title);
    if let Some(b) = bonds {
        // `from_particles` sorts by tag: map each tag to its gathered row.
        let row: std::collections::HashMap<rdem::Tag, usize> = (0..g.particles.nlocal())
            .map(|k| (g.particles.tag[k], k))
            .collect();
        for a in &mut f.atoms {
            a.molecule = g.custom[0][row[&a.id]] as u64;
        }
        let mut list = Vec::new();
        for a in &f.atoms {
            let k = row[&a.id];
            for s in 0..b.per_atom {
                let (tag, ty) = (g.custom[1 + 2 * s][k] as rdem::Tag, g.custom[2 + 2 * s][k]);
                if ty > 0.0 && a.id < tag {
                    list.push((a.id, tag, ty as u32));
                }
            }
        }
        f.bonds = list
            .into_iter()
            .enumerate()
            .map(|(n, (a, b, ty))| rdem_io::DataBond {
                id: n as u64 + 1,
                ty,
                atoms: [a, b],
            })
            .collect();
        f.nbondtypes = b.ntypes as u32;
    }
    f.layout = layout;
    rdem_io::write_atomic(
        std::path::Path::new(path),
        rdem_io::format_data(&f).as_bytes(),
    )?;
    Ok(())
}
