//! The binned half neighbor list against brute force, and the rebuild decision of
//! `neigh_modify delay / every / check` (SPEC §2 "neighbors").
//!
//! List contract: after a build, the list holds every pair of particles whose
//! minimum-image distance is below r_i + r_j + skin, each physical pair exactly once
//! (periodic images included, no particle paired with itself or its own image), and
//! nothing else. Property tests draw polydisperse configurations (radii spread 3×–10×,
//! 2–300 particles, random box corners and lengths down to twice the cutoff, each axis
//! periodic or fixed at random, particles on periodic axes up to two box lengths outside
//! so set-up has to remap them) and compare the list as a set of tag pairs with an O(N²)
//! brute force; each listed partner must sit at the minimum-image distance (1e-12 of the
//! box length). Pairs whose distance is within 1e-9 relative of the cutoff are excluded
//! from the set comparison (the brute force and the list compute the image difference with
//! different round-off).
//!
//! Skin contract: with `check yes` no pair in actual contact (distance < r_i + r_j) is ever
//! missing from the list, step after step, while particles move and wrap.
//!
//! Rebuild decision (LAMMPS semantics): rebuild at step s iff `s - last >= delay`,
//! `(s - last) % every == 0`, and — with `check yes` — some particle moved more than
//! skin/2 (strictly) since the last build; with `check no` on every allowed step.
//! "Dangerous" builds are counted as LAMMPS does, when the first allowed check
//! (`ago == max(every, delay)`) already finds a particle beyond skin/2.

use std::collections::{BTreeMap, BTreeSet};

use proptest::prelude::*;
use rdem::neighbor::Neighbor;
use rdem::particles::Particles;
use rdem::{
    Boundary, DVec3, Domain, Fix, FixKind, LostPolicy, NeighborSettings, NewParticle, World,
};

#[derive(Debug, Clone)]
struct Config {
    lo: [f64; 3],
    len_factor: [f64; 3],
    periodic: [bool; 3],
    rmin: f64,
    spread: f64,
    skin_frac: f64,
    /// Position in box units (periodic: any; fixed: clamped to [0, 1]) and radius in
    /// [0, 1] between rmin and rmax.
    parts: Vec<([f64; 3], f64)>,
    sort: bool,
}

fn config(max_n: usize) -> impl Strategy<Value = Config> {
    (
        prop::array::uniform3(-20.0f64..20.0),
        prop::array::uniform3(2.0f64..5.0),
        prop::array::uniform3(any::<bool>()),
        -3.0f64..-1.0,
        3.0f64..10.0,
        0.0f64..1.5,
        prop::collection::vec(
            (prop::array::uniform3(-2.0f64..3.0), 0.0f64..1.0),
            2..=max_n,
        ),
        any::<bool>(),
    )
        .prop_map(
            |(lo, len_factor, periodic, lg, spread, skin_frac, parts, sort)| Config {
                lo,
                len_factor,
                periodic,
                rmin: 10f64.powf(lg),
                spread,
                skin_frac,
                parts,
                sort,
            },
        )
}

impl Config {
    fn rmax(&self) -> f64 {
        self.rmin * self.spread
    }
    fn skin(&self) -> f64 {
        self.skin_frac * self.rmin
    }
    fn cutoff(&self) -> f64 {
        2.0 * self.rmax() + self.skin()
    }
    fn world(&self) -> World {
        let cut = self.cutoff();
        let lo = DVec3::from_array(self.lo) * cut;
        let len = DVec3::from_array(self.len_factor) * cut;
        let bc = self.periodic.map(|p| {
            if p {
                Boundary::Periodic
            } else {
                Boundary::Fixed
            }
        });
        let mut w = World::new(Domain::new(lo, lo + len, bc).unwrap());
        w.neighbor.settings = NeighborSettings {
            skin: self.skin(),
            delay: 0,
            every: 1,
            check: true,
            contact_distance_factor: 1.0,
        };
        w.sort.every = if self.sort { 1 } else { 0 };
        w.lost_policy = LostPolicy::Ignore;
        for (k, (f, t)) in self.parts.iter().enumerate() {
            let mut x = lo;
            for a in 0..3 {
                let u = if self.periodic[a] {
                    f[a]
                } else {
                    f[a].clamp(0.0, 1.0)
                };
                x[a] += u * len[a];
            }
            // The first two particles have the extreme radii, so the spread is real.
            let r = match k {
                0 => self.rmin,
                1 => self.rmax(),
                _ => self.rmin + t * (self.rmax() - self.rmin),
            };
            w.add_particle(&NewParticle::at(x, r, 1000.0)).unwrap();
        }
        w
    }
}

