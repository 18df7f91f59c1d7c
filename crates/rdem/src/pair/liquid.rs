//! The liquid of `cohesion easo/capillary/viscous` ([`crate::contact::liquid`]): the
//! per-particle properties LIGGGHTS 3.8 creates for it, the liquid flux of the bridges
//! that break in a force pass, and the transport step that moves the liquid.
//!
//! As LIGGGHTS (its `fix transportequation/scalar` named `liquidtransfer`), each particle
//! has a liquid content `surfaceLiquidContent` (starting at
//! `surfaceLiquidContentInitial`, refreshed on ghosts every step), a flux `liquidFlux`
//! (zeroed before each step's force pass, filled by the bridges that break, ghosts' shares
//! added to their owners) and a source `liquidSource` (0 unless set); at the end of the
//! step the content grows by (flux + source)·dt.

use std::sync::Mutex;

use super::PairGran;
use crate::comm::Comm;
use crate::contact::{CohesionKind, Materials};
use crate::error::Result;
use crate::particles::{Particles, PropId};

/// Name of the liquid content property (LIGGGHTS' `f_surfaceLiquidContent`).
pub const CONTENT: &str = "surfaceLiquidContent";
/// Name of the liquid flux property (`f_liquidFlux`).
pub const FLUX: &str = "liquidFlux";
/// Name of the liquid source property (`f_liquidSource`).
pub const SOURCE: &str = "liquidSource";

/// A bridge that broke in a force pass: near-list position `k` of the pair (i, j) and the
/// liquid fluxes into i and j.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BridgeBreak {
    /// Near-list position of the pair (the order in which the fluxes are added).
    pub k: u32,
    /// Owned particle.
    pub i: u32,
    /// Partner (owned or ghost).
    pub j: u32,
    /// Flux into i (content per time).
    pub flux_i: f64,
    /// Flux into j.
    pub flux_j: f64,
}

/// The breaks of one pass, recorded from any thread (breaks are rare: a lock each costs
/// nothing measurable) and applied in near-list order, so that the sums do not depend on
/// the thread count. The buffer keeps its capacity between passes.
#[derive(Debug, Default)]
pub(crate) struct Breaks(Mutex<Vec<BridgeBreak>>);

impl Clone for Breaks {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl Breaks {
    /// Records one break.
    pub(crate) fn push(&self, b: BridgeBreak) {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).push(b);
    }
}

/// The liquid properties' handles and the breaks of the current pass.
#[derive(Debug, Clone)]
pub struct LiquidState {
    /// `surfaceLiquidContent`.
    pub content: PropId,
    /// `liquidFlux`.
    pub flux: PropId,
    /// `liquidSource`.
    pub source: PropId,
    pub(crate) breaks: Breaks,
}

impl PairGran {
    /// With liquid bridges: makes the liquid properties if they do not exist (the content
    /// starting at `surfaceLiquidContentInitial`, forwarded to ghosts every step), and
    /// returns the neighbor contact distance factor the bridges need; 1 otherwise.
    pub fn setup_liquid(&mut self, p: &mut Particles, materials: &Materials) -> Result<f64> {
        if self.model.cohesion != CohesionKind::Easo {
            self.liquid = None;
            return Ok(1.0);
        }
        let l = &materials.liquid;
        let factor = l.contact_distance_factor()?;
        let content = p.add_property(CONTENT, 1, &[l.initial_content()?])?;
        p.set_forward(content);
        let flux = p.add_property(FLUX, 1, &[0.0])?;
        let source = p.add_property(SOURCE, 1, &[0.0])?;
        self.liquid = Some(LiquidState {
            content,
            flux,
            source,
            breaks: Breaks::default(),
        });
        Ok(factor)
    }

    /// The liquid properties, with liquid bridges (after [`PairGran::setup_liquid`]).
    pub fn liquid(&self) -> Option<&LiquidState> {
        self.liquid.as_ref()
    }

    /// Before a force pass: a step's pass (`update`) starts from zero flux; a run's set-up
    /// adds to what is there, as LIGGGHTS (which zeroes the flux in its initial
    /// integration).
    pub(super) fn begin_liquid(&mut self, p: &mut Particles, update: bool) {
        if let Some(l) = &self.liquid {
            if update {
                p.props[l.flux.0].data.fill(0.0);
            }
        }
    }

    /// After a force pass: the fluxes of the broken bridges added in near-list order
    /// (ghosts' shares stay on the ghosts until [`PairGran::reverse_liquid`]).
    pub(super) fn end_liquid(&mut self, p: &mut Particles) {
        let Some(l) = &mut self.liquid else {
            return;
        };
        let breaks = l.breaks.0.get_mut().unwrap_or_else(|e| e.into_inner());
        breaks.sort_unstable_by_key(|b| b.k);
        let flux = &mut p.props[l.flux.0].data;
        for b in breaks.drain(..) {
            flux[b.i as usize] += b.flux_i;
            flux[b.j as usize] += b.flux_j;
        }
    }

    /// Adds the ghosts' liquid flux onto their owners (after the force pass).
    pub fn reverse_liquid(&self, p: &mut Particles, comm: &dyn Comm) {
        if let Some(l) = &self.liquid {
            let mut flux = std::mem::take(&mut p.props[l.flux.0].data);
            comm.reverse_scalar(p, &mut flux);
            p.props[l.flux.0].data = flux;
        }
    }

    /// The end of a step: every owned particle's liquid content grows by
    /// (flux + source)·dt.
    pub fn integrate_liquid(&self, p: &mut Particles, dt: f64) {
        if let Some(l) = &self.liquid {
            let (c, f, s) = (l.content.0, l.flux.0, l.source.0);
            for i in 0..p.nlocal() {
                let add = (p.props[f].data[i] + p.props[s].data[i]) * dt;
                p.props[c].data[i] += add;
            }
        }
    }
}
