//! Periodic boxes shorter than twice the neighbor cutoff (but at least twice the largest
//! contact distance): the ghosts hold a particle's images through both faces, several
//! layers of them when the box is shorter than the cutoff, and the neighbor list may hold
//! two images of one partner, only one of which can touch. LIGGGHTS 3.8 (as LAMMPS) runs
//! such boxes; rdem must give the same physics as in a long box.
//!
//! - A collision across the face of a short box is bit-identical to the same collision in
//!   a long box (coordinates chosen so that every wrap and image shift is exact), on 1 and
//!   2 threads, for a box between the cutoff and twice it and for one below the cutoff;
//!   and equal to 1e-11 to the same collision translated to the middle of the long box.
//! - The contact history follows the image that touches: the far image of the partner
//!   (listed too) holds none.
//! - One particle in a box barely longer than its diameter plus the skin, or exactly twice
//!   its diameter with its own images in the list, falls freely (closed form).
//! - A dense random packing in a short box has half the contacts and energies of a box
//!   twice as long made of two copies of it, step after step, on 1 and 2 threads.

use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NeighborSettings, NewParticle,
    PairGran, World,
};

const R: f64 = 0.004;
const RHO: f64 = 2500.0;

/// Runs `f` on a pool of `threads` threads.
fn on_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(f)
}

