//! `cohesion bond/nonlinear` (LIGGGHTS-INL): the bond of [`crate::bond`] with a
//! hysteretic law in each of its normal force, twisting and bending torque.
//!
//! LIGGGHTS-INL has no manual page for it; this is what its build (idaholab/LIGGGHTS-INL,
//! d69df36) computes, measured against it in `tests/bond_nonlinear.rs`. Creation, the
//! bond's size (r_b, A, J, I), breakage, damping and the shear force are those of
//! `cohesion bond`, with these differences:
//!
//! - **Normal force**, from δ = d₀ − d (> 0 pressed, < 0 pulled) and the extremes δ_max ≥ 0
//!   of the present compression and δ_min ≤ 0 of the present tension (each set back to 0
//!   when δ changes sign). In tension, with the stiffnesses k, k_u, k_c of `_fn2`:
//!   F = k A δ on the first loading (δ = δ_min), F = k_u A (δ − δ_min) + k A δ_min on
//!   unloading down to δ_c = (k_u − k)/(k_u + k_c) δ_min, then F = −k_c A δ back to
//!   δ = 0. In compression, with `_fn1`, the same shape in √δ and without the area (as the
//!   build has it): F = k √δ on first loading, F = k_u √δ + (k − k_u) √δ_max on unloading
//!   to δ_c = ((k_u − k)/(k_u + k_c))² δ_max, then F = −k_c √δ. F > 0 pushes apart.
//! - **Twisting and bending torques** are not increments turned with the pair: the bond
//!   keeps the rotation angles θ_n += ω_n dt, θ_t += ω_t dt (in the global axes) and, per
//!   component, T = −k J θ on first loading, −k_u J θ + (k_u − k) J θ_max on unloading to
//!   θ_c = (k_u − k)/(k_u + k_c) θ_max, then k_c J θ (and the same towards θ_min); with the
//!   `_tn` stiffnesses and J for twisting, the `_tt` ones and I for bending.
//! - The shear force loses its normal part each step but is not rescaled to its length.
//! - Switches: no `dissipationBond` and no `druckerPrager`; `ratioTensionCompressionBond`
//!   (not `ratioTensionCompression`). Damping may be off altogether.
//! - Random-ID bonding reads the per-atom property `bondnonlinear_random_id`, which no
//!   template writes (as in the fork).
//!
//! The extremes are also moved by the evaluation at a run's set-up, with the angles this
//! step's plus one more increment (not kept), as the build does: a script of several
//! runs follows it. Where rdem differs from the build, on purpose: a new bond
//! starts with no extremes (the build keeps those of a broken bond of the same pair), the
//! extremes of a pair change roles with the pair (the build keeps their signs), and a wall
//! bond's shear velocity uses the full lever arm, as `cohesion bond` does in rdem.
//!
//! History layout: [`VEC`] values that change sign when i and j swap (F_t, θ_n, θ_t and
//! θ_max + θ_min of both torques), then the contact law's, then the tail: flag, d₀, (a
//! wall's anchor), and [`EXTRA`] values: δ_max, δ_min and θ_max − θ_min of both torques.

use glam::DVec3;

use super::{
    break_bond, damped, load, store, BondCoeff, BondFlags, BondForce, BondGeom, Event, Section,
};

/// History values that flip sign when i and j swap: F_t, θ_n, θ_t, θ_n,max + θ_n,min,
/// θ_t,max + θ_t,min (3 each).
pub const VEC: usize = 15;
/// Values at the end of the tail: δ_max, δ_min, θ_n,max − θ_n,min, θ_t,max − θ_t,min.
pub const EXTRA: usize = 8;

/// Properties of the stiffness tables, in [`Stiffness`]'s order.
pub const STIFFNESS_PROPERTIES: [&str; 13] = [
    "stiffnessPerUnitAreaK_fn1",
    "stiffnessPerUnitAreaKu_fn1",
    "stiffnessPerUnitAreaKc_fn1",
    "stiffnessPerUnitAreaK_fn2",
    "stiffnessPerUnitAreaKu_fn2",
    "stiffnessPerUnitAreaKc_fn2",
    "stiffnessPerUnitAreaK_ft",
    "stiffnessPerUnitAreaK_tn",
    "stiffnessPerUnitAreaKu_tn",
    "stiffnessPerUnitAreaKc_tn",
    "stiffnessPerUnitAreaK_tt",
    "stiffnessPerUnitAreaKu_tt",
    "stiffnessPerUnitAreaKc_tt",
];

