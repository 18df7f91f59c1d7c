//! `compute ID all pe [pair bond angle dihedral improper kspace]`: the potential energy of
//! the system, a global scalar. rdem's granular contacts tally no energy (as LIGGGHTS'
//! `pair gran`), and rdem has no bonded or long-range potentials, so it is always 0.

use super::{ComputeHead, ComputeRow, ScriptCompute, Shape};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: ComputeRow = ComputeRow::runs(
    "pe",
    parse,
    "potential energy (group `all`); keywords `pair bond angle dihedral improper kspace`",
)
.notes("always 0: granular contacts tally no energy, as in LIGGGHTS; rdem never stops with LIGGGHTS 3.8's \"Energy was not tallied on needed timestep\"");

/// The energy terms LIGGGHTS' `compute pe` can select.
const PE_KEYWORDS: [&str; 6] = ["pair", "bond", "angle", "dihedral", "improper", "kspace"];

/// Index of the group word in `compute ID group style ...`.
const GROUP_WORD: usize = 2;

/// `compute pe`.
#[derive(Debug)]
pub struct Pe;

impl ScriptCompute for Pe {
    fn shape(&self) -> Shape {
        Shape::scalar()
    }

    fn extensive(&self) -> bool {
        true
    }

    fn global(&self, sim: &Sim, c: &ComputeHead, idx: Option<usize>) -> Result<f64, Error> {
        if let Some(k) = idx {
            let id = &c.id;
            return Err(format!("c_{id}[{k}]: compute {id} has no global vector").into());
        }
        super::world(sim)?;
        Ok(0.0)
    }
}

/// Checks that a whole-system compute (`pe`, `pressure`) was given group `all`, as
/// LIGGGHTS requires.
pub(super) fn require_group_all(a: &Args, style: &str) -> CmdResult<()> {
    match a.words().get(GROUP_WORD) {
        Some(g) if g.text != "all" => Err(a.error_at(
            GROUP_WORD,
            format!("compute {style} must use group all"),
            Some(format!("compute ID all {style} ...")),
        )),
        _ => Ok(()),
    }
}

fn parse(_sim: &Sim, a: &mut Args) -> CmdResult<Box<dyn ScriptCompute>> {
    require_group_all(a, "pe")?;
    while !a.is_done() {
        a.keyword("pe keyword", &PE_KEYWORDS)?;
    }
    Ok(Box::new(Pe))
}
