//! `dump ID group atom/vtk N file`: VTK XML UnstructuredGrid with radii, id, type, proc,
//! mass, velocity_lin, velocity_ang and force, sorted by id, written on a background
//! thread.

use crate::error::Error;
use rdem_io::{AtomVtkDump, Compressor, DumpFileName, Sort};

use super::particles::{gather, Done};
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "atom/vtk",
    parse,
    "VTK XML UnstructuredGrid: radii, id, type, proc, mass, velocity_lin, velocity_ang, force, sorted by id; ASCII, `binary yes` (base64), `compressor zlib\\|lz4`",
)
.notes("written on a background thread; a name without `*` overwrites one file (LIGGGHTS crashes)");

fn parse(_sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    if let Some(w) = a.peek() {
        if w != "modify" {
            return Err(a.error_at(
                a.pos(),
                "dump atom/vtk takes no columns",
                Some(
                    "it always writes radii, id, type, proc, mass, velocity_lin, \
                     velocity_ang and force; use custom/vtk to choose columns"
                        .into(),
                ),
            ));
        }
    }
    Ok((
        Box::new(AtomVtk(AtomVtkDump::new(DumpFileName::new(file)))),
        Vec::new(),
    ))
}

/// The writer.
struct AtomVtk(AtomVtkDump);

impl DumpStyle for AtomVtk {
    fn write(
        &mut self,
        sim: &Sim,
        head: &DumpHead,
        columns: &[String],
        step: u64,
        time: f64,
        background: bool,
    ) -> Result<Done, Error> {
        let Some((g, _)) = gather(sim, head, columns)? else {
            return Ok(Vec::new());
        };
        let p = &g.particles;
        let sel: Vec<usize> = (0..p.nlocal()).collect();
        let procs = Some(g.procs.as_slice());
        if background {
            self.0.start(step, time, p, &sel, procs)
        } else {
            self.0
                .write(step, p, &sel, procs)
                .map(|path| vec![(time, path)])
        }
        .map_err(Error::from)
    }

    fn finish(&mut self) -> Result<Done, Error> {
        Ok(self.0.finish()?.into_iter().collect())
    }

    fn resolve(&self, sim: &Sim, columns: &[String]) -> Result<(), Error> {
        super::particles::columns(sim, columns).map(|_| ())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        self.0.name_mut()
    }

    fn set_sort(&mut self, s: Sort) -> Result<(), NotHere> {
        if s == Sort::Id {
            return Ok(());
        }
        Err((
            "dump atom/vtk always sorts by id",
            Some("use custom/vtk for another order"),
        ))
    }

    fn set_binary(&mut self, yes: bool) -> Result<(), NotHere> {
        self.0.binary = yes;
        Ok(())
    }

    fn set_compressor(&mut self, c: Compressor) -> Result<(), NotHere> {
        self.0.compressor = c;
        self.0.binary |= c != Compressor::None;
        Ok(())
    }
}