/// Loading, unloading and retracting stiffness of one hysteretic law.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Branches {
    /// First loading, k.
    pub k: f64,
    /// Unloading and reloading, k_u.
    pub ku: f64,
    /// Retracting, k_c.
    pub kc: f64,
}

impl Branches {
    /// (k_u − k)/(k_u + k_c): where unloading gives way to retracting, as a share of the
    /// extreme (0 when both are 0).
    #[inline(always)]
    fn turn(&self) -> f64 {
        let s = self.ku + self.kc;
        if s == 0.0 {
            0.0
        } else {
            (self.ku - self.k) / s
        }
    }
}

/// The stiffnesses of one type pair.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stiffness {
    /// Compression (`_fn1`).
    pub compression: Branches,
    /// Tension (`_fn2`).
    pub tension: Branches,
    /// Shear, k_ft.
    pub shear: f64,
    /// Twisting (`_tn`).
    pub twist: Branches,
    /// Bending (`_tt`).
    pub bend: Branches,
}

impl Stiffness {
    /// The stiffnesses from the 13 values in [`STIFFNESS_PROPERTIES`] order.
    pub fn from_values(v: [f64; 13]) -> Self {
        let b = |k: usize| Branches {
            k: v[k],
            ku: v[k + 1],
            kc: v[k + 2],
        };
        Self {
            compression: b(0),
            tension: b(3),
            shear: v[6],
            twist: b(7),
            bend: b(10),
        }
    }
}

/// The normal force F (> 0 pushes apart) at δ = d₀ − d, given this cycle's extremes.
#[inline(always)]
pub fn normal_force(s: &Stiffness, area: f64, delta: f64, dmax: f64, dmin: f64) -> f64 {
    let (t, c) = (&s.tension, &s.compression);
    let c2 = t.turn() * dmin;
    let c1 = c.turn() * c.turn() * dmax;
    if delta < c2 {
        t.ku * area * delta + (t.k - t.ku) * area * dmin
    } else if delta < 0.0 {
        -t.kc * area * delta
    } else if delta < c1 {
        -c.kc * delta.abs().sqrt()
    } else if delta < dmax {
        c.ku * delta.abs().sqrt() + (c.k - c.ku) * dmax.abs().sqrt()
    } else {
        c.k * delta.abs().sqrt()
    }
}

/// The torque component at angle θ with this cycle's extremes `max` ≥ 0 ≥ `min`, for a
/// law of stiffnesses `b` on the section modulus `m` (J or I).
#[inline(always)]
pub fn torque(b: &Branches, m: f64, theta: f64, max: f64, min: f64) -> f64 {
    if theta >= max || theta <= min {
        -b.k * m * theta
    } else if theta > b.turn() * max {
        -b.ku * m * theta + (b.ku - b.k) * m * max
    } else if theta >= b.turn() * min {
        b.kc * m * theta
    } else {
        -b.ku * m * theta + (b.ku - b.k) * m * min
    }
}

/// One torque law over the three components of the angle `theta`: the torque, and the
/// extremes after this step (stored as sum and difference, `sum` and `diff`).
#[inline(always)]
fn torques(b: &Branches, m: f64, theta: DVec3, sum: DVec3, diff: DVec3) -> (DVec3, DVec3, DVec3) {
    let mut t = [0.0; 3];
    let (mut s, mut d) = ([0.0; 3], [0.0; 3]);
    for k in 0..3 {
        let th = theta[k];
        let (mut max, mut min) = (0.5 * (sum[k] + diff[k]), 0.5 * (sum[k] - diff[k]));
        if th > 0.0 {
            min = 0.0;
        } else if th < 0.0 {
            max = 0.0;
        }
        t[k] = torque(b, m, th, max, min);
        max = max.max(th);
        min = min.min(th);
        s[k] = max + min;
        d[k] = max - min;
    }
    (DVec3::from(t), DVec3::from(s), DVec3::from(d))
}

