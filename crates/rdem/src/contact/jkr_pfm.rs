//! LIGGGHTS-PFM's `model jkr`: the JKR adhesive contact as that fork defines it, which
//! differs from LIGGGHTS_Flexible_Fibers' and PICI's law of the same name ([`super::jkr`]):
//!
//! - the adhesion is `cohesionEnergyDensity` γ per type pair, a surface energy: the work
//!   of adhesion is W = 2γ (the fork's force is 4E*a³/(3R*) − √(16πγE*a³), JKR's
//!   4E*a³/(3R*) − √(8πWE*a³));
//! - the force acts only while the spheres overlap (δ > 0): no neck holds them apart. (The
//!   fork computes a force for listed pairs apart down to JKR's δ_c but never applies it:
//!   its pair pass adds the forces of a pair that does not touch only when a cohesion
//!   model asks, and jkr does not; a wall apart gets none either.) Spheres still stick:
//!   the force is attractive from δ = 0 (−(8/9)·1.5πWR*) up to JKR's zero-load overlap;
//! - the tangential and rolling models see Hertz's normal force, (4/3)E*√(R*δ)·δ plus
//!   the damping, for their Coulomb and rolling limits (and `incremental_history`'s
//!   unloading test), with Hertz's k_t = 8G*√(R*δ); the damping is Hertz's,
//!   γ_{n,t} = −2√(5/6) β √(S_{n,t} m*), S_n = 2E*√(R*δ), S_t = 8G*√(R*δ).
//!
//! The contact radius a is the largest root of JKR's δ = a²/R* − √(2πWa/E*). The fork
//! finds it by at most 10 Newton steps from a = R*, enough where a is near R* (sticky
//! soft spheres, its example) and short of the root where a ≪ R*; rdem solves it exactly
//! ([`super::jkr::contact_radius_from`], warm-started from the step before). With γ = 0
//! the law is Hertz's (a = √(R*δ)), as the fork's Newton steps give.

use super::jkr::{contact_radius_from, force, Scales};
use super::normal::{finish, LawTraits, Normal};
use super::{Flags, Geom, NormalOut, PairCoeff};

/// `model jkr` of LIGGGHTS-PFM (rdem's name: `jkr/pfm`). History: the contact radius â
/// of the step before, the warm start of the solve.
pub struct JkrPfm;

