//! `dump ID group custom N file columns...`: text in LAMMPS' layout (OVITO reads it); a
//! `*` in the name gives one file per step.

use crate::error::Error;
use rdem_io::{DumpFileName, Sort, TextDump, TextOptions};

use super::particles::{gather, read_columns, Done};
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "custom",
    parse,
    "text in LAMMPS' layout (OVITO reads it); `*` in the name: one file per step",
);

fn parse(sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    let cols = read_columns(sim, a)?;
    let t = TextDump::new(DumpFileName::new(file), TextOptions::default());
    Ok((Box::new(Custom(t)), cols))
}

/// The text writer.
struct Custom(TextDump);

impl DumpStyle for Custom {
    fn write(
        &mut self,
        sim: &Sim,
        head: &DumpHead,
        columns: &[String],
        step: u64,
        _time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let Some((g, cols)) = gather(sim, head, columns)? else {
            return Ok(Vec::new());
        };
        let w = sim.world.as_ref().expect("gathered from a world");
        let p = &g.particles;
        let sel: Vec<usize> = (0..p.nlocal()).collect();
        self.0.write(step, p, &w.domain, &sel, &cols)?;
        Ok(Vec::new())
    }

    fn resolve(&self, sim: &Sim, columns: &[String]) -> Result<(), Error> {
        super::particles::columns(sim, columns).map(|_| ())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        self.0.name_mut()
    }

    fn has_collection(&self) -> bool {
        false
    }

    fn takes_region(&self) -> bool {
        true
    }

    fn set_sort(&mut self, s: Sort) -> Result<(), NotHere> {
        self.0.options.sort = s;
        Ok(())
    }

    fn set_format(&mut self, f: &str, ncols: usize) -> Result<Option<String>, NotHere> {
        Ok(super::set_line_formats(
            &mut self.0.options.formats,
            f,
            ncols,
        ))
    }
}
