//! `fix ID group multicontact/halfspace [geometric_prefactor γ]`: the multi-contact model
//! of Brodu et al. (2015) for the contacts whose model has `surface multicontact`
//! ([`rdem::multicontact`] states the model and what was measured of LIGGGHTS 3.8).
//!
//! γ defaults to 1.125, as LIGGGHTS 3.8 (measured: the same forces with and without
//! `geometric_prefactor 1.125`; its manual gives no default). The model acts on every
//! contact of a `surface multicontact` pair style or wall, whatever the fix's group.

use std::sync::Arc;

use rdem::multicontact::MultiContact;

use super::{style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "multicontact/halfspace",
    parse,
    Stages::NONE,
    "`[geometric_prefactor γ]` (default 1.125): each contact's overlap corrected for the particle's other contacts (Brodu et al. 2015); needs `surface multicontact` in `pair_style gran` or a `fix wall/gran`",
)
.notes("one MPI rank only (threads are fine); the fix's group is not used: every `surface multicontact` contact takes part, as in LIGGGHTS 3.8's tutorial");

/// LIGGGHTS 3.8's default prefactor (measured).
const DEFAULT_GAMMA: f64 = 1.125;

/// A defined fix: its prefactor (the store lives in `World::multicontact`).
struct HalfSpace {
    gamma: f64,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    let mut gamma = DEFAULT_GAMMA;
    while !a.is_done() {
        a.keyword("multicontact/halfspace keyword", &["geometric_prefactor"])?;
        gamma = a.positive("geometric prefactor γ")?;
    }
    if w.multicontact.is_some() && sim.fix_index(&head.id).is_none() {
        return Err(a.error_at(
            STYLE_WORD,
            "multicontact/halfspace: there is already one",
            Some("one multicontact/halfspace per script".into()),
        ));
    }
    Ok(Box::new(HalfSpace { gamma }))
}

impl ScriptFix for HalfSpace {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        w.multicontact = Some(Arc::new(MultiContact::new(self.gamma)));
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.multicontact = None;
        }
    }
}
