//! Tangential sub-models.

use glam::DVec3;

use super::{Flags, Geom, NormalOut, PairCoeff};

/// A tangential force law.
pub trait Tangential {
    /// History values per contact.
    const HIST: usize;
    /// How many of them (the leading ones, `hist`) are a vector tied to the i→j orientation,
    /// which changes sign when i and j swap; the rest (`even`) are scalars.
    const ODD: usize;
    /// Tangential force on i, given the relative tangential velocity of the contact points
    /// `vt` and the normal load `load` (≥ 0) that sets the Coulomb limit μ·load. `hist`
    /// holds the `ODD` history values, `even` the other `HIST − ODD`.
    #[allow(clippy::too_many_arguments)]
    fn force(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        hist: &mut [f64],
        even: &mut [f64],
    ) -> DVec3;
}

/// `ft` scaled to the magnitude `ft_max` if it is longer (the Coulomb limit).
#[inline(always)]
fn coulomb_cap(ft: DVec3, ft_max: f64) -> DVec3 {
    let mag2 = ft.length_squared();
    if mag2 > ft_max * ft_max {
        ft * (ft_max / mag2.sqrt())
    } else {
        ft
    }
}

/// `tangential history`: the spring ξ gains v_t dt, is projected onto the current tangent
/// plane, and F_t = −k_t ξ (the current k_t on the whole spring). If |F_t| > μ·load the force
/// is scaled to μ·load, ξ is reset to −F_t/k_t and no damping acts; otherwise
/// F_t −= γ_t v_t (with `tangential_damping on`). Without [`Geom::update`] the stored spring
/// is used as it is and not written back.
pub struct History;

impl Tangential for History {
    const HIST: usize = 3;
    const ODD: usize = 3;
    #[inline(always)]
    fn force(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        hist: &mut [f64],
        _even: &mut [f64],
    ) -> DVec3 {
        let mut s = DVec3::new(hist[0], hist[1], hist[2]);
        if g.update {
            s += vt * g.dt;
            s -= s.dot(g.n) * g.n;
        }
        let spring = -no.kt * s;
        let ft_max = c.mu * load;
        let mag2 = spring.length_squared();
        let ft = if mag2 > ft_max * ft_max {
            let ft = spring * (ft_max / mag2.sqrt());
            s = if no.kt > 0.0 {
                -ft / no.kt
            } else {
                DVec3::ZERO
            };
            ft
        } else if flags.tangential_damping {
            spring - no.gamma_t * vt
        } else {
            spring
        };
        if g.update {
            hist[0] = s.x;
            hist[1] = s.y;
            hist[2] = s.z;
        }
        ft
    }
}

/// `tangential no_history`: F_t = −γ_t v_t (no spring), capped at μ·load.
pub struct NoHistory;

impl Tangential for NoHistory {
    const HIST: usize = 0;
    const ODD: usize = 0;
    #[inline(always)]
    fn force(
        _g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        _hist: &mut [f64],
        _even: &mut [f64],
    ) -> DVec3 {
        if !flags.tangential_damping {
            return DVec3::ZERO;
        }
        coulomb_cap(-no.gamma_t * vt, c.mu * load)
    }
}

/// `tangential incremental_history` (LIGGGHTS-PFM; Thornton, Cummins & Cleary 2011, 2013):
/// the contact stores the tangential force itself, not a spring length. Each step the
/// stored force is projected onto the current tangent plane; while the normal contact force
/// falls (unloading) it is scaled by k_t/k_t,old, so that it vanishes with the load; then it
/// gains the increment −k_t v_t dt and, with `tangential_damping on`, the dashpot −γ_t v_t,
/// which stays in the stored force. If |F_t| > μ·load it is scaled to μ·load, and that is
/// stored. A run's set-up evaluation ([`Geom::update`] false) uses the stored force as it
/// is, uncapped. These choices (the unloading test on the normal force, damping included,
/// the stored dashpot, the set-up) are LIGGGHTS-PFM's, measured: rdem follows its oblique
/// impacts to 1e-13 (tests/incremental_history.rs). The history is the force (3 values,
/// tied to i→j), then k_t and the normal force of the step before.
pub struct IncrementalHistory;

impl Tangential for IncrementalHistory {
    const HIST: usize = 5;
    const ODD: usize = 3;
    #[inline(always)]
    fn force(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        hist: &mut [f64],
        even: &mut [f64],
    ) -> DVec3 {
        let mut ft = DVec3::new(hist[0], hist[1], hist[2]);
        if !g.update {
            // A run's set-up evaluation: the stored force as it is, not capped (PFM).
            return ft;
        }
        ft -= ft.dot(g.n) * g.n;
        let (kt_old, fn_old) = (even[0], even[1]);
        if no.fn_load < fn_old && kt_old > 0.0 {
            ft *= no.kt / kt_old;
        }
        ft -= no.kt * g.dt * vt;
        if flags.tangential_damping {
            ft -= no.gamma_t * vt;
        }
        let ft = coulomb_cap(ft, c.mu * load);
        hist[0] = ft.x;
        hist[1] = ft.y;
        hist[2] = ft.z;
        even[0] = no.kt;
        even[1] = no.fn_load;
        ft
    }
}
