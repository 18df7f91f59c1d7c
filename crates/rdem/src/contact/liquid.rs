//! `cohesion easo/capillary/viscous`: liquid bridges between wet particles (LIGGGHTS 3.8,
//! after Easo & Wassgren; capillary force of Soulié et al., viscous forces of Nase et al.,
//! rupture distance of Lian et al.).
//!
//! Each particle carries a surface liquid content (the per-particle property
//! `surfaceLiquidContent`). A bridge forms when two particles touch (a history flag) and
//! stays, pulling, while they are apart, until the gap exceeds the rupture distance or
//! (maxSeparationDistanceRatio − 1)(r_i + r_j); then its liquid goes back to the two
//! particles in proportion to their volumes, as a flux (`liquidFlux`) that the liquid
//! transport integrates at the end of the step.
//!
//! The arithmetic is LIGGGHTS 3.8's, checked by running it (tests in rdem-script's
//! `liquid_bridges.rs`). Where its code differs from its manual, rdem does as the code:
//! - the liquid content is used as a volume fraction: the liquid on particle i is
//!   V_i·c_i (the manual says c_i is in % of V_i);
//! - the bridge takes from each particle the share ½(1 − √(1 − r_j²/(r_i + r_j)²)) of its
//!   liquid (the manual: 5 % of both);
//! - the effective contact angle is ½·θ_i·θ_j (radians), not the manual's ½(θ_i + θ_j);
//! - while the spheres overlap the capillary force is that at zero gap, and the viscous
//!   forces use the gap minSeparationDistanceRatio · R* (apart, max(that, gap));
//! - the constants 4/3·1000 and 8/15 are LIGGGHTS' truncated 1333.333333 and 0.5333333.

use glam::DVec3;

use super::cohesion::{Bridge, Cohesion};
use super::{ContactForce, Flags, Geom, PairCoeff};

/// LIGGGHTS' 4/3 · 1000, as it writes it.
const VOL1000: f64 = 1333.333333;
/// LIGGGHTS' 8/15, as it writes it.
const EIGHT_15: f64 = 0.5333333;
/// Bridges with less liquid (× 1000) than this exert no force.
const VOL_MIN: f64 = 1e-14;

/// The liquid-bridge coefficients of a type pair.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LiquidCoeff {
    /// `surfaceTension` γ (N/m).
    pub surface_tension: f64,
    /// `fluidViscosity` μ (Pa s).
    pub viscosity: f64,
    /// Effective contact angle ½ θ_i θ_j (radians; `contactAngle` is in degrees).
    pub angle: f64,
    /// `minSeparationDistanceRatio`.
    pub min_sep: f64,
    /// `maxSeparationDistanceRatio`.
    pub max_sep: f64,
    /// ln(1/minSeparationDistanceRatio).
    pub ln_inv_min: f64,
}

/// A pair of the neighbor list that does not touch, as the bridge model sees it.
#[derive(Debug, Clone, Copy)]
pub struct Separated {
    /// x_i − x_j.
    pub d: DVec3,
    /// |d|.
    pub r: f64,
    /// Radius of i.
    pub ri: f64,
    /// Radius of j.
    pub rj: f64,
    /// v_i − v_j.
    pub vr: DVec3,
    /// Angular velocity of i.
    pub wi: DVec3,
    /// Angular velocity of j.
    pub wj: DVec3,
    /// Liquid content of i.
    pub lq_i: f64,
    /// Liquid content of j.
    pub lq_j: f64,
    /// Timestep.
    pub dt: f64,
}

/// The liquid volumes (× 1000, as LIGGGHTS) that particles i and j give to a bridge, and
/// the bridge's.
#[inline(always)]
fn bridge_volumes(ri: f64, rj: f64, lq_i: f64, lq_j: f64) -> (f64, f64, f64) {
    let pi = std::f64::consts::PI;
    let radsum = ri + rj;
    let vli = VOL1000 * pi * ri * ri * ri * lq_i;
    let vlj = VOL1000 * pi * rj * rj * rj * lq_j;
    let bi = 0.5 * vli * (1.0 - (1.0 - rj * rj / (radsum * radsum)).sqrt());
    let bj = 0.5 * vlj * (1.0 - (1.0 - ri * ri / (radsum * radsum)).sqrt());
    (bi, bj, bi + bj)
}

