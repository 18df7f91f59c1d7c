//! `model hysteretic/nonlinear1` and `model hysteretic/nonlinear2` (LIGGGHTS-INL): the
//! nonlinear elasto-plastic normal laws that INL fitted to the cyclic compression of
//! deformable biomass particles (Xia et al. 2019, Powder Technol. 345:1, "Discrete element
//! modeling of deformable pinewood chips in cyclic loading test"). LIGGGHTS-INL has no
//! manual page for them; the law below is written from its equations and checked against
//! runs of LIGGGHTS-INL built here (the tests in `rdem-cli`'s `hysteretic` module).
//!
//! With δ the overlap, δ₀ the plastic overlap (zero force on unloading), δ_max the largest
//! overlap of the contact and the per-type-pair coefficients α (`alphaCustom`),
//! C (`cinCustom`), A₁, A₂, A₃ (`aoneCustom`, `atwoCustom`, `athreeCustom`) and
//! k_c = `kcinCustom`·A₂:
//!
//! - **Loading** (the overlap grows and the spheres approach, or the first touch): the
//!   loading stiffness k₁ is A₂ until the first unloading, then the k₁ that unloading set;
//!   above δ₀ the force is α k₁ (δ − δ₀)² + f₀, f₀ the offset that the last unloading left.
//!   Below δ₀ the force stays on the unloading curve: β_n (δ − δ₀) down to δ_min and
//!   −k_c δ below it (nonlinear1), or C k₂ (e^{β_n(δ−δ₀)} − 1) (nonlinear2).
//! - **Unloading** (otherwise): the unloading stiffness k₂ is A₃ k₁ (nonlinear1, k₁ of the
//!   loading) or A₃ (A₁ δ_max + A₂) (nonlinear2); δ₀ = (1 − k₁/k₂) δ_max; the next loading
//!   stiffness is k₁ = A₁ δ_max + A₂. nonlinear1 unloads linearly along
//!   β k₂ (δ − δ₀), β = α k₁ (δ_max − δ₀')² / (k₂ (δ_max − δ₀)) so that the curve leaves
//!   the loading force at δ_max (δ₀' the plastic overlap of the loading), and below
//!   δ_min = β (k₂ − k₁)/(β k₂ + k_c) δ_max along the adhesive line −k_c δ. nonlinear2
//!   unloads along C k₂ (e^{β_n(δ−δ₀)} − 1) with β_n = ln(α k₁ (δ_max − δ₀')²/(C k₂) + 1)
//!   / (δ_max − δ₀). Above δ₀ both add (δ − δ₀) f₀'/(δ_max − δ₀), f₀' the offset the
//!   loading carried, and set the new offset f₀ to the unloading force less α k₁ (δ − δ₀)².
//! - **Damping**: γ = √(4 m* α k /(1 + (π/ln e)²)) · s, with k = k₁ and
//!   s = δ^¼ + δ₀^¼ (nonlinear1) or δ^½ + δ₀^½ (nonlinear2) on loading; on unloading
//!   k = k₁ of the loading and s = δ^¼ (nonlinear1) or 0.001 δ^−¼ (nonlinear2). The same γ
//!   damps the tangential motion (with `tangential_damping on`).
//! - The normal force is the elastic force, the damping −γ v_n and `pullOffForce`; the
//!   tangential stiffness is k₁. With `limitForce on`, a negative force is cut to zero when
//!   `coefficientAdhesionStiffness` and `pullOffForce` are both zero.
//!
//! The fork also requires `LoadingStiffness`, `UnloadingStiffness` and
//! `coefficientPlasticityDepth`, which its law does not use (LoadingStiffness enters only
//! the `limitForce` test, through k_c = `coefficientAdhesionStiffness`·LoadingStiffness);
//! rdem requires them too, so that a script runs in both or in neither.
//!
//! The fork writes the contact history at every evaluation, the force evaluation that
//! sets up a run included; rdem writes it only when the evaluation advances the history
//! ([`Geom::update`]). The two differ only on the first step of a contact that exists when
//! a run is set up with the spheres moved since the history was last written.

