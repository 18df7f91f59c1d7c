//! The JKR adhesive contact (Johnson, Kendall & Roberts 1971), in the dimensionless form of
//! Eidevåg et al. 2020 (Powder Technol. 361:1081), which LIGGGHTS_Flexible_Fibers' and
//! PICI's `model jkr` use:
//!
//! - a₀ = (9πW R*²/(2E*))^⅓, the contact radius at zero load (W the work of adhesion);
//! - δ_c = a₀²/(2·6^⅓ R*), the overlap scale: the neck breaks at δ = −δ_c;
//! - F_c = 1.5πW R*, the pull-off force under a fixed load;
//! - with â = a/a₀: δ/δ_c = 6^⅓(2â² − (4/3)â^½) and F/F_c = 4(â³ − â^{3/2}).
//!
//! Given δ, â is the largest root of the overlap equation. The fork reads it from a table
//! of 3·10⁵ points; rdem solves it exactly, by Newton's method on x = √â (see
//! [`contact_radius`]), warm-started from the contact's last â. [`Jkr`] is the normal law
//! built on it: its contact holds while the spheres are apart, down to δ = −δ_c.

use super::normal::{finish, LawTraits, Normal};
use super::{Flags, Geom, NormalOut, PairCoeff};

/// 6^⅓.
const CBRT6: f64 = 1.817_120_592_832_139_6;

/// The scales of one JKR contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// a₀: the contact radius at zero load.
    pub a0: f64,
    /// δ_c: the neck breaks at δ = −δ_c.
    pub delta_c: f64,
    /// F_c = 1.5πW R*: the pull-off force under a fixed load.
    pub f_c: f64,
}

impl Scales {
    /// The scales for work of adhesion `w`, effective radius `r_star` and effective
    /// Young's modulus `e_star`.
    pub fn new(w: f64, r_star: f64, e_star: f64) -> Self {
        Self::with(w, 4.5 * std::f64::consts::PI * w / e_star, r_star)
    }

    /// The scales of a contact of effective radius `r_star` between the type pair `c`.
    #[inline(always)]
    pub fn of(c: &PairCoeff, r_star: f64) -> Self {
        Self::with(c.jkr_w, c.jkr_k, r_star)
    }

    /// From W and k = 9πW/(2E*) (a₀³ = k R*²).
    #[inline(always)]
    fn with(w: f64, k: f64, r_star: f64) -> Self {
        let a0 = (k * r_star * r_star).cbrt();
        Self {
            a0,
            delta_c: a0 * a0 / (2.0 * CBRT6 * r_star),
            f_c: 1.5 * std::f64::consts::PI * w * r_star,
        }
    }
}

/// The smallest â on the stable branch, 6^(−2/3), where the neck breaks (δ = −δ_c).
pub const A_HAT_MIN: f64 = 0.302_853_432_138_689_9;

/// δ/δ_c for a contact radius â.
#[inline(always)]
pub fn overlap(a_hat: f64) -> f64 {
    CBRT6 * (2.0 * a_hat * a_hat - 4.0 / 3.0 * a_hat.sqrt())
}

/// F/F_c for a contact radius â (positive = repulsive).
#[inline(always)]
pub fn force(a_hat: f64) -> f64 {
    4.0 * (a_hat * a_hat * a_hat - a_hat * a_hat.sqrt())
}

/// â for an overlap `d` = δ/δ_c ≥ −1: the largest root of [`overlap`]`(â) = d`. Below −1
/// the neck has broken and there is no root; `None`.
///
/// With x = √â the equation is h(x) = 2x⁴ − (4/3)x − d/6^⅓ = 0. h is convex, with its
/// minimum at x³ = 1/6 (â = [`A_HAT_MIN`], d = −1), so Newton's method started right of
/// the root descends to it monotonically. The start x₀ = max(1, (1.5 d/6^⅓)^¼) is right
/// of the root: for x ≥ 1, h(x) ≥ (2/3)x⁴ − d/6^⅓. Each step costs a few multiplications;
/// it stops when a step changes x by less than 4 ulp or h is no longer positive (at
/// most [`MAX_STEPS`]; over δ/δ_c from −1 + 10⁻⁹ to 10⁸ it took at most 21, the most
/// next to −1, where the root is double).
pub fn contact_radius(d: f64) -> Option<f64> {
    solve(d).map(|(a, _)| a)
}

/// The most Newton steps [`contact_radius`] takes before it stops.
pub const MAX_STEPS: u32 = 60;

/// [`contact_radius`] and the number of Newton steps it took.
fn solve(d: f64) -> Option<(f64, u32)> {
    solve_from(d, 0.0)
}

