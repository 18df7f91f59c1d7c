//! Tangential sub-models.

use glam::DVec3;

use super::{Flags, Geom, NormalOut, PairCoeff};

/// A tangential force law.
pub trait Tangential {
    /// History values per contact.
    const HIST: usize;
    /// Tangential force on i, given the relative tangential velocity of the contact points
    /// `vt` and the normal load `load` (≥ 0) that sets the Coulomb limit μ·load.
    fn force(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        hist: &mut [f64],
    ) -> DVec3;
}

/// `tangential history`: the spring ξ gains v_t dt, is projected onto the current tangent
/// plane, and F_t = −k_t ξ (the current k_t on the whole spring). If |F_t| > μ·load the force
/// is scaled to μ·load, ξ is reset to −F_t/k_t and no damping acts; otherwise
/// F_t −= γ_t v_t (with `tangential_damping on`). Without [`Geom::update`] the stored spring
/// is used as it is and not written back.
pub struct History;

impl Tangential for History {
    const HIST: usize = 3;
    #[inline(always)]
    fn force(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        hist: &mut [f64],
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
    #[inline(always)]
    fn force(
        _g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        vt: DVec3,
        flags: Flags,
        _hist: &mut [f64],
    ) -> DVec3 {
        if !flags.tangential_damping {
            return DVec3::ZERO;
        }
        let ft = -no.gamma_t * vt;
        let ft_max = c.mu * load;
        let mag2 = ft.length_squared();
        if mag2 > ft_max * ft_max {
            ft * (ft_max / mag2.sqrt())
        } else {
            ft
        }
    }
}
