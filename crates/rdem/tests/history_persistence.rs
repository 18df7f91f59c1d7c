//! Contact history (the tangential spring ξ of `tangential history`, stored beside each
//! listed pair, `ContactModel::history_width()` values) must survive everything that
//! rebuilds or reorders the neighbor list: re-neighboring, spatial sorting, periodic wrap
//! (where a pair turns from local–local into local–ghost and may be seen from the other
//! particle, so its vector part changes sign), adding a particle, and a second `run`.
//!
//! The strongest check is bitwise: two particles pressed together by opposite `addforce`s
//! and sheared slowly while both drift across a periodic face give *bit-identical* forces,
//! torques, velocities and unwrapped positions in a run that re-neighbors and sorts every
//! step (`neigh_modify every 1 delay 0 check no`, `atom_modify sort 1`) and in one that
//! rebuilds rarely and never sorts. This holds exactly because the box [-0.1, 0.1) makes
//! every wrap exact (x ± 0.2 stays in the same binade, Sterbenz) and the contact law is
//! exactly antisymmetric under swapping i and j. Any lost, stale or wrongly signed history
//! changes the tangential force and breaks the equality.
//!
//! Determinism: two identical runs (300 polydisperse particles falling under gravity onto
//! a granular wall, periodic sides, 2000 steps) are bit-identical.

use rdem::{
    Boundary, ContactModel, DVec3, Domain, Fix, FixKind, Materials, NeighborSettings, NewParticle,
    PairGran, PrimitiveWall, WallShape, World,
};

const R: f64 = 0.01;
const RHO: f64 = 2500.0;

/// History of the pair of tags (a, b) as seen from a (vector part negated if the list
/// holds it as (b, a)), or None if the pair is not listed.
fn pair_hist(w: &World, a: u64, b: u64) -> Option<Vec<f64>> {
    let p = &w.particles;
    let l = &w.neighbor.list;
    let wd = l.width;
    for i in 0..p.nlocal() {
        for k in l.first[i] as usize..l.first[i + 1] as usize {
            let j = l.partner[k] as usize;
            let h = &l.hist[k * wd..(k + 1) * wd];
            if (p.tag[i], p.tag[j]) == (a, b) {
                return Some(h.to_vec());
            }
            if (p.tag[i], p.tag[j]) == (b, a) {
                return Some(
                    h.iter()
                        .enumerate()
                        .map(|(c, &v)| if c < l.odd { -v } else { v })
                        .collect(),
                );
            }
        }
    }
    None
}

/// Tag of the particle whose row lists the pair of tags (a, b).
fn lister(w: &World, a: u64, b: u64) -> Option<u64> {
    let p = &w.particles;
    (0..p.nlocal()).find_map(|i| {
        w.neighbor.list.partners(i).iter().find_map(|&j| {
            let t = p.tag[j as usize];
            ((p.tag[i], t) == (a, b) || (p.tag[i], t) == (b, a)).then_some(p.tag[i])
        })
    })
}

/// Per-tag state: (f, torque, v, omega, unwrapped x).
type State = Vec<(u64, [DVec3; 5])>;

fn state(w: &World) -> State {
    let p = &w.particles;
    let mut s: State = (0..p.nlocal())
        .map(|i| {
            (
                p.tag[i],
                [
                    p.f[i],
                    p.torque[i],
                    p.v[i],
                    p.omega[i],
                    w.domain.unmap(p.x[i], p.image[i].get()),
                ],
            )
        })
        .collect();
    s.sort_by_key(|e| e.0);
    s
}