/// Minimum-image separation vector from i to j (owned particles).
fn min_image(w: &World, i: usize, j: usize) -> DVec3 {
    let l = w.domain.prd();
    let mut d = w.particles.x[j] - w.particles.x[i];
    for a in 0..3 {
        if w.domain.periodic(a) {
            d[a] -= l[a] * (d[a] / l[a]).round();
        }
    }
    d
}

/// A set of tag pairs (smaller tag first).
type PairSet = BTreeSet<(u64, u64)>;

/// Brute force: (pairs within r_i + r_j + extra, pairs too close to the threshold to judge).
fn brute_force(w: &World, extra: f64) -> (PairSet, PairSet) {
    let p = &w.particles;
    let n = p.nlocal();
    let mut inside = BTreeSet::new();
    let mut ambiguous = BTreeSet::new();
    for i in 0..n {
        for j in i + 1..n {
            let rc = p.radius[i] + p.radius[j] + extra;
            let d = min_image(w, i, j).length();
            let key = (p.tag[i].min(p.tag[j]), p.tag[i].max(p.tag[j]));
            if (d - rc).abs() <= 1e-9 * rc {
                ambiguous.insert(key);
            } else if d < rc {
                inside.insert(key);
            }
        }
    }
    (inside, ambiguous)
}

/// The list as tag pairs, checking on the way that each entry is a distinct physical pair
/// at its minimum-image distance (`at_build`: every entry; between builds, where a
/// non-touching pair may drift past half a box length, the entries in contact).
fn listed(w: &World, at_build: bool) -> Result<BTreeSet<(u64, u64)>, TestCaseError> {
    let p = &w.particles;
    let n = p.nlocal();
    let list = &w.neighbor.list;
    let l = w.domain.prd();
    let lmax = l.max_element();
    prop_assert_eq!(list.first.len(), n + 1);
    let index: BTreeMap<u64, usize> = (0..n).map(|i| (p.tag[i], i)).collect();
    let mut set = BTreeSet::new();
    for i in 0..n {
        for &j in list.partners(i) {
            let j = j as usize;
            prop_assert!(j < p.len());
            prop_assert!(j != i);
            prop_assert!(
                p.tag[j] != p.tag[i],
                "particle {} paired with its own image",
                p.tag[i]
            );
            let key = (p.tag[i].min(p.tag[j]), p.tag[i].max(p.tag[j]));
            prop_assert!(set.insert(key), "pair {:?} listed twice", key);
            // The partner is its owner shifted by whole box lengths ...
            let o = index[&p.tag[j]];
            let shift = p.x[j] - p.x[o];
            for a in 0..3 {
                let k = shift[a] / l[a];
                prop_assert!(
                    (k - k.round()).abs() < 1e-9,
                    "ghost shift {} is not a lattice vector",
                    shift
                );
                if !w.domain.periodic(a) {
                    prop_assert_eq!(shift[a], 0.0);
                }
            }
            // ... and the listed separation is the minimum image.
            let d_list = (p.x[j] - p.x[i]).length();
            let d_min = min_image(w, i, o).length();
            if at_build || d_min < p.radius[i] + p.radius[j] {
                prop_assert!(
                    (d_list - d_min).abs() <= 1e-12 * lmax,
                    "listed {} vs minimum image {}",
                    d_list,
                    d_min
                );
            }
        }
    }
    Ok(set)
}