/// The capillary force (negative: attractive) of a bridge of volume `vol1000` (× 1000)
/// between spheres of radii `ri`, `rj` at gap `gap` (0 while they overlap):
/// −π γ √(r_i r_j) (exp(A·gap/R₂ + B) + C), R₂ the larger radius, V* = V/R₂³,
/// A = −1.1 V*^−0.53, B = (−0.148 ln V* − 0.96) θ² − 0.0082 ln V* + 0.48,
/// C = 0.0018 ln V* + 0.078.
#[inline(always)]
pub fn capillary(ri: f64, rj: f64, vol1000: f64, c: &LiquidCoeff, gap: Option<f64>) -> f64 {
    let r2 = if ri >= rj { ri } else { rj };
    let r2inv = 1.0 / r2;
    let scaled = vol1000 * r2inv * 0.001 * r2inv * r2inv;
    let ln = scaled.ln();
    let th = c.angle;
    let b = (-0.148 * ln - 0.96) * th * th - 0.0082 * ln + 0.48;
    let cc = 0.0018 * ln + 0.078;
    let e = match gap {
        None => b.exp(),
        Some(gap) => {
            let a = -1.1 * scaled.powf(-0.53);
            (a * gap / r2 + b).exp()
        }
    };
    -std::f64::consts::PI * c.surface_tension * (ri * rj).sqrt() * (e + cc)
}

/// The easo/capillary/viscous bridge model; its history is one flag (1: bridged).
pub struct Easo;

impl Cohesion for Easo {
    const HIST: usize = 1;
    const BRIDGE: bool = true;

    fn force(_: &Geom, _: &PairCoeff, _: Flags) -> f64 {
        0.0
    }

    /// Touching spheres: the bridge exists (the flag is set); capillary force at zero gap,
    /// viscous normal force −6πμR*·v_n/minSep, viscous tangential force
    /// −6πμR*(8/15 ln(1/minSep) + 0.9588)·v_t.
    #[inline(always)]
    fn touching(
        g: &Geom,
        c: &PairCoeff,
        _: Flags,
        vt_rel: DVec3,
        hist: &mut [f64],
    ) -> (f64, DVec3) {
        hist[0] = 1.0;
        if !g.rj.is_finite() {
            // Walls are dry (LIGGGHTS 3.8 gives wall bridges no liquid of the wall's).
            return (0.0, DVec3::ZERO);
        }
        let (ri, rj) = (g.ri, g.rj);
        let (_, _, vol) = bridge_volumes(ri, rj, g.lq_i, g.lq_j);
        if vol < VOL_MIN {
            return (0.0, DVec3::ZERO);
        }
        let l = &c.liquid;
        let r_eff = ri * rj / (ri + rj);
        let f_cap = capillary(ri, rj, vol, l, None);
        let stokes = -6.0 * std::f64::consts::PI * l.viscosity * r_eff;
        let vn = g.vr.dot(g.n);
        let f_visc_n = stokes * vn / l.min_sep;
        let ft_over_vt = (EIGHT_15 * l.ln_inv_min + 0.9588) * stokes;
        (-(f_cap + f_visc_n), ft_over_vt * vt_rel)
    }