/// Two spheres touching along y with overlap δ0, drifting along +x at different speeds
/// towards the periodic face x = 0.1, pressed together by ±P along y.
fn sheared_pair(neigh: NeighborSettings, sort_every: u64) -> World {
    let mut w = World::new(
        Domain::new(
            DVec3::splat(-0.1),
            DVec3::splat(0.1),
            [Boundary::Periodic, Boundary::Fixed, Boundary::Periodic],
        )
        .unwrap(),
    );
    w.materials = Materials::uniform(1, 5e6, 0.45, 0.5, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings = neigh;
    w.sort.every = sort_every;
    // Sort bins of 0.1: two per axis over the subdomain (seed 002 eq. 6).
    w.sort.binsize = 0.1;
    // Centre distance 2R - δ0, offset 4 mm along x so that the two cross the face ~800
    // steps apart.
    let d0 = 4.9e-5;
    let dx = 0.004;
    let dy = ((2.0 * R - d0).powi(2) - dx * dx).sqrt();
    // B (tag 1) is added first and lies above A (tag 2), so the sort reorders them.
    let mut b = NewParticle::at(DVec3::new(0.094, 0.05 + 0.5 * dy, 0.0), R, RHO)
        .with_v(DVec3::new(0.45, 0.0, 0.0));
    b.mask = 1 | 4;
    let mut a = NewParticle::at(DVec3::new(0.094 - dx, 0.05 - 0.5 * dy, 0.0), R, RHO)
        .with_v(DVec3::new(0.5, 0.0, 0.0))
        .with_omega(DVec3::new(0.0, 0.0, 3.0));
    a.mask = 1 | 2;
    w.add_particle(&b).unwrap();
    w.add_particle(&a).unwrap();
    // A bystander (tag 3), 5 cm below both along z, gives the spatial sort a second z bin
    // (it moves to the front), while A and B share one bin, so they stay in insertion
    // order: B lists the pair while both are local, A lists it (B's ghost lies above it)
    // while the pair straddles the face. The pair's orientation flips with each change.
    w.add_particle(&NewParticle::at(DVec3::new(0.092, 0.0, -0.05), R, RHO))
        .unwrap();
    let p = 0.1;
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    // A is also dragged along +x (0.03 N, below μP = 0.05 N): a steady shear.
    w.add_fix(
        Fix::new(
            "pa",
            2,
            FixKind::AddForce {
                force: DVec3::new(0.03, p, 0.0),
            },
        )
        .unwrap(),
    )
    .unwrap();
    w.add_fix(
        Fix::new(
            "pb",
            4,
            FixKind::AddForce {
                force: DVec3::new(0.0, -p, 0.0),
            },
        )
        .unwrap(),
    )
    .unwrap();
    w.set_timestep(1e-5).unwrap();
    w
}

#[test]
fn sheared_pair_across_periodic_face_is_bit_identical_with_sorting_and_rebuilds() {
    let mut every = sheared_pair(
        NeighborSettings {
            skin: 0.002,
            delay: 0,
            every: 1,
            check: false,
            contact_distance_factor: 1.0,
        },
        1,
    );
    let mut rare = sheared_pair(
        NeighborSettings {
            skin: 0.01,
            delay: 0,
            every: 1,
            check: true,
            contact_distance_factor: 1.0,
        },
        0,
    );
    assert_eq!(ContactModel::hertz_history().history_width(), 3);
    every.setup().unwrap();
    rare.setup().unwrap();
    assert_eq!(every.neighbor.list.width, 3);
    assert_eq!(state(&every), state(&rare));
    let steps = 3000;
    let mut ghost_pair_steps = 0;
    let mut flips = 0;
    let mut last_lister = lister(&every, 1, 2);
    let mut reordered_steps = 0;
    let mut max_spring: f64 = 0.0;
    let mut min_overlap = f64::INFINITY;
    for step in 1..=steps {
        every.advance().unwrap();
        rare.advance().unwrap();
        let (se, sr) = (state(&every), state(&rare));
        assert_eq!(se, sr, "runs diverged at step {step}");
        // Bookkeeping that shows the test exercises what it claims.
        let h = pair_hist(&every, 1, 2).expect("the pair must stay listed");
        let hr = pair_hist(&rare, 1, 2).expect("the pair must stay listed");
        assert_eq!(h, hr, "history differs at step {step}");
        max_spring = max_spring.max(DVec3::new(h[0], h[1], h[2]).length());
        let p = &every.particles;
        let n = p.nlocal();
        if (0..n).any(|i| {
            every
                .neighbor
                .list
                .partners(i)
                .iter()
                .any(|&j| j as usize >= n)
        }) {
            ghost_pair_steps += 1;
        }
        let now = lister(&every, 1, 2);
        if now != last_lister {
            flips += 1;
            last_lister = now;
        }
        if p.tag[..n] != [1, 2, 3] {
            reordered_steps += 1;
        }
        let d = (se[0].1[4] - se[1].1[4]).length(); // tags 1 and 2
        min_overlap = min_overlap.min(2.0 * R - d);
    }
    assert_eq!(every.neighbor.nbuilds, steps + 1);
    assert!(
        rare.neighbor.nbuilds < 10,
        "{} builds",
        rare.neighbor.nbuilds
    );
    assert!(min_overlap > 0.0, "the particles must stay in contact");
    assert!(
        max_spring > 1e-6,
        "the tangential spring must be loaded ({max_spring})"
    );
    assert!(
        flips >= 2,
        "the pair must change orientation ({flips} flips)"
    );
    assert!(
        ghost_pair_steps > 100,
        "the pair must spend time across the face ({ghost_pair_steps})"
    );
    assert!(
        reordered_steps > 100,
        "sorting must reorder the particles ({reordered_steps})"
    );
    // Both particles ended on the other side in the re-neighbored run.
    let p = &every.particles;
    for t in [1, 2] {
        let i = p.find_tag(t).unwrap();
        assert_eq!(p.image[i].get(), [1, 0, 0], "tag {t} at {}", p.x[i]);
    }
}

/// A pair in sliding contact; returns the world after `steps`.
fn loaded_pair(periodic: bool, with_wall: bool, steps: u64) -> World {
    let bc = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Fixed
    };
    let mut w = World::new(Domain::new(DVec3::splat(-0.1), DVec3::splat(0.1), [bc; 3]).unwrap());
    w.materials = Materials::uniform(1, 5e6, 0.45, 0.5, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings = NeighborSettings {
        skin: 0.002,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    // Across the x face when periodic, in the middle otherwise.
    let xc = if periodic { 0.1 } else { 0.0 };
    let d0 = 1e-4;
    w.add_particle(
        &NewParticle::at(DVec3::new(xc - R + 0.5 * d0, 0.0, 0.0), R, RHO)
            .with_v(DVec3::new(0.0, 0.02, 0.0)),
    )
    .unwrap();
    let x2 = if periodic {
        -0.1 + R - 0.5 * d0
    } else {
        R - 0.5 * d0
    };
    w.add_particle(
        &NewParticle::at(DVec3::new(x2, 0.0, 0.0), R, RHO).with_v(DVec3::new(0.0, -0.02, 0.0)),
    )
    .unwrap();
    if with_wall {
        let wall = PrimitiveWall::new(
            "floor",
            ContactModel::hertz_history(),
            1,
            WallShape::Plane {
                axis: 2,
                pos: -0.09,
            },
        )
        .unwrap();
        w.add_fix(Fix::new("floor", 1, FixKind::WallGran(Box::new(wall))).unwrap())
            .unwrap();
    }
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.set_timestep(1e-5).unwrap();
    w.run(steps).unwrap();
    w
}

#[test]
fn history_survives_adding_a_particle() {
    for periodic in [false, true] {
        let mut w = loaded_pair(periodic, false, 20);
        let before = pair_hist(&w, 1, 2).unwrap();
        assert!(
            before[1].abs() > 1e-8,
            "spring along y must be loaded: {before:?}"
        );
        w.add_particle(&NewParticle::at(DVec3::new(0.0, 0.05, 0.05), R, RHO))
            .unwrap();
        w.setup().unwrap();
        assert_eq!(w.particles.nlocal(), 3);
        assert_eq!(
            pair_hist(&w, 1, 2).unwrap(),
            before,
            "periodic = {periodic}"
        );
        // And once more, with two additions in a row.
        w.add_particle(&NewParticle::at(DVec3::new(0.0, -0.05, 0.05), R, RHO))
            .unwrap();
        w.add_particle(&NewParticle::at(DVec3::new(0.0, -0.05, -0.05), R, RHO))
            .unwrap();
        w.advance().unwrap();
        // The spring keeps growing from where it was (by at most |v_t| dt = 0.04 × 1e-5
        // per step); lost history would restart it from zero.
        let after = pair_hist(&w, 1, 2).unwrap();
        let grow = after[1] - before[1];
        assert!(grow > 0.0 && grow <= 0.04 * 1e-5, "{before:?} -> {after:?}");
    }
}

#[test]
fn history_survives_a_second_run_with_a_wall() {
    for periodic in [false, true] {
        let mut w = loaded_pair(periodic, true, 20);
        let before = pair_hist(&w, 1, 2).unwrap();
        assert!(before[1].abs() > 1e-8);
        w.setup().unwrap();
        assert_eq!(
            pair_hist(&w, 1, 2).unwrap(),
            before,
            "periodic = {periodic}"
        );
        w.run(5).unwrap();
        let after = pair_hist(&w, 1, 2).unwrap();
        let grow = after[1] - before[1];
        assert!(
            grow > 0.0 && grow <= 5.0 * 0.04 * 1e-5,
            "{before:?} -> {after:?}"
        );
    }
}

/// 300 polydisperse particles above a granular floor, periodic in x and y.
fn falling_bed() -> World {
    let mut w = World::new(
        Domain::new(
            DVec3::ZERO,
            DVec3::new(0.06, 0.06, 0.2),
            [Boundary::Periodic, Boundary::Fixed, Boundary::Fixed],
        )
        .unwrap(),
    );
    w.materials = Materials::uniform(1, 5e6, 0.3, 0.5, 0.5);
    w.pair = Some(PairGran::new(ContactModel::hertz_history()));
    w.neighbor.settings = NeighborSettings {
        skin: 0.001,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    w.sort.every = 50;
    let mut k = 0u64;
    'fill: for iz in 0..20 {
        for iy in 0..6 {
            for ix in 0..6 {
                if k == 300 {
                    break 'fill;
                }
                // Deterministic pseudo-random jitter and radii in [2, 3] mm.
                let h = |s: u64| ((k * 2654435761 + s * 40503) % 1000) as f64 / 1000.0;
                let x = DVec3::new(
                    0.005 + 0.01 * ix as f64 + 0.001 * h(1),
                    0.005 + 0.01 * iy as f64 + 0.001 * h(2),
                    0.01 + 0.0075 * iz as f64,
                );
                let r = 0.002 + 0.001 * h(3);
                let v = DVec3::new(h(4) - 0.5, h(5) - 0.5, -h(6));
                w.add_particle(&NewParticle::at(x, r, RHO).with_v(v))
                    .unwrap();
                k += 1;
            }
        }
    }
    let floor = PrimitiveWall::new(
        "floor",
        ContactModel::hertz_history(),
        1,
        WallShape::Plane { axis: 2, pos: 0.0 },
    )
    .unwrap();
    w.add_fix(Fix::new("floor", 1, FixKind::WallGran(Box::new(floor))).unwrap())
        .unwrap();
    for (id, pos) in [("ylo", 0.0), ("yhi", 0.06)] {
        let side = PrimitiveWall::new(
            id,
            ContactModel::hertz_history(),
            1,
            WallShape::Plane { axis: 1, pos },
        )
        .unwrap();
        w.add_fix(Fix::new(id, 1, FixKind::WallGran(Box::new(side))).unwrap())
            .unwrap();
    }
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.add_fix(Fix::gravity("g", 1, 9.81, DVec3::new(0.0, 0.0, -1.0)).unwrap())
        .unwrap();
    w.set_timestep(5e-5).unwrap();
    w
}

#[test]
fn identical_runs_are_bit_identical() {
    let mut a = falling_bed();
    let mut b = falling_bed();
    assert_eq!(a.particles.nlocal(), 300);
    a.setup().unwrap();
    b.setup().unwrap();
    let mut contacts_seen = 0;
    let mut wall_contacts = [0usize; 3];
    for step in 1..=2000 {
        a.advance().unwrap();
        b.advance().unwrap();
        if step % 100 == 0 {
            let (pa, pb) = (&a.particles, &b.particles);
            assert_eq!(pa.tag, pb.tag, "step {step}");
            assert_eq!(pa.x, pb.x, "step {step}");
            assert_eq!(pa.v, pb.v, "step {step}");
            assert_eq!(pa.omega, pb.omega, "step {step}");
            assert_eq!(pa.f, pb.f, "step {step}");
            assert_eq!(pa.torque, pb.torque, "step {step}");
            assert_eq!(pa.image, pb.image, "step {step}");
            assert_eq!(
                a.neighbor.list.partner, b.neighbor.list.partner,
                "step {step}"
            );
            assert_eq!(a.neighbor.list.hist, b.neighbor.list.hist, "step {step}");
            for (qa, qb) in pa.props.iter().zip(&pb.props) {
                assert_eq!(qa.data, qb.data, "property {} at step {step}", qa.name);
            }
            let n = pa.nlocal();
            for (qa, qb) in pa.sparse.iter().zip(&pb.sparse) {
                assert_eq!(
                    qa.dense(n),
                    qb.dense(n),
                    "history {} at step {step}",
                    qa.name
                );
            }
            contacts_seen += a.neighbor.list.hist.iter().filter(|&&h| h != 0.0).count();
            for (k, name) in ["wallhist_floor", "wallhist_ylo", "wallhist_yhi"]
                .iter()
                .enumerate()
            {
                let id = pa.sparse_property(name).expect("wall history property");
                let h = pa.sparse[id.0].dense(pa.nlocal());
                wall_contacts[k] += h.iter().filter(|&&h| h != 0.0).count();
            }
        }
    }
    assert!(
        contacts_seen > 0,
        "the bed must have loaded tangential springs"
    );
    for (name, n) in ["wallhist_floor", "wallhist_ylo", "wallhist_yhi"]
        .iter()
        .zip(wall_contacts)
    {
        assert!(n > 0, "wall {name} must have loaded springs");
    }
    assert!(a.neighbor.nbuilds > 10);
}
