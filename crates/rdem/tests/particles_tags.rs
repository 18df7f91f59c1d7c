//! The atom container of seed 002: tags, consistency checks, memory figure and named
//! per-particle properties.
//!
//! * Tag extension (eqs. 1–2): untagged particles get `max+1, max+2, ...` in storage order,
//!   where `max` is the largest tag present *now* — also after deletions (a deleted maximum
//!   is reused, deleted tags below the maximum are not), and after explicitly tagged
//!   particles. Through `World::setup` the same happens.
//! * Contiguity (eq. 3): tags are consecutive iff min = 1 and max = N; a duplicate is
//!   reported by its tag.
//! * Per-type radius consistency (eq. 10): one radius per type, else an error naming the
//!   type and both radii.
//! * Memory (eq. 13): the per-process figure grows with the particle count (at least the
//!   bytes of one record per particle) and with every property added (at least `8 × width`
//!   bytes per particle).
//! * Named properties: new particles get the default, values follow removals and
//!   permutations, ghosts carry copies, and the array length stays `width × len`.
//!
//! Everything here is exact (integers, copies); masses are checked to 1e-15 relative.

use rdem::particles::{Particles, PropId};
use rdem::{Boundary, DVec3, Domain, Error, LostPolicy, NewParticle, World};

fn p_at(x: f64) -> NewParticle {
    NewParticle::at(DVec3::new(x, 0.5, 0.5), 0.01, 1000.0)
}

fn filled(n: usize) -> Particles {
    let mut p = Particles::new();
    for k in 0..n {
        p.add_local(&p_at(k as f64 * 0.01)).unwrap();
    }
    p
}

fn tags(p: &Particles) -> Vec<u64> {
    p.tag[..p.nlocal()].to_vec()
}

#[test]
fn new_tags_start_at_one_in_storage_order() {
    let mut p = filled(5);
    assert_eq!(p.untagged(), 5);
    assert_eq!(p.tag_extent(), (0, 0));
    p.extend_tags();
    assert_eq!(tags(&p), vec![1, 2, 3, 4, 5]);
    assert_eq!(p.untagged(), 0);
    // Extending again changes nothing.
    p.extend_tags();
    assert_eq!(tags(&p), vec![1, 2, 3, 4, 5]);
    // Three more untagged particles: 6, 7, 8.
    for k in 0..3 {
        p.add_local(&p_at(0.1 + 0.01 * k as f64)).unwrap();
    }
    p.extend_tags();
    assert_eq!(tags(&p), vec![1, 2, 3, 4, 5, 6, 7, 8]);
    assert!(p.check_tags_consecutive().is_ok());
}

#[test]
fn tags_extend_from_the_current_maximum_after_deletions() {
    let mut p = filled(8);
    p.extend_tags();
    // Delete tags 3 and 8 (the maximum).
    let remove: Vec<bool> = tags(&p).iter().map(|&t| t == 3 || t == 8).collect();
    assert_eq!(p.remove_locals(&remove), 2);
    assert_eq!(tags(&p), vec![1, 2, 4, 5, 6, 7]);
    assert_eq!(p.tag_extent(), (1, 7));
    for k in 0..2 {
        p.add_local(&p_at(0.5 + 0.01 * k as f64)).unwrap();
    }
    p.extend_tags();
    // max was 7: new tags 8 and 9; tag 3 is not reused.
    assert_eq!(tags(&p), vec![1, 2, 4, 5, 6, 7, 8, 9]);
    assert!(matches!(
        p.check_tags_consecutive(),
        Err(Error::TagsNotConsecutive {
            min: 1,
            max: 9,
            count: 8
        })
    ));
}

#[test]
fn explicit_tags_set_the_maximum() {
    let mut p = Particles::new();
    p.add_local(&p_at(0.0)).unwrap();
    p.add_local(&p_at(0.1).with_tag(100)).unwrap();
    p.add_local(&p_at(0.2)).unwrap();
    p.add_local(&p_at(0.3).with_tag(7)).unwrap();
    p.extend_tags();
    assert_eq!(tags(&p), vec![101, 100, 102, 7]);
    // assign_tags_from (the parallel form) starts where it is told.
    p.add_local(&p_at(0.4)).unwrap();
    p.add_local(&p_at(0.5)).unwrap();
    p.assign_tags_from(1000);
    assert_eq!(tags(&p), vec![101, 100, 102, 7, 1000, 1001]);
}

