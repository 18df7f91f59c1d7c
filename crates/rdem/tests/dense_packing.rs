//! `fix insert/pack/dense`'s packing (`rdem::insert::DensePack`): the count and volume
//! fraction against the closed form φ V / v_p, no overlaps (the enlarged spheres never
//! touch, so real neighbours keep a gap of at least (f − 1)(rᵢ + rⱼ)), every sphere whole
//! inside the region, the same packing from the same seed, room left for particles that
//! are there already. LIGGGHTS 3.8 has no insert/pack/dense (LIGGGHTS-PFM's fix), so the
//! figures are closed forms and the algorithm's own promises.

use std::f64::consts::PI;

use rdem::insert::dense::MAX_VOLUME_FRACTION;
use rdem::insert::{DensePack, Distribution, ParticleTemplate, RadiusDist, Weighting};
use rdem::region::{Region, Shape};
use rdem::{Boundary, DVec3, Domain, NewParticle, World};

fn world() -> World {
    World::new(
        Domain::new(
            DVec3::new(-0.03, -0.03, 0.0),
            DVec3::new(0.03, 0.03, 0.06),
            [Boundary::Fixed; 3],
        )
        .unwrap(),
    )
}

fn dist(radii: &[(f64, f64)]) -> Distribution {
    let parts = radii
        .iter()
        .enumerate()
        .map(|(k, &(r, w))| {
            let t = ParticleTemplate::new(
                &format!("pts{k}"),
                15485863 + k as u64,
                1,
                2500.0,
                RadiusDist::Constant(r),
            )
            .unwrap();
            (t, w)
        })
        .collect();
    Distribution::new("pdd", 32452843, Weighting::Mass, parts).unwrap()
}

fn block(lo: DVec3, hi: DVec3) -> Region {
    Region::new(Shape::Block { lo, hi }).unwrap()
}

/// Packs `region` with `d` at `phi` into `w`; returns the fix and its report.
fn pack(
    w: &mut World,
    region: Region,
    d: Distribution,
    phi: f64,
    seed: u64,
) -> (DensePack, rdem::insert::DenseReport) {
    let mut p = DensePack::new("ins", seed, 0, region, d, phi, None).unwrap();
    assert!(p.due(0));
    let rep = p.insert(w).unwrap();
    assert!(!p.due(1), "once");
    (p, rep)
}

/// Every pair of particles at least `f`·(rᵢ + rⱼ) apart (less a rounding hair).
fn check_gaps(w: &World, f: f64) -> f64 {
    let p = &w.particles;
    let n = p.nlocal();
    let mut worst = f64::INFINITY;
    // A cell list would be faster; a few thousand particles are fine by brute force.
    for i in 0..n {
        for j in i + 1..n {
            let d = (p.x[i] - p.x[j]).length() / (p.radius[i] + p.radius[j]);
            worst = worst.min(d);
        }
    }
    assert!(
        worst >= f * (1.0 - 1e-12),
        "closest pair at {worst} (sum of radii), f = {f}"
    );
    worst
}

/// One size (r = 1 mm) in a 40 × 40 × 40 mm block at φ = 0.5: the count is within 2 %
/// of φ V / v_p = 0.5 × 6.4e-5 / 4.18879e-9 = 7639 (measured: the first packing, with
/// f = ∛(0.57/0.5) = 1.0446, holds 7091, 7.2 % short, as the front packs looser next to
/// the walls; the second, with f = 1.0192, 7665, +0.3 %), the reported volume fraction
/// is the count times v_p / V, every sphere is whole in the block, and no two come closer
/// than the enlarged radii.
#[test]
fn one_size_fills_a_block_to_the_volume_fraction() {
    let mut w = world();
    let (lo, hi) = (DVec3::new(-0.02, -0.02, 0.0), DVec3::new(0.02, 0.02, 0.04));
    let (p, rep) = pack(&mut w, block(lo, hi), dist(&[(0.001, 1.0)]), 0.5, 123);
    let vp = 4.0 / 3.0 * PI * 1e-9;
    let v = 0.04f64.powi(3);
    let want = 0.5 * v / vp;
    let n = w.particles.nlocal() as f64;
    eprintln!("inserted {n}, closed form {want:.0}, reported {rep:?}");
    assert_eq!(rep.inserted as f64, n);
    assert_eq!(rep.estimate, want.floor() as u64);
    assert!((n / want - 1.0).abs() < 0.02, "{n} vs {want}");
    assert!((rep.volume_fraction - n * vp / v).abs() < 1e-12);
    assert!((rep.mass - n * vp * 2500.0).abs() < 1e-9 * rep.mass);
    assert!((p.radius_factor() - (0.57f64 / 0.5).cbrt()).abs() < 1e-15);
    let f = rep.radius_factor;
    assert!(f > 1.0 && f < p.radius_factor(), "{f}");
    let ps = &w.particles;
    for i in 0..ps.nlocal() {
        let (x, r) = (ps.x[i], ps.radius[i]);
        // The enlarged sphere is inside, so the real one is with f r − r to spare.
        assert!(
            x.cmpge(lo + r * f * (1.0 - 1e-12)).all() && x.cmple(hi - r * f * (1.0 - 1e-12)).all()
        );
        assert_eq!(ps.v[i], DVec3::ZERO);
    }
    let gap = check_gaps(&w, f);
    eprintln!("closest pair: {gap} × (ri + rj)");
    assert!(w.particles.check_tags_consecutive().is_ok());
}

