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