#[test]
fn world_tags_particles_at_setup_and_after_losses() {
    let mut w = World::new(
        Domain::new(
            DVec3::ZERO,
            DVec3::ONE,
            [Boundary::Fixed, Boundary::Periodic, Boundary::Periodic],
        )
        .unwrap(),
    );
    w.lost_policy = LostPolicy::Ignore;
    w.neighbor.settings.skin = 0.01;
    for k in 0..6 {
        w.add_particle(&p_at(0.1 + 0.1 * k as f64)).unwrap();
    }
    w.setup().unwrap();
    let mut t = tags(&w.particles);
    t.sort_unstable();
    assert_eq!(t, vec![1, 2, 3, 4, 5, 6]);
    assert!(w.particles.check_tags_consecutive().is_ok());
    assert_eq!(w.natoms(), 6);
    // Push tag 6 out through the fixed x face; it is dropped at the next re-neighboring.
    let i6 = w.particles.find_tag(6).unwrap();
    w.particles.x[i6].x = 1.5;
    w.setup().unwrap();
    assert_eq!(w.lost, 1);
    assert_eq!(w.particles.nlocal(), 5);
    w.add_particle(&p_at(0.05)).unwrap();
    w.add_particle(&p_at(0.95)).unwrap();
    w.setup().unwrap();
    let mut t = tags(&w.particles);
    t.sort_unstable();
    assert_eq!(t, vec![1, 2, 3, 4, 5, 6, 7], "max was 5 after the loss");
}

#[test]
fn contiguity_is_min_one_and_max_n() {
    let mut p = filled(4);
    assert!(
        p.check_tags_consecutive().is_err(),
        "untagged (0) is not consecutive"
    );
    for (t, ok) in [
        (vec![1, 2, 3, 4], true),
        (vec![4, 2, 3, 1], true),
        (vec![2, 3, 4, 5], false),
        (vec![0, 1, 2, 3], false),
        (vec![1, 2, 3, 5], false),
    ] {
        p.tag = t.clone();
        assert_eq!(p.check_tags_consecutive().is_ok(), ok, "{t:?}");
    }
    p.tag = vec![2, 3, 4, 5];
    assert_eq!(
        p.check_tags_consecutive(),
        Err(Error::TagsNotConsecutive {
            min: 2,
            max: 5,
            count: 4
        })
    );
    // min = 1 and max = N but a duplicate (hence a gap).
    p.tag = vec![1, 2, 2, 4];
    assert_eq!(p.check_tags_consecutive(), Err(Error::DuplicateTag(2)));
    p.tag = vec![4, 1, 4, 3];
    assert_eq!(p.check_tags_consecutive(), Err(Error::DuplicateTag(4)));
    // Empty is fine.
    assert!(Particles::new().check_tags_consecutive().is_ok());
    // Ghosts do not count.
    p.tag = vec![1, 2, 3, 4];
    p.push_ghost(0, DVec3::X);
    assert_eq!(p.len(), 5);
    assert!(p.check_tags_consecutive().is_ok());
}

#[test]
fn radius_per_type() {
    let mut p = Particles::new();
    for (ty, r) in [(1, 0.01), (2, 0.02), (1, 0.01), (3, 0.005), (2, 0.02)] {
        p.add_local(&NewParticle::at(DVec3::ZERO, r, 1000.0).with_type(ty))
            .unwrap();
    }
    assert!(p.check_radius_per_type().is_ok());
    p.add_local(&NewParticle::at(DVec3::ZERO, 0.021, 1000.0).with_type(2))
        .unwrap();
    assert_eq!(
        p.check_radius_per_type(),
        Err(Error::InconsistentRadius {
            ty: 2,
            r1: 0.02,
            r2: 0.021
        })
    );
    // Changing the radius (fix adapt) of the odd one restores consistency; mass follows.
    let i = p.nlocal() - 1;
    p.set_radius(i, 0.02).unwrap();
    assert!(p.check_radius_per_type().is_ok());
    let m = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.02f64.powi(3);
    assert!((p.rmass[i] - m).abs() <= 1e-15 * m);
    // Huge type numbers are fine (no table indexed by type).
    let mut q = Particles::new();
    for r in [0.01, 0.01, 0.02] {
        q.add_local(&NewParticle::at(DVec3::ZERO, r, 1000.0).with_type(u32::MAX))
            .unwrap();
    }
    assert_eq!(
        q.check_radius_per_type(),
        Err(Error::InconsistentRadius {
            ty: u32::MAX,
            r1: 0.01,
            r2: 0.02
        })
    );
    // A ghost with another radius is not checked (it copies its owner anyway).
    p.push_ghost(0, DVec3::X);
    let g = p.len() - 1;
    p.radius[g] = 0.5;
    assert!(p.check_radius_per_type().is_ok());
}

