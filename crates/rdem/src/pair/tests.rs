//! Tests of the parent module.

use crate::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NewParticle, PairGran,
    PrimitiveWall, WallShape, World,
};

/// A simple cubic lattice of slightly overlapping spheres (spacing 2 mm, diameter
/// 2.01 mm, skin 0.4 mm) settling on a floor under gravity, after `steps` steps on
/// `threads` threads; `whole_fraction` as in [`PairGran`]. Gives the particles' and
/// the history's bits and whether the passes walked the whole neighbor list.
fn lattice(threads: usize, whole_fraction: f64, steps: u64) -> (Vec<[u64; 12]>, Vec<u64>, bool) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let n = 14;
        let side = n as f64 * 0.002;
        let mut w =
            World::new(Domain::new(DVec3::ZERO, DVec3::splat(side), [Boundary::Fixed; 3]).unwrap());
        w.materials = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
        let mut pair = PairGran::new(ContactModel::hertz_history());
        pair.whole_fraction = whole_fraction;
        w.pair = Some(pair);
        w.neighbor.settings.skin = 0.0004;
        w.neighbor.settings.delay = 0;
        w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
            .unwrap();
        w.add_fix(
            Fix::new(
                "g",
                1,
                FixKind::Gravity {
                    accel: DVec3::new(0.0, 0.0, -9.81),
                },
            )
            .unwrap(),
        )
        .unwrap();
        let shape = WallShape::Plane { axis: 2, pos: 0.0 };
        let floor = PrimitiveWall::new("floor", ContactModel::hertz_history(), 1, shape);
        w.add_fix(Fix::new("floor", 1, FixKind::WallGran(Box::new(floor.unwrap()))).unwrap())
            .unwrap();
        for a in 0..n {
            for b in 0..n {
                for c in 0..n {
                    let x = DVec3::new(a as f64 + 0.5, b as f64 + 0.5, c as f64 + 0.5) * 0.002;
                    w.add_particle(&NewParticle::at(x, 0.001005, 2500.0))
                        .unwrap();
                }
            }
        }
        w.set_timestep(1e-5).unwrap();
        w.run(steps).unwrap();
        let p = &w.particles;
        let state = (0..p.nlocal())
            .map(|i| {
                let v = [p.x[i], p.v[i], p.f[i], p.omega[i]];
                std::array::from_fn(|k| v[k / 3].to_array()[k % 3].to_bits())
            })
            .collect();
        let hist = w.neighbor.list.hist.iter().map(|h| h.to_bits()).collect();
        (state, hist, w.pair.as_ref().unwrap().near.whole)
    })
}

/// In a packed lattice every listed pair is near, so the passes walk the neighbor list
/// itself; the run is then the one with a near list, bit for bit, on 1 and 2 threads.
#[test]
fn walking_the_whole_list_changes_no_bit() {
    let (want, want_hist, whole) = lattice(1, f64::INFINITY, 300);
    assert!(!whole);
    assert!(
        want_hist.iter().filter(|&&h| h != 0).count() > 3000,
        "the lattice must be in contact"
    );
    for threads in [1, 2] {
        let (got, got_hist, whole) = lattice(threads, super::WHOLE_FRACTION, 300);
        assert!(whole, "{threads} threads: the near list was kept");
        assert!(got == want, "{threads} threads: the particles differ");
        assert!(
            got_hist == want_hist,
            "{threads} threads: the history differs"
        );
    }
}

/// Every touching pair of a moving, colliding gas in a walled box is in the near list at
/// every step, every particle touching a wall is among that wall's candidates, and the
/// near list is a sub-list of the neighbor list.
#[test]
fn near_list_never_misses_a_contact() {
    let mut w =
        World::new(Domain::new(DVec3::ZERO, DVec3::splat(0.04), [Boundary::Fixed; 3]).unwrap());
    w.materials = Materials::uniform(1, 1e7, 0.3, 0.9, 0.3);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings.skin = 0.002;
    w.neighbor.settings.delay = 0;
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    for axis in 0..3 {
        for (k, pos) in [0.0, 0.04].into_iter().enumerate() {
            let shape = WallShape::Plane { axis, pos };
            let id = format!("wall{axis}{k}");
            let wall = PrimitiveWall::new(&id, ContactModel::hertz_history(), 1, shape).unwrap();
            w.add_fix(Fix::new(&id, 1, FixKind::WallGran(Box::new(wall))).unwrap())
                .unwrap();
        }
    }
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for a in 0..6 {
        for b in 0..6 {
            for c in 0..6 {
                let x = DVec3::new(a as f64 + 0.5, b as f64 + 0.5, c as f64 + 0.5) * 0.0066;
                let v = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 2.0;
                w.add_particle(&NewParticle::at(x, 0.002 + 0.0012 * rnd(), 2500.0).with_v(v))
                    .unwrap();
            }
        }
    }
    w.set_timestep(2e-6).unwrap();
    w.setup().unwrap();
    let mut touching_seen = 0;
    let mut wall_touches = 0;
    let mut near_rebuilds = 0;
    let mut last = w.pair.as_ref().unwrap().near.xref.clone();
    for _ in 0..3000 {
        w.advance().unwrap();
        let p = &w.particles;
        let pair = w.pair.as_ref().unwrap();
        if pair.near.xref != last {
            near_rebuilds += 1;
            last = pair.near.xref.clone();
        }
        let n = p.nlocal();
        for i in 0..n {
            for j in i + 1..n {
                let rs = p.radius[i] + p.radius[j];
                if (p.x[i] - p.x[j]).length_squared() < rs * rs {
                    touching_seen += 1;
                    let listed = |a: usize, b: usize| {
                        let (s, e) = (pair.near.first[a] as usize, pair.near.first[a + 1] as usize);
                        pair.near.partner[s..e].contains(&(b as u32))
                    };
                    assert!(
                        listed(i, j) || listed(j, i),
                        "touching pair {i} {j} not in the near list"
                    );
                }
            }
        }
        for fix in &w.fixes {
            if let FixKind::WallGran(wall) = &fix.kind {
                for i in 0..n {
                    if wall.shape.distance(p.x[i]).0 < p.radius[i] {
                        wall_touches += 1;
                        assert!(
                            wall.candidates().contains(&(i as u32)),
                            "wall contact of {i} missed"
                        );
                    }
                }
            }
        }
        for (k, &slot) in pair.near.slot.iter().enumerate() {
            assert_eq!(w.neighbor.list.partner[slot as usize], pair.near.partner[k]);
        }
    }
    assert!(
        touching_seen > 1000,
        "the gas must collide ({touching_seen})"
    );
    assert_eq!(w.particles.nlocal(), 216);
    assert!(wall_touches > 100, "the walls must be hit ({wall_touches})");
    assert!(
        near_rebuilds > 10 && near_rebuilds < 3000,
        "{near_rebuilds} near-list rebuilds"
    );
}
