//! `fix ave/euler` in the run loop and the text of `dump euler/vtk`.
//!
//! The fix is evaluated at the end of every `nevery`-th step, before that step's dumps,
//! and at a run's set-up; the engine computes the per-particle contact virial on exactly
//! those steps ([`wants_virial`] sets [`rdem::World::want_virial`]), and on every step
//! while a `compute stress/atom` with a pair term exists.
//!
//! `dump ID group euler/vtk N file_*.vtk` writes the last result of the (single)
//! `fix ave/euler`: [`check_euler_dump_name`] when the dump is defined,
//! [`euler_snapshot`] (or [`write_euler_snapshot`]) when it is due.

use std::path::Path;

use rdem::euler::{self, EulerGrid};

use crate::computes;
use crate::fixes::FrontFix;
use crate::sim::Sim;

fn due(nevery: u64, step: u64, setup: bool) -> bool {
    setup || step % nevery == 0
}

/// Whether the force pass of `step` (or of the set-up at `step`) must compute the contact
/// virial: a `fix ave/euler` is due then, or a `compute stress/atom` with a pair term
/// exists (its values may be asked for at any step).
pub fn wants_virial(sim: &Sim, step: u64, setup: bool) -> bool {
    sim.computes.iter().any(computes::needs_virial)
        || sim
            .fixes
            .iter()
            .any(|f| matches!(&f.kind, FrontFix::AveEuler(e) if due(e.nevery, step, setup)))
}

/// Evaluates every `fix ave/euler` due at `step` (all of them at a set-up).
pub fn end_of_step(sim: &mut Sim, step: u64, setup: bool) -> Result<(), String> {
    let Some(w) = sim.world.as_ref() else {
        return Ok(());
    };
    for f in &mut sim.fixes {
        let FrontFix::AveEuler(e) = &mut f.kind else {
            continue;
        };
        if !due(e.nevery, step, setup) {
            continue;
        }
        let virial = w.current_virial().ok_or_else(|| {
            format!(
                "fix {} (ave/euler): the contact virial of step {step} was not computed",
                f.id
            )
        })?;
        let p = &w.particles;
        let rmax = w
            .comm
            .max(p.radius[..p.nlocal()].iter().copied().fold(0.0, f64::max));
        let grid = EulerGrid::new(
            w.domain.boxlo,
            w.domain.boxhi,
            e.cell_size_relative * 2.0 * rmax,
        );
        let base = match &e.base_region {
            None => None,
            Some((_, region)) => {
                if e.base_volumes.as_ref().map(|(g, _)| *g) != Some(grid) {
                    e.base_volumes = Some((grid, grid.base_volumes(region)));
                }
                e.base_volumes.as_ref().map(|(_, v)| v.as_slice())
            }
        };
        e.cells = Some(euler::average(&grid, p, f.groupbit, virial, base, &*w.comm));
        e.step = step;
    }
    Ok(())
}

/// The ID of the `fix ave/euler` a `dump euler/vtk` writes (LIGGGHTS allows only one;
/// `None` when there is none).
pub fn euler_fix_id(sim: &Sim) -> Option<&str> {
    sim.fixes
        .iter()
        .find(|f| matches!(f.kind, FrontFix::AveEuler(_)))
        .map(|f| f.id.as_str())
}

/// Checks a `dump euler/vtk` file name (must contain `*`; `%` and `.bin` are errors).
pub fn check_euler_dump_name(name: &str) -> Result<(), String> {
    rdem_io::euler_vtk::check_euler_vtk_name(name)
}

/// The text of a `dump euler/vtk` file: the last result of fix `fix_id` (`None`: the
/// one `fix ave/euler`).
pub fn euler_snapshot(sim: &Sim, fix_id: Option<&str>) -> Result<String, String> {
    let id = match fix_id {
        Some(id) => id,
        None => {
            euler_fix_id(sim).ok_or("dump euler/vtk needs a fix ave/euler (none is defined)")?
        }
    };
    let f = sim
        .fixes
        .iter()
        .find(|f| f.id == id)
        .ok_or_else(|| format!("dump euler/vtk: no fix '{id}'"))?;
    let FrontFix::AveEuler(e) = &f.kind else {
        return Err(format!(
            "dump euler/vtk: fix {id} is {}, not ave/euler",
            f.style
        ));
    };
    let cells = e.cells.as_ref().ok_or_else(|| {
        format!("dump euler/vtk: fix {id} (ave/euler) has not been evaluated yet (it is at a run's set-up)")
    })?;
    Ok(rdem_io::euler_vtk::format_euler_vtk(cells))
}

/// Writes [`euler_snapshot`] to `path` (atomically, creating missing directories) on
/// rank 0; the cells are global (summed over the ranks by [`rdem::euler::average`]), so
/// the other ranks only check that there is something to write. Returns whether this
/// rank wrote the file.
pub fn write_euler_snapshot(sim: &Sim, fix_id: Option<&str>, path: &Path) -> Result<bool, String> {
    let text = euler_snapshot(sim, fix_id)?;
    let root = sim.world.as_ref().is_none_or(|w| w.comm.is_root());
    if root {
        rdem_io::write_atomic(path, text.as_bytes()).map_err(|e| e.to_string())?;
    }
    Ok(root)
}