/// Bytes of one owned particle's record in the fixed arrays: tag, type, mask, 5 vectors,
/// radius/mass/density, image (only ghosts have an origin entry).
const RECORD: usize = 8 + 4 + 4 + 5 * 24 + 3 * 8 + 12;

#[test]
fn memory_grows_with_particles_and_properties() {
    let small = filled(10);
    let big = filled(2000);
    assert!(small.memory_bytes() >= 10 * RECORD);
    assert!(big.memory_bytes() >= 2000 * RECORD);
    assert!(big.memory_bytes() > small.memory_bytes());
    // Not absurdly over-allocated: Vec growth at most doubles.
    assert!(big.memory_bytes() <= 2 * 2048 * RECORD + 4096);

    let mut p = filled(1000);
    let m0 = p.memory_bytes();
    p.add_property("a", 3, &[0.0; 3]).unwrap();
    let m1 = p.memory_bytes();
    assert!(m1 >= m0 + 1000 * 3 * 8, "{m0} -> {m1}");
    p.add_property("b", 1, &[0.0]).unwrap();
    let m2 = p.memory_bytes();
    assert!(m2 >= m1 + 1000 * 8, "{m1} -> {m2}");

    // World adds the neighbor list on top.
    let mut w = World::new(Domain::new(DVec3::ZERO, DVec3::ONE, [Boundary::Periodic; 3]).unwrap());
    w.neighbor.settings.skin = 0.01;
    for k in 0..100 {
        let x = DVec3::new(
            (k % 5) as f64 * 0.2 + 0.05,
            ((k / 5) % 5) as f64 * 0.2 + 0.05,
            (k / 25) as f64 * 0.2 + 0.05,
        );
        w.add_particle(&NewParticle::at(x, 0.1, 1000.0)).unwrap();
    }
    w.setup().unwrap();
    let pairs = w.neighbor.list.len();
    assert!(pairs > 0);
    assert!(w.memory_bytes() >= w.particles.memory_bytes() + 4 * pairs);
}

fn prop(p: &Particles, id: PropId) -> Vec<Vec<f64>> {
    (0..p.len())
        .map(|i| p.props[id.0].get(i).to_vec())
        .collect()
}

