//! Cohesion sub-models: an attractive normal force k·A with k the cohesion energy density.

use super::{Geom, PairCoeff};

/// A cohesion law: magnitude of the attractive normal force.
pub trait Cohesion {
    /// Attractive force (≥ 0).
    fn force(g: &Geom, c: &PairCoeff) -> f64;
}

/// No cohesion.
pub struct Off;

impl Cohesion for Off {
    #[inline(always)]
    fn force(_: &Geom, _: &PairCoeff) -> f64 {
        0.0
    }
}

/// `cohesion sjkr`: A is the area of the circle where the two spheres intersect,
/// A = −π/4 (d−r_i−r_j)(d+r_i−r_j)(d−r_i+r_j)(d+r_i+r_j)/d²; against a wall A = π(r_i² − d²).
pub struct Sjkr;

impl Cohesion for Sjkr {
    #[inline(always)]
    fn force(g: &Geom, c: &PairCoeff) -> f64 {
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
    fn force(g: &Geom, c: &PairCoeff) -> f64 {
        let two_r = if g.rj.is_finite() {
            2.0 * g.r_star
        } else {
            g.ri
        };
        c.cohesion * 2.0 * std::f64::consts::PI * g.delta * two_r
    }
}
