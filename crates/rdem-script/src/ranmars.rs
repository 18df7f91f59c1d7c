//! Marsaglia's RANMAR generator (G. Marsaglia, A. Zaman & W. W. Tsang 1990, Stat. Prob.
//! Lett. 9:35; as F. James describes it, Comp. Phys. Comm. 60 (1990) 329): the uniform
//! generator LAMMPS and LIGGGHTS use for the `random()` function of variables. With the
//! same seed it gives the same numbers, so a script's random values are LIGGGHTS' values.
//! Written here from the published algorithm: no crate has it.

/// The generator's state.
#[derive(Debug, Clone)]
pub struct RanMars {
    u: [f64; 98],
    i97: usize,
    j97: usize,
    c: f64,
}

const CD: f64 = 7654321.0 / 16777216.0;
const CM: f64 = 16777213.0 / 16777216.0;

impl RanMars {
    /// The generator for `seed`, 0 < seed < 900000000 (LAMMPS' range): `None` outside it.
    pub fn new(seed: i64) -> Option<Self> {
        if seed <= 0 || seed >= 900_000_000 {
            return None;
        }
        // The seed splits into the four start values of the lagged Fibonacci table.
        let ij = (seed - 1) / 30082;
        let kl = (seed - 1) - 30082 * ij;
        let mut i = (ij / 177) % 177 + 2;
        let mut j = ij % 177 + 2;
        let mut k = (kl / 169) % 178 + 1;
        let mut l = kl % 169;
        let mut u = [0.0; 98];
        for slot in u.iter_mut().skip(1) {
            let mut s = 0.0;
            let mut t = 0.5;
            for _ in 0..24 {
                let m = ((i * j) % 179) * k % 179;
                i = j;
                j = k;
                k = m;
                l = (53 * l + 1) % 169;
                if (l * m) % 64 >= 32 {
                    s += t;
                }
                t *= 0.5;
            }
            *slot = s;
        }
        let mut r = Self {
            u,
            i97: 97,
            j97: 33,
            c: 362436.0 / 16777216.0,
        };
        // LIGGGHTS' generator draws once when it is made: its first `random()` is
        // RANMAR's second number (measured on LIGGGHTS 3.8).
        r.uniform();
        Some(r)
    }

    /// The next number, uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        let mut uni = self.u[self.i97] - self.u[self.j97];
        if uni < 0.0 {
            uni += 1.0;
        }
        self.u[self.i97] = uni;
        self.i97 -= 1;
        if self.i97 == 0 {
            self.i97 = 97;
        }
        self.j97 -= 1;
        if self.j97 == 0 {
            self.j97 = 97;
        }
        self.c -= CD;
        if self.c < 0.0 {
            self.c += CM;
        }
        uni -= self.c;
        if uni < 0.0 {
            uni += 1.0;
        }
        uni
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_outside_the_range_are_refused() {
        assert!(RanMars::new(0).is_none());
        assert!(RanMars::new(900_000_000).is_none());
        assert!(RanMars::new(1).is_some());
    }

    #[test]
    fn numbers_are_uniform_in_the_unit_interval() {
        let mut r = RanMars::new(32452843).unwrap();
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = r.uniform();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        // Mean 1/2, standard error 1/√(12 n) = 9.1e-4: 5 sigma.
        assert!((sum / n as f64 - 0.5).abs() < 4.6e-3);
    }
}
