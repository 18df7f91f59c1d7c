//! Spatial sort of seed 002 eqs. (6)–(9).
//!
//! * Eq. (6): `n_a = max(1, floor(extent_a / h))` bins per axis — bins are
//!   `extent / n_a` wide (at least h, not exactly h), and there is always one bin, whatever h.
//! * Eq. (7): bin index `clamp(floor((x_a - lo_a) n_a / extent_a), 0, n_a - 1)`, so
//!   particles outside the bounding box go to the first or last bin.
//! * Eq. (8): bins numbered with x fastest, then y, then z.
//! * Eq. (9): a stable counting sort — equal bins keep their order — applied as one
//!   permutation to every per-particle array.
//!
//! The permutation is checked against an independent implementation of eqs. (6)–(7) on
//! random input. Through `World`, `atom_modify sort` with the user bin size or half the
//! neighbor cutoff orders the particles by those bins, and sorting every step changes
//! nothing about any particle: per-tag records (tag, type, mask, x, v, ω, radius, mass,
//! density, image flags and named properties) are bit-identical to a run without sorting,
//! for ballistic particles under gravity crossing periodic faces; with contact forces the
//! records of a static packing stay bit-identical except the summed forces and torques,
//! which may differ in the last bits (summation order) — 1e-12 relative to the largest.

use std::collections::BTreeMap;

use proptest::prelude::*;
use rdem::sort::sort_permutation;
use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, LostPolicy, Materials, NeighborSettings,
    NewParticle, PairGran, World,
};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// Seed 002 eqs. (6)–(8), written independently of the engine.
fn seed_bin(x: DVec3, lo: DVec3, hi: DVec3, h: f64) -> usize {
    let mut n = [1usize; 3];
    let mut k = [0usize; 3];
    for a in 0..3 {
        let ext = hi[a] - lo[a];
        n[a] = ((ext / h).floor() as usize).max(1);
        let f = ((x[a] - lo[a]) * n[a] as f64 / ext).floor();
        k[a] = f.max(0.0).min((n[a] - 1) as f64) as usize;
    }
    k[0] + n[0] * (k[1] + n[1] * k[2])
}

#[test]
fn bins_are_floor_of_extent_over_h_wide() {
    // Extent 1, h = 0.3: floor(3.33) = 3 bins of width 1/3 (not 0.3). 0.32 and 0.05 share
    // bin 0, so the stable sort keeps their order; with 0.3-wide bins 0.32 would move
    // behind 0.05.
    let x = vec![v(0.32, 0.0, 0.0), v(0.05, 0.0, 0.0)];
    assert_eq!(
        sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.3),
        vec![0, 1]
    );
    // 0.34 is in bin 1 of 3.
    let x = vec![v(0.34, 0.0, 0.0), v(0.05, 0.0, 0.0)];
    assert_eq!(
        sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.3),
        vec![1, 0]
    );
    // Extent 1, h = 0.26: floor(3.85) = 3 bins, so 0.3 and 0.2 share bin 0 (with a
    // ceiling, 4 bins, 0.3 would be in bin 1 and move behind 0.2).
    let x = vec![v(0.3, 0.0, 0.0), v(0.2, 0.0, 0.0)];
    assert_eq!(
        sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.26),
        vec![0, 1]
    );
    let x = vec![v(0.34, 0.0, 0.0), v(0.2, 0.0, 0.0)];
    assert_eq!(
        sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.26),
        vec![1, 0]
    );
}

#[test]
fn there_is_always_at_least_one_bin() {
    let x = vec![v(0.9, 0.9, 0.9), v(0.1, 0.1, 0.1), v(0.5, 0.5, 0.5)];
    for h in [1.0, 5.0, 1e300, f64::INFINITY] {
        assert_eq!(
            sort_permutation(&x, DVec3::ZERO, DVec3::ONE, h),
            vec![0, 1, 2],
            "h = {h}"
        );
    }
    // Degenerate inputs (no extent along an axis, no bin size) do not panic: one bin.
    assert_eq!(
        sort_permutation(&x, DVec3::ZERO, v(1.0, 0.0, 1.0), 5.0),
        vec![0, 1, 2]
    );
    for h in [0.0, -1.0, f64::NAN] {
        assert_eq!(
            sort_permutation(&x, DVec3::ZERO, DVec3::ONE, h),
            vec![0, 1, 2],
            "h = {h}"
        );
    }
    assert!(sort_permutation(&[], DVec3::ZERO, DVec3::ONE, 0.1).is_empty());
}

