//! Lees–Edwards boundaries: simple shear of a box periodic in x, y and z (`fix lebc` of
//! LIGGGHTS_CFDRC). The mean flow is u_x = γ̇ (y − y_c) (y_c the box centre); the images
//! of the box above and below it slide along x with it:
//!
//! - the image shifted by +L_y along y is shifted by the **offset** d along x and moves
//!   γ̇ L_y faster along x; the image shifted by −L_y by −d and γ̇ L_y slower. The offset
//!   grows by γ̇ L_y dt each step and is kept in [0, L_x);
//! - a particle that leaves through a y face comes back through the other with its x
//!   shifted and its x velocity changed to match (through the lower face: x + d,
//!   v_x + γ̇ L_y);
//! - ghosts across a y face carry the same shift and velocity jump
//!   ([`crate::comm::Comm::borders`] makes them along y first, so that their images
//!   along x follow), and between re-neighborings their x follows the offset.
//!
//! The neighbor list's distance check counts the drift of the offset since the build
//! ([`Shear::drift`]): an image slides past its partners even when no particle moves.
//!
//! Image counts: a particle's unwrapped position is x + n ⊙ L + n_y d x̂, which stays
//! continuous: the wrap through a y face changes n_y and x together, and when the offset
//! wraps by k box lengths, n_x grows by k n_y ([`crate::World`] does it after the step's
//! advance). A rigid clump's sphere is placed from its body by the same relation
//! (`crate::multisphere`), with v_x less n_y γ̇ L_y.

use glam::DVec3;

use crate::particles::Particles;

/// The state of a Lees–Edwards shear.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shear {
    /// Shear rate γ̇ (1/time).
    pub rate: f64,
    /// The x shift of the image above the box (shifted by +L_y), in [0, L_x).
    pub offset: f64,
    /// [`Shear::offset`] when the ghosts were last made.
    pub built: f64,
}

impl Shear {
    /// A shear at rate `rate`, images not yet shifted.
    pub fn new(rate: f64) -> Self {
        Self {
            rate,
            offset: 0.0,
            built: 0.0,
        }
    }

    /// The x velocity jump across the y faces: γ̇ L_y.
    pub fn jump(&self, ly: f64) -> f64 {
        self.rate * ly
    }

    /// Advances the offset by one step of `dt` (box lengths `lx`, `ly`); returns k, the
    /// number of box lengths taken off to keep it in [0, L_x) (0 on most steps; −1 when
    /// a negative rate wraps it up).
    pub fn advance(&mut self, dt: f64, lx: f64, ly: f64) -> i32 {
        self.offset += self.rate * ly * dt;
        let mut k = (self.offset / lx).floor();
        self.offset -= k * lx;
        if self.offset >= lx {
            self.offset = 0.0;
            k += 1.0;
        }
        k as i32
    }

    /// The offset as the ghosts made at the last build see it now: the value congruent to
    /// [`Shear::offset`] modulo `lx` nearest [`Shear::built`] (so that a wrap of the
    /// offset does not move the ghosts by a box length).
    pub fn current(&self, lx: f64) -> f64 {
        let d = self.offset - self.built;
        self.built + d - (d / lx).round() * lx
    }

    /// How far the images have slid along x since the ghosts were made.
    pub fn drift(&self, lx: f64) -> f64 {
        (self.current(lx) - self.built).abs()
    }
}

/// Shifts ghosts `range` that lie `ny` box lengths up along y from the particles they
/// copy: x by `ny` × `offset`, v_x by `ny` × `jump`.
pub fn shift_ghosts(
    p: &mut Particles,
    range: std::ops::Range<usize>,
    ny: i32,
    offset: f64,
    jump: f64,
) {
    if ny == 0 {
        return;
    }
    let (dx, dv) = (ny as f64 * offset, ny as f64 * jump);
    for g in range {
        p.x[g].x += dx;
        p.v[g].x += dv;
    }
}

/// Wraps an owned particle that left through a y face back in (x and v_x shifted to
/// match, see the module docs); the caller then wraps x and z as usual.
pub fn wrap_y(shear: &Shear, lo: DVec3, prd: DVec3, x: &mut DVec3, v: &mut DVec3) {
    if x.y >= lo.y && x.y < lo.y + prd.y {
        return;
    }
    // n > 0: above the box, it comes back n box lengths lower.
    let n = ((x.y - lo.y) / prd.y).floor();
    x.x -= n * shear.offset;
    v.x -= n * shear.jump(prd.y);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_wraps_and_current_follows_the_build() {
        let mut s = Shear::new(10.0);
        // γ̇ L_y dt = 10 · 2 · 0.01 = 0.2 per step, L_x = 1.
        for _ in 0..4 {
            assert_eq!(s.advance(0.01, 1.0, 2.0), 0);
        }
        assert!((s.offset - 0.8).abs() < 1e-12);
        s.built = s.offset;
        assert_eq!(s.advance(0.01, 1.0, 2.0), 1);
        assert_eq!(s.advance(0.01, 1.0, 2.0), 0);
        // Wrapped to 0.2, seen from the build as 1.2.
        assert!((s.offset - 0.2).abs() < 1e-12);
        assert!((s.current(1.0) - 1.2).abs() < 1e-12);
        assert!((s.drift(1.0) - 0.4).abs() < 1e-12);
    }

    #[test]
    fn leaving_through_the_lower_face_shifts_forward() {
        let s = Shear {
            rate: 2.0,
            offset: 0.3,
            built: 0.3,
        };
        let (lo, prd) = (DVec3::ZERO, DVec3::new(1.0, 2.0, 1.0));
        let mut x = DVec3::new(0.5, -0.1, 0.5);
        let mut v = DVec3::new(1.0, -1.0, 0.0);
        wrap_y(&s, lo, prd, &mut x, &mut v);
        // y is wrapped later by the usual remap; x and v_x shift by +d, +γ̇ L_y.
        assert_eq!(x, DVec3::new(0.8, -0.1, 0.5));
        assert_eq!(v, DVec3::new(5.0, -1.0, 0.0));
        let mut x = DVec3::new(0.5, 2.1, 0.5);
        let mut v = DVec3::new(1.0, 1.0, 0.0);
        wrap_y(&s, lo, prd, &mut x, &mut v);
        assert!((x.x - 0.2).abs() < 1e-15);
        assert_eq!(v.x, -3.0);
    }
}
