//! `read_data`, `write_data`: particles and box from and to LAMMPS data files;
//! `read_restart`, `write_restart`: the whole state from and to rdem's restart files
//! ([`crate::restart_state`]).

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
    let data = rdem_io::read_data(std::path::Path::new(file))
        .map_err(|e| a.error_at(1, e.to_string(), None))?;
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
        w.particles.image[i] = image;
    }
    sim.outputs
        .out
        .line(&format!("  {} atoms", data.atoms.len()));
    w.materials.ntypes = data.ntypes as usize;
    sim.world = Some(w);
    super::settings::disc_masses(sim);
    Ok(())
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
/// timestep of a restart file, in place of `create_box`.
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
        decompose(sim, w, a, 1).map_err(|e| e.message)
    })
    .map_err(|m| a.error_at(1, format!("{file}: {m}"), None))?;
    sim.outputs.out.line(&format!("  {natoms} atoms"));
    Ok(())
}

/// Writes the particles and the box (and the step, in the title line) to `path` as a
/// data file, which `read_data` reads. Every rank sends its owned particles; rank 0
/// writes them all, sorted by tag, under a temporary name renamed to `path` when
/// complete (`rdem_io`'s atomic writes). Under `rdem -check` nothing is written.
pub(crate) fn write_data_file(sim: &Sim, path: &str) -> Result<(), String> {
    if sim.script.check {
        return Ok(());
    }
    let ntypes = sim.ntypes() as u32;
    let w = sim.world.as_ref().ok_or("no simulation box")?;
    let all: Vec<usize> = (0..w.particles.nlocal()).collect();
    if let Some(g) = dumps::gather_owned(&*w.comm, &w.particles, &all, &[]) {
        rdem_io::write_data(
            std::path::Path::new(path),
            &g.particles,
            &w.domain,
            ntypes,
            w.step,
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}
