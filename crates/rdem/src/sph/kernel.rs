//! SPH interpolation kernels W(r, h) and their radial derivatives dW/dr, all with compact
//! support 2h (q = r/h < 2), as LIGGGHTS 3.8 names them: `cubicspline`, `cubicspline2d`
//! (Monaghan & Lattanzio 1985), `wendland`, `wendland2d` (Wendland 1995, C2),
//! `spiky`, `spiky2d` (Desbrun & Cani 1996, support H = 2h).
//!
//! The normalisation constants σ (W = σ/h^d · f(q)) are those LIGGGHTS 3.8 uses, measured
//! by running it on two particles (density by summation gives W, the pressure force gives
//! dW/dr; `tests/data/sph/kernels`): they are the exact values rounded to a few digits
//! (cubic spline 3d: 0.318308 for 1/π, 2d: 0.4547284 for 10/(7π); Wendland 3d:
//! 0.417781726 for 21/(16π), 2d: 0.557042301 for 7/(4π); spiky 3d: 0.59683104 for
//! 15/(8π), 2d: 0.79577471544 for 10/(4π)). A kernel therefore integrates to 1 within
//! that rounding (6e-6 for the 3d cubic spline, below 1e-8 for the others). Its gradients
//! of the Wendland 3d and spiky kernels use other constants (rounded otherwise, or exact
//! for spiky2d: 5e-11 to 9e-9 relative, [`Kernel::SIGMA_GRAD`]).
//!
//! Each kernel is a zero-sized type implementing [`Kernel`], so that the SPH passes are
//! monomorphized on it ([`with_kernel`] dispatches once per pass, not per pair).

/// A smoothing kernel with support 2h.
pub trait Kernel: Copy + Send + Sync {
    /// Normalisation constant σ: W = σ / h^d · f(q).
    const SIGMA: f64;
    /// The constant of the gradient, dW/dr = σ_g / h^(d+1) · f'(q): σ itself, except
    /// where LIGGGHTS 3.8 rounds its gradient's constant differently (measured:
    /// Wendland 3d, spiky 3d and 2d, by 5e-11 to 9e-9 relative).
    const SIGMA_GRAD: f64 = Self::SIGMA;
    /// Space dimension the normalisation is for.
    const DIM: i32;
    /// The shape f(q), 0 for q ≥ 2.
    fn shape(q: f64) -> f64;
    /// df/dq, 0 for q ≥ 2.
    fn dshape(q: f64) -> f64;

    /// W(r, h).
    #[inline(always)]
    fn w(r: f64, h: f64) -> f64 {
        Self::SIGMA / h.powi(Self::DIM) * Self::shape(r / h)
    }

    /// dW/dr at (r, h): negative inside the support, 0 outside.
    #[inline(always)]
    fn dw(r: f64, h: f64) -> f64 {
        Self::SIGMA_GRAD / h.powi(Self::DIM + 1) * Self::dshape(r / h)
    }

    /// W at q = r/h given 1/h: [`Kernel::w`] without a division, for the pair passes.
    #[inline(always)]
    fn w_q(q: f64, inv_h: f64) -> f64 {
        Self::SIGMA * inv_h.powi(Self::DIM) * Self::shape(q)
    }

    /// dW/dr at q = r/h given 1/h: [`Kernel::dw`] without a division.
    #[inline(always)]
    fn dw_q(q: f64, inv_h: f64) -> f64 {
        Self::SIGMA_GRAD * inv_h.powi(Self::DIM + 1) * Self::dshape(q)
    }
}

/// Cubic spline f(q): 1 − 3/2 q² + 3/4 q³ (q < 1), ¼ (2 − q)³ (1 ≤ q < 2).
#[inline(always)]
fn spline(q: f64) -> f64 {
    if q < 1.0 {
        1.0 - 1.5 * q * q + 0.75 * q * q * q
    } else if q < 2.0 {
        let t = 2.0 - q;
        0.25 * t * t * t
    } else {
        0.0
    }
}

#[inline(always)]
fn dspline(q: f64) -> f64 {
    if q < 1.0 {
        -3.0 * q + 2.25 * q * q
    } else if q < 2.0 {
        let t = 2.0 - q;
        -0.75 * t * t
    } else {
        0.0
    }
}

/// Wendland C2 f(q): (1 − q/2)⁴ (2q + 1), q < 2.
#[inline(always)]
fn wendland(q: f64) -> f64 {
    if q < 2.0 {
        let t = 1.0 - 0.5 * q;
        let t2 = t * t;
        t2 * t2 * (2.0 * q + 1.0)
    } else {
        0.0
    }
}

