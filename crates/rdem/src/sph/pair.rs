//! `pair_style sph/artVisc/tensCorr`: the SPH momentum equation (Monaghan 1992, eq. 3.1),
//!
//! dv_a/dt = −Σ_b m_b (P_a/ρ_a² + P_b/ρ_b² + Π_ab + R f_ab⁴) ∇_a W_ab,
//!
//! as LIGGGHTS 3.8 evaluates it (each detail measured on two- and three-particle cases,
//! `tests/data/sph/`):
//! - h̄ = (sl_a + sl_b)/2 per pair (LIGGGHTS reads the per-type `sl`; the `h` of the
//!   `pair_style` line is not used);
//! - `artVisc`: Π_ab = (−ᾱ c̄ μ_ab + β̄ μ_ab²)/ρ̄ when v̂_ab·r_ab < 0, else 0, with
//!   μ_ab = h̄ v̂_ab·r_ab/(r² + η²) (Monaghan & Gingold 1983), c̄, ρ̄, ᾱ, β̄ arithmetic means
//!   of the two particles' (per-type `speedOfSound`, `artViscAlpha`, `artViscBeta`;
//!   scalar `artViscEta` is η², used as given) and v̂ the velocity estimate of [`super`];
//! - `tensCorr` (Monaghan 2000): R = Σ ε|P|/ρ² over the particles with negative pressure,
//!   or, when neither is negative, R = 0.01 (P_a/ρ_a² + P_b/ρ_b²); f_ab = W(r)/W(Δp̄),
//!   Δp̄ the mean of the per-type `tensCorrDeltaP`, ε the scalar `tensCorrEpsilon`; the
//!   exponent is 4.
//!
//! The pass also runs at a run's set-up (see [`super`]).

use glam::DVec3;

use super::kernel::{with_kernel, Kernel, KernelKind};
use super::{props_mut, SphProps};
use crate::comm::Comm;
use crate::error::{Error, Result};
use crate::neighbor::NeighborList;
use crate::particles::Particles;

/// The SPH pair style and its per-type tables (index = type, entry 0 unused).
#[derive(Debug, Clone, Default)]
pub struct SphPair {
    /// Kernel of the pair style.
    pub kernel: Option<KernelKind>,
    /// `artVisc` given.
    pub art_visc: bool,
    /// `tensCorr` given.
    pub tens_corr: bool,
    /// Smoothing length per type (`sl`).
    pub sl: Vec<f64>,
    /// Speed of sound per type (`speedOfSound`, with artVisc).
    pub c: Vec<f64>,
    /// α per type (`artViscAlpha`).
    pub alpha: Vec<f64>,
    /// β per type (`artViscBeta`).
    pub beta: Vec<f64>,
    /// η² (`artViscEta`: the value is η² itself, as the tutorials' `0.01 h²` and
    /// LIGGGHTS 3.8 use it).
    pub eta2: f64,
    /// ε (`tensCorrEpsilon`).
    pub eps: f64,
    /// Δp per type (`tensCorrDeltaP`).
    pub deltap: Vec<f64>,
    /// The constants of each type pair, row `t_a`, column `t_b` ([`SphPair::prepare`]).
    pairs: Vec<TypePair>,
    /// Row length of `pairs` (ntypes + 1).
    stride: usize,
    /// Scratch: per-particle sums of a pass (locals and ghosts).
    buf: Vec<f64>,
    /// Scratch: second per-particle sum.
    buf2: Vec<f64>,
}

/// What the pair passes need of a type pair, computed once per run
/// ([`SphPair::prepare`]): the per-type means and the smoothing length's powers, so that a
/// pair costs no division for them.
#[derive(Debug, Clone, Copy, Default)]
struct TypePair {
    /// h̄ = (sl_a + sl_b)/2.
    h: f64,
    /// 1/h̄.
    inv_h: f64,
    /// The support squared, (2h̄)².
    cut2: f64,
    /// c̄ (`artVisc`).
    c: f64,
    /// ᾱ (`artVisc`).
    alpha: f64,
    /// β̄ (`artVisc`).
    beta: f64,
    /// 1/W(Δp̄, h̄) with the pair style's kernel (`tensCorr`).
    inv_w_dp: f64,
}

impl SphPair {
    /// A pair style with `kernel` and its switches; the tables come from
    /// [`SphPair::set_tables`].
    pub fn new(kernel: KernelKind, art_visc: bool, tens_corr: bool) -> Self {
        Self {
            kernel: Some(kernel),
            art_visc,
            tens_corr,
            ..Self::default()
        }
    }

