//! Periodic image counts packed in one integer per particle.

/// Bits per axis.
const BITS: u32 = 21;
const MASK: u64 = (1 << BITS) - 1;

/// The periodic image counts of a particle (box lengths crossed along x, y, z), packed
/// in 64 bits: 21 bits per axis, two's complement, from −[`Image::MAX`] to
/// [`Image::MAX`]. A count beyond that stays at the limit (a particle that has crossed a
/// periodic box a million times); LIGGGHTS packs 10 bits per axis, and its counts wrap
/// at ±512.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Image(u64);

impl Image {
    /// Largest count held on one axis (2^20 − 1).
    pub const MAX: i32 = (1 << (BITS - 1)) - 1;

    /// The counts `c` (each clamped to ±[`Image::MAX`]).
    pub fn new(c: [i32; 3]) -> Self {
        Self(
            c.iter()
                .enumerate()
                .map(|(a, &v)| {
                    ((v.clamp(-Self::MAX, Self::MAX) as u64) & MASK) << (BITS * a as u32)
                })
                .fold(0, |acc, v| acc | v),
        )
    }

    /// The counts along x, y, z.
    pub fn get(self) -> [i32; 3] {
        [0, 1, 2].map(|a| {
            let v = ((self.0 >> (BITS * a)) & MASK) as u32;
            // Sign-extend the 21-bit field.
            ((v << (32 - BITS)) as i32) >> (32 - BITS)
        })
    }
}

impl From<[i32; 3]> for Image {
    fn from(c: [i32; 3]) -> Self {
        Self::new(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_round_trip_and_clamp() {
        assert_eq!(Image::default().get(), [0, 0, 0]);
        for c in [
            [0, 0, 0],
            [1, -1, 0],
            [-7, 123_456, -1],
            [Image::MAX, -Image::MAX, 5],
        ] {
            assert_eq!(Image::new(c).get(), c);
        }
        assert_eq!(
            Image::new([i32::MAX, i32::MIN, Image::MAX + 1]).get(),
            [Image::MAX, -Image::MAX, Image::MAX]
        );
        assert_eq!(Image::new([0, 0, 0]), Image::default());
    }
}