use super::normal::{LawTraits, Normal};
use super::{Flags, Geom, NormalKind, NormalOut, PairCoeff};

/// The per-type-pair coefficients of the hysteretic nonlinear laws.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HystereticCoeff {
    /// α (`alphaCustom`).
    pub alpha: f64,
    /// C (`cinCustom`).
    pub cin: f64,
    /// A₁ (`aoneCustom`): the growth of the loading stiffness with δ_max.
    pub a1: f64,
    /// A₂ (`atwoCustom`): the first loading stiffness.
    pub a2: f64,
    /// A₃ (`athreeCustom`): the unloading stiffness factor.
    pub a3: f64,
    /// k_c = `kcinCustom`·A₂: the adhesive branch's stiffness (nonlinear1).
    pub kc_adh: f64,
    /// `pullOffForce`: a constant added to the normal force.
    pub pull_off: f64,
    /// Whether `limitForce` may cut a negative force: `coefficientAdhesionStiffness` and
    /// `pullOffForce` both zero.
    pub limitable: bool,
    /// 4/(1 + (π/ln e)²), e the coefficient of restitution: the damping's factor.
    pub damp: f64,
}

/// The history values, in order.
mod h {
    pub const DMAX: usize = 0;
    pub const D0: usize = 1;
    pub const K1: usize = 2;
    pub const D0_OLD: usize = 3;
    pub const K1_OLD: usize = 4;
    pub const PREV: usize = 5;
    pub const DMIN: usize = 6;
    pub const BETA: usize = 7;
    pub const F0: usize = 8;
    pub const F0_OLD: usize = 9;
}

/// Both hysteretic nonlinear laws: one kernel, the law chosen per contact from
/// [`Flags`] (both keep the same history).
pub struct HystereticNonlinear;

