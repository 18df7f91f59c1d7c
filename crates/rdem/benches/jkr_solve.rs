//! Cost of the JKR contact radius ([`rdem::contact::jkr`]): rdem solves â exactly by
//! Newton's method; the fork (LIGGGHTS_Flexible_Fibers) interpolates a table of 3·10⁵
//! points. Three ways over one impact's path of overlaps (δ/δ_c from −1 up to 40 and
//! back in 400 steps, about 10 steps per δ_c as in a real run):
//!
//! * `cold`: the solve from its cold start, as for a new contact;
//! * `warm`: the solve from the contact's â of the step before, as the passes call it;
//! * `table`: a lookup with linear interpolation in a table of 3·10⁵ points uniform in
//!   δ/δ_c over [−1, 56.4] (the fork's range at `resolutionJKR 1e-4`), written here to
//!   show what a table costs; it is not rdem's method.
//!
//! criterion reports elements/s = solves/s.

use std::hint::black_box;

use criterion::{Criterion, Throughput};
use rdem::contact::jkr::{contact_radius, contact_radius_from, overlap, A_HAT_MIN};

/// The overlaps δ/δ_c of one impact, 401 steps.
fn path() -> Vec<f64> {
    (0..=400)
        .map(|k| -1.0 + 41.0 * (std::f64::consts::PI * k as f64 / 400.0).sin())
        .collect()
}

/// â at `n` points uniform in δ/δ_c over [−1, `d_max`] (bisection on the stable branch).
fn table(n: usize, d_max: f64) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let d = -1.0 + (d_max + 1.0) * k as f64 / (n - 1) as f64;
            let (mut lo, mut hi) = (A_HAT_MIN, 100.0);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if overlap(mid) > d {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            0.5 * (lo + hi)
        })
        .collect()
}

fn main() {
    let ds = path();
    let (n, d_max) = (300_000, 56.4);
    let tab = table(n, d_max);
    let step = (d_max + 1.0) / (n - 1) as f64;
    let mut c = Criterion::default().configure_from_args();
    let mut g = c.benchmark_group("jkr_contact_radius");
    g.throughput(Throughput::Elements(ds.len() as u64));
    g.bench_function("cold", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &d in &ds {
                s += contact_radius(black_box(d)).unwrap();
            }
            s
        })
    });
    g.bench_function("warm", |b| {
        b.iter(|| {
            let mut a = 0.0;
            let mut s = 0.0;
            for &d in &ds {
                a = contact_radius_from(black_box(d), a).unwrap();
                s += a;
            }
            s
        })
    });
    g.bench_function("table", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for &d in &ds {
                let x = (black_box(d) + 1.0) / step;
                let k = (x as usize).min(n - 2);
                let f = x - k as f64;
                s += tab[k] + f * (tab[k + 1] - tab[k]);
            }
            s
        })
    });
    g.finish();
    c.final_summary();
}