/// As [`contact_radius`], warm-started from `a_start`, the contact's â of the step before
/// (0 for none: the cold start). A start left of the root is moved right of it by one
/// Newton step (h is convex, so the step overshoots the root), from where the descent is
/// monotonic as from the cold start.
pub fn contact_radius_from(d: f64, a_start: f64) -> Option<f64> {
    solve_from(d, a_start).map(|(a, _)| a)
}

/// [`contact_radius_from`] and the number of Newton steps it took.
fn solve_from(d: f64, a_start: f64) -> Option<(f64, u32)> {
    if d.is_nan() || d < -1.0 {
        return None;
    }
    let x_min = A_HAT_MIN.sqrt();
    let q = d / CBRT6;
    let h_of = |x: f64| {
        let x3 = x * x * x;
        (2.0 * x3 * x - 4.0 / 3.0 * x - q, 8.0 * x3 - 4.0 / 3.0)
    };
    // The cold start, right of the root: for x ≥ 1, h(x) ≥ (2/3)x⁴ − q.
    let cold = (1.5 * q).max(1.0).sqrt().sqrt();
    let mut steps = 0;
    let mut x = if a_start > A_HAT_MIN {
        let x = a_start.sqrt();
        let (h, dh) = h_of(x);
        if h >= 0.0 {
            x.min(cold)
        } else {
            // Left of the root: one step lands right of it (or on it); next to the
            // neck's end, where h is flat, no farther than the cold start.
            steps += 1;
            (x - h / dh).min(cold)
        }
    } else {
        cold
    };
    while steps < MAX_STEPS {
        steps += 1;
        let (h, dh) = h_of(x);
        if h <= 0.0 || dh <= 0.0 {
            // At the root (to rounding), or at the neck's end.
            break;
        }
        let next = (x - h / dh).max(x_min);
        let done = x - next <= 4.0 * f64::EPSILON * x;
        x = next;
        if done {
            break;
        }
    }
    Some((x * x, steps))
}

/// `model jkr` (LIGGGHTS_Flexible_Fibers, PICI): the JKR force F_c·F(â) with
/// k_n = (4/3)E*a, k_t = 8G*a (a = â a₀, the JKR contact radius), and Hertz's damping
/// γ_{n,t} = −2√(5/6) β √(S_{n,t} m*), S_n = 2E*√(R*δ), S_t = 8G*√(R*δ), which is zero
/// while the spheres are apart (δ ≤ 0). The fork does so: the force on a pair thrown
/// apart with e = 0.5 follows S = 2E*√(R*δ) to 1e-8 and no damping below δ = 0, where
/// S = 2E*a misses by 50 % (measured against the fork; the runs of `tests/jkr.rs` check it).
///
/// A contact forms when the spheres touch (δ = 0, where â^{3/2} = 2/3 and F = −(8/9)F_c)
/// and holds while they are apart until δ = −δ_c, where the neck breaks ([`Normal::holds`]).
/// While apart (δ ≤ 0) only this force acts: the tangential springs are cleared and act
/// again from zero at the next touch, as in the fork (measured: a sphere sticking to a
/// plane with spin, crossing δ = 0 ten times, follows the fork to 1e-8 so, and misses it
/// by 7 % with the springs kept). The rolling springs are cleared by the same rule (not
/// compared with the fork).
/// History: the contact radius â of the last step (0: no contact), the warm start of the
/// solve and the sign that the neck exists.
pub struct Jkr;