fn compare(w: &World, extra: f64, exact: bool) -> Result<(), TestCaseError> {
    let got = listed(w, exact)?;
    let (want, ambiguous) = brute_force(w, extra);
    let got_clear: BTreeSet<_> = got.difference(&ambiguous).copied().collect();
    let missing: Vec<_> = want.difference(&got_clear).collect();
    prop_assert!(
        missing.is_empty(),
        "pairs missing from the list: {:?}",
        missing
    );
    if exact {
        let extra_pairs: Vec<_> = got_clear.difference(&want).collect();
        prop_assert!(
            extra_pairs.is_empty(),
            "pairs listed but beyond the cutoff: {:?}",
            extra_pairs
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// After set-up the half list equals the brute-force list.
    #[test]
    fn half_list_equals_brute_force(cfg in config(300)) {
        let mut w = cfg.world();
        w.setup().unwrap();
        let n = w.particles.nlocal();
        prop_assert_eq!(n, cfg.parts.len(), "no particle may be lost at set-up");
        // Set-up folded every particle into the box along periodic axes.
        for i in 0..n {
            for a in 0..3 {
                if w.domain.periodic(a) {
                    prop_assert!(w.domain.boxlo[a] <= w.particles.x[i][a] && w.particles.x[i][a] < w.domain.boxhi[a]);
                }
            }
        }
        prop_assert!((w.neighbor.cutoff - cfg.cutoff()).abs() <= 1e-15 * cfg.cutoff());
        compare(&w, cfg.skin(), true)?;
    }

    /// Moving particles (ballistic, wrapping through periodic faces, some lost through fixed
    /// ones): with `check yes` every pair in contact is listed at every step, and with
    /// `check no` (a rebuild every step) the list equals the brute force at the end.
    #[test]
    fn contacts_are_never_missed_while_moving(
        cfg in config(120),
        vel in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 120),
        steps in 5u64..25,
        check in any::<bool>(),
    ) {
        let mut w = cfg.world();
        w.neighbor.settings.check = check;
        let dt = 1e-3;
        let l = w.domain.prd();
        for (i, v) in vel.iter().enumerate().take(w.particles.nlocal()) {
            // Up to half a box length over the run.
            w.particles.v[i] = DVec3::from_array(*v) * l * (0.5 / (steps as f64 * dt));
        }
        w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap()).unwrap();
        w.set_timestep(dt).unwrap();
        w.setup().unwrap();
        for _ in 0..steps {
            w.advance().unwrap();
            compare(&w, 0.0, false)?;
        }
        if !check {
            prop_assert_eq!(w.neighbor.nbuilds, 1 + steps);
            compare(&w, cfg.skin(), true)?;
        }
    }
}