#[test]
fn outside_points_are_clamped_to_the_end_bins() {
    // 4 bins of 0.25 along x.
    let x = vec![
        v(7.0, 0.5, 0.5),  // clamped to bin 3
        v(0.6, 0.5, 0.5),  // bin 2
        v(-7.0, 0.5, 0.5), // clamped to bin 0
        v(0.1, 0.5, 0.5),  // bin 0
        v(1.0, 0.5, 0.5),  // exactly hi: bin 3 by clamping
        v(0.0, 0.5, 0.5),  // exactly lo: bin 0
    ];
    let perm = sort_permutation(&x, DVec3::ZERO, v(1.0, 0.1, 0.1), 0.25);
    assert_eq!(perm, vec![2, 3, 5, 1, 0, 4]);
}

#[test]
fn bins_are_numbered_x_fastest() {
    // 2×2×2 bins; the eight corners of the cube listed in reverse order.
    let mut x = Vec::new();
    for k in (0..8).rev() {
        x.push(v(
            0.25 + 0.5 * (k & 1) as f64,
            0.25 + 0.5 * ((k >> 1) & 1) as f64,
            0.25 + 0.5 * (k >> 2) as f64,
        ));
    }
    let perm = sort_permutation(&x, DVec3::ZERO, DVec3::ONE, 0.5);
    assert_eq!(perm, vec![7, 6, 5, 4, 3, 2, 1, 0]);
}

