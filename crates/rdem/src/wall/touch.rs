//! Where each particle last touched a wall, for the lost-particle report: a particle that
//! leaks through a wall touched it last, whatever path it took afterwards. The wall
//! passes write the record at each contact (a store per contact, no cost per particle);
//! the record lives in the per-particle property [`TOUCH_PROPERTY`], so it moves with
//! its particle between ranks, through sorting and removal. It exists only while lost
//! particles are looked for (a fixed box face, walls, and a lost policy that reports).

/// Name of the per-particle property: [`TOUCH_WIDTH`] values per particle, the wall
/// fix's index in the world's fixes, the mesh and triangle ([`pack_triangle`], or −1 for
/// a primitive wall), and the step of the touch; all −1 before any touch.
pub const TOUCH_PROPERTY: &str = "wall_last_touch";

/// Values per particle in [`TOUCH_PROPERTY`].
pub const TOUCH_WIDTH: usize = 3;

/// A mesh (index in the world's meshes) and its triangle as one exact number.
pub fn pack_triangle(mesh: usize, tri: u32) -> f64 {
    (mesh as f64) * 4_294_967_296.0 + tri as f64
}

/// The mesh and triangle of [`pack_triangle`].
pub fn unpack_triangle(v: f64) -> (usize, u32) {
    let mesh = (v / 4_294_967_296.0).floor();
    (mesh as usize, (v - mesh * 4_294_967_296.0) as u32)
}

/// The fix index of a record whose wall fix was removed since the touch.
pub const REMOVED: f64 = -3.0;

/// After the fix at index `k` of the world's fixes is removed: the records `data` of
/// its wall say [`REMOVED`], and those of the fixes after it follow their new index.
pub fn forget_fix(data: &mut [f64], k: usize) {
    for rec in data.chunks_exact_mut(TOUCH_WIDTH) {
        let fix = rec[0];
        if fix == k as f64 {
            rec[0] = REMOVED;
            rec[1] = -1.0;
        } else if fix > k as f64 {
            rec[0] = fix - 1.0;
        }
    }
}

/// The last-touch records of one range of particles, handed to a wall's pass.
pub struct Touches<'a> {
    /// [`TOUCH_WIDTH`] values per particle of the range, or empty for no record.
    pub data: &'a mut [f64],
    /// The wall fix's index in the world's fixes.
    pub fix: usize,
    /// The current step.
    pub step: u64,
}

impl Touches<'_> {
    /// No record (no lost-particle report asked for).
    pub fn none() -> Touches<'static> {
        Touches {
            data: &mut [],
            fix: 0,
            step: 0,
        }
    }

    /// Particle `k` of the range touches the wall, at a triangle ([`pack_triangle`]) or
    /// −1 for a primitive wall.
    #[inline]
    pub fn note(&mut self, k: usize, triangle: f64) {
        if let Some(s) = self.data.get_mut(k * TOUCH_WIDTH..(k + 1) * TOUCH_WIDTH) {
            s.copy_from_slice(&[self.fix as f64, triangle, self.step as f64]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_pack_exactly() {
        for (m, t) in [(0, 0), (3, 17), (65_535, u32::MAX), (1 << 19, 123_456_789)] {
            assert_eq!(unpack_triangle(pack_triangle(m, t)), (m, t));
        }
        let mut data = [-1.0; 6];
        let mut touches = Touches {
            data: &mut data,
            fix: 4,
            step: 99,
        };
        touches.note(1, pack_triangle(2, 5));
        touches.note(7, -1.0); // past the range: no record, no panic
        assert_eq!(data, [-1.0, -1.0, -1.0, 4.0, pack_triangle(2, 5), 99.0]);
        // Fix 2 removed: fix 4 becomes 3. Fix 3 removed: its record says so.
        forget_fix(&mut data, 2);
        assert_eq!(data, [-1.0, -1.0, -1.0, 3.0, pack_triangle(2, 5), 99.0]);
        forget_fix(&mut data, 3);
        assert_eq!(data, [-1.0, -1.0, -1.0, REMOVED, -1.0, 99.0]);
    }
}
