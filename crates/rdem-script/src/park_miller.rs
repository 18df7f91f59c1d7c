//! LAMMPS' `RanPark`: the Park–Miller "minimal standard" generator (Park & Miller 1988,
//! with Schrage's factorisation), which LIGGGHTS' `displace_atoms random` and
//! LIGGGHTS-PFM's `fix remove` draw from: the same seed gives the same numbers.

use glam::DVec3;

/// The generator's state (a number in 1..2³¹ − 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct ParkMiller(pub i32);

impl ParkMiller {
    const IA: i32 = 16807;
    const IM: i32 = 2147483647;
    const IQ: i32 = 127773;
    const IR: i32 = 2836;
    /// 1/IM, as LAMMPS multiplies by it.
    const AM: f64 = 1.0 / 2147483647.0;

    /// A uniform number in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        let k = self.0 / Self::IQ;
        self.0 = Self::IA * (self.0 - k * Self::IQ) - Self::IR * k;
        if self.0 < 0 {
            self.0 += Self::IM;
        }
        Self::AM * f64::from(self.0)
    }

    /// The generator LAMMPS seeds from `seed` and a position: a one-at-a-time hash of the
    /// seed's and the coordinates' bytes (each read as a signed char, as on x86), kept to
    /// 27 bits, then five numbers drawn.
    pub fn seeded(seed: i32, x: DVec3) -> Self {
        let mut hash: u32 = 0;
        let mut mix = |b: u8| {
            hash = hash.wrapping_add(b as i8 as i32 as u32);
            hash = hash.wrapping_add(hash << 10);
            hash ^= hash >> 6;
        };
        seed.to_ne_bytes().into_iter().for_each(&mut mix);
        for c in x.to_array() {
            c.to_ne_bytes().into_iter().for_each(&mut mix);
        }
        hash = hash.wrapping_add(hash << 3);
        hash ^= hash >> 11;
        hash = hash.wrapping_add(hash << 15);
        let s = (hash & 0x7ff_ffff) as i32;
        let mut g = Self(if s == 0 { 1 } else { s });
        for _ in 0..5 {
            g.uniform();
        }
        g
    }
}
