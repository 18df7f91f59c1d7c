//! `dump ID group euler/vtk N file_*.vtk`: the cells of the `fix ave/euler` as legacy
//! VTK, exactly as LIGGGHTS writes them (the dump's group and sort do not apply).

use crate::error::Error;
use rdem_io::{DumpFileName, Sort};

use super::particles::Done;
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "euler/vtk",
    parse,
    "the cells of `fix ave/euler`, legacy VTK exactly as LIGGGHTS writes it",
)
.notes("the name must contain `*`");

fn parse(_sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    crate::euler::check_euler_dump_name(file).map_err(|m| {
        a.error_prev(
            m,
            Some("e.g. post/euler_*.vtk: one legacy VTK file per snapshot".into()),
        )
    })?;
    if let Some(w) = a.peek() {
        if w != "modify" {
            return Err(a.error_at(
                a.pos(),
                "dump euler/vtk takes no columns",
                Some(
                    "it writes the cells of fix ave/euler: v_avg, volumefraction, radius \
                     and pressure"
                        .into(),
                ),
            ));
        }
    }
    Ok((Box::new(EulerVtk(DumpFileName::new(file))), Vec::new()))
}

/// The file name pattern.
struct EulerVtk(DumpFileName);

impl DumpStyle for EulerVtk {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        _columns: &[String],
        step: u64,
        time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        // The cells are global (summed over the ranks); rank 0 writes them.
        let path = self.0.path(step, 0);
        let wrote = crate::euler::write_euler_snapshot(sim, None, &path)?;
        Ok(if wrote {
            vec![(time, path)]
        } else {
            Vec::new()
        })
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.0
    }

    fn set_sort(&mut self, _: Sort) -> Result<(), NotHere> {
        Err(("dump euler/vtk writes cells: sort does not apply", None))
    }
}