#[test]
fn named_properties_grow_shrink_and_follow_permutations() {
    let mut p = Particles::new();
    // Added before any particle.
    let a = p.add_property("a", 2, &[1.5, -2.0]).unwrap();
    for k in 0..4 {
        p.add_local(&p_at(k as f64)).unwrap();
    }
    // Added after.
    let b = p.add_property("b", 1, &[7.0]).unwrap();
    assert_eq!(prop(&p, a), vec![vec![1.5, -2.0]; 4]);
    assert_eq!(prop(&p, b), vec![vec![7.0]; 4]);
    // Same name, same width: same handle; other width or bad defaults: refused.
    assert_eq!(p.add_property("a", 2, &[0.0, 0.0]).unwrap(), a);
    assert!(p.add_property("a", 3, &[0.0; 3]).is_err());
    assert!(p.add_property("c", 0, &[]).is_err());
    assert!(p.add_property("c", 2, &[0.0]).is_err());
    assert_eq!(p.property("b"), Some(b));
    assert_eq!(p.property("nope"), None);
    p.extend_tags();
    // Give every particle values derived from its tag.
    for i in 0..4 {
        let t = p.tag[i] as f64;
        p.props[a.0].get_mut(i).copy_from_slice(&[t, 10.0 * t]);
        p.props[b.0].get_mut(i)[0] = 100.0 * t;
    }
    // Permutation: new i holds old perm[i].
    p.permute(&[3, 1, 0, 2]);
    assert_eq!(tags(&p), vec![4, 2, 1, 3]);
    for i in 0..4 {
        let t = p.tag[i] as f64;
        assert_eq!(p.props[a.0].get(i), &[t, 10.0 * t]);
        assert_eq!(p.props[b.0].get(i), &[100.0 * t]);
        assert_eq!(p.x[i].x, t - 1.0, "positions follow too");
    }
    // A long cycle and a fixed point together.
    p.permute(&[1, 2, 3, 0]);
    assert_eq!(tags(&p), vec![2, 1, 3, 4]);
    for i in 0..4 {
        assert_eq!(p.props[a.0].get(i)[0], p.tag[i] as f64);
    }
    // Ghosts carry copies and are dropped with clear_ghosts.
    let g = p.push_ghost(2, DVec3::X);
    assert_eq!(p.props[a.0].get(g), p.props[a.0].get(2));
    assert_eq!(p.props[a.0].data.len(), 2 * p.len());
    p.clear_ghosts();
    assert_eq!(p.props[a.0].data.len(), 2 * 4);
    // Removal takes the values with the particle.
    let remove: Vec<bool> = tags(&p).iter().map(|&t| t == 1 || t == 4).collect();
    p.remove_locals(&remove);
    assert_eq!(tags(&p), vec![2, 3]);
    assert_eq!(p.props[a.0].data, vec![2.0, 20.0, 3.0, 30.0]);
    assert_eq!(p.props[b.0].data, vec![200.0, 300.0]);
    // A new particle gets the defaults.
    p.add_local(&p_at(9.0)).unwrap();
    assert_eq!(p.props[a.0].get(2), &[1.5, -2.0]);
    assert_eq!(p.props[b.0].get(2), &[7.0]);
}

#[test]
fn every_per_particle_array_follows_a_permutation() {
    let mut p = Particles::new();
    let h = p.add_property("h", 3, &[0.0; 3]).unwrap();
    for k in 0..7 {
        let f = k as f64;
        let np = NewParticle::at(
            DVec3::new(f, 2.0 * f, 3.0 * f),
            0.01 * (1.0 + f),
            1000.0 + f,
        )
        .with_v(DVec3::splat(-f))
        .with_omega(DVec3::new(f, 0.0, -f))
        .with_type(1 + k % 3);
        let i = p.add_local(&np).unwrap();
        p.mask[i] |= 1 << (k + 1);
        p.f[i] = DVec3::splat(f * 0.5);
        p.torque[i] = DVec3::splat(f * 0.25);
        p.image[i] = [k as i32, -(k as i32), 2 * k as i32].into();
        p.props[h.0].get_mut(i).copy_from_slice(&[f, f * f, -f]);
    }
    p.extend_tags();
    let perm = [6, 0, 5, 1, 4, 2, 3];
    p.permute(&perm);
    for (i, &k) in perm.iter().enumerate() {
        let f = k as f64;
        assert_eq!(p.tag[i], k as u64 + 1);
        assert_eq!(p.ty[i], 1 + k as u32 % 3);
        assert_eq!(p.mask[i], 1 | (1 << (k + 1)));
        assert_eq!(p.x[i], DVec3::new(f, 2.0 * f, 3.0 * f));
        assert_eq!(p.v[i], DVec3::splat(-f));
        assert_eq!(p.omega[i], DVec3::new(f, 0.0, -f));
        assert_eq!(p.f[i], DVec3::splat(f * 0.5));
        assert_eq!(p.torque[i], DVec3::splat(f * 0.25));
        assert_eq!(p.radius[i], 0.01 * (1.0 + f));
        assert_eq!(p.density[i], 1000.0 + f);
        let m = (1000.0 + f) * 4.0 / 3.0 * std::f64::consts::PI * (0.01 * (1.0 + f)).powi(3);
        assert!((p.rmass[i] - m).abs() <= 1e-15 * m);
        assert_eq!(p.image[i].get(), [k as i32, -(k as i32), 2 * k as i32]);
        assert_eq!(p.props[h.0].get(i), &[f, f * f, -f]);
        assert_eq!(p.origin(i), i, "a local particle is its own origin");
    }
}
