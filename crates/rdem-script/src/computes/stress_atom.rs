//! `compute ID group stress/atom [keywords]`: per-atom stress × volume (6 columns:
//! xx yy zz xy xz yz), LAMMPS' convention −(m v ⊗ v + ½ Σ r_ij ⊗ F_ij).

use super::kernels::{stress_atom, STRESS_KEYWORDS};
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "stress/atom",
    parse,
    "stress × volume, 6 columns; `ke`, `pair`, `virial`",
)
.notes("wall contacts do not count, as in LIGGGHTS");

/// Which terms it sums.
#[derive(Debug)]
pub struct StressAtom {
    /// The kinetic term −m v ⊗ v.
    ke: bool,
    /// The pair contact virial.
    pair: bool,
}

impl ScriptCompute for StressAtom {
    fn shape(&self) -> Shape {
        Shape::peratom(6)
    }

    fn needs_virial(&self) -> bool {
        self.pair
    }

    fn peratom(&self, sim: &Sim, c: &ComputeHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let k = super::pick_index(&c.id, col, 6)?;
        stress_atom(super::world(sim)?, c.groupbit, self.ke, self.pair, k)
    }
}

/// `compute ID group stress/atom [ke pair virial ...]`.
fn parse(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    // No keyword: every term; otherwise only the listed ones (`virial`: all but ke).
    let (mut ke, mut pair, mut any) = (false, false, false);
    while !a.is_done() {
        match a.keyword("stress/atom keyword", &STRESS_KEYWORDS)? {
            "ke" => ke = true,
            "pair" | "virial" => pair = true,
            _ => {}
        }
        any = true;
    }
    if !any {
        (ke, pair) = (true, true);
    }
    Ok(Box::new(StressAtom { ke, pair }))
}
