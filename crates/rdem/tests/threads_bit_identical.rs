//! The particle–particle force pass gives bit-identical results whatever the size of the
//! rayon pool it runs on: a dense, randomly perturbed bed (periodic in x and y, so that
//! ghosts take forces too; walls below and above) run for 200 steps on 1, 2 and 4 threads.

use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NewParticle, PairGran,
    PrimitiveWall, WallShape, World,
};

/// The state compared between runs, as bits.
#[derive(Debug, PartialEq, Eq)]
struct State {
    x: Vec<[u64; 3]>,
    v: Vec<[u64; 3]>,
    omega: Vec<[u64; 3]>,
    f: Vec<[u64; 3]>,
    torque: Vec<[u64; 3]>,
    hist: Vec<u64>,
    virial: Vec<[u64; 6]>,
    contacts: usize,
}

fn bits(a: &[DVec3]) -> Vec<[u64; 3]> {
    a.iter()
        .map(|v| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()])
        .collect()
}

fn dense_bed(virial: bool) -> World {
    let (lo, hi) = (DVec3::ZERO, DVec3::new(0.04, 0.04, 0.05));
    let periodic = [Boundary::Periodic, Boundary::Periodic, Boundary::Fixed];
    let mut w = World::new(Domain::new(lo, hi, periodic).unwrap());
    w.materials = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings.skin = 0.0005;
    w.neighbor.settings.delay = 0;
    w.want_virial = virial;
    w.add_fix(Fix::gravity("g", 1, 9.81, DVec3::NEG_Z).unwrap())
        .unwrap();
    for (id, pos) in [("floor", lo.z), ("lid", hi.z)] {
        let shape = WallShape::Plane { axis: 2, pos };
        let wall = PrimitiveWall::new(id, ContactModel::hertz_history(), 1, shape).unwrap();
        w.add_fix(Fix::new(id, 1, FixKind::WallGran(Box::new(wall))).unwrap())
            .unwrap();
    }
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    // A simple cubic lattice with spacing a touch under the mean diameter: every
    // particle starts in contact with most of its six lattice neighbours.
    let a = 0.002;
    let n = (0.04 / a) as usize;
    for ix in 0..n {
        for iy in 0..n {
            for iz in 0..12 {
                let jitter = DVec3::new(rnd(), rnd(), rnd()) - 0.5;
                let x = DVec3::new(ix as f64 + 0.5, iy as f64 + 0.5, iz as f64 + 0.5) * a
                    + jitter * (0.05 * a);
                let r = 0.5 * a * (0.98 + 0.06 * rnd());
                let v = (DVec3::new(rnd(), rnd(), rnd()) - 0.5) * 0.2;
                w.add_particle(&NewParticle::at(x, r, 2500.0).with_v(v))
                    .unwrap();
            }
        }
    }
    w.set_timestep(2e-6).unwrap();
    w
}

/// The bed after 200 steps on `threads` threads.
fn run(threads: usize, virial: bool) -> State {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        assert_eq!(rayon::current_num_threads(), threads);
        let mut w = dense_bed(virial);
        w.run(200).unwrap();
        let p = &w.particles;
        let n = p.nlocal();
        let contacts = w.neighbor.list.hist.iter().filter(|h| **h != 0.0).count();
        State {
            x: bits(&p.x[..n]),
            v: bits(&p.v[..n]),
            omega: bits(&p.omega[..n]),
            f: bits(&p.f[..n]),
            torque: bits(&p.torque[..n]),
            hist: w.neighbor.list.hist.iter().map(|h| h.to_bits()).collect(),
            virial: w.virial.iter().map(|v| v.map(f64::to_bits)).collect(),
            contacts,
        }
    })
}

fn check(virial: bool) {
    let one = run(1, virial);
    assert_eq!(one.x.len(), 20 * 20 * 12);
    assert!(
        one.contacts > 5000,
        "the bed must be in dense contact ({} nonzero history values)",
        one.contacts
    );
    if virial {
        assert_eq!(one.virial.len(), one.x.len());
    }
    for threads in [2, 4] {
        let other = run(threads, virial);
        assert!(
            other == one,
            "{threads} threads differ from 1 (virial: {virial})"
        );
    }
}

#[test]
fn force_pass_is_bit_identical_on_1_2_and_4_threads() {
    check(false);
}

#[test]
fn force_pass_with_virial_is_bit_identical_on_1_2_and_4_threads() {
    check(true);
}

/// Runs `f` on a pool of `threads` threads.
fn on_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        assert_eq!(rayon::current_num_threads(), threads);
        f()
    })
}