    /// Apart: the bridge holds while the gap is below both the rupture distance
    /// (1 + θ/2)·∛V and (maxSep − 1)(r_i + r_j); it then pulls with the capillary force at
    /// that gap and the viscous forces at gap max(gap, minSep·R*) (torques on the radii,
    /// not on contact lever arms). Beyond, it breaks: the liquid goes back in proportion
    /// to the particle volumes.
    #[inline(always)]
    fn separated(s: &Separated, c: &PairCoeff, hist: &mut [f64]) -> Bridge {
        if hist[0] != 1.0 {
            return Bridge::None;
        }
        let l = &c.liquid;
        let (ri, rj) = (s.ri, s.rj);
        let radsum = ri + rj;
        let gap = s.r - radsum;
        let (bi, bj, vol) = bridge_volumes(ri, rj, s.lq_i, s.lq_j);
        let dist_max = (1.0 + 0.5 * l.angle) * vol.cbrt() * 0.1;
        let limit = (l.max_sep - 1.0) * radsum;
        if !(gap < dist_max && gap < limit) {
            hist[0] = 0.0;
            let pi = std::f64::consts::PI;
            let invdt = 1.0 / s.dt;
            let ratio = rj / ri;
            let split = 1.0 / (1.0 + ratio * ratio * ratio);
            return Bridge::Breaks {
                flux_i: invdt * (split * vol - bi) / (VOL1000 * pi * ri * ri * ri),
                flux_j: invdt * ((1.0 - split) * vol - bj) / (VOL1000 * pi * rj * rj * rj),
            };
        }
        if vol < VOL_MIN {
            return Bridge::None;
        }
        let r_eff = ri * rj / (ri + rj);
        let f_cap = capillary(ri, rj, vol, l, Some(gap));
        let rinv = 1.0 / s.r;
        let n = s.d * rinv;
        let vn = s.vr.dot(n);
        let vt = s.vr - vn * n;
        let wr = (ri * s.wi + rj * s.wj) * rinv;
        let vtr = vt - wr.cross(s.d);
        let stokes = -6.0 * std::f64::consts::PI * l.viscosity * r_eff;
        let sep = l.min_sep.max(gap / r_eff);
        let f_visc_n = stokes * vn / sep;
        let ft = ((EIGHT_15 * (1.0 / sep).ln() + 0.9588) * stokes) * vtr;
        let tor = n.cross(ft);
        let fn_total = f_cap + f_visc_n;
        Bridge::Force(ContactForce {
            f_i: fn_total * n + ft,
            t_i: -ri * tor,
            t_j: -rj * tor,
            fn_total,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    const R: f64 = 1e-3;
    const GAMMA: f64 = 0.0728;
    const MU: f64 = 0.05;
    const THETA_DEG: f64 = 20.0;

    fn coeff() -> PairCoeff {
        coeff_min(1.01)
    }

    /// The coefficients with minSeparationDistanceRatio `min`.
    fn coeff_min(min: f64) -> PairCoeff {
        let th = THETA_DEG * PI / 180.0;
        PairCoeff {
            liquid: LiquidCoeff {
                surface_tension: GAMMA,
                viscosity: MU,
                angle: 0.5 * th * th,
                min_sep: min,
                max_sep: 1.1,
                ln_inv_min: (1.0 / min).ln(),
            },
            ..Default::default()
        }
    }

    /// Two spheres of radius R, content `c` each, i at +x at gap `gap`, relative velocity
    /// `vr`.
    fn apart(gap: f64, c: (f64, f64), vr: DVec3) -> Separated {
        Separated {
            d: DVec3::new(2.0 * R + gap, 0.0, 0.0),
            r: 2.0 * R + gap,
            ri: R,
            rj: R,
            vr,
            wi: DVec3::ZERO,
            wj: DVec3::ZERO,
            lq_i: c.0,
            lq_j: c.1,
            dt: 1e-6,
        }
    }

    /// The bridge volume of two equal spheres with content c: each gives
    /// ½(1 − √(1 − ¼)) of its liquid V·c.
    fn bridge_volume(c: f64) -> f64 {
        4.0 / 3.0 * PI * R.powi(3) * c * (1.0 - 0.75f64.sqrt())
    }

    /// The manual's capillary force, typed afresh: −π γ √(R R) (exp(A s/R + B) + C).
    fn capillary_closed_form(gap: f64, c: f64) -> f64 {
        let th = 0.5 * (THETA_DEG * PI / 180.0).powi(2);
        let vs = bridge_volume(c) / R.powi(3);
        let a = -1.1 * vs.powf(-0.53);
        let b = (-0.148 * vs.ln() - 0.96) * th * th - 0.0082 * vs.ln() + 0.48;
        let cc = 0.0018 * vs.ln() + 0.078;
        -PI * GAMMA * R * ((a * gap / R + b).exp() + cc)
    }

    fn force(b: Bridge) -> ContactForce {
        match b {
            Bridge::Force(f) => f,
            other => panic!("expected a force, got {other:?}"),
        }
    }

    /// Capillary force of two equal spheres at rest at a gap, against the manual's formula
    /// (rdem uses LIGGGHTS' truncated 4/3·1000, so 1e-8 relative), and the viscous normal
    /// force 6πμR*²u/s at approach speed u, R* = R/2 (with minSeparationDistanceRatio
    /// 0.01, below s/R*).
    #[test]
    fn capillary_and_viscous_normal_force_at_a_gap() {
        let c = coeff_min(0.01);
        let gap = 2e-5;
        let f = force(Easo::separated(
            &apart(gap, (0.01, 0.01), DVec3::ZERO),
            &c,
            &mut [1.0],
        ));
        let want = capillary_closed_form(gap, 0.01);
        assert!(want < -1e-4, "an attraction of a fraction of a mN: {want}");
        assert!(
            (f.f_i.x - want).abs() <= 1e-8 * want.abs(),
            "{} vs {want}",
            f.f_i.x
        );
        assert_eq!(f.f_i.y, 0.0);
        let u = 0.02;
        let fv = force(Easo::separated(
            &apart(gap, (0.01, 0.01), DVec3::new(-u, 0.0, 0.0)),
            &c,
            &mut [1.0],
        ));
        let r_star = 0.5 * R;
        let visc = 6.0 * PI * MU * r_star * r_star * u / gap;
        assert!(
            ((fv.f_i.x - f.f_i.x) - visc).abs() <= 1e-12 * visc,
            "viscous {} vs {visc}",
            fv.f_i.x - f.f_i.x
        );
        // Closer than minSep·R* (with the recommended 1.01, always: bridges break before
        // s = 1.01 R*): the gap is taken as minSep·R*.
        let c = coeff();
        let near = 1e-6;
        let fn_ = force(Easo::separated(
            &apart(near, (0.01, 0.01), DVec3::new(-u, 0.0, 0.0)),
            &c,
            &mut [1.0],
        ));
        let f0 = capillary_closed_form(near, 0.01);
        let visc = 6.0 * PI * MU * r_star * u / 1.01;
        assert!(((fn_.f_i.x - f0) - visc).abs() <= 1e-7 * visc);
    }

    /// Viscous tangential force −6πμR*(8/15 ln(R*/s) + 0.9588)·v_t and its torques on the
    /// radii (minSeparationDistanceRatio 0.01, below s/R*).
    #[test]
    fn viscous_tangential_force_and_torques() {
        let c = coeff_min(0.01);
        let gap = 1e-4;
        let v = 0.01;
        let f0 = force(Easo::separated(
            &apart(gap, (0.01, 0.01), DVec3::ZERO),
            &c,
            &mut [1.0],
        ));
        let f = force(Easo::separated(
            &apart(gap, (0.01, 0.01), DVec3::new(0.0, v, 0.0)),
            &c,
            &mut [1.0],
        ));
        let r_star = 0.5 * R;
        let want = -6.0 * PI * MU * r_star * (8.0 / 15.0 * (r_star / gap).ln() + 0.9588) * v;
        // 8/15 is LIGGGHTS' 0.5333333.
        assert!(
            (f.f_i.y - want).abs() <= 1e-7 * want.abs(),
            "{} vs {want}",
            f.f_i.y
        );
        assert_eq!(f.f_i.x, f0.f_i.x);
        assert!((f.t_i.z - (-R * want)).abs() <= 1e-7 * (R * want).abs());
        assert_eq!(f.t_i, f.t_j, "equal radii: equal torques");
    }

    /// The bridge holds below the rupture distance (1 + θ/2)∛V and breaks above it,
    /// sharing the liquid: with equal radii each particle ends with
    /// c + ¼(1 − √¾)(c_other − c). Without the flag nothing happens.
    #[test]
    fn rupture_distance_and_liquid_transfer() {
        let c = coeff();
        let (c1, c2) = (0.004, 0.006);
        let th = 0.5 * (THETA_DEG * PI / 180.0).powi(2);
        let vb = 4.0 / 3.0 * PI * R.powi(3) * (1.0 - 0.75f64.sqrt()) * 0.5 * (c1 + c2);
        let rupture = (1.0 + 0.5 * th) * vb.cbrt();
        assert!(rupture < 0.1 * 2.0 * R, "the rupture distance decides here");
        let mut flag = [1.0];
        let held = Easo::separated(
            &apart(0.999 * rupture, (c1, c2), DVec3::ZERO),
            &c,
            &mut flag,
        );
        assert!(matches!(held, Bridge::Force(_)));
        assert_eq!(flag[0], 1.0);
        let broke = Easo::separated(
            &apart(1.001 * rupture, (c1, c2), DVec3::ZERO),
            &c,
            &mut flag,
        );
        assert_eq!(flag[0], 0.0);
        let Bridge::Breaks { flux_i, flux_j } = broke else {
            panic!("{broke:?}")
        };
        let k = 1.0 - 0.75f64.sqrt();
        let dt = 1e-6;
        assert!((c1 + flux_i * dt - (c1 + 0.25 * k * (c2 - c1))).abs() < 1e-9 * c1);
        assert!((c2 + flux_j * dt - (c2 + 0.25 * k * (c1 - c2))).abs() < 1e-9 * c2);
        assert!(
            (flux_i + flux_j).abs() < 1e-9 * flux_i.abs(),
            "liquid is conserved"
        );
        // No bridge: nothing.
        let none = Easo::separated(&apart(0.5 * rupture, (c1, c2), DVec3::ZERO), &c, &mut [0.0]);
        assert_eq!(none, Bridge::None);
        // A lot of liquid: maxSeparationDistanceRatio decides.
        let mut flag = [1.0];
        let far = Easo::separated(&apart(0.21 * R, (0.5, 0.5), DVec3::ZERO), &c, &mut flag);
        assert!(matches!(far, Bridge::Breaks { .. }) && flag[0] == 0.0);
        let mut flag = [1.0];
        let close = Easo::separated(&apart(0.19 * R, (0.5, 0.5), DVec3::ZERO), &c, &mut flag);
        assert!(matches!(close, Bridge::Force(_)));
    }
}