proptest! {
    /// The permutation is a permutation, orders by the seed's bin, and is stable.
    #[test]
    fn permutation_is_a_stable_sort_by_seed_bin(
        pts in prop::collection::vec(prop::array::uniform3(-0.5f64..1.5), 0..400),
        lo in prop::array::uniform3(-1.0f64..1.0),
        ext in prop::array::uniform3(0.1f64..3.0),
        h in 0.05f64..2.0,
    ) {
        let lo = DVec3::from_array(lo);
        let hi = lo + DVec3::from_array(ext);
        let x: Vec<DVec3> = pts.iter().map(|p| lo + DVec3::from_array(*p) * (hi - lo)).collect();
        let perm = sort_permutation(&x, lo, hi, h);
        prop_assert_eq!(perm.len(), x.len());
        let mut seen = vec![false; x.len()];
        for &i in &perm {
            prop_assert!(!seen[i]);
            seen[i] = true;
        }
        for w in perm.windows(2) {
            let (b0, b1) = (seed_bin(x[w[0]], lo, hi, h), seed_bin(x[w[1]], lo, hi, h));
            prop_assert!(b0 < b1 || (b0 == b1 && w[0] < w[1]), "bins {} {} indices {} {}", b0, b1, w[0], w[1]);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Through World.

/// Everything a particle carries, bit for bit (f64 as bits so NaN-free equality is exact).
type Record = (
    u32,
    u32,
    [u64; 3],
    [u64; 3],
    [u64; 3],
    [u64; 3],
    [i32; 3],
    Vec<u64>,
);

fn bits(v: DVec3) -> [u64; 3] {
    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
}

/// Per-tag records of the owned particles (forces excluded), and the forces and torques.
fn records(w: &World) -> (BTreeMap<u64, Record>, BTreeMap<u64, (DVec3, DVec3)>) {
    let p = &w.particles;
    let mut rec = BTreeMap::new();
    let mut ft = BTreeMap::new();
    for i in 0..p.nlocal() {
        let props: Vec<u64> = p
            .props
            .iter()
            .map(|q| q.get(i))
            .chain(p.sparse.iter().map(|q| q.get(i)))
            .flat_map(|v| v.iter().map(|v| v.to_bits()))
            .collect();
        let r = (
            p.ty[i],
            p.mask[i],
            bits(p.x[i]),
            bits(p.v[i]),
            bits(p.omega[i]),
            [
                p.radius[i].to_bits(),
                p.rmass[i].to_bits(),
                p.density[i].to_bits(),
            ],
            p.image[i].get(),
            props,
        );
        assert!(rec.insert(p.tag[i], r).is_none(), "tag {} twice", p.tag[i]);
        ft.insert(p.tag[i], (p.f[i], p.torque[i]));
    }
    (rec, ft)
}

#[derive(Debug, Clone)]
struct Swarm {
    periodic: [bool; 3],
    parts: Vec<([f64; 3], [f64; 3], f64)>,
}

fn swarm() -> impl Strategy<Value = Swarm> {
    (
        prop::array::uniform3(any::<bool>()),
        prop::collection::vec(
            (
                prop::array::uniform3(0.0f64..1.0),
                prop::array::uniform3(-1.0f64..1.0),
                0.0f64..1.0,
            ),
            1..200,
        ),
    )
        .prop_map(|(periodic, parts)| Swarm { periodic, parts })
}

/// Particles with named properties (widths 1 and 3, values unique per particle) flying
/// through a unit box under gravity; no contacts.
fn ballistic(s: &Swarm, sort_every: u64) -> World {
    let bc = s.periodic.map(|p| {
        if p {
            Boundary::Periodic
        } else {
            Boundary::Fixed
        }
    });
    let mut w = World::new(Domain::new(DVec3::ZERO, DVec3::ONE, bc).unwrap());
    w.neighbor.settings = NeighborSettings {
        skin: 0.01,
        delay: 0,
        every: 1,
        check: false,
        contact_distance_factor: 1.0,
    };
    w.sort.every = sort_every;
    w.lost_policy = LostPolicy::Ignore;
    let a = w.particles.add_property("a", 1, &[-1.0]).unwrap();
    let b = w.particles.add_property("b", 3, &[0.0; 3]).unwrap();
    for (k, (x, vel, r)) in s.parts.iter().enumerate() {
        let mut np = NewParticle::at(DVec3::from_array(*x), 0.005 + 0.02 * r, 1000.0 + k as f64)
            .with_v(DVec3::from_array(*vel) * 2.0)
            .with_omega(DVec3::new(k as f64, -(k as f64), 0.5))
            .with_type(1 + (k % 3) as u32);
        np.mask |= 1 << (1 + k % 5);
        let i = w.add_particle(&np).unwrap();
        w.particles.props[a.0].get_mut(i)[0] = k as f64 * 1.5;
        w.particles.props[b.0]
            .get_mut(i)
            .copy_from_slice(&[k as f64, -(k as f64), x[0]]);
    }
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(Fix::gravity("g", 1, 9.81, v(0.3, -0.2, -1.0)).unwrap())
        .unwrap();
    w.set_timestep(1e-3).unwrap();
    w
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// Sorting every step (re-neighboring every step) versus never: identical records by tag.
    #[test]
    fn sorting_every_step_preserves_every_record(s in swarm(), steps in 1u64..60) {
        let mut sorted = ballistic(&s, 1);
        let mut plain = ballistic(&s, 0);
        sorted.run(steps).unwrap();
        plain.run(steps).unwrap();
        let (rs, fs) = records(&sorted);
        let (rp, fp) = records(&plain);
        prop_assert_eq!(sorted.lost, plain.lost);
        prop_assert_eq!(&rs, &rp);
        prop_assert_eq!(fs, fp);
        // The named properties still sit with the right tags (value = f(tag)).
        let a = sorted.particles.property("a").unwrap();
        for i in 0..sorted.particles.nlocal() {
            let k = sorted.particles.tag[i] - 1;
            prop_assert_eq!(sorted.particles.props[a.0].get(i)[0], k as f64 * 1.5);
        }
        prop_assert_eq!(sorted.neighbor.nbuilds, steps + 1);
    }
}

/// A static granular packing (touching spheres, no integration): re-neighboring and
/// sorting every step must leave every record untouched and the forces equal up to
/// summation order.
#[test]
fn sorting_a_packing_changes_nothing_but_summation_order() {
    let build = |sort_every: u64| {
        let mut w = World::new(
            Domain::new(DVec3::ZERO, DVec3::splat(0.1), [Boundary::Periodic; 3]).unwrap(),
        );
        w.materials = Materials::uniform(1, 5e6, 0.3, 0.5, 0.5);
        w.pair = Some(PairGran::new(ContactModel::hertz_history()));
        w.neighbor.settings = NeighborSettings {
            skin: 0.001,
            delay: 0,
            every: 1,
            check: false,
            contact_distance_factor: 1.0,
        };
        w.sort.every = sort_every;
        let hist = w.particles.add_property("tagcopy", 2, &[0.0, 0.0]).unwrap();
        let mut k = 0;
        for iz in 0..10 {
            for iy in 0..10 {
                for ix in 0..10 {
                    // Reverse order so that the sort has work to do; overlaps of
                    // 0.04 to 0.1 µm on a lattice of spacing 1 cm.
                    let x = v(
                        0.005 + 0.01 * (9 - ix) as f64,
                        0.005 + 0.01 * (9 - iy) as f64,
                        0.005 + 0.01 * (9 - iz) as f64,
                    );
                    let r = 0.00502 + 0.00001 * ((ix + 2 * iy + 3 * iz) % 4) as f64;
                    let i = w.add_particle(&NewParticle::at(x, r, 2500.0)).unwrap();
                    k += 1;
                    w.particles.props[hist.0]
                        .get_mut(i)
                        .copy_from_slice(&[k as f64, -(k as f64)]);
                }
            }
        }
        w.set_timestep(1e-6).unwrap();
        w
    };
    let mut sorted = build(1);
    let mut plain = build(0);
    sorted.run(20).unwrap();
    plain.run(20).unwrap();
    let (rs, fs) = records(&sorted);
    let (rp, fp) = records(&plain);
    assert_eq!(rs, rp);
    let fmax = fp.values().map(|(f, _)| f.length()).fold(0.0, f64::max);
    let tmax = fp.values().map(|(_, t)| t.length()).fold(0.0, f64::max);
    assert!(fmax > 0.0, "the packing must be loaded");
    for (t, (f, tq)) in &fs {
        let (f0, tq0) = fp[t];
        assert!(
            (*f - f0).length() <= 1e-12 * fmax,
            "force of {t}: {f} vs {f0}"
        );
        assert!(
            (*tq - tq0).length() <= 1e-12 * tmax.max(1e-300),
            "torque of {t}: {tq} vs {tq0}"
        );
    }
    // The storage orders differ (the sort did something) but the contacts are the same.
    assert_ne!(sorted.particles.tag[..1000], plain.particles.tag[..1000]);
    assert_eq!(sorted.neighbor.list.len(), plain.neighbor.list.len());
    let hs: usize = sorted
        .neighbor
        .list
        .hist
        .iter()
        .filter(|&&h| h != 0.0)
        .count();
    let hp: usize = plain
        .neighbor
        .list
        .hist
        .iter()
        .filter(|&&h| h != 0.0)
        .count();
    assert_eq!(hs, hp);
}

/// World sorts by the seed's bins: with particles at two opposite corners the bounding box
/// is the box, so the storage order after set-up must be the stable sort of the insertion
/// order by `seed_bin` with bin size h (user value, or half the neighbor cutoff). Enough
/// particles that the bin count stays below World's cap of 8 N + 64.
#[test]
fn world_orders_particles_by_seed_bins() {
    for binsize in [0.0, 0.13] {
        let mut w = World::new(
            Domain::new(v(-0.5, 0.0, 1.0), v(0.5, 0.8, 1.6), [Boundary::Fixed; 3]).unwrap(),
        );
        w.neighbor.settings = NeighborSettings {
            skin: 0.02,
            delay: 0,
            every: 1,
            check: true,
            contact_distance_factor: 1.0,
        };
        w.sort.every = 1000;
        w.sort.binsize = binsize;
        let lo = w.domain.boxlo;
        let hi = w.domain.boxhi;
        let mut xs = vec![lo, hi];
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2500 {
            xs.push(lo + DVec3::new(rnd(), rnd(), rnd()) * (hi - lo));
        }
        for x in &xs {
            w.add_particle(&NewParticle::at(*x, 0.02, 1000.0)).unwrap();
        }
        w.setup().unwrap();
        let h = if binsize > 0.0 {
            binsize
        } else {
            0.5 * (2.0 * 0.02 + 0.02)
        };
        let mut want: Vec<usize> = (0..xs.len()).collect();
        want.sort_by_key(|&i| seed_bin(xs[i], lo, hi, h)); // stable
        let got: Vec<usize> = w.particles.tag[..xs.len()]
            .iter()
            .map(|&t| t as usize - 1)
            .collect();
        assert_eq!(got, want, "binsize {binsize}");
        // And the positions went with their tags.
        for (i, &k) in got.iter().enumerate() {
            assert_eq!(w.particles.x[i], xs[k]);
        }
    }
}