/// The neighbor list (rows and partners, and every pair's history) after the set-up and
/// after 150 steps with rebuilds, on 1, 2 and 4 threads: the parallel search joins its
/// layers in order, so the lists are the same, pair for pair.
#[test]
fn neighbor_list_is_identical_on_1_2_and_4_threads() {
    type Lists = Vec<(Vec<u32>, Vec<u32>, Vec<u64>)>;
    let build = |threads: usize| -> (Lists, u64) {
        on_pool(threads, || {
            let mut w = dense_bed(false);
            assert!(w.particles.nlocal() >= rdem::par::PAR_MIN, "parallel path");
            assert!(
                w.particles.nlocal() > 2 * rdem::par::CHUNK,
                "several chunks"
            );
            w.setup().unwrap();
            let mut lists = Vec::new();
            let mut snap = |w: &World| {
                let l = &w.neighbor.list;
                let hist = l.hist.iter().map(|h| h.to_bits()).collect();
                lists.push((l.first.clone(), l.partner.clone(), hist));
            };
            snap(&w);
            for _ in 0..3 {
                for _ in 0..50 {
                    w.advance().unwrap();
                }
                w.setup().unwrap();
                snap(&w);
            }
            (lists, w.neighbor.nbuilds)
        })
    };
    let (one, nbuilds) = build(1);
    assert!(nbuilds >= 4, "{nbuilds} builds");
    assert!(one[0].1.len() > 10_000, "{} pairs", one[0].1.len());
    assert!(one[0].0.len() > rdem::par::PAR_MIN);
    for threads in [2, 4] {
        let (other, _) = build(threads);
        assert_eq!(other.len(), one.len());
        for (k, (a, b)) in other.iter().zip(&one).enumerate() {
            assert!(a.0 == b.0, "{threads} threads, list {k}: other rows");
            assert!(a.1 == b.1, "{threads} threads, list {k}: other partners");
            assert!(a.2 == b.2, "{threads} threads, list {k}: other history");
        }
    }
}

/// Wall forces, torques, wall history and candidate lists on 1, 2 and 4 threads: the bed
/// against its floor and lid and a cylinder through it, with viscous damping and an
/// added force after the walls, evaluated once (set-up) and after 100 steps; the
/// cylinder stores its force on each particle (`store_force`), which must be the same on
/// every thread count and must not change any force (against a run without it).
#[test]
fn wall_forces_are_bit_identical_on_1_2_and_4_threads() {
    type Snap = (
        Vec<[u64; 3]>,
        Vec<[u64; 3]>,
        Vec<Vec<u64>>,
        Vec<Vec<u32>>,
        Vec<u64>,
    );
    // `store`: the cylinder keeps its force on each particle (`store_force yes`).
    let walls = |threads: usize, store: bool| -> Vec<Snap> {
        on_pool(threads, || {
            let mut w = dense_bed(false);
            let shape = WallShape::Cylinder {
                axis: 2,
                radius: 0.0123,
                c1: 0.02,
                c2: 0.02,
            };
            let mut cyl =
                PrimitiveWall::new("cyl", ContactModel::hertz_history(), 1, shape).unwrap();
            if store {
                cyl.store_force = Some("force_cyl".into());
            }
            w.add_fix(Fix::new("cyl", 1, FixKind::WallGran(Box::new(cyl))).unwrap())
                .unwrap();
            w.add_fix(Fix::new("visc", 1, FixKind::Viscous { gamma: 1e-4 }).unwrap())
                .unwrap();
            let force = DVec3::new(1e-5, -2e-5, 3e-5);
            w.add_fix(Fix::new("push", 1, FixKind::AddForce { force }).unwrap())
                .unwrap();
            assert!(w.particles.nlocal() >= rdem::par::PAR_MIN, "parallel path");
            let snap = |w: &World| -> Snap {
                let p = &w.particles;
                let n = p.nlocal();
                let mut hist = Vec::new();
                let mut cands = Vec::new();
                for fix in &w.fixes {
                    if let FixKind::WallGran(wall) = &fix.kind {
                        let id = p.sparse_property(&wall.history_name).unwrap();
                        let h = p.sparse[id.0].dense(n);
                        hist.push(h.iter().map(|h| h.to_bits()).collect());
                        cands.push(wall.candidates().to_vec());
                    }
                }
                let stored = p.property("force_cyl").map_or_else(Vec::new, |id| {
                    p.props[id.0].data[..3 * n]
                        .iter()
                        .map(|v| v.to_bits())
                        .collect()
                });
                (bits(&p.f[..n]), bits(&p.torque[..n]), hist, cands, stored)
            };
            w.setup().unwrap();
            let first = snap(&w);
            w.run(100).unwrap();
            vec![first, snap(&w)]
        })
    };
    let one = walls(1, true);
    for (s, snap) in one.iter().enumerate() {
        let touching = |c: usize| snap.2[c].iter().filter(|&&h| h != 0).count();
        // floor, lid, cylinder: the floor and the cylinder must carry contacts.
        assert_eq!(snap.3.len(), 3);
        assert!(
            snap.3[2].len() > 100,
            "{} cylinder candidates",
            snap.3[2].len()
        );
        if s == 1 {
            assert!(touching(0) > 100, "floor contacts {}", touching(0));
            assert!(touching(2) > 100, "cylinder contacts {}", touching(2));
            let pushed = snap.4.chunks(3).filter(|f| f != &[0; 3]).count();
            assert!(pushed > 100, "stored cylinder forces {pushed}");
        }
    }
    // Storing the cylinder's force leaves every force as it was.
    let plain = walls(1, false);
    for (s, (a, b)) in plain.iter().zip(&one).enumerate() {
        assert!(a.4.is_empty());
        assert!(
            a.0 == b.0 && a.1 == b.1,
            "snapshot {s}: store_force moved a force"
        );
    }
    for threads in [2, 4] {
        let other = walls(threads, true);
        for (s, (a, b)) in other.iter().zip(&one).enumerate() {
            assert!(
                a.3 == b.3,
                "{threads} threads, snapshot {s}: other candidates"
            );
            assert!(
                a.2 == b.2,
                "{threads} threads, snapshot {s}: other wall history"
            );
            assert!(a.0 == b.0, "{threads} threads, snapshot {s}: other forces");
            assert!(a.1 == b.1, "{threads} threads, snapshot {s}: other torques");
            assert!(
                a.4 == b.4,
                "{threads} threads, snapshot {s}: other stored forces"
            );
        }
    }
}
