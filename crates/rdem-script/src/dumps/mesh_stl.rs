//! `dump ID group mesh/stl N file [mesh IDs]`: the triangles of the meshes (all without
//! IDs) at their current positions, one ASCII STL solid per snapshot, as LIGGGHTS writes
//! it.

use crate::error::Error;
use rdem_io::{DumpFileName, Sort};

use super::particles::Done;
use super::{mesh_ids, DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{suggest, Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs("mesh/stl", parse, "mesh IDs (none: all meshes)")
    .notes("one ASCII STL solid of the current triangles per snapshot, as LIGGGHTS writes it");

/// The registry row of the old name, which LIGGGHTS 3.8 still takes (measured: the same
/// files as `mesh/stl`).
pub(super) const ROW_OLD_NAME: DumpRow = DumpRow::runs("stl", parse, "the old name of `mesh/stl`");

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    // Mesh IDs (none: every mesh); LIGGGHTS' parallel selectors mean the whole mesh with
    // one process, which is what rdem writes.
    let mut ids = Vec::new();
    while let Some(w) = a.peek() {
        if w == "modify" {
            break;
        }
        if matches!(w, "local" | "ghost" | "all") {
            a.seek(a.pos() + 1);
            continue;
        }
        let known = mesh_ids(sim);
        if !known.contains(&w) {
            return Err(a.error_at(
                a.pos(),
                format!("dump mesh/stl: no mesh '{w}' (a fix mesh/surface ID)"),
                Some(suggest(w, &known)),
            ));
        }
        ids.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    Ok((Box::new(MeshStl(DumpFileName::new(file))), ids))
}

/// The file name pattern (the mesh IDs are the dump's columns).
struct MeshStl(DumpFileName);

impl DumpStyle for MeshStl {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        columns: &[String],
        step: u64,
        _time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let w = sim
            .world
            .as_ref()
            .ok_or("dump before the simulation box is defined")?;
        // Every rank holds every mesh: rank 0 writes.
        if w.comm.rank() != 0 {
            return Ok(Vec::new());
        }
        let path = self.0.path(step, 0);
        let (mut tris, mut normals) = (Vec::new(), Vec::new());
        for m in w
            .meshes
            .iter()
            .filter(|m| columns.is_empty() || columns.contains(&m.id))
        {
            for t in 0..m.mesh.tris.len() {
                tris.push(m.mesh.corners(t as u32));
                normals.push(m.mesh.normals[t]);
            }
        }
        rdem_io::stl::write_ascii_stl(&path, &tris, &normals)?;
        Ok(Vec::new())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.0
    }

    fn has_collection(&self) -> bool {
        false
    }

    fn set_sort(&mut self, _: Sort) -> Result<(), NotHere> {
        Err(("mesh dumps write triangles: sort does not apply", None))
    }
}
