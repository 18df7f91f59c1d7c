//! Rolling friction sub-models. Each returns the torque on i; j receives the opposite.
//! The relative rotation is w_r = ω_i − ω_j (against a wall, ω_i scaled by
//! [`Geom::roll_scale`]); its normal (torsion) part is removed unless `torsionTorque on`.

use glam::DVec3;

use super::{Flags, Geom, NormalOut, PairCoeff, RollingKind};

/// A rolling resistance law.
pub trait Rolling {
    /// History values per contact.
    const HIST: usize;
    /// Rolling torque on i.
    /// `load` is the normal load of the contact (≥ 0), as for the Coulomb limit.
    fn torque(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        flags: Flags,
        hist: &mut [f64],
    ) -> DVec3;
}

/// w_r = ω_i − ω_j (ω_i scaled by [`Geom::roll_scale`] against a wall).
#[inline(always)]
fn relative_rotation(g: &Geom) -> DVec3 {
    g.roll_scale * g.wi - g.wj
}

#[inline(always)]
fn without_torsion(v: DVec3, g: &Geom, flags: Flags) -> DVec3 {
    if flags.torsion_torque {
        v
    } else {
        v - v.dot(g.n) * g.n
    }
}

/// No rolling friction.
pub struct Off;

impl Rolling for Off {
    const HIST: usize = 0;
    #[inline(always)]
    fn torque(_: &Geom, _: &PairCoeff, _: &NormalOut, _: f64, _: Flags, _: &mut [f64]) -> DVec3 {
        DVec3::ZERO
    }
}

/// `rolling_friction cdt`: torque μ_r k_n δ R* against the direction of w_r, k_n the normal
/// law's stiffness (as LIGGGHTS: k_n δ is the elastic force of Hertz and Hooke, not of
/// hooke/hysteresis, JKR or the hysteretic nonlinear laws); the torsion part is removed
/// from the torque. The same kernel runs `rolling_friction cdtnonlinear2` (LIGGGHTS-INL),
/// whose torque takes the normal law's whole force (damping and `limitForce` included)
/// for k_n δ, as the fork's code does (it has no manual page).
pub struct Cdt;

impl Rolling for Cdt {
    const HIST: usize = 0;
    #[inline(always)]
    fn torque(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        _load: f64,
        flags: Flags,
        _: &mut [f64],
    ) -> DVec3 {
        let wr = relative_rotation(g);
        let mag = wr.length();
        if mag > 0.0 {
            let load = if flags.rolling == RollingKind::CdtNonlinear2 {
                no.fn_contact
            } else {
                no.kn * g.delta
            };
            without_torsion(-(c.mu_r * load * g.r_star / mag) * wr, g, flags)
        } else {
            DVec3::ZERO
        }
    }
}

/// Elastic–plastic spring torque shared by epsd and epsd2: M += −k_r w_r dt, capped at
/// μ_r R* · load. As in LIGGGHTS the stored torque is not turned with the contact.
/// Returns the spring torque and whether it is below the cap.
#[inline(always)]
fn spring_torque(
    g: &Geom,
    c: &PairCoeff,
    kr: f64,
    wr: DVec3,
    load: f64,
    hist: &mut [f64],
) -> (DVec3, bool) {
    let mut m = DVec3::new(hist[0], hist[1], hist[2]);
    m -= kr * g.dt * wr;
    let m_max = c.mu_r * g.r_star * load;
    let mag2 = m.length_squared();
    let elastic = mag2 <= m_max * m_max;
    if !elastic {
        m *= m_max / mag2.sqrt();
    }
    if g.update {
        hist[0] = m.x;
        hist[1] = m.y;
        hist[2] = m.z;
    }
    (m, elastic)
}

/// The epsd and epsd3 torque for rolling stiffness prefactor `k`: k_r = k k_n μ_r² R*²,
/// spring torque capped at μ_r R* · load, plus viscous torque −C_r w_r while below the cap,
/// with C_r = η_r · 2√(I_r k_r) and 1/I_r = 1/(I_i + m_i r_i²) + 1/(I_j + m_j r_j²).
#[inline(always)]
fn epsd_torque(
    g: &Geom,
    c: &PairCoeff,
    k: f64,
    no: &NormalOut,
    load: f64,
    flags: Flags,
    hist: &mut [f64],
) -> DVec3 {
    let wr = without_torsion(relative_rotation(g), g, flags);
    let kr = k * no.kn * c.mu_r * c.mu_r * g.r_star * g.r_star;
    let (m, elastic) = spring_torque(g, c, kr, wr, load, hist);
    if elastic {
        let ir = 1.0 / (1.0 / g.inertia_i + 1.0 / g.inertia_j);
        let cr = c.eta_r * 2.0 * (ir * kr).sqrt();
        m - cr * wr
    } else {
        m
    }
}

/// `rolling_friction epsd` (Ai et al. 2011) and `epsd3`: [`epsd_torque`] with the
/// prefactor of the table, [`PairCoeff::roll_stiffness`]: 2.25 for epsd, `rollingStiffness`
/// for epsd3. One type serves both, so that each kernel is compiled once for the two.
pub struct Epsd;

impl Rolling for Epsd {
    const HIST: usize = 3;
    #[inline(always)]
    fn torque(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        flags: Flags,
        hist: &mut [f64],
    ) -> DVec3 {
        epsd_torque(g, c, c.roll_stiffness, no, load, flags, hist)
    }
}

/// `rolling_friction epsd2` (Iwashita–Oda): k_r = k_t R*², spring torque capped at
/// μ_r R* |F_n|, no damping.
pub struct Epsd2;

impl Rolling for Epsd2 {
    const HIST: usize = 3;
    #[inline(always)]
    fn torque(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        flags: Flags,
        hist: &mut [f64],
    ) -> DVec3 {
        let wr = without_torsion(relative_rotation(g), g, flags);
        let kr = no.kt * g.r_star * g.r_star;
        spring_torque(g, c, kr, wr, load, hist).0
    }
}

/// The kernel of `rolling_friction epsd`, `epsd2` and `epsd3`, which keep the same
/// spring torque: it runs the law that [`Flags`] names, so that one kernel serves the
/// three.
pub struct Spring;

impl Rolling for Spring {
    const HIST: usize = 3;
    #[inline(always)]
    fn torque(
        g: &Geom,
        c: &PairCoeff,
        no: &NormalOut,
        load: f64,
        flags: Flags,
        hist: &mut [f64],
    ) -> DVec3 {
        if flags.rolling == RollingKind::Epsd2 {
            Epsd2::torque(g, c, no, load, flags, hist)
        } else {
            Epsd::torque(g, c, no, load, flags, hist)
        }
    }
}
