//! Cohesion sub-models: an attractive normal force k·A with k the cohesion energy density
//! (`sjkr`, `sjkr2`), and the liquid bridges of `easo/capillary/viscous` ([`super::liquid`]).

use glam::DVec3;

use super::{CohesionKind, Flags, Geom, PairCoeff};

/// A cohesion law: the attractive normal force of a touching pair and, for liquid
/// bridges, the forces of a bridged pair that no longer touches.
pub trait Cohesion {
    /// History values of the cohesion model (after the others').
    const HIST: usize = 0;
    /// True for a liquid-bridge model: it reads the particles' liquid contents, adds a
    /// tangential force, and acts on pairs that do not touch ([`Cohesion::separated`]).
    const BRIDGE: bool = false;
    /// True for `cohesion bond`: no cohesive force of its own, but the passes carry the
    /// bonds' history and forces (so only these kernels are compiled with the bond code).
    const BONDS: bool = false;

    /// Attractive force (≥ 0) of a touching pair.
    fn force(g: &Geom, c: &PairCoeff, flags: Flags) -> f64;

    /// Touching pair, bridge models: the attractive normal force (≥ 0 pulls; a repulsive
    /// viscous force is negative) and the tangential force on i, given the relative
    /// tangential velocity of the contact points `vt_rel`; `hist` is the model's history.
    #[inline(always)]
    fn touching(
        g: &Geom,
        c: &PairCoeff,
        flags: Flags,
        _vt_rel: DVec3,
        _hist: &mut [f64],
    ) -> (f64, DVec3) {
        (Self::force(g, c, flags), DVec3::ZERO)
    }

    /// A pair of the neighbor list that does not touch (bridge models only): the bridge's
    /// force, its end, or nothing. `hist` is the model's history.
    #[inline(always)]
    fn separated(_s: &super::liquid::Separated, _c: &PairCoeff, _hist: &mut [f64]) -> Bridge {
        Bridge::None
    }
}

/// What a bridged pair that does not touch does this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bridge {
    /// No bridge.
    None,
    /// The bridge holds: force on i, torques on i and j.
    Force(super::ContactForce),
    /// The bridge breaks: the liquid goes back to the particles; the rates of change of
    /// their liquid contents (per time) are `flux_i`, `flux_j`.
    Breaks {
        /// Liquid flux into i (content per time).
        flux_i: f64,
        /// Liquid flux into j.
        flux_j: f64,
    },
}

/// No cohesion.
pub struct Off;

impl Cohesion for Off {
    #[inline(always)]
    fn force(_: &Geom, _: &PairCoeff, _: Flags) -> f64 {
        0.0
    }
}

/// `cohesion bond`: no cohesion force (the bonds act in [`crate::bond`]); the kernels
/// made with it are the only ones the pair and wall passes run with bonds.
pub struct Bonded;

impl Cohesion for Bonded {
    const BONDS: bool = true;
    #[inline(always)]
    fn force(_: &Geom, _: &PairCoeff, _: Flags) -> f64 {
        0.0
    }
}

/// `cohesion sjkr`: A is the area of the circle where the two spheres intersect,
/// A = −π/4 (d−r_i−r_j)(d+r_i−r_j)(d−r_i+r_j)(d+r_i+r_j)/d²; against a wall A = π(r_i² − d²).
pub struct Sjkr;

impl Cohesion for Sjkr {
    #[inline(always)]
    fn force(g: &Geom, c: &PairCoeff, _: Flags) -> f64 {
        let d = g.dist;
        let a = if g.rj.is_finite() {
            let (ri, rj) = (g.ri, g.rj);
            -std::f64::consts::FRAC_PI_4
                * ((d - ri - rj) * (d + ri - rj) * (d - ri + rj) * (d + ri + rj))
                / (d * d)
        } else {
            std::f64::consts::PI * (g.ri * g.ri - d * d)
        };
        c.cohesion * a.max(0.0)
    }
}

/// `cohesion sjkr2`: A = 2π δ (2R*) between particles; against a wall LIGGGHTS 3.8 uses
/// A = 2π δ r_i (no factor 2), and so do we.
pub struct Sjkr2;

impl Cohesion for Sjkr2 {
    #[inline(always)]
    fn force(g: &Geom, c: &PairCoeff, _: Flags) -> f64 {
        let two_r = if g.rj.is_finite() {
            2.0 * g.r_star
        } else {
            g.ri
        };
        c.cohesion * 2.0 * std::f64::consts::PI * g.delta * two_r
    }
}

/// The kernel of `cohesion sjkr` and `sjkr2`, which keep no history: it runs the law
/// that [`Flags`] names ([`super::ContactModel::kernel_flags`]), so that one kernel serves
/// both; with the seldom-used normal laws ([`super::normal::Normal::SELDOM`]) it serves
/// `off` too, with no pull (the contact's normal force less 0.0 is that force, bit for
/// bit).
pub struct Pull;

impl Cohesion for Pull {
    #[inline(always)]
    fn force(g: &Geom, c: &PairCoeff, flags: Flags) -> f64 {
        match flags.cohesion {
            CohesionKind::Sjkr2 => Sjkr2::force(g, c, flags),
            CohesionKind::Off => 0.0,
            _ => Sjkr::force(g, c, flags),
        }
    }
}