#[test]
fn list_on_a_lattice_across_periodic_faces() {
    // 4×4×4 touching spheres on a cubic lattice of spacing 1 in a periodic box of length 4:
    // every particle has exactly 6 face neighbours at distance 1 < 2r + skin = 1.05, and
    // the 12 at √2 are beyond it. 64 · 6 / 2 = 192 pairs, half of them across faces for the
    // outer layers.
    let mut w =
        World::new(Domain::new(DVec3::ZERO, DVec3::splat(4.0), [Boundary::Periodic; 3]).unwrap());
    w.neighbor.settings = NeighborSettings {
        skin: 0.05,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    for k in 0..64 {
        let x = DVec3::new((k % 4) as f64, ((k / 4) % 4) as f64, (k / 16) as f64);
        w.add_particle(&NewParticle::at(x, 0.5, 1000.0)).unwrap();
    }
    w.setup().unwrap();
    assert_eq!(w.neighbor.list.len(), 192);
    let mut per = vec![0usize; 65];
    let p = &w.particles;
    for i in 0..p.nlocal() {
        for &j in w.neighbor.list.partners(i) {
            per[p.tag[i] as usize] += 1;
            per[p.tag[j as usize] as usize] += 1;
            let d = (p.x[j as usize] - p.x[i]).length();
            assert!((d - 1.0).abs() < 1e-12, "listed pair at distance {d}");
        }
    }
    assert!(per[1..].iter().all(|&c| c == 6), "{per:?}");
    // Ghosts exist for the faces (cutoff 1.05: layers at 0 and 3 are imaged).
    assert!(w.particles.nghost() > 0);
}

// ---------------------------------------------------------------------------------------
// Rebuild decision.

fn settings(delay: u64, every: u64, check: bool) -> NeighborSettings {
    NeighborSettings {
        skin: 0.5,
        delay,
        every,
        check,
        contact_distance_factor: 1.0,
    }
}

/// A neighbor manager built at `step` over 5 particles at integer positions.
fn built(s: NeighborSettings, step: u64) -> (Neighbor, Vec<DVec3>) {
    let mut p = Particles::new();
    for k in 0..5 {
        // y = 0 so that a move along y is represented exactly.
        p.add_local(&NewParticle::at(
            DVec3::new(k as f64 * 2.0, 0.0, -3.0),
            0.1,
            1.0,
        ))
        .unwrap();
    }
    p.extend_tags();
    let mut nb = Neighbor::new(s);
    nb.build(&p, step);
    (nb, p.x.clone())
}

fn moved(x: &[DVec3], by: f64) -> Vec<DVec3> {
    let mut y = x.to_vec();
    y[3].y += by; // one particle of five is enough
    y
}

/// Steps in `from..=to` at which `decide` says "rebuild" for positions `x`.
fn decisions(nb: &mut Neighbor, x: &[DVec3], from: u64, to: u64) -> Vec<u64> {
    (from..=to).filter(|&s| nb.decide(s, x, |b| b)).collect()
}

#[test]
fn check_yes_triggers_strictly_beyond_half_the_skin() {
    let (mut nb, x) = built(settings(0, 1, true), 0);
    assert!(!nb.decide(1, &x, |b| b), "nothing moved");
    assert!(
        !nb.decide(1, &moved(&x, 0.25), |b| b),
        "exactly skin/2 is not enough"
    );
    assert!(!nb.decide(1, &moved(&x, -0.25), |b| b));
    let just = f64::from_bits(0.25f64.to_bits() + 1);
    assert!(nb.decide(1, &moved(&x, just), |b| b));
    assert!(nb.decide(1, &moved(&x, -just), |b| b));
    // Diagonal move of length 0.3 > 0.25 although each component is 0.3/√3 < 0.25.
    let mut y = x.clone();
    y[0] += DVec3::splat(0.3 / 3f64.sqrt());
    assert!(nb.decide(1, &y, |b| b));
    // A different particle count (particles added or lost) forces a rebuild.
    assert!(nb.decide(1, &x[..4], |b| b));
    assert_eq!(nb.xhold(), x);
}

#[test]
fn delay_every_and_check_combine_as_in_lammps() {
    // (delay, every) -> steps (1..=13) that rebuild when a particle is far away.
    for (delay, every, want) in [
        (0, 1, (1..=13).collect::<Vec<u64>>()),
        (5, 1, (5..=13).collect()),
        (0, 3, vec![3, 6, 9, 12]),
        (6, 3, vec![6, 9, 12]),
        (4, 2, vec![4, 6, 8, 10, 12]),
        (10, 1, vec![10, 11, 12, 13]),
        // Settings LIGGGHTS refuses (see bad_input.rs) still decide without panicking:
        // every 0 behaves as every 1, a delay that is no multiple of every waits for both.
        (0, 0, (1..=13).collect()),
        (4, 3, vec![6, 9, 12]),
    ] {
        for check in [true, false] {
            let (mut nb, x) = built(settings(delay, every, check), 0);
            let far = moved(&x, 1.0);
            assert_eq!(
                decisions(&mut nb, &far, 1, 13),
                want,
                "delay {delay} every {every} check {check}"
            );
            // Without motion: never with check, the same steps without check.
            let still = decisions(&mut nb, &x, 1, 13);
            if check {
                assert!(still.is_empty(), "delay {delay} every {every}: {still:?}");
            } else {
                assert_eq!(still, want, "check no rebuilds on every allowed step");
            }
        }
    }
}

#[test]
fn decision_counts_from_the_last_build() {
    let (mut nb, x) = built(settings(5, 2, true), 10);
    let far = moved(&x, 1.0);
    assert_eq!(decisions(&mut nb, &far, 11, 20), vec![16, 18, 20]);
    // Building again at 16 restarts the count.
    let mut p = Particles::new();
    for y in &far {
        p.add_local(&NewParticle::at(*y, 0.1, 1.0)).unwrap();
    }
    p.extend_tags();
    nb.build(&p, 16);
    assert_eq!(nb.xhold(), far);
    assert_eq!(decisions(&mut nb, &far, 17, 30), Vec::<u64>::new());
    let farther = moved(&far, 1.0);
    assert_eq!(
        decisions(&mut nb, &farther, 17, 30),
        vec![22, 24, 26, 28, 30]
    );
}

#[test]
fn dangerous_builds_are_counted_as_lammps_does() {
    // LAMMPS counts a build as dangerous when the distance check triggers at the first
    // step it is allowed, ago == max(every, delay) (the LIGGGHTS reference reports
    // "Dangerous builds = 20" for 20 builds of a particle moving 0.55 skin per step with
    // `delay 0 every 1 check yes`). Decisions are made without building in between, so
    // only the first one can count.
    for (delay, every) in [(0, 1), (3, 1), (0, 4), (6, 2), (10, 5)] {
        let (mut nb, x) = built(settings(delay, every, true), 0);
        let far = moved(&x, 1.0);
        let steps = decisions(&mut nb, &far, 1, 12);
        assert_eq!(steps[0], every.max(delay));
        assert_eq!(nb.ndangerous, 1, "delay {delay} every {every}");
        // Not moving: no dangerous builds.
        let (mut nb, x) = built(settings(delay, every, true), 0);
        decisions(&mut nb, &x, 1, 12);
        assert_eq!(nb.ndangerous, 0);
    }
}

/// The LIGGGHTS reference case of `tests/data/neighbor_builds/`: one particle of diameter
/// 0.01 flying at `vx` through a periodic unit box (a second one at rest far away),
/// `neighbor 0.01 bin`, timestep 1e-3, 20 steps. Returns (builds during the run,
/// dangerous builds), the two numbers LIGGGHTS prints after a run.
fn ballistic_builds(delay: u64, every: u64, check: bool, vx: f64) -> (u64, u64) {
    let mut w = World::new(Domain::new(DVec3::ZERO, DVec3::ONE, [Boundary::Periodic; 3]).unwrap());
    w.neighbor.settings = NeighborSettings {
        skin: 0.01,
        delay,
        every,
        check,
        contact_distance_factor: 1.0,
    };
    assert!(w.neighbor.settings.validate().is_ok());
    let moving = NewParticle::at(DVec3::splat(0.5), 0.005, 2500.0).with_v(DVec3::new(vx, 0.0, 0.0));
    w.add_particle(&moving).unwrap();
    w.add_particle(&NewParticle::at(DVec3::splat(0.2), 0.005, 2500.0))
        .unwrap();
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.set_timestep(1e-3).unwrap();
    w.setup().unwrap();
    assert_eq!((w.neighbor.nbuilds, w.neighbor.ndangerous), (1, 0));
    for _ in 0..20 {
        w.advance().unwrap();
    }
    (w.neighbor.nbuilds - 1, w.neighbor.ndangerous)
}

#[test]
fn world_rebuilds_as_the_liggghts_reference() {
    // (delay, every, check, vx) -> LIGGGHTS 3.8 "Neighbor list builds" and "Dangerous
    // builds" (tests/data/neighbor_builds/README.md).
    for (delay, every, check, vx, builds, dangerous) in [
        // 1.1e-3 per step: 4 steps = 4.4e-3 < skin/2 < 5.5e-3 = 5 steps.
        (0, 1, true, 1.1, 4, 0),
        (2, 1, true, 1.1, 4, 0),
        (0, 3, true, 1.1, 3, 0),
        (7, 1, true, 1.1, 2, 2),
        // More than skin/2 every step: every build is dangerous.
        (0, 1, true, 5.5, 20, 20),
        (6, 2, true, 5.5, 3, 3),
        (0, 4, true, 1.6, 5, 5),
        // check no: every allowed step, counted from the last build.
        (0, 1, false, 1.1, 20, 0),
        (0, 4, false, 1.1, 5, 0),
        (4, 2, false, 1.1, 5, 0),
    ] {
        assert_eq!(
            ballistic_builds(delay, every, check, vx),
            (builds, dangerous),
            "delay {delay} every {every} check {check} vx {vx}"
        );
    }
}

/// Between rebuilds the serial communicator keeps every ghost an exact image of its owner:
/// position shifted by whole box lengths, same velocity, angular velocity, radius and mass
/// (a radius changed in place, as `fix adapt` does, must reach the ghosts too, or a
/// contact across a periodic face would use the old radius on one side).
#[test]
fn ghosts_mirror_their_owners_between_rebuilds() {
    let mut w = World::new(Domain::new(DVec3::ZERO, DVec3::ONE, [Boundary::Periodic; 3]).unwrap());
    w.neighbor.settings = NeighborSettings {
        skin: 0.05,
        delay: 0,
        every: 1,
        check: true,
        contact_distance_factor: 1.0,
    };
    for k in 0..27 {
        let x = DVec3::new((k % 3) as f64, ((k / 3) % 3) as f64, (k / 9) as f64) * 0.33
            + DVec3::splat(0.01);
        let v = DVec3::new(0.1 * (k % 5) as f64 - 0.2, 0.05, -0.1);
        w.add_particle(
            &NewParticle::at(x, 0.02, 1000.0)
                .with_v(v)
                .with_omega(DVec3::splat(k as f64)),
        )
        .unwrap();
    }
    w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
        .unwrap();
    w.set_timestep(1e-3).unwrap();
    w.setup().unwrap();
    let builds = w.neighbor.nbuilds;
    for step in 0..20 {
        if step == 5 {
            w.particles.set_radius(0, 0.021).unwrap();
        }
        w.advance().unwrap();
        let p = &w.particles;
        assert!(p.nghost() > 0);
        let l = w.domain.prd();
        for g in p.nlocal()..p.len() {
            let o = p.find_tag(p.tag[g]).unwrap();
            let s = (p.x[g] - p.x[o]) / l;
            assert!(
                (s - s.round()).abs().max_element() < 1e-12 && s.round() != DVec3::ZERO,
                "step {step}"
            );
            assert_eq!((p.v[g], p.omega[g]), (p.v[o], p.omega[o]), "step {step}");
            assert_eq!(
                (p.radius[g], p.rmass[g]),
                (p.radius[o], p.rmass[o]),
                "step {step}, tag {}",
                p.tag[g]
            );
        }
    }
    assert!(
        w.neighbor.nbuilds < builds + 5,
        "the test needs steps without a rebuild"
    );
}
