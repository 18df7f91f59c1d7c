//! `compute ID all bond/counter` (LIGGGHTS-INL; seed 003): bonds created and broken since
//! the previous evaluation and intact now, for pairs and for walls: a global vector of 6.

use crate::error::Error;
use std::cell::RefCell;

use super::kernels::{bond_counter, BondCounterState};
use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "bond/counter",
    parse,
    "bonds created, broken and intact, for pairs and walls (LIGGGHTS-INL)",
)
.notes("one per script");

/// The counter and what it remembers between evaluations.
#[derive(Debug, Default)]
pub struct BondCounter(RefCell<BondCounterState>);

impl ScriptCompute for BondCounter {
    fn shape(&self) -> Shape {
        Shape::vector(6)
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let id = &c.id;
        let Some(_) = idx else {
            return Err(format!(
                "compute {id} is a global vector of 6: use c_{id}[1] .. c_{id}[6]"
            )
            .into());
        };
        let k = super::pick_index(id, idx, 6)?;
        Ok(bond_counter(super::world(sim)?, &self.0)[k])
    }
}

/// `compute ID all bond/counter` (one per script).
fn parse(sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    if let Some(other) = sim.defs.computes.iter().find(|c| c.style == "bond/counter") {
        return Err(a.error_at(
            3,
            format!(
                "only one compute bond/counter is allowed (compute {} is one)",
                other.id()
            ),
            Some(format!("use c_{}[1..6]", other.id())),
        ));
    }
    Ok(Box::new(BondCounter::default()))
}
