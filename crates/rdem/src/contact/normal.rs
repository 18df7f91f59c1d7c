//! Normal force sub-models. Each returns the normal contact force (elastic + damping,
//! positive = repulsive, after `limitForce`) and the stiffness and damping the tangential
//! and rolling sub-models need.

use super::{Flags, Geom, NormalOut, PairCoeff};

/// What the rest of rdem needs to know of a normal law besides its force: the material
/// properties it reads and how its force grows with the overlap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawTraits {
    /// Stiffness and damping come from `kn`, `kt`, `gamman`, `gammat`, not from Young's
    /// modulus and the coefficient of restitution.
    pub stiffness: bool,
    /// It reads `characteristicVelocity`.
    pub characteristic_velocity: bool,
    /// It reads the hysteresis properties (`loadingStiffness`, ...).
    pub hysteresis: bool,
    /// It reads `workOfAdhesion` and `resolutionJKR`.
    pub adhesion: bool,
    /// The default of `limitForce` (off but for the laws whose fork makes it on).
    pub limit_force: bool,
    /// The exponent p of its elastic force, F ~ δ^p (heat/gran's area correction).
    pub force_exponent: f64,
}

/// A normal force law. A new law is a type implementing this, one row of the table in
/// `contact/mod.rs` (its kind and script name), its material properties, and its tests.
pub trait Normal {
    /// History values it keeps per contact.
    const HIST: usize;
    /// What the rest of rdem needs to know of it.
    const TRAITS: LawTraits;
    /// True for a law whose contact holds while the particles are apart (a JKR neck):
    /// the passes then ask [`Normal::holds`] of a listed pair that does not touch.
    const NECK: bool = false;
    /// True for a seldom-used law: its kernels serve `cohesion off` with the `sjkr`/`sjkr2`
    /// kernel ([`super::cohesion::Pull`], which pulls with nothing under `off`), so that
    /// rdem is compiled for fewer kernels. The common laws keep kernels of their own.
    const SELDOM: bool = false;
    /// Normal force for normal relative velocity `vn` (negative while approaching). With
    /// [`Normal::NECK`], `g.delta` may be negative (the contact holds apart).
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, hist: &mut [f64]) -> NormalOut;
    /// For a pair apart by −`delta` (> 0) with effective radius `r_star`: whether its
    /// contact still holds (then the passes evaluate it with the negative overlap). With
    /// `update`, a contact that no longer holds is ended in `hist` (the law's history).
    #[inline(always)]
    fn holds(_delta: f64, _r_star: f64, _c: &PairCoeff, _hist: &mut [f64], _update: bool) -> bool {
        false
    }
}

/// The normal contact force from its elastic and damping parts, after `limitForce`.
#[inline(always)]
pub(super) fn finish(fn_elastic: f64, fn_damp: f64, flags: Flags) -> f64 {
    let f = fn_elastic + fn_damp;
    if flags.limit_force && f < 0.0 {
        0.0
    } else {
        f
    }
}

/// `model hertz`: k_n = 4/3 E*√(R*δ), k_t = 8G*√(R*δ),
/// γ_{n,t} = −2√(5/6) β √(S_{n,t} m*) with S_n = 2E*√(R*δ), S_t = k_t.
pub struct Hertz;

impl Normal for Hertz {
    const HIST: usize = 0;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.5,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, _hist: &mut [f64]) -> NormalOut {
        let sq = (g.r_star * g.delta).sqrt();
        let kt = 8.0 * c.g_star * sq;
        let kn = 4.0 / 3.0 * c.e_star * sq;
        // γ = −2√(5/6) β √(S m*) with S ∝ √(R*δ): one square root of √(R*δ) m* serves
        // both, times the precomputed −2√(5/6) β √(2E*) and −2√(5/6) β √(8G*).
        let s = (sq * g.m_star).sqrt();
        let gamma_n = c.hertz_damp_n * s;
        let gamma_t = c.hertz_damp_t * s;
        let fn_elastic = kn * g.delta;
        let fn_contact = finish(fn_elastic, -gamma_n * vn, flags);
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic,
            kn,
            kt,
            gamma_t,
        }
    }
}

/// Hooke stiffness from the characteristic velocity V_c (LIGGGHTS `gran_model_hooke`):
/// k_n = 16/15 √R* E* (15 m* V_c² / (16 √R* E*))^{1/5}.
#[inline(always)]
pub fn hooke_kn(c: &PairCoeff, r_star: f64, m_star: f64) -> f64 {
    let sr = r_star.sqrt();
    16.0 / 15.0 * sr * c.e_star * (15.0 * m_star * c.vc * c.vc / (16.0 * sr * c.e_star)).powf(0.2)
}

/// Hooke damping: γ_n = √(4 m* k_n ln²e / (ln²e + π²)).
#[inline(always)]
pub fn hooke_gamma(c: &PairCoeff, kn: f64, m_star: f64) -> f64 {
    (4.0 * m_star * kn * c.ln_e_ratio).sqrt()
}

/// `model hooke`: linear spring with k_t = k_n and γ_t = γ_n.
pub struct Hooke;