impl Normal for JkrPfm {
    const HIST: usize = 1;
    const SELDOM: bool = true;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.5,
    };

    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, hist: &mut [f64]) -> NormalOut {
        let sq = (g.r_star * g.delta).sqrt();
        let kn = 4.0 / 3.0 * c.e_star * sq;
        let kt = 8.0 * c.g_star * sq;
        let sm = (sq * g.m_star).sqrt();
        let fn_damp = -c.hertz_damp_n * sm * vn;
        let fn_hertz = kn * g.delta;
        let fn_elastic = if c.jkr_w > 0.0 {
            let s = Scales::of(c, g.r_star);
            let a_hat = contact_radius_from(g.delta / s.delta_c, hist[0])
                .expect("a positive overlap has a contact radius");
            if g.update {
                hist[0] = a_hat;
            }
            s.f_c * force(a_hat)
        } else {
            fn_hertz
        };
        NormalOut {
            fn_contact: finish(fn_elastic, fn_damp, flags),
            fn_load: fn_hertz + fn_damp,
            fn_elastic,
            kn,
            kt,
            gamma_t: c.hertz_damp_t * sm,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pair of type-pair coefficients with E*, G*, β and the JKR scales of W = 2γ.
    fn coeff(gamma: f64) -> PairCoeff {
        let (e_star, g_star, beta) = (3.0e6, 1.1e6, -0.2);
        PairCoeff {
            e_star,
            g_star,
            beta,
            hertz_damp_n: -2.0 * (5.0f64 / 6.0).sqrt() * beta * (2.0 * e_star).sqrt(),
            hertz_damp_t: -2.0 * (5.0f64 / 6.0).sqrt() * beta * (8.0 * g_star).sqrt(),
            jkr_w: 2.0 * gamma,
            jkr_k: 4.5 * std::f64::consts::PI * 2.0 * gamma / e_star,
            ..Default::default()
        }
    }

    fn geom(delta: f64) -> Geom {
        Geom {
            n: glam::DVec3::Z,
            delta,
            dist: 0.003 - delta,
            ri: 0.0015,
            rj: 0.0015,
            r_star: 7.5e-4,
            m_star: 1e-5,
            ci: 0.0015,
            cj: 0.0015,
            vr: glam::DVec3::ZERO,
            wi: glam::DVec3::ZERO,
            wj: glam::DVec3::ZERO,
            roll_scale: 1.0,
            inertia_i: 1.0,
            inertia_j: 1.0,
            dt: 1e-6,
            lq_i: 0.0,
            lq_j: 0.0,
            update: true,
        }
    }

    /// The force is the fork's formula, 4E*a³/(3R*) − √(16πγE*a³), at the a that solves
    /// δ = a²/R* − 2√(πγ/E*)·√a (the fork's Newton relation); the loads are Hertz's.
    #[test]
    fn the_forks_force_and_hertz_loads() {
        let gamma = 30.0;
        let c = coeff(gamma);
        let pi = std::f64::consts::PI;
        for delta in [1e-7, 1e-5, 1e-4, 5e-4] {
            let g = geom(delta);
            let vn = -0.01;
            let no = JkrPfm::normal(&g, &c, vn, Flags::default(), &mut [0.0]);
            // Bisection on the relation, from a = 0 (below the root: the relation is
            // negative there) to a = 10R*.
            let f =
                |a: f64| a * a / g.r_star - 2.0 * (pi * gamma / c.e_star).sqrt() * a.sqrt() - delta;
            let (mut lo, mut hi) = (
                ((pi * gamma / c.e_star).sqrt() * g.r_star).powf(2.0 / 3.0),
                10.0 * g.r_star,
            );
            assert!(f(lo) < 0.0 && f(hi) > 0.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if f(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let a = 0.5 * (lo + hi);
            let want = 4.0 / 3.0 * c.e_star * a.powi(3) / g.r_star
                - (16.0 * pi * gamma * c.e_star * a.powi(3)).sqrt();
            assert!(
                (no.fn_elastic - want).abs() <= 1e-9 * want.abs(),
                "{delta}: {} {want}",
                no.fn_elastic
            );
            let sq = (g.r_star * delta).sqrt();
            let damp = -c.hertz_damp_n * (sq * g.m_star).sqrt() * vn;
            assert!((no.fn_contact - (want + damp)).abs() <= 1e-9 * want.abs().max(damp.abs()));
            let hertz = 4.0 / 3.0 * c.e_star * sq * delta;
            assert!((no.fn_load - (hertz + damp)).abs() <= 1e-12 * hertz);
            assert!((no.kt - 8.0 * c.g_star * sq).abs() <= 1e-12 * no.kt);
        }
    }

    /// Just after touching the force pulls with JKR's −(8/9)·1.5πWR*; with γ = 0 the law
    /// is Hertz's.
    #[test]
    fn the_pull_at_touch_and_hertz_without_adhesion() {
        let gamma = 0.5;
        let c = coeff(gamma);
        let g = geom(1e-15);
        let no = JkrPfm::normal(&g, &c, 0.0, Flags::default(), &mut [0.0]);
        let f_c = 1.5 * std::f64::consts::PI * 2.0 * gamma * g.r_star;
        assert!(
            (no.fn_elastic + 8.0 / 9.0 * f_c).abs() < 1e-6 * f_c,
            "{}",
            no.fn_elastic
        );
        let c = coeff(0.0);
        let g = geom(1e-5);
        let no = JkrPfm::normal(&g, &c, 0.0, Flags::default(), &mut [0.0]);
        let hertz = 4.0 / 3.0 * c.e_star * (g.r_star * g.delta).sqrt() * g.delta;
        assert_eq!(no.fn_elastic, hertz);
        assert_eq!(no.fn_contact, hertz);
    }
}