/// A box with fixed x and y faces at ±0.1 and periodic z from `zlo` to `zhi`, Hertz with
/// tangential history, nve/sphere, time step 1e-6 s.
fn world(zlo: f64, zhi: f64, neigh: NeighborSettings) -> World {
    let mut w = World::new(
        Domain::new(
            DVec3::new(-0.1, -0.1, zlo),
            DVec3::new(0.1, 0.1, zhi),
            [Boundary::Fixed, Boundary::Fixed, Boundary::Periodic],
        )
        .unwrap(),
    );
    w.materials = Materials::uniform(1, 1e7, 0.3, 0.5, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings = neigh;
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.set_timestep(1e-6).unwrap();
    w
}

/// Two spheres A (tag 1) and B (tag 2) closing along z at 1 m/s, B offset 2 mm along x
/// and A spinning (an oblique, frictional impact), A's centre at `za` and B's at
/// `za + 0.0082` (given as `zb`, which may be that position wrapped into the box).
fn add_pair(w: &mut World, za: f64, zb: f64) {
    let a = NewParticle::at(DVec3::new(0.05, 0.05, za), R, RHO)
        .with_v(DVec3::new(0.0, 0.0, 0.5))
        .with_omega(DVec3::new(0.0, 20.0, 0.0));
    let b = NewParticle::at(DVec3::new(0.052, 0.05, zb), R, RHO).with_v(DVec3::new(0.0, 0.0, -0.5));
    w.add_particle(&a).unwrap();
    w.add_particle(&b).unwrap();
}

/// Per tag: position (z mapped up by `lz` when below 0), velocity, angular velocity,
/// force, torque, as bits.
fn state(w: &World, lz: f64) -> Vec<[u64; 15]> {
    let p = &w.particles;
    let mut s: Vec<(u64, [u64; 15])> = (0..p.nlocal())
        .map(|i| {
            let mut x = p.x[i];
            if x.z < 0.0 {
                x.z += lz;
            }
            let mut b = [0u64; 15];
            for (k, v) in [x, p.v[i], p.omega[i], p.f[i], p.torque[i]]
                .iter()
                .enumerate()
            {
                b[3 * k] = v.x.to_bits();
                b[3 * k + 1] = v.y.to_bits();
                b[3 * k + 2] = v.z.to_bits();
            }
            (p.tag[i], b)
        })
        .collect();
    s.sort_by_key(|e| e.0);
    s.into_iter().map(|e| e.1).collect()
}

/// Listed pairs of tags 1 and 2: (distance, history is non-zero).
fn images_of_pair(w: &World) -> Vec<(f64, bool)> {
    let p = &w.particles;
    let l = &w.neighbor.list;
    let mut out = Vec::new();
    for i in 0..p.nlocal() {
        for k in l.first[i] as usize..l.first[i + 1] as usize {
            let j = l.partner[k] as usize;
            let mut t = [p.tag[i], p.tag[j]];
            t.sort();
            if t == [1, 2] {
                let h = &l.hist[k * l.width..(k + 1) * l.width];
                out.push(((p.x[j] - p.x[i]).length(), h.iter().any(|&v| v != 0.0)));
            }
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// The collision across the face z = 0.025 of the box [-0.025, 0.025) (length 0.05,
/// contact distance 0.008), rebuilt every step, against the same collision in the box
/// [-0.1, 0.1) rebuilt only when needed. Every z stays within 0.0156..0.0313 in magnitude
/// (one binade), where adding or removing 0.05 is exact: B's ghost in the short box is at
/// B's position in the long one, bit for bit, and so is every step after.
fn collision_across_short_face(skin: f64, threads: usize) {
    let lz = 0.05;
    let every = NeighborSettings {
        skin,
        delay: 0,
        every: 1,
        check: false,
        contact_distance_factor: 1.0,
    };
    let (short_hist, long_hist, listed_twice, three_images) = on_pool(threads, || {
        let mut short = world(-0.025, 0.025, every);
        let mut long = world(
            -0.1,
            0.1,
            NeighborSettings {
                check: true,
                ..every
            },
        );
        let (za, zb) = (0.0209, 0.0291);
        add_pair(&mut short, za, zb - lz);
        add_pair(&mut long, za, zb);
        short.setup().unwrap();
        long.setup().unwrap();
        assert_eq!(state(&short, lz), state(&long, lz));
        let (mut listed_twice, mut three_images) = (0, 0);
        let (mut sh, mut lh) = (0.0f64, 0.0f64);
        for step in 1..=1200 {
            short.advance().unwrap();
            long.advance().unwrap();
            assert!(
                state(&short, lz) == state(&long, lz),
                "skin {skin}, {threads} threads: the runs differ at step {step}"
            );
            let im = images_of_pair(&short);
            // At most one image carries history, and it is the nearest one.
            assert!(
                im.iter().skip(1).all(|e| !e.1),
                "step {step}: history on a far image {im:?}"
            );
            if im.len() > 1 {
                listed_twice += 1;
            }
            if im.len() > 2 {
                three_images += 1;
            }
            // Every image of B within the cutoff of A is listed once (brute force over
            // the images: a box shorter than the cutoff needs two layers of them).
            let (pa, pb) = {
                let p = &short.particles;
                let f = |t: u64| p.x[(0..p.nlocal()).find(|&i| p.tag[i] == t).unwrap()];
                (f(1), f(2))
            };
            let rc = 2.0 * R + skin;
            let expect = (-5..=5)
                .filter(|&n| (pb + DVec3::new(0.0, 0.0, n as f64 * lz) - pa).length() < rc)
                .count();
            assert_eq!(im.len(), expect, "step {step}: {im:?}");
            let h = |w: &World| {
                let l = &w.neighbor.list;
                l.hist.iter().fold(0.0f64, |a, v| a.max(v.abs()))
            };
            sh = sh.max(h(&short));
            lh = lh.max(h(&long));
        }
        (sh, lh, listed_twice, three_images)
    });
    // The impact happened, with a tangential spring, and the short box listed both images
    // of B while it did.
    assert!(long_hist > 1e-6, "no tangential history: {long_hist}");
    assert_eq!(short_hist, long_hist);
    assert!(
        listed_twice > 1000,
        "skin {skin}: two images listed at {listed_twice} steps"
    );
    if skin > 0.045 {
        assert!(three_images > 900, "{three_images}");
    }
}

/// Cutoff 0.048: the box (0.05) is between the cutoff and twice it.
#[test]
fn collision_across_a_face_shorter_than_twice_the_cutoff_is_bit_identical() {
    collision_across_short_face(0.04, 1);
    collision_across_short_face(0.04, 2);
}

/// Cutoff 0.058: the box is shorter than the cutoff itself (two layers of images).
#[test]
fn collision_across_a_face_shorter_than_the_cutoff_is_bit_identical() {
    collision_across_short_face(0.05, 1);
    collision_across_short_face(0.05, 2);
}

/// The same collision in the middle of the long box (centres at z = ∓0.0041): positions
/// differ in their last bits from the run at the face, so the trajectories agree to 1e-11
/// (relative, velocities and angular velocities; positions relative to the diameter;
/// measured: 2.3e-12 for the velocities).
#[test]
fn collision_across_a_short_face_matches_the_middle_of_a_long_box() {
    let lz = 0.05;
    let neigh = NeighborSettings {
        skin: 0.04,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    let mut short = world(-0.025, 0.025, neigh);
    let mut long = world(-0.1, 0.1, neigh);
    add_pair(&mut short, 0.0209, 0.0291 - lz);
    add_pair(&mut long, -0.0041, 0.0041);
    short.setup().unwrap();
    long.setup().unwrap();
    let mut worst = [0.0f64; 3];
    for _ in 0..1200 {
        short.advance().unwrap();
        long.advance().unwrap();
        let (ps, pl) = (&short.particles, &long.particles);
        let t = |p: &rdem::Particles, tag: u64| (0..p.nlocal()).find(|&i| p.tag[i] == tag).unwrap();
        let (sa, sb, la, lb) = (t(ps, 1), t(ps, 2), t(pl, 1), t(pl, 2));
        // Unwrapped separation B - A.
        let mut ds = short.domain.unmap(ps.x[sb], ps.image[sb].get())
            - short.domain.unmap(ps.x[sa], ps.image[sa].get());
        // B started one box below the image that A hits.
        ds.z -= lz * (ds.z / lz).round();
        let dl = pl.x[lb] - pl.x[la];
        worst[0] = worst[0].max((ds - dl).length() / (2.0 * R));
        for (s, l) in [(sa, la), (sb, lb)] {
            worst[1] = worst[1].max((ps.v[s] - pl.v[l]).length() / 0.5);
            worst[2] = worst[2].max((ps.omega[s] - pl.omega[l]).length() / 20.0);
        }
    }
    assert!(worst.iter().all(|&e| e < 1e-11), "{worst:?}");
    // The impact turned the velocities (A rebounds).
    let p = &short.particles;
    let a = (0..2).find(|&i| p.tag[i] == 1).unwrap();
    assert!(p.v[a].z < -0.1, "{:?}", p.v[a]);
}

/// One particle (radius R) falling under g = 9.81 in a periodic box along z, from 20 µm
/// above the lower face, across it: its force is m g exactly at every step, with no
/// contact with its own images, and it falls as z0 − g t²/2, v = −g t (velocity Verlet is
/// exact for a constant force; to 1e-11 of the box and 1e-12 of the speed).
fn free_fall(lz: f64, skin: f64, expect_self_images: bool) {
    let mut w = world(
        0.0,
        lz,
        NeighborSettings {
            skin,
            delay: 0,
            every: 1,
            // Rebuilt (remapped, ghosts made again) every step.
            check: false,
            contact_distance_factor: 1.0,
        },
    );
    let g = 9.81;
    w.add_fix(Fix::gravity("g", 1, g, DVec3::NEG_Z).unwrap())
        .unwrap();
    let z0 = 2e-5;
    w.add_particle(&NewParticle::at(DVec3::new(0.0, 0.0, z0), R, RHO))
        .unwrap();
    w.setup().unwrap();
    let m = w.particles.rmass[0];
    let dt = 1e-6;
    let mut self_listed = 0;
    for n in 1..=3000u64 {
        w.advance().unwrap();
        let p = &w.particles;
        assert_eq!(p.f[0], DVec3::new(0.0, 0.0, -m * g), "step {n}");
        assert_eq!(p.torque[0], DVec3::ZERO, "step {n}");
        let t = n as f64 * dt;
        let z = w.domain.unmap(p.x[0], p.image[0].get()).z;
        let ze = z0 - 0.5 * g * t * t;
        assert!((z - ze).abs() <= 1e-11 * lz, "step {n}: z {z} vs {ze}");
        assert!((p.v[0].z + g * t).abs() <= 1e-12 * g * t, "step {n}");
        self_listed += w.neighbor.list.len();
    }
    assert_eq!(self_listed > 0, expect_self_images, "{self_listed}");
    // It crossed the periodic face.
    assert_eq!(w.particles.image[0].get()[2], -1);
}

#[test]
fn a_particle_in_a_box_just_above_its_diameter_plus_skin_falls_freely() {
    // Diameter 0.008 + skin 0.009 = the cutoff 0.017; the box a little longer (its own
    // images are not listed, but the ghost exchange sends it through both faces).
    free_fall(0.017 * (1.0 + 1e-9), 0.009, false);
}

#[test]
fn a_particle_in_a_box_twice_its_diameter_falls_freely_beside_its_own_images() {
    // Box 0.016 = twice the contact distance (the shortest allowed), skin 0.01: the
    // cutoff 0.018 exceeds the box, so the particle's own images (0.016 away) are listed.
    free_fall(0.016, 0.01, true);
}

/// 27 × 27 × 3 particles of radii 0.00198..0.00206 on a jittered lattice of spacing 0.004
/// (many overlapping), random velocities and spins, in a box 0.108 × 0.108 periodic along
/// x and y and `copies` × 0.012 along z, the packing repeated `copies` times along z.
/// Contact distance at most 0.00412, cutoff 0.00712 with skin 0.003: the box of 0.012 is
/// between twice the contact distance and twice the cutoff.
fn packing(copies: usize) -> World {
    let (lxy, lz) = (0.108, 0.012);
    let mut w = World::new(
        Domain::new(
            DVec3::ZERO,
            DVec3::new(lxy, lxy, lz * copies as f64),
            [Boundary::Periodic; 3],
        )
        .unwrap(),
    );
    w.materials = Materials::uniform(1, 5e6, 0.45, 0.5, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    // Rebuilt every step: the history is saved and handed back by tag at every step.
    w.neighbor.settings = NeighborSettings {
        skin: 0.003,
        delay: 0,
        every: 1,
        check: false,
        contact_distance_factor: 1.0,
    };
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.set_timestep(2e-6).unwrap();
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut one = Vec::new();
    for ix in 0..27 {
        for iy in 0..27 {
            for iz in 0..3 {
                let jitter = DVec3::new(rnd(), rnd(), rnd()) - 0.5;
                let x =
                    (DVec3::new(ix as f64, iy as f64, iz as f64) + 0.5) * 0.004 + jitter * 0.0002;
                let r = 0.00198 + 0.00008 * rnd();
                let v = (DVec3::new(rnd(), rnd(), rnd()) - 0.5) * 0.2;
                let om = (DVec3::new(rnd(), rnd(), rnd()) - 0.5) * 50.0;
                one.push(NewParticle::at(x, r, 2500.0).with_v(v).with_omega(om));
            }
        }
    }
    for c in 0..copies {
        for np in &one {
            let mut q = np.clone();
            q.x.z += lz * c as f64;
            w.add_particle(&q).unwrap();
        }
    }
    w
}

/// (touching pairs, pairs with history, translational and rotational kinetic energy).
fn tallies(w: &World) -> (usize, usize, f64, f64) {
    let p = &w.particles;
    let l = &w.neighbor.list;
    let mut touching = 0;
    let mut with_hist = 0;
    for i in 0..p.nlocal() {
        for k in l.first[i] as usize..l.first[i + 1] as usize {
            let j = l.partner[k] as usize;
            if (p.x[j] - p.x[i]).length() < p.radius[i] + p.radius[j] {
                touching += 1;
            }
            if l.hist[k * l.width..(k + 1) * l.width]
                .iter()
                .any(|&v| v != 0.0)
            {
                with_hist += 1;
            }
        }
    }
    let (et, er) = p.kinetic_energy();
    (touching, with_hist, et, er)
}

#[test]
fn dense_packing_in_a_short_box_matches_two_copies_in_a_box_twice_as_long() {
    let run = |copies: usize, threads: usize| {
        on_pool(threads, || {
            let mut w = packing(copies);
            assert!(w.particles.nlocal() >= rdem::par::PAR_MIN, "parallel path");
            w.setup().unwrap();
            let mut out = vec![tallies(&w)];
            for _ in 0..4 {
                for _ in 0..50 {
                    w.advance().unwrap();
                }
                out.push(tallies(&w));
            }
            (out, w.neighbor.nbuilds, w.particles.x.clone())
        })
    };
    let (one, builds, x1) = run(1, 1);
    let (two, _, _) = run(2, 1);
    let (one_t2, _, x1_t2) = run(1, 2);
    assert_eq!(one, one_t2, "1 and 2 threads differ");
    assert!(x1 == x1_t2, "1 and 2 threads differ");
    assert!(builds > 2, "{builds} builds");
    assert!(one[0].0 > 1000, "dense contact: {:?}", one[0]);
    for (k, (a, b)) in one.iter().zip(&two).enumerate() {
        assert_eq!(2 * a.0, b.0, "after {} steps: touching pairs", 50 * k);
        assert_eq!(2 * a.1, b.1, "after {} steps: pairs with history", 50 * k);
        for (ea, eb) in [(a.2, b.2), (a.3, b.3)] {
            assert!(
                (2.0 * ea - eb).abs() <= 1e-9 * eb,
                "after {} steps: energies {ea} × 2 vs {eb}",
                50 * k
            );
        }
    }
    // Energy was exchanged through the contacts (the check is not of a free gas).
    assert!((one[4].2 - one[0].2).abs() > 0.05 * one[0].2, "{one:?}");
}
