//! The text of `dump euler/vtk`: the cells of a `fix ave/euler`
//! ([`crate::fixes::ave_euler`], evaluated at the end of every `nevery`-th step, before that
//! step's dumps, and at a run's set-up).
//!
//! `dump ID group euler/vtk N file_*.vtk` writes the last result of the (single)
//! `fix ave/euler`: [`check_euler_dump_name`] when the dump is defined,
//! [`euler_snapshot`] (or [`write_euler_snapshot`]) when it is due.

use crate::error::Error;
use std::path::Path;

use crate::fixes::ave_euler::AveEuler;
use crate::sim::Sim;

/// The ID of the `fix ave/euler` a `dump euler/vtk` writes (LIGGGHTS allows only one;
/// `None` when there is none).
pub fn euler_fix_id(sim: &Sim) -> Option<&str> {
    sim.defs
        .fixes
        .iter()
        .find(|f| f.downcast::<AveEuler>().is_some())
        .map(|f| f.id())
}

/// Checks a `dump euler/vtk` file name (must contain `*`; `%` and `.bin` are errors).
pub fn check_euler_dump_name(name: &str) -> Result<(), Error> {
    rdem_io::euler_vtk::check_euler_vtk_name(name).map_err(|e| Error::Invalid(e.to_string()))
}

/// The text of a `dump euler/vtk` file: the last result of fix `fix_id` (`None`: the
/// one `fix ave/euler`).
pub fn euler_snapshot(sim: &Sim, fix_id: Option<&str>) -> Result<String, Error> {
    let id = match fix_id {
        Some(id) => id,
        None => {
            euler_fix_id(sim).ok_or("dump euler/vtk needs a fix ave/euler (none is defined)")?
        }
    };
    let f = sim
        .defs
        .fixes
        .iter()
        .find(|f| f.id() == id)
        .ok_or_else(|| Error::undefined("fix", id).within("dump euler/vtk"))?;
    let Some(e) = f.downcast::<AveEuler>() else {
        return Err(format!(
            "dump euler/vtk: fix {id} is {}, not ave/euler",
            f.head.style
        )
        .into());
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
pub fn write_euler_snapshot(sim: &Sim, fix_id: Option<&str>, path: &Path) -> Result<bool, Error> {
    let text = euler_snapshot(sim, fix_id)?;
    let root = sim.world.as_ref().is_none_or(|w| w.comm.is_root());
    if root {
        rdem_io::write_atomic(path, text.as_bytes())?;
    }
    Ok(root)
}
