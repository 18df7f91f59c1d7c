//! `read_data`, `write_data`, `read_restart`, `write_restart`: particles and box from and
//! to LAMMPS data files (rdem's restart files are data files too).

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
    if a.name() == "read_restart" {
        // The step written by write_restart (or write_data) into the title line.
        w.step = data
            .title
            .rsplit_once("timestep = ")
            .and_then(|(_, n)| n.trim().parse().ok())
            .ok_or_else(|| {
                a.error_at(
                    1,
                    format!("{file}: not an rdem restart file (no 'timestep = N' in its title)"),
                    None,
                )
            })?;
    }
    w.materials.ntypes = data.ntypes as usize;
    sim.world = Some(w);
    super::settings::disc_masses(sim);
    Ok(())
}

/// `write_data FILE [nocoeff] [nofix]`, `write_restart FILE`: rdem's restart files are portable data files (particles, box, step); the LIGGGHTS binary restart format is not written or read.
pub(super) fn write_data(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let restart = a.name() == "write_restart";
    let f = a.word("file name")?;
    while !a.is_done() {
        if restart {
            a.keyword("write_restart keyword", &[])?;
        } else {
            a.keyword("write_data keyword", &["nocoeff", "nofix"])?;
        }
    }
    let step = sim.world_ref(a)?.step;
    let f = f.replace('*', &step.to_string());
    write_restart_file(sim, &f).map_err(|m| a.error_at(1, m, None))
}

/// Writes the particles and the box (and the step, in the title line) to `path` as a
/// data file, which `read_data` and `read_restart` read: the writer of `write_data`,
/// `write_restart` and `restart`. Every rank sends its owned particles; rank 0 writes
/// them all, sorted by tag, under a temporary name renamed to `path` when complete
/// (`rdem_io`'s atomic writes). Under `rdem -check` nothing is written.
pub(crate) fn write_restart_file(sim: &Sim, path: &str) -> Result<(), String> {
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