    /// Checks the tables: one positive `sl` per type (and the others when used).
    pub fn check(&self, ntypes: usize) -> Result<()> {
        let need = |what: &'static str, t: &[f64], pos: bool| -> Result<()> {
            if t.len() != ntypes + 1 || t[1..].iter().any(|v| !v.is_finite() || (pos && *v <= 0.0))
            {
                return Err(Error::Invalid {
                    what,
                    reason: format!(
                        "needs {ntypes} finite value(s){}",
                        if pos { " > 0" } else { "" }
                    ),
                });
            }
            Ok(())
        };
        need("sl", &self.sl, true)?;
        if self.art_visc {
            need("speedOfSound", &self.c, false)?;
            need("artViscAlpha", &self.alpha, false)?;
            need("artViscBeta", &self.beta, false)?;
        }
        if self.tens_corr {
            need("tensCorrDeltaP", &self.deltap, true)?;
        }
        Ok(())
    }

    /// Computes the type-pair constants from the per-type tables (at each run's set-up,
    /// after [`SphPair::check`]).
    pub fn prepare(&mut self) {
        let nt = self.sl.len();
        let mean = |t: &[f64], a: usize, b: usize| {
            if t.len() == nt {
                0.5 * (t[a] + t[b])
            } else {
                0.0
            }
        };
        self.stride = nt;
        self.pairs.clear();
        for a in 0..nt {
            for b in 0..nt {
                let h = 0.5 * (self.sl[a] + self.sl[b]);
                let dp = mean(&self.deltap, a, b);
                let inv_w_dp = match self.kernel {
                    Some(k) if self.tens_corr && a > 0 && b > 0 => 1.0 / k.w(dp, h),
                    _ => 0.0,
                };
                self.pairs.push(TypePair {
                    h,
                    inv_h: 1.0 / h,
                    cut2: 4.0 * h * h,
                    c: mean(&self.c, a, b),
                    alpha: mean(&self.alpha, a, b),
                    beta: mean(&self.beta, a, b),
                    inv_w_dp,
                });
            }
        }
    }

    /// The constants of types `a` and `b`'s row (`a`'s), indexed by `b`'s type.
    #[inline]
    fn row(&self, a: u32) -> &[TypePair] {
        let a = a as usize;
        &self.pairs[a * self.stride..(a + 1) * self.stride]
    }

    /// Pair forces onto `p.f` (ghosts' forces go to their owners in the reverse
    /// communication that follows).
    pub fn compute(&self, p: &mut Particles, props: SphProps, list: &NeighborList) {
        let Some(k) = self.kernel else { return };
        with_kernel!(k, K, self.forces::<K>(p, props, list))
    }

    fn forces<K: Kernel>(&self, p: &mut Particles, props: SphProps, list: &NeighborList) {
        let n = p.nlocal();
        if list.first.len() != n + 1 {
            return;
        }
        let rho = &p.props[props.rho.0].data;
        let pr = &p.props[props.p.0].data;
        let vest = &p.props[props.vest.0].data;
        let (x, ty, m) = (&p.x, &p.ty, &p.rmass);
        let f = &mut p.f;
        let eta2 = self.eta2;
        for i in 0..n {
            let row = self.row(ty[i]);
            let (xi, mi, rhoi, pi) = (x[i], m[i], rho[i], pr[i]);
            let vi = DVec3::from_slice(&vest[3 * i..3 * i + 3]);
            let pi_r2 = pi / (rhoi * rhoi);
            for &j in list.partners(i) {
                let j = j as usize;
                let tp = row[ty[j] as usize];
                let del = xi - x[j];
                let rsq = del.length_squared();
                if rsq >= tp.cut2 || rsq == 0.0 {
                    continue;
                }
                let r = rsq.sqrt();
                let q = r * tp.inv_h;
                let (rhoj, pj) = (rho[j], pr[j]);
                let pj_r2 = pj / (rhoj * rhoj);
                let mut term = pi_r2 + pj_r2;
                if self.art_visc {
                    let vj = DVec3::from_slice(&vest[3 * j..3 * j + 3]);
                    let vr = (vi - vj).dot(del);
                    if vr < 0.0 {
                        let mu = tp.h * vr / (rsq + eta2);
                        term += (-tp.alpha * tp.c * mu + tp.beta * mu * mu) / (0.5 * (rhoi + rhoj));
                    }
                }
                if self.tens_corr {
                    let mut rr = 0.0;
                    if pi < 0.0 {
                        rr += self.eps * pi.abs() / (rhoi * rhoi);
                    }
                    if pj < 0.0 {
                        rr += self.eps * pj.abs() / (rhoj * rhoj);
                    }
                    if rr == 0.0 {
                        rr = 0.01 * (pi_r2 + pj_r2);
                    }
                    let fab = K::w_q(q, tp.inv_h) * tp.inv_w_dp;
                    let f2 = fab * fab;
                    term += rr * f2 * f2;
                }
                let fpair = -mi * m[j] * term * K::dw_q(q, tp.inv_h) / r;
                f[i] += fpair * del;
                f[j] -= fpair * del;
            }
        }
    }

    /// `fix sph/density/continuity`: dρ_a/dt = Σ_b m_b (v̂_a − v̂_b)·∇_a W_ab for the owned
    /// particles of `groupbit` (ghosts' shares added to their owners).
    pub fn density_rate(
        &mut self,
        k: KernelKind,
        p: &mut Particles,
        props: SphProps,
        list: &NeighborList,
        groupbit: u32,
        comm: &dyn Comm,
    ) {
        let mut buf = std::mem::take(&mut self.buf);
        buf.clear();
        buf.resize(p.len(), 0.0);
        with_kernel!(k, K, self.rate::<K>(p, props, list, groupbit, &mut buf));
        comm.reverse_scalar(p, &mut buf);
        let n = p.nlocal();
        let drho = &mut p.props[props.drho.0].data;
        for i in 0..n {
            if p.mask[i] & groupbit != 0 {
                drho[i] = buf[i];
            }
        }
        self.buf = buf;
    }

    fn rate<K: Kernel>(
        &self,
        p: &Particles,
        props: SphProps,
        list: &NeighborList,
        bit: u32,
        out: &mut [f64],
    ) {
        let n = p.nlocal();
        if list.first.len() != n + 1 {
            return;
        }
        let vest = &p.props[props.vest.0].data;
        for i in 0..n {
            let vi = DVec3::from_slice(&vest[3 * i..3 * i + 3]);
            let row = self.row(p.ty[i]);
            for &j in list.partners(i) {
                let j = j as usize;
                let tp = row[p.ty[j] as usize];
                let del = p.x[i] - p.x[j];
                let rsq = del.length_squared();
                if rsq >= tp.cut2 || rsq == 0.0 {
                    continue;
                }
                let r = rsq.sqrt();
                let vj = DVec3::from_slice(&vest[3 * j..3 * j + 3]);
                let s = (vi - vj).dot(del) * K::dw_q(r * tp.inv_h, tp.inv_h) / r;
                if p.mask[i] & bit != 0 {
                    out[i] += p.rmass[j] * s;
                }
                if p.mask[j] & bit != 0 {
                    out[j] += p.rmass[i] * s;
                }
            }
        }
    }

    /// `fix sph/density/corr shepard`: ρ_a = Σ_b m_b W_ab / Σ_b (m_b/ρ_b) W_ab over b
    /// including a, for the owned particles of `groupbit`.
    pub fn shepard(
        &mut self,
        k: KernelKind,
        p: &mut Particles,
        props: SphProps,
        list: &NeighborList,
        groupbit: u32,
        comm: &dyn Comm,
    ) {
        self.density_sums(k, p, props, list, groupbit, comm, true);
    }

    /// `fix sph/density/summation`: ρ_a = Σ_b m_b W_ab over b including a, for the owned
    /// particles of `groupbit`.
    pub fn summation(
        &mut self,
        k: KernelKind,
        p: &mut Particles,
        props: SphProps,
        list: &NeighborList,
        groupbit: u32,
        comm: &dyn Comm,
    ) {
        self.density_sums(k, p, props, list, groupbit, comm, false);
    }

    /// The density of [`Self::shepard`] (`normalised`: Σ m W / Σ (m/ρ) W) or of
    /// [`Self::summation`] (Σ m W).
    #[allow(clippy::too_many_arguments)]
    fn density_sums(
        &mut self,
        k: KernelKind,
        p: &mut Particles,
        props: SphProps,
        list: &NeighborList,
        groupbit: u32,
        comm: &dyn Comm,
        normalised: bool,
    ) {
        let mut num = std::mem::take(&mut self.buf);
        let mut den = std::mem::take(&mut self.buf2);
        for b in [&mut num, &mut den] {
            b.clear();
            b.resize(p.len(), 0.0);
        }
        with_kernel!(
            k,
            K,
            self.shepard_sums::<K>(p, props, list, &mut num, &mut den)
        );
        comm.reverse_scalar(p, &mut num);
        if normalised {
            comm.reverse_scalar(p, &mut den);
        }
        let n = p.nlocal();
        let [rho] = props_mut(&mut p.props, [props.rho]);
        for i in 0..n {
            if p.mask[i] & groupbit != 0 {
                rho[i] = if normalised { num[i] / den[i] } else { num[i] };
            }
        }
        self.buf = num;
        self.buf2 = den;
    }

    fn shepard_sums<K: Kernel>(
        &self,
        p: &Particles,
        props: SphProps,
        list: &NeighborList,
        num: &mut [f64],
        den: &mut [f64],
    ) {
        let n = p.nlocal();
        let rho = &p.props[props.rho.0].data;
        for i in 0..n {
            let w0 = K::w(0.0, self.sl[p.ty[i] as usize]);
            num[i] += p.rmass[i] * w0;
            den[i] += p.rmass[i] / rho[i] * w0;
        }
        if list.first.len() != n + 1 {
            return;
        }
        for i in 0..n {
            let row = self.row(p.ty[i]);
            for &j in list.partners(i) {
                let j = j as usize;
                let tp = row[p.ty[j] as usize];
                let rsq = (p.x[i] - p.x[j]).length_squared();
                if rsq >= tp.cut2 {
                    continue;
                }
                let w = K::w_q(rsq.sqrt() * tp.inv_h, tp.inv_h);
                num[i] += p.rmass[j] * w;
                den[i] += p.rmass[j] / rho[j] * w;
                num[j] += p.rmass[i] * w;
                den[j] += p.rmass[i] / rho[i] * w;
            }
        }
    }
}
