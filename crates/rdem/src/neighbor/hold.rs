//! Positions at the last neighbor build, against which the rebuild check measures how far
//! each particle has moved.
//!
//! They are held in single precision, relative to the middle of the particles' extent:
//! 12 bytes a particle instead of 24. A held position `h` then differs from the true one
//! by a rounding error of at most `err` (measured at the build, over all particles), so
//! a particle whose distance from `h` is at most skin/2 − err has moved at most skin/2:
//! the check subtracts `err` from its allowance and the list stays valid (it may rebuild
//! a step earlier than with exact positions, never later). Where the coordinates are so
//! large against the skin that `err` would exceed [`MAX_LOSS`] of skin/2, the positions
//! are held in double precision (`err` is then 0).

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::par::parallel_light;

/// Largest share of skin/2 that the rounding of single precision may take.
const MAX_LOSS: f64 = 1.0 / 16.0;

/// Positions at the last build (see the module docs).
#[derive(Debug, Clone)]
pub(crate) enum Hold {
    /// Single precision, relative to `origin`; each held position is
    /// `origin + x[i]` (as f64), within `err` of the true one.
    Single {
        origin: DVec3,
        x: Vec<Vec3>,
        err: f64,
    },
    /// Double precision.
    Exact(Vec<DVec3>),
}

impl Default for Hold {
    fn default() -> Self {
        Self::Exact(Vec::new())
    }
}

impl Hold {
    /// Holds the positions `x` for a skin of `skin`.
    pub(crate) fn new(x: &[DVec3], skin: f64) -> Self {
        if x.is_empty() {
            return Self::default();
        }
        let (lo, hi) = x
            .iter()
            .fold((x[0], x[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        let origin = 0.5 * (lo + hi);
        let single: Vec<Vec3> = x.iter().map(|&p| (p - origin).as_vec3()).collect();
        let err = x
            .iter()
            .zip(&single)
            .map(|(&p, &s)| (origin + s.as_dvec3() - p).length())
            .fold(0.0, f64::max);
        if err.is_finite() && err <= MAX_LOSS * 0.5 * skin {
            Self::Single {
                origin,
                x: single,
                err,
            }
        } else {
            Self::Exact(x.to_vec())
        }
    }

    /// Number of positions held.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Single { x, .. } => x.len(),
            Self::Exact(x) => x.len(),
        }
    }

    /// True if some particle of `x` (one per held position) is farther than `half` from
    /// where it was held, allowing for the rounding of the held positions: that is, if
    /// it may have moved farther than `half`.
    pub(crate) fn moved_beyond(&self, x: &[DVec3], half: f64) -> bool {
        match self {
            Self::Exact(held) => beyond(x, held, half, |h| *h),
            Self::Single {
                origin,
                x: held,
                err,
            } => beyond(x, held, half - err, |h| *origin + h.as_dvec3()),
        }
    }

    /// The held positions (for tests and diagnostics).
    pub(crate) fn positions(&self) -> Vec<DVec3> {
        match self {
            Self::Single { origin, x, .. } => x.iter().map(|s| *origin + s.as_dvec3()).collect(),
            Self::Exact(x) => x.clone(),
        }
    }

    /// Bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        match self {
            Self::Single { x, .. } => x.capacity() * std::mem::size_of::<Vec3>(),
            Self::Exact(x) => x.capacity() * std::mem::size_of::<DVec3>(),
        }
    }
}

/// True if some `x[i]` is farther than `lim` from `at(&held[i])` (always when `lim` is
/// not positive).
fn beyond<T: Sync>(x: &[DVec3], held: &[T], lim: f64, at: impl Fn(&T) -> DVec3 + Sync) -> bool {
    if lim <= 0.0 {
        return true;
    }
    let lim2 = lim * lim;
    let far = |(p, h): (&DVec3, &T)| (*p - at(h)).length_squared() > lim2;
    if parallel_light(x.len()) {
        x.par_iter().zip(held).any(far)
    } else {
        x.iter().zip(held).any(far)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_precision_moves_the_threshold_by_at_most_its_rounding() {
        // Coordinates that single precision cannot hold exactly.
        let x: Vec<DVec3> = (0..100)
            .map(|i| DVec3::new(0.1 + 1e-3 * i as f64 / 3.0, 0.7 / 3.0, 0.2))
            .collect();
        let hold = Hold::new(&x, 1e-3);
        let Hold::Single { err, .. } = hold else {
            panic!("a 0.03 wide packing with a skin of 1e-3 fits in single precision")
        };
        assert!(err > 0.0 && err < 1e-8, "err {err}");
        let half = 0.5e-3;
        assert!(!hold.moved_beyond(&x, half), "nothing moved");
        let shift = |d: f64| -> Vec<DVec3> {
            let mut y = x.clone();
            y[7].x += d;
            y
        };
        // Beyond half: always seen. Within half − 3 err (room for the rounding of the
        // test's own sums): never.
        assert!(hold.moved_beyond(&shift(half * (1.0 + 1e-12)), half));
        assert!(hold.moved_beyond(&shift(-half * (1.0 + 1e-12)), half));
        assert!(!hold.moved_beyond(&shift(half - 3.0 * err), half));
        assert!(!hold.moved_beyond(&shift(-(half - 3.0 * err)), half));
        for (h, p) in hold.positions().iter().zip(&x) {
            assert!((*h - *p).length() <= err);
        }
    }

    #[test]
    fn large_coordinates_against_the_skin_are_held_exactly() {
        let x = vec![DVec3::new(1000.1, 0.0, 0.0), DVec3::new(-1000.3, 0.0, 0.0)];
        let hold = Hold::new(&x, 1e-4);
        assert!(matches!(hold, Hold::Exact(_)));
        assert_eq!(hold.positions(), x);
        let mut y = x.clone();
        y[1].x -= 0.5e-4;
        assert!(
            !hold.moved_beyond(&y, 0.5e-4),
            "exactly skin/2 is not beyond"
        );
        y[1].x -= 1e-10;
        assert!(hold.moved_beyond(&y, 0.5e-4));
    }

    #[test]
    fn no_allowance_means_moved() {
        let x = vec![DVec3::ZERO];
        assert!(Hold::new(&x, 1.0).moved_beyond(&x, 0.0));
        assert!(!Hold::new(&x, 1.0).moved_beyond(&x, 1.0));
    }
}
