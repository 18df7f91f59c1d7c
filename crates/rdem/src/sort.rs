//! Spatial sort of the owned particles (seed 002 eqs. 6–9): bins of size `h` over a
//! bounding box, `n_a = max(1, floor(extent_a / h))` bins per axis, bin index
//! `clamp(floor((x_a − lo_a) · n_a / extent_a), 0, n_a − 1)`, a stable counting sort by bin
//! (x fastest), applied as one permutation to every per-particle array.

use glam::DVec3;

use crate::particles::Particles;

/// The permutation that orders `x` by bin, stable within a bin: entry `k` is the old index
/// of the particle that goes to position `k`.
pub fn sort_permutation(x: &[DVec3], lo: DVec3, hi: DVec3, h: f64) -> Vec<usize> {
    let ext = hi - lo;
    let nb: [usize; 3] = [0, 1, 2].map(|a| {
        if h > 0.0 && ext[a] > 0.0 {
            ((ext[a] / h).floor() as usize).max(1)
        } else {
            1
        }
    });
    let bin = |p: DVec3| -> usize {
        let k: [usize; 3] = [0, 1, 2].map(|a| {
            if ext[a] > 0.0 {
                let f = ((p[a] - lo[a]) * nb[a] as f64 / ext[a]).floor();
                f.clamp(0.0, (nb[a] - 1) as f64) as usize
            } else {
                0
            }
        });
        (k[2] * nb[1] + k[1]) * nb[0] + k[0]
    };
    let nbins = nb[0] * nb[1] * nb[2];
    let bins: Vec<usize> = x.iter().map(|&p| bin(p)).collect();
    let mut start = vec![0usize; nbins + 1];
    for &b in &bins {
        start[b + 1] += 1;
    }
    for b in 0..nbins {
        start[b + 1] += start[b];
    }
    let mut perm = vec![0usize; x.len()];
    for (i, &b) in bins.iter().enumerate() {
        perm[start[b]] = i;
        start[b] += 1;
    }
    perm
}

/// Sorts the owned particles of `p` spatially with bin size `h` over `[lo, hi]`.
pub fn sort_particles(p: &mut Particles, lo: DVec3, hi: DVec3, h: f64) {
    p.clear_ghosts();
    let perm = sort_permutation(&p.x, lo, hi, h);
    p.permute(&perm);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_clamp_and_stay_stable() {
        let x = vec![
            DVec3::new(0.9, 0.1, 0.1),
            DVec3::new(0.1, 0.1, 0.1),
            DVec3::new(1.5, 0.1, 0.1), // outside: clamped into the last bin
            DVec3::new(0.2, 0.1, 0.1),
            DVec3::new(-3.0, 0.9, 0.1), // clamped into x-bin 0, y-bin 1
        ];
        let perm = sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.5);
        assert_eq!(perm, vec![1, 3, 0, 2, 4]);
    }

    #[test]
    fn bin_count_is_floor_of_extent_over_size() {
        // extent 1, h = 0.4 -> floor(2.5) = 2 bins of width 0.5 each.
        let x = vec![
            DVec3::new(0.45, 0.0, 0.0),
            DVec3::new(0.55, 0.0, 0.0),
            DVec3::new(0.05, 0.0, 0.0),
        ];
        let perm = sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.4);
        assert_eq!(perm, vec![0, 2, 1]);
        // h larger than the extent -> a single bin, identity.
        assert_eq!(
            sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 5.0),
            vec![0, 1, 2]
        );
    }
}