impl Normal for Jkr {
    const HIST: usize = 1;
    const SELDOM: bool = true;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: true,
        limit_force: false,
        force_exponent: 1.5,
    };
    const NECK: bool = true;

    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, hist: &mut [f64]) -> NormalOut {
        if c.jkr_w == 0.0 {
            // No work of adhesion (W = 0): Hertz's contact for the type pair, ending at
            // δ = 0 (no neck: `Scales` gives δ_c = 0, and `holds` never keeps it), as
            // both forks code it (their examples measure a restitution coefficient so).
            return super::normal::Hertz::normal(g, c, vn, flags, hist);
        }
        let s = Scales::of(c, g.r_star);
        // The pass calls the law apart only while the neck holds (δ ≥ −δ_c).
        let d = (g.delta / s.delta_c).max(-1.0);
        let a_hat = contact_radius_from(d, hist[0]).unwrap_or(A_HAT_MIN);
        if g.update {
            hist[0] = a_hat;
        }
        let a = a_hat * s.a0;
        let sq = (g.r_star * g.delta.max(0.0)).sqrt();
        let sm = (sq * g.m_star).sqrt();
        let fn_elastic = s.f_c * force(a_hat);
        let fn_contact = finish(fn_elastic, -c.hertz_damp_n * sm * vn, flags);
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic,
            kn: 4.0 / 3.0 * c.e_star * a,
            kt: 8.0 * c.g_star * a,
            gamma_t: c.hertz_damp_t * sm,
        }
    }

    #[inline(always)]
    fn holds(delta: f64, r_star: f64, c: &PairCoeff, hist: &mut [f64], update: bool) -> bool {
        if hist[0] == 0.0 {
            return false;
        }
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let held = delta >= -Scales::of(c, r_star).delta_c;
        if !held && update {
            // The neck has broken: the next touch forms a new contact.
            hist[0] = 0.0;
        }
        held
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The classic JKR points: zero load at â = 1 (δ/δ_c = (2/3)6^⅓); pull-off under a
    /// fixed load, F = −F_c, at â = (1/2)^(2/3); the neck's end, δ = −δ_c, at â = 6^(−2/3)
    /// with F = −(5/9)F_c.
    #[test]
    fn the_classic_points() {
        assert!((CBRT6 - 6f64.cbrt()).abs() < 1e-15);
        assert!((A_HAT_MIN - 6f64.powf(-2.0 / 3.0)).abs() < 1e-15);
        assert_eq!(force(1.0), 0.0);
        assert!((overlap(1.0) - 2.0 / 3.0 * CBRT6).abs() < 1e-15);
        let a_pull = 0.5f64.powf(2.0 / 3.0);
        assert!((force(a_pull) + 1.0).abs() < 1e-15);
        assert!((overlap(A_HAT_MIN) + 1.0).abs() < 1e-15);
        assert!((force(A_HAT_MIN) + 5.0 / 9.0).abs() < 1e-15);
        // The solve returns these radii.
        let a = contact_radius(overlap(1.0)).unwrap();
        assert!((a - 1.0).abs() < 1e-15, "{a}");
        let a = contact_radius(overlap(a_pull)).unwrap();
        assert!((a - a_pull).abs() < 1e-14, "{a}");
        let a = contact_radius(-1.0).unwrap();
        assert!((a - A_HAT_MIN).abs() < 1e-7, "{a}");
        assert_eq!(contact_radius(-1.0 - 1e-12), None);
        assert_eq!(contact_radius(f64::NAN), None);
    }

    /// The root is the largest one, exact to rounding, over twelve decades of overlap:
    /// the overlap equation gives back d, and the branch is the stable one (â ≥ 6^(−2/3)).
    #[test]
    fn the_root_is_exact_and_on_the_stable_branch() {
        // d from −1 + 1e-9 up through 0 to 1e8: 1e-9…1 below −1's neighbourhood in
        // geometric steps, then 1e-9…1e8.
        let mut ds = Vec::new();
        let mut e = 1e-9;
        while e < 1.0 {
            ds.push(-1.0 + e);
            ds.push(-e);
            ds.push(e);
            e *= 1.3;
        }
        while e < 1e8 {
            ds.push(e);
            e *= 1.3;
        }
        let mut most = 0;
        for d in ds {
            let (a, steps) = solve(d).unwrap();
            most = most.max(steps);
            assert!(a >= A_HAT_MIN, "{d}: {a}");
            let back = overlap(a);
            assert!(
                (back - d).abs() <= 1e-13 * d.abs().max(1.0),
                "{d}: â {a} gives {back}"
            );
        }
        // The cost: the most Newton steps any overlap took from the cold start (21 when
        // measured, next to −1, where the root is double and Newton only halves the gap).
        assert!(most <= 25, "{most} steps");
        eprintln!("most Newton steps: {most}");
    }

    /// For deep overlaps JKR tends to Hertz: F → (4/3)E*√R* δ^{3/2}. With W small against
    /// E*, at δ = 1000 δ_c the force is Hertz's within 5 %, and the difference shrinks
    /// with δ.
    #[test]
    fn deep_overlaps_tend_to_hertz() {
        let (w, r, e) = (0.05, 0.005, 1e8);
        let s = Scales::new(w, r, e);
        let mut last = f64::INFINITY;
        for k in [1e3, 1e4, 1e5] {
            let delta = k * s.delta_c;
            let f = s.f_c * force(contact_radius(delta / s.delta_c).unwrap());
            let hertz = 4.0 / 3.0 * e * r.sqrt() * delta.powf(1.5);
            let gap = (f - hertz).abs() / hertz;
            assert!(gap < last, "{k}: {gap}");
            last = gap;
        }
        assert!(last < 0.05 * 0.1, "{last}");
    }

    /// The scales: a₀³ = 9πWR*²/(2E*), δ_c = a₀²/(2·6^⅓R*), F_c = 1.5πWR*; and the force
    /// at δ = 0 is that of â where the overlap equation vanishes (â^{3/2} = 2/3).
    #[test]
    fn scales_and_the_force_at_first_touch() {
        let (w, r, e) = (0.2, 0.002, 5e7);
        let s = Scales::new(w, r, e);
        let pi = std::f64::consts::PI;
        assert!((s.a0.powi(3) - 9.0 * pi * w * r * r / (2.0 * e)).abs() < 1e-12 * s.a0.powi(3));
        assert!((s.delta_c - s.a0 * s.a0 / (2.0 * 6f64.cbrt() * r)).abs() < 1e-15 * s.delta_c);
        assert!((s.f_c - 1.5 * pi * w * r).abs() < 1e-15);
        let a = contact_radius(0.0).unwrap();
        assert!((a.powf(1.5) - 2.0 / 3.0).abs() < 1e-15, "{a}");
        // F(δ = 0) = 4F_c(â³ − â^{3/2}) = 4F_c(4/9 − 2/3) = −(8/9)F_c.
        assert!((force(a) + 8.0 / 9.0).abs() < 1e-14);
    }

    /// Warm starts (the contact's â of the step before) find the cold start's root to
    /// rounding from either side. Over an impact's smooth path (δ/δ_c from −1 up to 40
    /// and back in 400 steps, as at ~10 steps per δ_c) they take 4.1 steps on average
    /// and at most 8 (measured); only at the neck's very end (δ/δ_c = −1, where the root
    /// is double and Newton's method only halves the gap) do both starts take 25–30.
    #[test]
    fn warm_starts_find_the_same_root_in_fewer_steps() {
        for &d in &[-0.999, -0.5, 0.0, 0.3, 2.0, 40.0, 1e4] {
            let cold = contact_radius(d).unwrap();
            for &start in &[A_HAT_MIN * 1.0001, 0.5, 1.0, 3.0, 100.0] {
                let warm = contact_radius_from(d, start).unwrap();
                assert!(
                    (warm - cold).abs() <= 1e-14 * cold,
                    "{d} from {start}: {warm} {cold}"
                );
            }
        }
        let (mut prev, mut most_warm, mut total, mut ends) = (0.0, 0, 0, 0);
        for k in 0..=400 {
            let t = k as f64 / 400.0;
            let d = -1.0 + 41.0 * (std::f64::consts::PI * t).sin();
            let (a, warm) = solve_from(d, prev).unwrap();
            if k == 0 || k == 400 {
                ends = ends.max(warm);
            } else {
                most_warm = most_warm.max(warm);
                total += warm;
            }
            prev = a;
        }
        let mean = total as f64 / 399.0;
        assert!(
            most_warm <= 8 && mean < 5.0,
            "{most_warm} warm steps, mean {mean}"
        );
        assert!(ends <= MAX_STEPS, "{ends}");
        eprintln!("Newton steps along the path: mean {mean:.2}, most {most_warm}, ends {ends}");
    }

    /// The neck holds while δ ≥ −δ_c once a contact exists, and its end clears the
    /// contact (only when the history is advanced).
    #[test]
    fn the_neck_holds_down_to_minus_delta_c() {
        let m = super::super::Materials {
            work_of_adhesion: vec![0.5],
            resolution_jkr: Some(1e-4),
            ..super::super::Materials::uniform(1, 1e7, 0.3, 0.5, 0.5)
        };
        let needs = super::super::Needs {
            work_of_adhesion: true,
            ..Default::default()
        };
        let t = super::super::CoeffTable::new(&m, needs).unwrap();
        let c = t.get(1, 1);
        let r = 5e-4;
        let dc = Scales::of(c, r).delta_c;
        assert!((dc - Scales::new(0.5, r, c.e_star).delta_c).abs() < 1e-15 * dc);
        // The reach the neighbor lists add covers every neck, closely.
        for rr in [1e-6, 1e-3, 1.0] {
            let need = Scales::of(c, rr).delta_c;
            let reach = t.neck_reach(rr);
            assert!(
                reach >= need && reach < need * (1.0 + 1e-9),
                "{rr}: {reach} {need}"
            );
        }
        assert!(!Jkr::holds(-0.1 * dc, r, c, &mut [0.0], true));
        let mut h = [0.8];
        assert!(Jkr::holds(-dc * (1.0 - 1e-12), r, c, &mut h, true));
        assert!(!Jkr::holds(-dc * (1.0 + 1e-9), r, c, &mut h, false));
        assert_eq!(h, [0.8]);
        assert!(!Jkr::holds(-dc * (1.0 + 1e-9), r, c, &mut h, true));
        assert_eq!(h, [0.0]);
        assert!(!Jkr::holds(-0.1 * dc, r, c, &mut h, true));
        // A missing or negative work of adhesion is refused with its name.
        let mut bad = m.clone();
        bad.work_of_adhesion = vec![-0.1];
        let err = super::super::CoeffTable::new(&bad, needs).unwrap_err();
        assert!(err.to_string().contains("workOfAdhesion"), "{err}");
        bad.work_of_adhesion.clear();
        assert!(super::super::CoeffTable::new(&bad, needs).is_err());
    }
}