impl Normal for Hooke {
    const HIST: usize = 0;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: true,
        hysteresis: false,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.0,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, _hist: &mut [f64]) -> NormalOut {
        let kn = hooke_kn(c, g.r_star, g.m_star);
        let gamma_n = hooke_gamma(c, kn, g.m_star);
        let fn_elastic = kn * g.delta;
        let fn_contact = finish(fn_elastic, -gamma_n * vn, flags);
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic,
            kn,
            kt: kn,
            gamma_t: gamma_n,
        }
    }
}

/// `model hooke/hysteresis` (Walton–Braun, as LIGGGHTS 3.8): loading along k1 (the Hooke
/// k_n); unloading and reloading along k2 = k1 + (k2max − k1) δ_max/δ_lim, which reaches
/// k2max = `coefficientMaxElasticStiffness`·k1 at δ_lim = k2max/(k2max − k1) · φ_f · 2R*
/// (φ_f = `coefficientPlasticityDepth`); below zero force an adhesive branch of stiffness
/// kc = `coefficientAdhesionStiffness`·k1. History: the largest overlap δ_max. Damping as
/// Hooke; `limitForce` does not apply (the adhesive branch is the point of the model).
pub struct HookeHysteresis;

impl Normal for HookeHysteresis {
    const HIST: usize = 1;
    const SELDOM: bool = true;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: true,
        hysteresis: true,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.0,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, _flags: Flags, hist: &mut [f64]) -> NormalOut {
        let k1 = hooke_kn(c, g.r_star, g.m_star);
        let gamma_n = hooke_gamma(c, k1, g.m_star);
        let k2max = c.k2max_ratio * k1;
        let kc = c.kc_ratio * k1;
        let delta = g.delta;
        let dmax = hist[0].max(delta);
        hist[0] = dmax;
        let dlim = k2max / (k2max - k1) * c.phi_f * 2.0 * g.r_star;
        let branch = if dmax >= dlim {
            k2max * (delta - dlim) + k1 * dlim
        } else {
            let k2 = k1 + (k2max - k1) * dmax / dlim;
            let f = k2 * (delta - dmax) + k1 * dmax;
            if f >= k1 * delta {
                k1 * delta
            } else {
                f
            }
        };
        let fe = if branch > -kc * delta {
            branch
        } else {
            // Adhesive branch: the unloading line is moved to meet it.
            if g.update {
                hist[0] = 0.5
                    * (delta
                        + (delta * delta + 4.0 * (k1 + kc) * delta * dlim / (k2max - k1)).sqrt());
            }
            -kc * delta
        };
        let fn_contact = fe - gamma_n * vn;
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic: fe,
            kn: k1,
            kt: k1,
            gamma_t: gamma_n,
        }
    }
}

/// `model hertz/stiffness` (LIGGGHTS 3.8): the given per-type-pair coefficients scaled by
/// √(R*δ): k_n = kn √(R*δ), k_t = kt √(R*δ), γ_n = gamman m* √(R*δ), γ_t = gammat m* √(R*δ).
/// LIGGGHTS 3.8 has no `absolute_damping` for this model (it stops on the keyword).
pub struct HertzStiffness;

impl Normal for HertzStiffness {
    const HIST: usize = 0;
    const TRAITS: LawTraits = LawTraits {
        stiffness: true,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.5,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, _hist: &mut [f64]) -> NormalOut {
        let sq = (g.r_star * g.delta).sqrt();
        let kn = c.kn * sq;
        let msq = g.m_star * sq;
        let fn_elastic = kn * g.delta;
        let fn_contact = finish(fn_elastic, -c.gamman * msq * vn, flags);
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic,
            kn,
            kt: c.kt * sq,
            gamma_t: c.gammat * msq,
        }
    }
}

/// `model hooke/stiffness` (LIGGGHTS 3.8): constant k_n = kn, k_t = kt; γ_n = gamman m*,
/// γ_t = gammat m*, or with `absolute_damping on` γ_n = gamman_abs, γ_t = gammat_abs
/// (the table holds whichever the flag selects).
pub struct HookeStiffness;

impl Normal for HookeStiffness {
    const HIST: usize = 0;
    const TRAITS: LawTraits = LawTraits {
        stiffness: true,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: false,
        limit_force: false,
        force_exponent: 1.0,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, _hist: &mut [f64]) -> NormalOut {
        let m = if flags.absolute_damping {
            1.0
        } else {
            g.m_star
        };
        let fn_elastic = c.kn * g.delta;
        let fn_contact = finish(fn_elastic, -c.gamman * m * vn, flags);
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic,
            kn: c.kn,
            kt: c.kt,
            gamma_t: c.gammat * m,
        }
    }
}

/// The kernel type of `hertz/stiffness` and `hooke/stiffness`, which keep no history:
/// the law is picked per contact from [`Flags::normal`] (the same all run), so that the
/// two seldom-used laws are compiled into one set of kernels instead of two. Its
/// `TRAITS` are never read: each law's own are ([`super::NormalKind::traits`]).
pub struct Stiffness;

impl Normal for Stiffness {
    const HIST: usize = 0;
    const SELDOM: bool = true;
    const TRAITS: LawTraits = HertzStiffness::TRAITS;
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, hist: &mut [f64]) -> NormalOut {
        if flags.normal == super::NormalKind::HookeStiffness {
            HookeStiffness::normal(g, c, vn, flags, hist)
        } else {
            HertzStiffness::normal(g, c, vn, flags, hist)
        }
    }
}
