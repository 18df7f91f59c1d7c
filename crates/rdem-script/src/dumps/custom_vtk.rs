//! `dump ID group custom/vtk N file columns...`: legacy VTK polydata as LIGGGHTS writes
//! it (`.vtk`, plus its `_boundingBox` file), or VTK XML PolyData (`.vtp`) or
//! UnstructuredGrid (`.vtu`): the suffix picks the format, as in LIGGGHTS.

use crate::error::Error;
use rdem_io::{Compressor, DumpFileName, Sort, VtkDump};

use super::particles::{gather, read_columns, Done};
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "custom/vtk",
    parse,
    "legacy VTK polydata laid out as LIGGGHTS writes it (`.vtk`; `binary yes`: big-endian binary), plus its `_boundingBox` file; `.vtp` XML PolyData and `.vtu` XML UnstructuredGrid",
)
.notes("XML variants default to zlib-compressed binary (`compressor none`, `binary no` for LIGGGHTS' ASCII)");

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    // The parallel `.pvtp`/`.pvtu` and anything else are refused.
    if ![".vtk", ".vtp", ".vtu"].iter().any(|s| file.ends_with(s)) {
        return Err(a.error_prev(
            format!("dump custom/vtk: the file name '{file}' must end in .vtk, .vtp or .vtu"),
            Some(
                "the suffix picks the format: .vtk legacy VTK, .vtp XML PolyData, .vtu XML \
                 UnstructuredGrid"
                    .into(),
            ),
        ));
    }
    let cols = read_columns(sim, a)?;
    Ok((
        Box::new(CustomVtk(VtkDump::new(DumpFileName::new(file)))),
        cols,
    ))
}

/// The VTK writer.
struct CustomVtk(VtkDump);

impl DumpStyle for CustomVtk {
    fn write(
        &mut self,
        sim: &Sim,
        head: &DumpHead,
        columns: &[String],
        step: u64,
        time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let Some((g, cols)) = gather(sim, head, columns)? else {
            return Ok(Vec::new());
        };
        let w = sim.world.as_ref().expect("gathered from a world");
        let p = &g.particles;
        let sel: Vec<usize> = (0..p.nlocal()).collect();
        let [main, _] = self.0.write(step, p, &w.domain, &sel, &cols)?;
        Ok(vec![(time, main)])
    }

    fn resolve(&self, sim: &Sim, columns: &[String]) -> Result<(), Error> {
        super::particles::columns(sim, columns).map(|_| ())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        self.0.name_mut()
    }

    fn takes_region(&self) -> bool {
        true
    }

    fn set_sort(&mut self, s: Sort) -> Result<(), NotHere> {
        self.0.sort = s;
        Ok(())
    }

    fn set_binary(&mut self, yes: bool) -> Result<(), NotHere> {
        self.0.binary = yes;
        Ok(())
    }

    fn set_compressor(&mut self, c: Compressor) -> Result<(), NotHere> {
        if !self.0.is_xml() {
            return Err((
                "compressor applies to VTK XML output (atom/vtk, custom/vtk with .vtp or .vtu)",
                Some("legacy .vtk files cannot be compressed"),
            ));
        }
        self.0.compressor = c;
        self.0.binary |= c != Compressor::None;
        Ok(())
    }
}