/// A 30/70 mass mix of 0.75 and 1 mm spheres in a cylinder at φ = 0.55: no overlaps, the
/// count within 6 % of φ V / v̄ (v̄ the number-weighted mean volume), and the same seed
/// gives the same packing while another seed gives another.
#[test]
fn two_sizes_in_a_cylinder_without_overlaps_and_reproducible() {
    let cyl = || {
        Region::new(Shape::Cylinder {
            axis: 2,
            c1: 0.0,
            c2: 0.0,
            radius: 0.02,
            lo: 0.0,
            hi: 0.03,
        })
        .unwrap()
    };
    let d = || dist(&[(0.00075, 0.3), (0.001, 0.7)]);
    let mut w1 = world();
    let (_, rep) = pack(&mut w1, cyl(), d(), 0.55, 7);
    let v = PI * 0.02 * 0.02 * 0.03;
    let want = 0.55 * v / d().mean_particle_volume();
    let n = w1.particles.nlocal() as f64;
    eprintln!("inserted {n}, closed form {want:.0}, {rep:?}");
    assert!((n / want - 1.0).abs() < 0.06, "{n} vs {want}");
    check_gaps(&w1, rep.radius_factor);
    let small = (0..w1.particles.nlocal())
        .filter(|&i| w1.particles.radius[i] < 0.0009)
        .count() as f64
        / n;
    let want_small = d().number_fraction[1];
    assert!((small - want_small).abs() < 0.03, "{small} vs {want_small}");
    for i in 0..w1.particles.nlocal() {
        assert!(cyl().contains_sphere(w1.particles.x[i], w1.particles.radius[i]));
    }
    let mut w2 = world();
    pack(&mut w2, cyl(), d(), 0.55, 7);
    assert_eq!(w1.particles.x, w2.particles.x, "same seed, same packing");
    assert_eq!(w1.particles.radius, w2.particles.radius);
    let mut w3 = world();
    pack(&mut w3, cyl(), d(), 0.55, 8);
    assert_ne!(w1.particles.x[..10], w3.particles.x[..10]);
}

/// Particles already in the region keep their place: the packing grows around them
/// without touching them (their own radii count), and their volume is taken off the
/// estimate.
#[test]
fn packs_around_particles_already_there() {
    let mut w = world();
    let (lo, hi) = (DVec3::new(-0.01, -0.01, 0.0), DVec3::new(0.01, 0.01, 0.02));
    let big = [DVec3::new(0.0, 0.0, 0.01), DVec3::new(0.005, -0.005, 0.004)];
    for x in big {
        w.add_particle(&NewParticle::at(x, 0.003, 2500.0)).unwrap();
    }
    w.extend_tags();
    let (_, rep) = pack(&mut w, block(lo, hi), dist(&[(0.0005, 1.0)]), 0.4, 99);
    let vp = 4.0 / 3.0 * PI * 0.0005f64.powi(3);
    let present = 2.0 * 4.0 / 3.0 * PI * 0.003f64.powi(3);
    assert_eq!(rep.estimate, ((0.4 * 8e-6 - present) / vp).floor() as u64);
    let ps = &w.particles;
    assert_eq!(ps.x[0], big[0]);
    let f = rep.radius_factor;
    for i in 2..ps.nlocal() {
        for (k, &b) in big.iter().enumerate() {
            let d = (ps.x[i] - b).length();
            assert!(
                d > 0.003 + f * ps.radius[i],
                "particle {i} overlaps big sphere {k}"
            );
        }
    }
    check_gaps(&w, 1.0);
    assert!(rep.inserted > 1000, "{rep:?}");
}

/// The settings the fix refuses.
#[test]
fn bad_settings_are_refused() {
    let r = || block(DVec3::splat(-0.01), DVec3::splat(0.01));
    for phi in [0.0, -0.1, MAX_VOLUME_FRACTION + 0.01] {
        assert!(DensePack::new("i", 1, 0, r(), dist(&[(0.001, 1.0)]), phi, None).is_err());
    }
    assert!(DensePack::new("i", 1, 0, r(), dist(&[(0.001, 1.0)]), 0.5, Some(0)).is_err());
    let plane = Region::new(Shape::Plane {
        point: DVec3::ZERO,
        normal: DVec3::Z,
    })
    .unwrap();
    assert!(DensePack::new("i", 1, 0, plane, dist(&[(0.001, 1.0)]), 0.5, None).is_err());
}