impl Normal for HystereticNonlinear {
    const HIST: usize = 10;
    const SELDOM: bool = true;
    const TRAITS: LawTraits = LawTraits {
        stiffness: false,
        characteristic_velocity: false,
        hysteresis: false,
        adhesion: false,
        // The fork registers `limitForce` on by default for these laws.
        limit_force: true,
        force_exponent: 1.0,
    };
    #[inline(always)]
    fn normal(g: &Geom, c: &PairCoeff, vn: f64, flags: Flags, hist: &mut [f64]) -> NormalOut {
        let second = flags.normal == NormalKind::HystereticNonlinear2;
        let p = &c.hysteretic;
        let delta = g.delta;
        let mut s = [0.0; 10];
        s.copy_from_slice(&hist[..10]);
        s[h::DMAX] = s[h::DMAX].max(delta);
        let dmax = s[h::DMAX];
        let prev = s[h::PREV];
        let loading = delta >= prev && (prev == 0.0 || vn <= 0.0);
        // √(4 m* α k /(1 + (π/ln e)²)) for the loading stiffness k.
        let damp = |k: f64| (p.damp * g.m_star * p.alpha * k).sqrt();
        let (f, gamma, k1) = if loading {
            let d0 = s[h::D0];
            let k1 = if d0 == 0.0 { p.a2 } else { s[h::K1] };
            let f = if delta > d0 {
                p.alpha * k1 * (delta - d0) * (delta - d0) + s[h::F0]
            } else if second {
                p.cin * p.a3 * s[h::K1] * ((s[h::BETA] * (delta - d0)).exp() - 1.0)
            } else if delta <= s[h::DMIN] {
                -p.kc_adh * delta
            } else {
                s[h::BETA] * (delta - d0)
            };
            let reach = if second {
                delta.sqrt() + d0.sqrt()
            } else {
                delta.sqrt().sqrt() + d0.sqrt().sqrt()
            };
            s[h::K1] = k1;
            s[h::D0_OLD] = d0;
            s[h::K1_OLD] = k1;
            s[h::F0_OLD] = s[h::F0];
            (f, damp(k1) * reach, k1)
        } else {
            let k1_old = s[h::K1_OLD];
            let k2 = if second {
                p.a3 * (p.a1 * dmax + p.a2)
            } else {
                p.a3 * k1_old
            };
            let d0 = (1.0 - k1_old / k2) * dmax;
            let lift = p.alpha * k1_old * (dmax - s[h::D0_OLD]) * (dmax - s[h::D0_OLD]);
            let k1 = dmax * p.a1 + p.a2;
            let above = delta >= d0;
            // The share of the loading's offset that the unloading curve carries.
            let carried = if above {
                (delta - d0) * s[h::F0_OLD] / (dmax - d0)
            } else {
                0.0
            };
            let f = if second {
                let beta = (lift / (p.cin * k2) + 1.0).ln() / (dmax - d0);
                s[h::BETA] = beta;
                s[h::DMIN] = beta * (k2 - k1_old) / (beta * k2 + p.kc_adh) * dmax;
                p.cin * k2 * ((beta * (delta - d0)).exp() - 1.0) + carried
            } else {
                let beta = lift / k2 / (dmax - d0);
                let dmin = beta * (k2 - k1_old) / (beta * k2 + p.kc_adh) * dmax;
                s[h::DMIN] = dmin;
                if delta >= dmin {
                    s[h::BETA] = beta * k2;
                    beta * k2 * (delta - d0) + carried
                } else {
                    -p.kc_adh * delta
                }
            };
            s[h::F0] = if above && (second || delta >= s[h::DMIN]) {
                f - p.alpha * k1 * (delta - d0) * (delta - d0)
            } else {
                0.0
            };
            s[h::D0] = d0;
            s[h::K1] = k1;
            let reach = if second {
                0.001 / delta.sqrt().sqrt()
            } else {
                delta.sqrt().sqrt()
            };
            (f, damp(k1_old) * reach, k1)
        };
        s[h::PREV] = delta;
        if g.update {
            hist[..10].copy_from_slice(&s);
        }
        let fe = f + p.pull_off;
        let mut fn_contact = fe - gamma * vn;
        if flags.limit_force && fn_contact < 0.0 && p.limitable {
            fn_contact = 0.0;
        }
        NormalOut {
            fn_contact,
            fn_load: fn_contact,
            fn_elastic: fe,
            kn: k1,
            kt: k1,
            gamma_t: gamma,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    const ALPHA: f64 = 20.0;
    const A1: f64 = 1e9;
    const A2: f64 = 4e4;
    const A3: f64 = 8.0;
    const KCIN: f64 = 1e-4;
    const CIN: f64 = 1e-7;

    fn coeff(e: f64) -> PairCoeff {
        let ln_e = f64::ln(e);
        PairCoeff {
            hysteretic: HystereticCoeff {
                alpha: ALPHA,
                cin: CIN,
                a1: A1,
                a2: A2,
                a3: A3,
                kc_adh: KCIN * A2,
                pull_off: 0.0,
                limitable: true,
                damp: 4.0 / (1.0 + std::f64::consts::PI.powi(2) / (ln_e * ln_e)),
            },
            ..Default::default()
        }
    }

    fn geom(delta: f64) -> Geom {
        Geom {
            n: DVec3::Z,
            delta,
            dist: 0.003 - delta,
            ri: 0.0015,
            rj: 0.0015,
            r_star: 0.00075,
            m_star: 4e-6,
            ci: 0.0015,
            cj: 0.0015,
            vr: DVec3::ZERO,
            wi: DVec3::ZERO,
            wj: DVec3::ZERO,
            roll_scale: 1.0,
            inertia_i: 1.0,
            inertia_j: 1.0,
            dt: 1e-6,
            lq_i: 0.0,
            lq_j: 0.0,
            update: true,
        }
    }

    fn flags(law: NormalKind) -> Flags {
        Flags {
            normal: law,
            ..Flags::default()
        }
    }

    /// The elastic force along a path of overlaps, quasi-statically (v_n = 0).
    fn path(law: NormalKind, deltas: &[f64], hist: &mut [f64; 10]) -> Vec<f64> {
        let c = coeff(0.3);
        deltas
            .iter()
            .map(|&d| HystereticNonlinear::normal(&geom(d), &c, 0.0, flags(law), hist).fn_elastic)
            .collect()
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * a.abs().max(b.abs()).max(1e-300)
    }

    /// First loading is α A₂ δ²; unloading leaves it at δ_max and reaches zero force at
    /// the plastic overlap δ₀ = (1 − 1/A₃) δ_max, linearly (nonlinear1) or exponentially
    /// (nonlinear2, whose k₂ = A₃ (A₁ δ_max + A₂) gives δ₀ = (1 − A₂/k₂) δ_max).
    #[test]
    fn loading_and_unloading_branches() {
        let dmax = 1e-4;
        let up: Vec<f64> = (1..=100).map(|k| dmax * k as f64 / 100.0).collect();
        for law in [
            NormalKind::HystereticNonlinear1,
            NormalKind::HystereticNonlinear2,
        ] {
            let mut h = [0.0; 10];
            let f = path(law, &up, &mut h);
            for (d, f) in up.iter().zip(&f) {
                assert!(
                    close(*f, ALPHA * A2 * d * d, 1e-12),
                    "{law:?} loading at {d}"
                );
            }
            let top = ALPHA * A2 * dmax * dmax;
            let k2 = if law == NormalKind::HystereticNonlinear1 {
                A3 * A2
            } else {
                A3 * (A1 * dmax + A2)
            };
            let d0 = (1.0 - A2 / k2) * dmax;
            // Just below δ_max the unloading force is the loading force at δ_max.
            let eps = dmax * 1e-9;
            let f = path(law, &[dmax - eps], &mut h)[0];
            assert!(close(f, top, 1e-6), "{law:?}: {f} leaving {top}");
            let mid = 0.5 * (d0 + dmax);
            let f = path(law, &[mid], &mut h)[0];
            let want = if law == NormalKind::HystereticNonlinear1 {
                0.5 * top
            } else {
                let beta = (top / (CIN * k2) + 1.0).ln() / (dmax - d0);
                CIN * k2 * ((beta * (mid - d0)).exp() - 1.0)
            };
            assert!(close(f, want, 1e-9), "{law:?}: {f} against {want} half way");
            assert!(f < 0.5 * top || law == NormalKind::HystereticNonlinear1);
            let f = path(law, &[d0], &mut h)[0];
            assert!(f.abs() < 1e-12 * top, "{law:?}: {f} at δ₀");
        }
    }

    /// nonlinear1 below δ₀: the unloading line goes on to δ_min, then the adhesive line
    /// −k_c δ; reloading from below δ₀ comes back along the same lines.
    #[test]
    fn adhesive_branch_below_the_plastic_overlap() {
        let law = NormalKind::HystereticNonlinear1;
        let dmax = 1e-4;
        let mut h = [0.0; 10];
        path(law, &[0.5 * dmax, dmax], &mut h);
        let k2 = A3 * A2;
        let d0 = (1.0 - 1.0 / A3) * dmax;
        let beta = ALPHA * A2 * dmax * dmax / k2 / (dmax - d0);
        let kc = KCIN * A2;
        let dmin = beta * (k2 - A2) / (beta * k2 + kc) * dmax;
        assert!(dmin > 0.0 && dmin < d0);
        let above = 0.5 * (dmin + d0);
        let below = 0.5 * dmin;
        let f = path(law, &[above, below], &mut h);
        assert!(close(f[0], beta * k2 * (above - d0), 1e-12), "{}", f[0]);
        assert!(close(f[1], -kc * below, 1e-12), "{}", f[1]);
        // Reloading below δ₀ retraces the lines.
        let f = path(law, &[0.75 * dmin, above], &mut h);
        assert!(close(f[0], -kc * 0.75 * dmin, 1e-12), "{}", f[0]);
        assert!(close(f[1], beta * k2 * (above - d0), 1e-12), "{}", f[1]);
    }

    /// Reloading from a partial unloading continues from the force where unloading
    /// stopped, along the stiffer k₁ = A₁ δ_max + A₂.
    #[test]
    fn reloading_is_continuous_and_stiffer() {
        for law in [
            NormalKind::HystereticNonlinear1,
            NormalKind::HystereticNonlinear2,
        ] {
            let dmax = 1e-4;
            let mut h = [0.0; 10];
            path(law, &[0.5 * dmax, dmax], &mut h);
            let dr = 0.98 * dmax;
            let fr = path(law, &[dr], &mut h)[0];
            let eps = dmax * 1e-7;
            let f = path(law, &[dr + eps, dr + 2.0 * eps], &mut h);
            let k1 = A1 * dmax + A2;
            let d0 = h[h::D0];
            // Loading now: α k₁ (δ − δ₀)² + f₀, through (δ_r, F_r).
            let slope = 2.0 * ALPHA * k1 * (dr - d0);
            assert!(
                close(f[0], fr + slope * eps, 1e-6),
                "{law:?}: {} {fr}",
                f[0]
            );
            assert!(h[h::K1] == k1);
        }
    }

    /// The damping: γ = √(4 m* α k₁/(1 + (π/ln e)²)) (δ^¼ + δ₀^¼) on first loading
    /// (nonlinear1; δ^½ + δ₀^½ for nonlinear2), also on the tangential motion;
    /// `limitForce` (on by default for these laws) cuts the pull of fast unloading.
    #[test]
    fn damping_and_limit_force() {
        let c = coeff(0.3);
        let d = 5e-5;
        let g = geom(d);
        let ln_e = f64::ln(0.3);
        let base = (4.0 * g.m_star * ALPHA * A2
            / (1.0 + std::f64::consts::PI.powi(2) / (ln_e * ln_e)))
            .sqrt();
        for (law, s) in [
            (NormalKind::HystereticNonlinear1, d.powf(0.25)),
            (NormalKind::HystereticNonlinear2, d.sqrt()),
        ] {
            let mut h = [0.0; 10];
            let out = HystereticNonlinear::normal(&g, &c, -0.01, flags(law), &mut h);
            assert!(close(out.gamma_t, base * s, 1e-12), "{law:?}");
            assert!(close(
                out.fn_contact - out.fn_elastic,
                0.01 * base * s,
                1e-12
            ));
            assert_eq!((out.kn, out.kt), (A2, A2));
            // Fast unloading: the damping pulls harder than the spring pushes.
            let g2 = geom(0.999 * d);
            let mut lim = flags(law);
            let free = HystereticNonlinear::normal(&g2, &c, 10.0, lim, &mut h.clone());
            assert!(free.fn_contact < 0.0, "{law:?}: {}", free.fn_contact);
            lim.limit_force = true;
            let cut = HystereticNonlinear::normal(&g2, &c, 10.0, lim, &mut h);
            assert_eq!(cut.fn_contact, 0.0);
        }
        assert!(NormalKind::HystereticNonlinear1.traits().limit_force);
        assert!(!NormalKind::Hertz.traits().limit_force);
    }

    /// An evaluation that does not advance the history leaves it as it was.
    #[test]
    fn no_update_keeps_the_history() {
        let c = coeff(0.3);
        let mut h = [0.0; 10];
        path(
            NormalKind::HystereticNonlinear1,
            &[5e-5, 1e-4, 9e-5],
            &mut h,
        );
        let before = h;
        let mut g = geom(8e-5);
        g.update = false;
        HystereticNonlinear::normal(&g, &c, 0.1, flags(NormalKind::HystereticNonlinear1), &mut h);
        assert_eq!(h, before);
    }
}
