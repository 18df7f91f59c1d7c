//! The fixes LIGGGHTS 3.8 adds for `cohesion easo/capillary/viscous`: its liquid transport
//! `liquidtransfer` (style `transportequation/scalar`; `f_liquidtransfer` is the sum of
//! the particles' liquid contents) and the per-particle properties `surfaceLiquidContent`,
//! `liquidFlux` and `liquidSource` (`f_surfaceLiquidContent`, also written
//! `f_surfaceLiquidContent[0]`, in dumps and atom-style variables).
//!
//! rdem defines them with `pair_style gran ... cohesion easo/capillary/viscous` (LIGGGHTS
//! at the first run; its manual asks for a `run 0` before they are used); the engine
//! makes the values at a run's set-up ([`rdem::PairGran::setup_liquid`]), so they read as
//! an error before the first run. IDs a script has already defined are left alone.

use crate::error::Error;
use rdem::pair::{LIQUID_CONTENT, LIQUID_FLUX, LIQUID_SOURCE};

use super::{FixEntry, FixHead, ScriptFix, Stages};
use crate::sim::Sim;

/// ID of the liquid transport fix.
const TRANSFER: &str = "liquidtransfer";

/// One of the liquid properties, read by name from the particles.
#[derive(Debug)]
struct LiquidProperty(&'static str);

impl ScriptFix for LiquidProperty {
    fn peratom_shape(&self) -> Option<(usize, u64)> {
        Some((0, 1))
    }

    fn peratom(&self, sim: &Sim, _head: &FixHead, _col: Option<usize>) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no simulation box")?;
        let p = &w.particles;
        let id = p.property(self.0).ok_or_else(|| {
            format!(
                "'{}' of cohesion easo/capillary/viscous exists from the first run on (write 'run 0' first, as LIGGGHTS asks)",
                self.0
            )
        })?;
        Ok(p.props[id.0].data[..p.nlocal()].to_vec())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// The liquid transport: its value is the total liquid content.
#[derive(Debug)]
struct LiquidTransfer;

impl ScriptFix for LiquidTransfer {
    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no simulation box")?;
        let p = &w.particles;
        let id = p
            .property(LIQUID_CONTENT)
            .ok_or("exists from the first run on (write 'run 0' first)")?;
        let here: f64 = p.props[id.0].data[..p.nlocal()].iter().sum();
        Ok(vec![w.comm.sum(here)])
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// Defines the liquid fixes whose IDs are free (called by `pair_style gran` with
/// `cohesion easo/capillary/viscous`).
pub fn define(sim: &mut Sim) {
    let mut add = |id: &'static str, style: &'static str, stages, imp: Box<dyn ScriptFix>| {
        if sim.fix_index(id).is_none() {
            sim.defs.fixes.push(FixEntry {
                head: FixHead {
                    id: id.to_string(),
                    style,
                    groupbit: 1,
                },
                stages,
                origin: None,
                energy: false,
                imp,
                seconds: 0.0,
            });
        }
    };
    add(
        TRANSFER,
        "transportequation/scalar",
        Stages::VALUES,
        Box::new(LiquidTransfer),
    );
    for name in [LIQUID_CONTENT, LIQUID_FLUX, LIQUID_SOURCE] {
        add(
            name,
            "property/atom",
            Stages::NONE,
            Box::new(LiquidProperty(name)),
        );
    }
}
