//! `compute ID group com`: the centre of mass of the group, from the unwrapped positions
//! (`x + image · box length`), mass-weighted: a global vector of 3 (0 for an empty group).

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "com",
    parse,
    "the group's centre of mass (unwrapped positions): a global vector of 3",
)
.notes("the group's mass is summed at each evaluation; LIGGGHTS 3.8 sums it when a run starts, so its value is off while a run inserts or removes particles of the group");

fn parse(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    a.done()?;
    Ok(Box::new(Com))
}

/// `compute com`.
#[derive(Debug)]
pub struct Com;

impl ScriptCompute for Com {
    fn shape(&self) -> Shape {
        Shape::vector(3)
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        let id = &c.id;
        let a = match idx {
            Some(k @ 1..=3) => k - 1,
            Some(k) => return Err(format!("c_{id}[{k}]: compute {id} gives 3 values").into()),
            None => {
                return Err(format!("c_{id}: compute {id} gives a vector: use c_{id}[1..3]").into())
            }
        };
        Ok(super::kernels::group_com(super::world(sim)?, c.groupbit).1[a])
    }
}