#[inline(always)]
fn dwendland(q: f64) -> f64 {
    if q < 2.0 {
        // d/dq [(1 − q/2)⁴ (2q + 1)] = −5 q (1 − q/2)³
        let t = 1.0 - 0.5 * q;
        -5.0 * q * t * t * t
    } else {
        0.0
    }
}

/// Spiky f(q): ((2 − q)/2)³, q < 2.
#[inline(always)]
fn spiky(q: f64) -> f64 {
    if q < 2.0 {
        let t = 1.0 - 0.5 * q;
        t * t * t
    } else {
        0.0
    }
}

#[inline(always)]
fn dspiky(q: f64) -> f64 {
    if q < 2.0 {
        let t = 1.0 - 0.5 * q;
        -1.5 * t * t
    } else {
        0.0
    }
}

macro_rules! kernel {
    ($(#[$doc:meta])* $name:ident, $sigma:expr, $dim:expr, $f:ident, $df:ident) => {
        kernel!($(#[$doc])* $name, $sigma, $sigma, $dim, $f, $df);
    };
    ($(#[$doc:meta])* $name:ident, $sigma:expr, $grad:expr, $dim:expr, $f:ident, $df:ident) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, Default)]
        pub struct $name;
        impl Kernel for $name {
            const SIGMA: f64 = $sigma;
            const SIGMA_GRAD: f64 = $grad;
            const DIM: i32 = $dim;
            #[inline(always)]
            fn shape(q: f64) -> f64 {
                $f(q)
            }
            #[inline(always)]
            fn dshape(q: f64) -> f64 {
                $df(q)
            }
        }
    };
}

kernel!(
    /// `cubicspline`: Monaghan & Lattanzio (1985), 3d, σ = 1/π (0.318308).
    CubicSpline,
    0.318308,
    3,
    spline,
    dspline
);
kernel!(
    /// `cubicspline2d`: the cubic spline in 2d, σ = 10/(7π) (0.4547284).
    CubicSpline2d,
    0.4547284,
    2,
    spline,
    dspline
);
kernel!(
    /// `wendland`: Wendland (1995) C2, 3d, σ = 21/(16π) (0.417781726).
    Wendland,
    0.417781726,
    // LIGGGHTS' gradient: 2.0889086275 = 5 σ_g (measured to 1e-15).
    2.0889086275 / 5.0,
    3,
    wendland,
    dwendland
);
kernel!(
    /// `wendland2d`: Wendland C2 in 2d, σ = 7/(4π) (0.557042301).
    Wendland2d,
    0.557042301,
    2,
    wendland,
    dwendland
);
kernel!(
    /// `spiky`: Desbrun & Cani (1996), 3d, 15/(π H⁶)(H − r)³ with H = 2h: σ = 15/(8π).
    Spiky,
    0.59683104,
    // LIGGGHTS' gradient: 0.895246556 = 1.5 σ_g (measured to 1e-15).
    0.895246556 / 1.5,
    3,
    spiky,
    dspiky
);
kernel!(
    /// `spiky2d`: the spiky kernel in 2d, 10/(π H⁵)(H − r)³ with H = 2h: σ = 10/(4π).
    Spiky2d,
    0.79577471544,
    // LIGGGHTS' gradient: the exact 10/(4π), unlike its W (measured to 1e-15).
    10.0 / (4.0 * std::f64::consts::PI),
    2,
    spiky,
    dspiky
);

/// A kernel chosen by its LIGGGHTS name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelKind {
    /// `cubicspline`
    CubicSpline,
    /// `cubicspline2d`
    CubicSpline2d,
    /// `wendland`
    Wendland,
    /// `wendland2d`
    Wendland2d,
    /// `spiky`
    Spiky,
    /// `spiky2d`
    Spiky2d,
}

impl KernelKind {
    /// Every kernel with its LIGGGHTS name, in the order of the manual.
    pub const ALL: [(&'static str, KernelKind); 6] = [
        ("cubicspline", KernelKind::CubicSpline),
        ("cubicspline2d", KernelKind::CubicSpline2d),
        ("wendland", KernelKind::Wendland),
        ("wendland2d", KernelKind::Wendland2d),
        ("spiky", KernelKind::Spiky),
        ("spiky2d", KernelKind::Spiky2d),
    ];

    /// The kernel called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|&(_, k)| k)
    }

    /// The LIGGGHTS name.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, k)| *k == self)
            .map_or("", |(n, _)| n)
    }

    /// W(r, h) (a dynamic dispatch: for set-up and tests, not hot loops).
    pub fn w(self, r: f64, h: f64) -> f64 {
        with_kernel!(self, K, K::w(r, h))
    }

    /// dW/dr(r, h) (dynamic dispatch, as [`KernelKind::w`]).
    pub fn dw(self, r: f64, h: f64) -> f64 {
        with_kernel!(self, K, K::dw(r, h))
    }

    /// The space dimension its normalisation is for.
    pub fn dim(self) -> i32 {
        with_kernel!(self, K, K::DIM)
    }
}

/// Runs `$body` with `$k` the kernel type of `$kind` (one `match` per call: put it
/// around a whole pass).
#[macro_export]
macro_rules! with_kernel {
    ($kind:expr, $k:ident, $body:expr) => {{
        use $crate::sph::kernel as __k;
        match $kind {
            __k::KernelKind::CubicSpline => {
                type $k = __k::CubicSpline;
                $body
            }
            __k::KernelKind::CubicSpline2d => {
                type $k = __k::CubicSpline2d;
                $body
            }
            __k::KernelKind::Wendland => {
                type $k = __k::Wendland;
                $body
            }
            __k::KernelKind::Wendland2d => {
                type $k = __k::Wendland2d;
                $body
            }
            __k::KernelKind::Spiky => {
                type $k = __k::Spiky;
                $body
            }
            __k::KernelKind::Spiky2d => {
                type $k = __k::Spiky2d;
                $body
            }
        }
    }};
}
pub use with_kernel;

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ W dV over the support, by the midpoint rule in r: 2π ∫ W r dr in 2d,
    /// 4π ∫ W r² dr in 3d.
    fn integral(k: KernelKind, h: f64) -> f64 {
        let n = 200_000;
        let dr = 2.0 * h / n as f64;
        let mut s = 0.0;
        for i in 0..n {
            let r = (i as f64 + 0.5) * dr;
            let w = k.w(r, h);
            s += if k.dim() == 2 {
                2.0 * std::f64::consts::PI * r * w
            } else {
                4.0 * std::f64::consts::PI * r * r * w
            } * dr;
        }
        s
    }

    /// Every kernel is normalised: ∫ W dV = 1 within the rounding of LIGGGHTS 3.8's
    /// constant (the 3d cubic spline's 0.318308 is 6e-6 below 1/π, the 2d spline's
    /// 0.4547284 is 1.9e-8 below 10/(7π); the others are rounded below 1e-8) plus the
    /// quadrature error (1e-9).
    #[test]
    fn kernels_integrate_to_one() {
        for (name, k) in KernelKind::ALL {
            for h in [0.012, 1.0, 3.5] {
                let s = integral(k, h);
                let tol = match k {
                    KernelKind::CubicSpline => 7e-6,
                    KernelKind::CubicSpline2d => 2.1e-8,
                    _ => 1e-8,
                };
                assert!((s - 1.0).abs() < tol, "{name} h={h}: {s}");
            }
        }
    }

    /// dW/dr is the derivative of W: a central difference agrees to 1e-6 relative,
    /// away from the spline's joints, and both vanish beyond 2h.
    #[test]
    fn gradients_match_finite_differences() {
        for (name, k) in KernelKind::ALL {
            let h = 0.012;
            for i in 1..200 {
                let r = i as f64 * 0.01 * h + 1e-4 * h;
                let e = 1e-7 * h;
                let fd = (k.w(r + e, h) - k.w(r - e, h)) / (2.0 * e);
                let an = k.dw(r, h);
                let scale = k.dw(0.0, h).abs().max(k.w(0.0, h) / h);
                assert!(
                    (fd - an).abs() < 1e-6 * scale,
                    "{name} r/h={}: {fd} vs {an}",
                    r / h
                );
            }
            assert_eq!(k.w(2.0 * h, h), 0.0);
            assert_eq!(k.dw(2.0 * h, h), 0.0);
            assert_eq!(k.w(3.0 * h, h), 0.0);
        }
    }

    #[test]
    fn names_round_trip() {
        for (name, k) in KernelKind::ALL {
            assert_eq!(KernelKind::from_name(name), Some(k));
            assert_eq!(k.name(), name);
        }
        assert_eq!(KernelKind::from_name("quintic"), None);
    }
}