/// One bonded pair (the tail's flag must be set) under the nonlinear law: forces and
/// torques, and whether it broke. `vecs` are the [`VEC`] odd history values, `tail` the
/// flag, d₀, (anchor) and the [`EXTRA`] values.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn bond(
    g: &BondGeom,
    c: &BondCoeff,
    s: &Stiffness,
    fl: BondFlags,
    vecs: &mut [f64],
    tail: &mut [f64],
) -> (BondForce, Event) {
    let sec = match Section::of(g, c, fl, vecs, tail) {
        Ok(s) => s,
        Err(out) => return out,
    };
    let Section {
        r,
        n,
        rb,
        area,
        j_polar,
        i_bend,
        vn,
        v_shear,
        wn,
        wt,
        minvel,
        ..
    } = sec;
    let (update, dt) = (g.update, g.dt);
    let smooth = fl.damping_smooth;
    let damping = fl.damping || smooth;

    let x0 = tail.len() - EXTRA;
    let delta = tail[1] - r;
    let dmax = tail[x0].max(delta);
    let dmin = tail[x0 + 1].min(delta);
    let mut fnorm = DVec3::ZERO;
    let mut fnorm_d = DVec3::ZERO;
    if (fl.tension && delta < -1e-15) || (fl.compression && delta > 1e-15) {
        fnorm = normal_force(s, area, delta, dmax, dmin) * n;
        fnorm_d = if damping {
            damped(fnorm, vn, c.damping[0], smooth, minvel, dt)
        } else {
            fnorm
        };
    }
    let mut ft = load(vecs, 0);
    let mut ft_d = DVec3::ZERO;
    if fl.shear {
        ft = ft - ft.dot(n) * n - s.shear * area * dt * v_shear;
        ft_d = if damping {
            damped(ft, v_shear, c.damping[1], smooth, minvel, dt)
        } else {
            ft
        };
    }
    let x = |k: usize| DVec3::new(tail[x0 + k], tail[x0 + k + 1], tail[x0 + k + 2]);
    let (mut th_n, mut tn, mut tn_d) = (load(vecs, 1), DVec3::ZERO, DVec3::ZERO);
    let (mut sum_n, mut diff_n) = (load(vecs, 3), x(2));
    if fl.normal_torque {
        th_n += wn * dt;
        (tn, sum_n, diff_n) = torques(&s.twist, j_polar, th_n, sum_n, diff_n);
        tn_d = if damping {
            damped(tn, wn, c.damping[2], false, minvel, dt)
        } else {
            tn
        };
    }
    let (mut th_t, mut tt, mut tt_d) = (load(vecs, 2), DVec3::ZERO, DVec3::ZERO);
    let (mut sum_t, mut diff_t) = (load(vecs, 4), x(5));
    if fl.shear_torque {
        th_t += wt * dt;
        (tt, sum_t, diff_t) = torques(&s.bend, i_bend, th_t, sum_t, diff_t);
        tt_d = if damping {
            damped(tt, wt, c.damping[3], false, minvel, dt)
        } else {
            tt
        };
    }
    if fl.stress_break && update {
        let sigma = fnorm.length() / area + tt.length() * rb / i_bend;
        let tau = ft.length() / area + tn.length() * rb / j_polar;
        let sigma_max = if fl.ratio_tc && delta < -1e-15 {
            c.max_sigma * c.ratio_tc
        } else {
            c.max_sigma
        };
        if sigma > sigma_max || tau > c.max_tau {
            break_bond(vecs, tail);
            return (BondForce::default(), Event::Broken);
        }
    }
    if update {
        store(vecs, 0, ft);
        store(vecs, 1, th_n);
        store(vecs, 2, th_t);
    }
    // This cycle's extremes, set back when δ or an angle changes sign. As the fork, also
    // at a run's set-up, where the angles are this step's plus one more increment.
    store(vecs, 3, sum_n);
    store(vecs, 4, sum_t);
    tail[x0] = if delta < 0.0 { 0.0 } else { dmax };
    tail[x0 + 1] = if delta > 0.0 { 0.0 } else { dmin };
    tail[x0 + 2..x0 + 5].copy_from_slice(&diff_n.to_array());
    tail[x0 + 5..x0 + 8].copy_from_slice(&diff_t.to_array());
    (sec.forces(fnorm_d, ft_d, tn_d + tt_d), Event::None)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> Branches {
        Branches {
            k: 2.0,
            ku: 4.0,
            kc: 1.0,
        }
    }

    /// The torque of one component over a loading, unloading and retracting cycle: the
    /// first loading line −kθ, unloading at k_u from the extreme, the turn at
    /// θ_c = (k_u − k)/(k_u + k_c) θ_max where the unloading line meets k_c θ, and
    /// continuity at every branch change.
    #[test]
    fn torque_branches_meet() {
        let b = law();
        let (m, max) = (1.0, 1.0);
        assert_eq!(torque(&b, m, 1.0, 0.0, 0.0), -2.0);
        // Unloading from θ_max = 1: −4θ + 2.
        assert_eq!(torque(&b, m, 0.75, max, 0.0), -1.0);
        let tc = (4.0 - 2.0) / (4.0 + 1.0) * max;
        let below = torque(&b, m, tc - 1e-12, max, 0.0);
        let above = torque(&b, m, tc + 1e-12, max, 0.0);
        assert!((below - above).abs() < 1e-10, "{below} {above}");
        assert!((below - 1.0 * tc).abs() < 1e-10);
        // At the extreme itself both lines give −k θ_max.
        let at = torque(&b, m, max - 1e-12, max, 0.0);
        assert!((at + 2.0 * max).abs() < 1e-10, "{at}");
        // Odd: the mirrored angle with mirrored extremes gives the opposite torque.
        for th in [0.9, 0.5, 0.3, 0.1] {
            assert_eq!(torque(&b, m, -th, 0.0, -max), -torque(&b, m, th, max, 0.0));
        }
    }

    /// The normal force: first loading k A δ in tension and k √δ in compression,
    /// unloading lines that meet the retracting lines at the turns, and continuity.
    #[test]
    fn normal_branches_meet() {
        let t = law();
        let c = Branches {
            k: 3.0,
            ku: 5.0,
            kc: 2.0,
        };
        let s = Stiffness {
            compression: c,
            tension: t,
            ..Default::default()
        };
        let a = 0.5;
        // First tension loading at δ = δ_min = −1: k A δ.
        assert_eq!(normal_force(&s, a, -1.0, 0.0, -1.0), -1.0);
        let c2 = -((4.0 - 2.0) / (4.0 + 1.0));
        let l = normal_force(&s, a, c2 - 1e-12, 0.0, -1.0);
        let r = normal_force(&s, a, c2 + 1e-12, 0.0, -1.0);
        assert!((l - r).abs() < 1e-10, "{l} {r}");
        assert!((r - 1.0 * a * -c2).abs() < 1e-10);
        // First compression loading at δ = δ_max = 4: k √δ.
        assert_eq!(normal_force(&s, a, 4.0, 4.0, 0.0), 6.0);
        let c1 = ((5.0f64 - 3.0) / (5.0 + 2.0)).powi(2) * 4.0;
        let l = normal_force(&s, a, c1 - 1e-12, 4.0, 0.0);
        let r = normal_force(&s, a, c1 + 1e-12, 4.0, 0.0);
        assert!((l - r).abs() < 1e-5, "{l} {r}");
        assert!((l + 2.0 * c1.sqrt()).abs() < 1e-5);
    }

    /// Stored as sum and difference, the extremes come back exactly, are set back when
    /// the angle changes sign, and follow the angle beyond them.
    #[test]
    fn extremes_round_trip() {
        let b = law();
        let (t, s, d) = torques(
            &b,
            1.0,
            DVec3::new(0.3, -0.2, 0.0),
            DVec3::ZERO,
            DVec3::ZERO,
        );
        assert_eq!(t, DVec3::new(-0.6, 0.4, 0.0));
        assert_eq!((s.x, d.x), (0.3, 0.3));
        assert_eq!((s.y, d.y), (-0.2, 0.2));
        // Back to 0.2 on x (unloading from 0.3), and over to +0.1 on y (a new cycle).
        let (t, s2, d2) = torques(&b, 1.0, DVec3::new(0.2, 0.1, 0.0), s, d);
        assert_eq!(t.x, -4.0 * 0.2 + 2.0 * 0.3);
        assert_eq!(t.y, -0.2);
        assert_eq!((s2.x, d2.x), (0.3, 0.3));
        assert_eq!((s2.y, d2.y), (0.1, 0.1));
    }
}
