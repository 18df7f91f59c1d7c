//! `dump ID group decomposition/vtk N file`: the processor grid — the cuts of the box
//! between the MPI subdomains — as a legacy VTK rectilinear grid, one cell per
//! subdomain, as LIGGGHTS 3.8 writes it (ASCII, the coordinates printed with `%f`; its
//! header line names "mesh/gran/VTK export"). rdem's subdomains share each axis equally,
//! so the cuts are `lo + (hi − lo)·m/P`; serially the grid is the box, one cell.

use crate::error::Error;
use rdem_io::{DumpFileName, Sort};

use super::particles::Done;
use super::{DumpHead, DumpRow, DumpStyle, NotHere};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: DumpRow = DumpRow::runs(
    "decomposition/vtk",
    parse,
    "no arguments: the processor grid as a VTK rectilinear grid",
)
.notes(
    "ASCII, as LIGGGHTS 3.8 writes it; the group is not used; `dump_modify binary` does not apply",
);

fn parse(_sim: &Sim, a: &mut Args, file: &str) -> CmdResult<(Box<dyn DumpStyle>, Vec<String>)> {
    if let Some(w) = a.peek().filter(|w| *w != "modify") {
        return Err(a.error_at(
            a.pos(),
            format!("dump decomposition/vtk takes no arguments after the file name, not '{w}'"),
            None,
        ));
    }
    Ok((Box::new(Decomposition(DumpFileName::new(file))), Vec::new()))
}

/// The file name pattern.
struct Decomposition(DumpFileName);

/// The text of the grid: `cuts[a]` the cut coordinates along axis a, ends included.
fn grid_text(cuts: &[Vec<f64>; 3]) -> String {
    let mut s = String::from(
        "# vtk DataFile Version 2.0\nLIGGGHTS mesh/gran/VTK export\nASCII\nDATASET RECTILINEAR_GRID\n",
    );
    s += &format!(
        "DIMENSIONS {} {} {}\n",
        cuts[0].len(),
        cuts[1].len(),
        cuts[2].len()
    );
    for (name, c) in ["X", "Y", "Z"].iter().zip(cuts) {
        s += &format!("{name}_COORDINATES {} float\n", c.len());
        for v in c {
            s += &format!("{v:.6} ");
        }
        s.push('\n');
    }
    s
}

impl DumpStyle for Decomposition {
    fn write(
        &mut self,
        sim: &Sim,
        _head: &DumpHead,
        _columns: &[String],
        step: u64,
        _time: f64,
        _background: bool,
    ) -> Result<Done, Error> {
        let w = sim
            .world
            .as_ref()
            .ok_or("dump before the simulation box is defined")?;
        if w.comm.rank() != 0 {
            return Ok(Vec::new());
        }
        let d = &w.domain;
        let cuts: [Vec<f64>; 3] =
            std::array::from_fn(|a| (0..=d.procgrid[a]).map(|m| d.cut(a, m)).collect());
        let path = self.0.path(step, 0);
        rdem_io::write_atomic(&path, grid_text(&cuts).as_bytes())?;
        Ok(Vec::new())
    }

    fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.0
    }

    fn has_collection(&self) -> bool {
        false
    }

    fn set_sort(&mut self, _: Sort) -> Result<(), NotHere> {
        Err((
            "dump decomposition/vtk writes the processor grid: sort does not apply",
            None,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_is_written_as_liggghts_writes_it() {
        // LIGGGHTS 3.8 on 2 ranks (grid 1 × 1 × 2) of the box ±0.05 × ±0.05 × [0, 0.1].
        let want = "# vtk DataFile Version 2.0
LIGGGHTS mesh/gran/VTK export
ASCII
DATASET RECTILINEAR_GRID
DIMENSIONS 2 2 3
X_COORDINATES 2 float
-0.050000 0.050000 
Y_COORDINATES 2 float
-0.050000 0.050000 
Z_COORDINATES 3 float
0.000000 0.050000 0.100000 
";
        let cuts = [vec![-0.05, 0.05], vec![-0.05, 0.05], vec![0.0, 0.05, 0.1]];
        assert_eq!(grid_text(&cuts), want);
    }
}
