//! `fix ave/euler nevery N cell_size_relative c [cy cz] parallel yes|no
//! [basevolume_region R]`: cell averages on a regular grid ([`rdem::euler`]) at the end of every `nevery`-th step
//! and at a run's set-up, for `dump euler/vtk`. The engine computes the per-particle
//! contact virial on exactly those steps ([`ScriptFix::wants_virial`]).

use crate::error::Error;
use rdem::euler::{self, EulerGrid};

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "ave/euler",
    parse,
    Stages::END_OF_STEP,
    "`nevery N cell_size_relative c [cy cz] parallel yes\\|no [basevolume_region R]`",
)
.notes("per cell: mass-weighted velocity, mean radius, volume fraction, pressure (kinetic fluctuation + contact virial); one per script, as LIGGGHTS; three cell sizes (x, y, z) as LIGGGHTS-PFM takes them; `basevolume_region` volumes from a 20³ point grid per cell");

fn due(nevery: u64, step: u64, setup: bool) -> bool {
    setup || step % nevery == 0
}

/// `fix ave/euler nevery N cell_size_relative c parallel yes|no [basevolume_region R]`:
/// cell averages on a regular grid ([`rdem::euler`]), computed at the end of every
/// `nevery`-th step (and at a run's set-up) for `dump euler/vtk`.
pub struct AveEuler {
    /// Compute every this many steps.
    pub nevery: u64,
    /// Cell edges (x, y, z) in multiples of the largest particle diameter: one value in
    /// LIGGGHTS 3.8, one per axis in LIGGGHTS-PFM.
    pub cell_size_relative: rdem::DVec3,
    /// `parallel yes|no` (with one process both give the same grid over the whole box).
    pub parallel: bool,
    /// `basevolume_region`: the cells' volumes are their parts inside this region.
    pub base_region: Option<(String, rdem::region::Region)>,
    /// Base volumes cached for a grid.
    pub base_volumes: Option<(rdem::euler::EulerGrid, Vec<f64>)>,
    /// The last result (`None` until the first evaluation).
    pub cells: Option<rdem::euler::EulerCells>,
    /// Step of the last result.
    pub step: u64,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let id = head.id.as_str();
    // LIGGGHTS 3.8 stops a second ave/euler with "Reuse of compute ID" (each creates an
    // internal compute of the same name); say so plainly.
    if let Some(other) = sim
        .defs
        .fixes
        .iter()
        .find(|f| f.head.style == "ave/euler" && f.id() != id)
    {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "only one fix ave/euler can exist (fix {} is one already)",
                other.id()
            ),
            Some(format!(
                "LIGGGHTS 3.8 stops on a second one too; 'unfix {}' first",
                other.id()
            )),
        ));
    }
    a.keyword("ave/euler keyword", &["nevery"])?;
    let nevery = a.count("nevery")?;
    a.keyword("ave/euler keyword", &["cell_size_relative"])?;
    let c = a.positive("cell_size_relative")?;
    // LIGGGHTS-PFM reads three sizes (x, y, z); LIGGGHTS 3.8 one.
    let cell_size_relative = if a.peek().is_some_and(|w| w != "parallel") {
        rdem::DVec3::new(c, a.positive("cell size y")?, a.positive("cell size z")?)
    } else {
        rdem::DVec3::splat(c)
    };
    a.keyword("ave/euler keyword", &["parallel"])?;
    let parallel = a.yes_no("parallel")?;
    let mut base_region = None;
    while !a.is_done() {
        a.keyword("ave/euler keyword", &["basevolume_region"])?;
        let name = a.peek().unwrap_or("").to_string();
        let r = sim.fixed_region(a, "fix ave/euler basevolume_region")?;
        base_region = Some((name, r));
    }
    Ok(Box::new(AveEuler {
        nevery,
        cell_size_relative,
        parallel,
        base_region,
        base_volumes: None,
        cells: None,
        step: 0,
    }))
}

impl ScriptFix for AveEuler {
    fn wants_virial(&self, step: u64, setup: bool) -> bool {
        due(self.nevery, step, setup)
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let step = ctx.step;
        let setup = ctx.setup;
        if !due(self.nevery, step, setup) {
            return Ok(());
        }
        let w = ctx.world_ref();
        let virial = w.current_virial().ok_or_else(|| {
            format!(
                "fix {} (ave/euler): the contact virial of step {step} was not computed",
                head.id
            )
        })?;
        let p = &w.particles;
        let rmax = w
            .comm
            .max(p.radius[..p.nlocal()].iter().copied().fold(0.0, f64::max));
        let grid = EulerGrid::new(
            w.domain.boxlo,
            w.domain.boxhi,
            self.cell_size_relative * 2.0 * rmax,
        );
        let base = match &self.base_region {
            None => None,
            Some((_, region)) => {
                if self.base_volumes.as_ref().map(|(g, _)| *g) != Some(grid) {
                    self.base_volumes = Some((grid, grid.base_volumes(region)));
                }
                self.base_volumes.as_ref().map(|(_, v)| v.as_slice())
            }
        };
        self.cells = Some(euler::average(
            &grid,
            p,
            head.groupbit,
            virial,
            base,
            &*w.comm,
        ));
        self.step = step;
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
