//! Seed 000 domain predicates and seed 002 eq. (4) periodic remapping, exactly as SPEC §4
//! states them.
//!
//! * `is_in_domain`: the closed box, so every face, edge and corner belongs to it and the
//!   next representable number outside does not.
//! * `is_in_subdomain`: half-open `lo <= x < hi`; a subdomain face that coincides with the
//!   global box face (absolute tolerance 1e-13) is padded outward by 1e-8. A 2×2×2
//!   decomposition of [0, 2]³ is emulated by setting `sublo/subhi/procgrid/myloc` by hand:
//!   every point of a lattice that includes the internal faces, edges and corners must be
//!   owned by exactly one of the eight subdomains, points within the padding too, points
//!   beyond it by none.
//! * `is_in_extended_subdomain`: per axis no constraint with one process, `x >= lo` for the
//!   last process, `x <= hi` for the first, `lo <= x < hi` for the others.
//! * `check_dist_subbox_borders` (`|x - lo| >= d` and `|x - hi| >= d` on every axis) and
//!   `dist_subbox_borders` (the smallest of the six face distances).
//! * `min_subbox_extent`: smallest extent and its axis, ties going to the higher axis.
//! * `is_periodic_ghost` (eq. 9, strict inequalities, ghosts only) and
//!   `is_owned_or_first_ghost` (eq. 10, `i == map(tag_i)`).
//! * `remap`/`unmap`: `x_unwrapped = x + n ⊙ L`; a particle several box lengths away is
//!   folded in one call, lands in `[lo, hi)` and unmaps to where it was (1e-12 relative to
//!   the box length); image counts never overflow.
//! * shrink-wrapping: `s` faces follow the particle extent with a margin of 1e-4 × the box
//!   length at creation (LAMMPS' `small`); `m` faces do the same but never move inside the
//!   initial box; the wrapped box depends only on the current particles.
//! * `check_inside_fixed` and `is_lost`: only fixed faces count, and the faces themselves are
//!   inside.
//!
//! Predicates are compared exactly (they are boolean); lengths to 1e-15 relative unless a
//! tolerance is stated at the assertion.

use rdem::domain::{Boundary, Domain, FACE_MATCH_TOL, SHRINK_MARGIN, SUBDOMAIN_PAD};
use rdem::{DVec3, Error};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The next representable number above `x` (no `f64::next_up`: MSRV 1.80).
fn up(x: f64) -> f64 {
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// The next representable number below `x`.
fn down(x: f64) -> f64 {
    -up(-x)
}

fn unit_box(b: Boundary) -> Domain {
    Domain::new(DVec3::ZERO, DVec3::ONE, [b; 3]).unwrap()
}

/// Domain [0, 2]³ decomposed 2×2×2; this process at `loc`.
fn brick(loc: [usize; 3]) -> Domain {
    let mut d = Domain::new(DVec3::ZERO, DVec3::splat(2.0), [Boundary::Fixed; 3]).unwrap();
    d.procgrid = [2, 2, 2];
    d.myloc = loc;
    for (a, &m) in loc.iter().enumerate() {
        d.sublo[a] = m as f64;
        d.subhi[a] = m as f64 + 1.0;
    }
    d
}

fn all_bricks() -> Vec<Domain> {
    let mut v = Vec::new();
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                v.push(brick([i, j, k]));
            }
        }
    }
    v
}

#[test]
fn is_in_domain_is_the_closed_box() {
    let d = unit_box(Boundary::Fixed);
    // All 27 face/edge/corner/centre combinations of {0, 0.5, 1} are inside.
    for &x in &[0.0, 0.5, 1.0] {
        for &y in &[0.0, 0.5, 1.0] {
            for &z in &[0.0, 0.5, 1.0] {
                assert!(d.is_in_domain(v(x, y, z)), "({x},{y},{z}) must be inside");
            }
        }
    }
    // One ulp outside any face is outside, also at corners.
    for a in 0..3 {
        let mut p = DVec3::splat(0.5);
        p[a] = down(0.0);
        assert!(!d.is_in_domain(p));
        p[a] = up(1.0);
        assert!(!d.is_in_domain(p));
    }
    assert!(!d.is_in_domain(v(up(1.0), 1.0, 1.0)));
    assert!(!d.is_in_domain(v(0.0, down(0.0), 0.0)));
    assert!(!d.is_in_domain(DVec3::NAN));
    // No padding on the global box.
    assert!(!d.is_in_domain(v(-0.5 * SUBDOMAIN_PAD, 0.5, 0.5)));
}

#[test]
fn constants_are_the_spec_values() {
    assert_eq!(SUBDOMAIN_PAD, 1e-8);
    assert_eq!(FACE_MATCH_TOL, 1e-13);
    assert_eq!(SHRINK_MARGIN, 1e-4);
}

#[test]
fn serial_subdomain_is_padded_on_every_face() {
    let d = unit_box(Boundary::Periodic);
    let inside = 0.99 * SUBDOMAIN_PAD;
    let outside = 1.01 * SUBDOMAIN_PAD;
    for a in 0..3 {
        let mut p = DVec3::splat(0.5);
        for (x, expect) in [
            (0.0, true),
            (1.0, true), // the hi face is padded, so the face itself is inside
            (-inside, true),
            (-outside, false),
            (1.0 + inside, true),
            (1.0 + outside, false),
        ] {
            p[a] = x;
            assert_eq!(d.is_in_subdomain(p), expect, "axis {a}, x = {x:e}");
        }
    }
    // Corners of the padded cube.
    assert!(d.is_in_subdomain(DVec3::splat(-inside)));
    assert!(d.is_in_subdomain(DVec3::splat(1.0 + inside)));
    assert!(!d.is_in_subdomain(v(1.0 + inside, 1.0 + inside, 1.0 + outside)));
    assert!(!d.is_in_subdomain(DVec3::NAN));
}

#[test]
fn brick_subdomains_are_half_open_and_padded_only_on_box_faces() {
    let inside = 0.99 * SUBDOMAIN_PAD;
    let outside = 1.01 * SUBDOMAIN_PAD;
    let b000 = brick([0, 0, 0]);
    let b111 = brick([1, 1, 1]);
    let b101 = brick([1, 0, 1]);
    // Lower brick: padded below 0, half-open (and unpadded) at the internal face 1.
    assert!(b000.is_in_subdomain(v(-inside, -inside, -inside)));
    assert!(!b000.is_in_subdomain(v(-outside, 0.5, 0.5)));
    assert!(b000.is_in_subdomain(v(down(1.0), down(1.0), down(1.0))));
    assert!(!b000.is_in_subdomain(v(1.0, 0.5, 0.5)));
    assert!(!b000.is_in_subdomain(v(0.5, 1.0, 0.5)));
    assert!(!b000.is_in_subdomain(v(0.5, 0.5, 1.0)));
    // Upper brick: the internal face 1 is its closed lower face, without padding.
    assert!(b111.is_in_subdomain(v(1.0, 1.0, 1.0)));
    assert!(!b111.is_in_subdomain(v(down(1.0), 1.5, 1.5)));
    assert!(!b111.is_in_subdomain(v(1.0 - inside, 1.5, 1.5)));
    assert!(b111.is_in_subdomain(v(2.0, 2.0, 2.0)));
    assert!(b111.is_in_subdomain(v(2.0 + inside, 2.0 + inside, 2.0 + inside)));
    assert!(!b111.is_in_subdomain(v(2.0 + outside, 1.5, 1.5)));
    // Mixed brick: x and z upper halves, y lower half.
    assert!(b101.is_in_subdomain(v(2.0 + inside, -inside, 1.0)));
    assert!(!b101.is_in_subdomain(v(2.0 + inside, 1.0, 1.0)));
    assert!(!b101.is_in_subdomain(v(2.0 + inside, -inside, 1.0 - inside)));
}

#[test]
fn brick_subdomains_partition_the_padded_box() {
    let bricks = all_bricks();
    let inside = 0.5 * SUBDOMAIN_PAD;
    let outside = 2.0 * SUBDOMAIN_PAD;
    let coords = [
        -inside,
        0.0,
        0.25,
        down(1.0),
        1.0,
        up(1.0),
        1.5,
        2.0,
        2.0 + inside,
    ];
    let mut checked = 0;
    for &x in &coords {
        for &y in &coords {
            for &z in &coords {
                let owners = bricks
                    .iter()
                    .filter(|b| b.is_in_subdomain(v(x, y, z)))
                    .count();
                assert_eq!(owners, 1, "({x}, {y}, {z}) has {owners} owners");
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 729);
    for a in 0..3 {
        for bad in [-outside, 2.0 + outside] {
            let mut p = DVec3::splat(0.5);
            p[a] = bad;
            assert!(bricks.iter().all(|b| !b.is_in_subdomain(p)));
        }
    }
}

#[test]
fn padding_needs_the_face_to_match_the_box_within_1e_13() {
    // A box face at 0 and a subdomain face 0.5e-13 above it: still "the box face".
    let mut d = unit_box(Boundary::Fixed);
    d.sublo.x = 0.5e-13;
    assert!(d.is_in_subdomain(v(0.5e-13 - 0.99 * SUBDOMAIN_PAD, 0.5, 0.5)));
    // 2e-13 away: an internal face, not padded, half-open.
    d.sublo.x = 2e-13;
    assert!(!d.is_in_subdomain(v(0.0, 0.5, 0.5)));
    assert!(!d.is_in_subdomain(v(down(2e-13), 0.5, 0.5)));
    assert!(d.is_in_subdomain(v(2e-13, 0.5, 0.5)));
    // Same on the upper face.
    let mut d = unit_box(Boundary::Fixed);
    d.subhi.y = 1.0 - 0.5e-13;
    assert!(d.is_in_subdomain(v(0.5, 1.0 + 0.99 * SUBDOMAIN_PAD, 0.5)));
    d.subhi.y = 1.0 - 2e-13;
    assert!(!d.is_in_subdomain(v(0.5, 1.0 - 2e-13, 0.5)));
    assert!(d.is_in_subdomain(v(0.5, down(1.0 - 2e-13), 0.5)));
    assert!(!d.is_in_subdomain(v(0.5, 1.0, 0.5)));
}

#[test]
fn extended_subdomain_first_middle_last_and_single() {
    // x: 3 processes over [0, 3]; y: one process; z: 2 processes over [0, 2].
    let mk = |mx: usize, mz: usize| {
        let mut d = Domain::new(DVec3::ZERO, v(3.0, 1.0, 2.0), [Boundary::Fixed; 3]).unwrap();
        d.procgrid = [3, 1, 2];
        d.myloc = [mx, 0, mz];
        d.sublo = v(mx as f64, 0.0, mz as f64);
        d.subhi = v(mx as f64 + 1.0, 1.0, mz as f64 + 1.0);
        d
    };
    let far = 1e6;
    // First along x: only x <= hi (closed), anything below.
    let d = mk(0, 0);
    assert!(d.is_in_extended_subdomain(v(1.0, 0.5, 0.5)));
    assert!(d.is_in_extended_subdomain(v(-far, 0.5, 0.5)));
    assert!(!d.is_in_extended_subdomain(v(up(1.0), 0.5, 0.5)));
    // Single process along y: no constraint at all.
    assert!(d.is_in_extended_subdomain(v(0.5, far, 0.5)));
    assert!(d.is_in_extended_subdomain(v(0.5, -far, 0.5)));
    // First along z: z <= 1.
    assert!(d.is_in_extended_subdomain(v(0.5, 0.5, 1.0)));
    assert!(!d.is_in_extended_subdomain(v(0.5, 0.5, up(1.0))));
    assert!(d.is_in_extended_subdomain(v(0.5, 0.5, -far)));
    // Middle along x: lo <= x < hi, nothing extended.
    let d = mk(1, 1);
    assert!(d.is_in_extended_subdomain(v(1.0, 0.5, 1.5)));
    assert!(!d.is_in_extended_subdomain(v(down(1.0), 0.5, 1.5)));
    assert!(!d.is_in_extended_subdomain(v(2.0, 0.5, 1.5)));
    assert!(d.is_in_extended_subdomain(v(down(2.0), 0.5, 1.5)));
    // Last along z: z >= lo (closed), anything above.
    assert!(d.is_in_extended_subdomain(v(1.5, 0.5, 1.0)));
    assert!(d.is_in_extended_subdomain(v(1.5, 0.5, far)));
    assert!(!d.is_in_extended_subdomain(v(1.5, 0.5, down(1.0))));
    // Last along x.
    let d = mk(2, 0);
    assert!(d.is_in_extended_subdomain(v(2.0, 0.5, 0.5)));
    assert!(d.is_in_extended_subdomain(v(far, 0.5, 0.5)));
    assert!(!d.is_in_extended_subdomain(v(down(2.0), 0.5, 0.5)));
    // Serial: everything, even far outside the box.
    let d = unit_box(Boundary::Fixed);
    assert!(d.is_in_extended_subdomain(v(-far, far, 3.0)));
}

#[test]
fn distances_to_subbox_borders() {
    let mut d = unit_box(Boundary::Fixed);
    d.sublo = v(0.0, 1.0, -1.0);
    d.subhi = v(2.0, 4.0, 1.0);
    let x = v(0.3, 2.0, 0.25);
    // Face distances: x 0.3/1.7, y 1/2, z 1.25/0.75 -> 0.3.
    assert!((d.dist_subbox_borders(x) - 0.3).abs() < 1e-15);
    assert!((d.dist_subbox_borders(v(1.0, 3.9, 0.0)) - 0.1).abs() < 1e-15);
    assert_eq!(d.dist_subbox_borders(v(0.0, 2.0, 0.0)), 0.0);
    // check_dist_subbox_borders: >= d on every axis, per-axis tolerances.
    assert!(d.check_dist_subbox_borders(x, v(0.3, 1.0, 0.75)));
    assert!(!d.check_dist_subbox_borders(x, v(up(0.3), 1.0, 0.75)));
    assert!(!d.check_dist_subbox_borders(x, v(0.3, up(1.0), 0.75)));
    assert!(!d.check_dist_subbox_borders(x, v(0.3, 1.0, up(0.75))));
    assert!(d.check_dist_subbox_borders(x, DVec3::ZERO));
    // The seed's formula takes absolute distances: a point far outside is "far from the
    // borders" (callers only ask about points inside).
    assert!(d.check_dist_subbox_borders(v(10.0, 10.0, 10.0), DVec3::ONE));
    // Consistency of the two functions on a grid.
    for k in 0..50 {
        let p = v(
            0.04 * k as f64,
            1.0 + 0.06 * k as f64,
            -1.0 + 0.04 * k as f64,
        );
        let dist = d.dist_subbox_borders(p);
        assert!(d.check_dist_subbox_borders(p, DVec3::splat(dist)));
        assert!(!d.check_dist_subbox_borders(p, DVec3::splat(up(dist))));
    }
}

#[test]
fn min_subbox_extent_ties_go_to_the_higher_axis() {
    let mut d = unit_box(Boundary::Fixed);
    let mut ext = |e: [f64; 3]| {
        d.sublo = DVec3::ZERO;
        d.subhi = DVec3::from_array(e);
        d.min_subbox_extent()
    };
    assert_eq!(ext([2.0, 1.0, 3.0]), (1.0, 1));
    assert_eq!(ext([0.5, 1.0, 3.0]), (0.5, 0));
    assert_eq!(ext([3.0, 2.0, 0.25]), (0.25, 2));
    assert_eq!(ext([1.0, 1.0, 2.0]), (1.0, 1));
    assert_eq!(ext([1.0, 2.0, 1.0]), (1.0, 2));
    assert_eq!(ext([2.0, 1.0, 1.0]), (1.0, 2));
    assert_eq!(ext([1.0, 1.0, 1.0]), (1.0, 2));
    assert_eq!(ext([1.0, up(1.0), up(1.0)]), (1.0, 0));
}

#[test]
fn periodic_ghost_predicate() {
    let d = Domain::new(
        DVec3::ZERO,
        DVec3::splat(10.0),
        [Boundary::Periodic, Boundary::Fixed, Boundary::Periodic],
    )
    .unwrap();
    let rc = 1.0;
    let nlocal = 5;
    // Locals are never periodic ghosts.
    assert!(!d.is_periodic_ghost(4, nlocal, v(0.5, 5.0, 5.0), rc));
    // Ghosts near a periodic face, strictly within rc.
    assert!(d.is_periodic_ghost(5, nlocal, v(0.5, 5.0, 5.0), rc));
    assert!(d.is_periodic_ghost(7, nlocal, v(5.0, 5.0, 9.5), rc));
    assert!(d.is_periodic_ghost(7, nlocal, v(-0.5, 5.0, 5.0), rc));
    assert!(d.is_periodic_ghost(7, nlocal, v(10.5, 5.0, 5.0), rc));
    assert!(d.is_periodic_ghost(5, nlocal, v(down(1.0), 5.0, 5.0), rc));
    assert!(!d.is_periodic_ghost(5, nlocal, v(1.0, 5.0, 5.0), rc));
    assert!(!d.is_periodic_ghost(5, nlocal, v(5.0, 5.0, 9.0), rc));
    assert!(d.is_periodic_ghost(5, nlocal, v(5.0, 5.0, up(9.0)), rc));
    // Near a fixed face only: not a periodic ghost.
    assert!(!d.is_periodic_ghost(5, nlocal, v(5.0, 0.5, 5.0), rc));
    assert!(!d.is_periodic_ghost(5, nlocal, v(5.0, 9.5, 5.0), rc));
    // In the middle.
    assert!(!d.is_periodic_ghost(5, nlocal, v(5.0, 5.0, 5.0), rc));
}

#[test]
fn owned_or_first_ghost_is_i_equals_map_of_tag() {
    // Index: 0 1 2 | 3 4 5 (ghosts); tags 10 11 12 | 10 12 10. The map points at the owned
    // copy for 10 and 12 and, for a tag with no owned copy here (13 at index 6, 7), at the
    // first ghost.
    let tags = [10u64, 11, 12, 10, 12, 10, 13, 13];
    let map = |t: u64| match t {
        10 => Some(0),
        11 => Some(1),
        12 => Some(2),
        13 => Some(6),
        _ => None,
    };
    let got: Vec<bool> = (0..tags.len())
        .map(|i| Domain::is_owned_or_first_ghost(i, tags[i], map))
        .collect();
    assert_eq!(
        got,
        vec![true, true, true, false, false, false, true, false]
    );
    assert!(!Domain::is_owned_or_first_ghost(0, 99, map));
}

#[test]
fn remap_folds_many_box_lengths_and_unmap_restores() {
    let d = Domain::new(
        v(-1.0, 2.0, 0.0),
        v(3.0, 2.5, 1.0),
        [Boundary::Periodic, Boundary::Periodic, Boundary::Fixed],
    )
    .unwrap();
    let l = d.prd();
    let cases: [(DVec3, [i32; 3], [i32; 3]); 6] = [
        // (position, image before, expected image after)
        (v(0.5, 2.25, 0.5), [0, 0, 0], [0, 0, 0]),
        (v(-1.0 + 3.25 * 4.0, 2.1, 0.5), [0, 0, 0], [3, 0, 0]),
        (
            v(-1.0 - 2.5 * 4.0, 2.0 + 7.2 * 0.5, 0.5),
            [1, -2, 0],
            [1 - 3, -2 + 7, 0],
        ),
        (v(3.0, 2.0, 7.0), [0, 0, 5], [1, 0, 5]), // exactly on hi -> lo; z fixed: untouched
        (v(-1.0, 1.5, -3.0), [0, 0, 0], [0, -1, 0]), // exactly on lo stays
        (v(1e5, -1e5, 0.5), [0, 0, 0], [25000, -200000 - 4, 0]),
    ];
    for (x0, img0, img_expect) in cases {
        let mut x = x0;
        let mut img = img0;
        let before = d.unmap(x0, img0);
        d.remap(&mut x, &mut img);
        assert_eq!(img, img_expect, "image flags for {x0}");
        for a in 0..2 {
            assert!(
                d.boxlo[a] <= x[a] && x[a] < d.boxhi[a],
                "{x} not folded into the box"
            );
        }
        assert_eq!(x.z, x0.z, "a fixed axis is never remapped");
        let after = d.unmap(x, img);
        for a in 0..3 {
            let tol = 1e-12 * l[a] * (1.0 + (x0[a] / l[a]).abs());
            assert!(
                (after[a] - before[a]).abs() <= tol,
                "unmap {after} != {before}"
            );
        }
        // Seed 002 eq. (4) literally: x + n ⊙ L.
        let lit = x + DVec3::new(img[0] as f64, img[1] as f64, img[2] as f64) * l;
        assert_eq!(lit, after);
    }
}

#[test]
fn remap_handles_round_off_at_the_upper_face() {
    let d = unit_box(Boundary::Periodic);
    // -1e-17 + 1 rounds to exactly 1 = hi: must end at lo with the net image unchanged.
    let mut x = v(-1e-17, 0.5, 0.5);
    let mut img = [0; 3];
    d.remap(&mut x, &mut img);
    assert!(x.x >= 0.0 && x.x < 1.0);
    assert!((d.unmap(x, img).x - -1e-17).abs() < 1e-15);
    // A remapped position is a fixed point.
    let (x1, i1) = (x, img);
    d.remap(&mut x, &mut img);
    assert_eq!((x, img), (x1, i1));
}

#[test]
fn remap_never_panics_on_absurd_positions() {
    // A blown-up simulation can put a particle 1e300 box lengths away; the image count
    // must saturate instead of overflowing (which panics in debug builds).
    let d = unit_box(Boundary::Periodic);
    let mut img = [i32::MAX - 1, i32::MIN + 1, 0];
    let mut x = v(1e300, -1e300, 0.5);
    d.remap(&mut x, &mut img);
    assert_eq!(img, [i32::MAX, i32::MIN, 0]);
    assert!(x.x >= 0.0 && x.x < 1.0 && x.y >= 0.0 && x.y < 1.0);
    let mut x = v(f64::INFINITY, f64::NAN, 0.5);
    let mut img = [5, 5, 5];
    d.remap(&mut x, &mut img);
    assert!(!x.x.is_finite() && x.y.is_nan());
    assert_eq!(img[1], 5, "NaN must leave the image alone");
}

#[test]
fn shrink_wrap_s_follows_particles_m_keeps_initial_box() {
    // Initial box [0, 2] × [0, 1] × [0, 4]: margins 2e-4, 1e-4, 4e-4 for ever after
    // (LAMMPS' `small` is fixed when the box is created).
    let mut d = Domain::with_faces(
        DVec3::ZERO,
        v(2.0, 1.0, 4.0),
        [
            [Boundary::Shrink, Boundary::Shrink],
            [Boundary::ShrinkMin, Boundary::ShrinkMin],
            [Boundary::Fixed, Boundary::Shrink],
        ],
    )
    .unwrap();
    let small = v(2.0, 1.0, 4.0) * SHRINK_MARGIN;
    let tol = 1e-15;
    // Particles inside the initial box: s shrinks onto them, m stays at the initial box,
    // a fixed face never moves.
    d.shrink_wrap(v(0.2, 0.3, 0.1), v(0.6, 0.7, 0.4));
    assert!((d.boxlo.x - (0.2 - small.x)).abs() < tol);
    assert!((d.boxhi.x - (0.6 + small.x)).abs() < tol);
    assert_eq!((d.boxlo.y, d.boxhi.y), (0.0, 1.0));
    assert_eq!(d.boxlo.z, 0.0);
    assert!((d.boxhi.z - (0.4 + small.z)).abs() < tol);
    assert_eq!(
        (d.sublo, d.subhi),
        (d.boxlo, d.boxhi),
        "serially the subdomain is the box"
    );
    // Particles beyond the initial box: both kinds grow, same margins.
    d.shrink_wrap(v(-1.0, -2.0, 0.1), v(3.0, 4.0, 0.4));
    assert!((d.boxlo.x - (-1.0 - small.x)).abs() < tol);
    assert!((d.boxhi.x - (3.0 + small.x)).abs() < tol);
    assert!((d.boxlo.y - (-2.0 - small.y)).abs() < tol);
    assert!((d.boxhi.y - (4.0 + small.y)).abs() < tol);
    // The wrapped box depends only on the particles, not on the wrapping history.
    d.shrink_wrap(v(0.4, 0.4, 0.1), v(0.5, 0.5, 0.4));
    let once = d.clone();
    for _ in 0..3 {
        d.shrink_wrap(v(0.4, 0.4, 0.1), v(0.5, 0.5, 0.4));
    }
    assert_eq!(d, once);
    assert!((d.boxlo.x - (0.4 - small.x)).abs() < tol);
    assert!((d.boxhi.x - (0.5 + small.x)).abs() < tol);
    // m returns to (not inside) the initial box.
    assert_eq!((d.boxlo.y, d.boxhi.y), (0.0, 1.0));
    // No particles (empty extent): nothing moves.
    let before = d.clone();
    d.shrink_wrap(DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    assert_eq!(d, before);
    // With a decomposition the subdomains follow the wrapped box (an equal share each).
    let mut d = Domain::new(DVec3::ZERO, DVec3::ONE, [Boundary::Shrink; 3]).unwrap();
    d.set_grid([2, 1, 1], 1);
    assert_eq!((d.sublo, d.subhi), (v(0.5, 0.0, 0.0), DVec3::ONE));
    d.shrink_wrap(DVec3::splat(0.1), DVec3::splat(0.9));
    let m = 1e-4;
    assert!((d.sublo - v(0.5, 0.1 - m, 0.1 - m)).abs().max_element() < 1e-15);
    assert!((d.subhi - DVec3::splat(0.9 + m)).abs().max_element() < 1e-15);
    assert!(d.has_shrink());
    assert!(!unit_box(Boundary::Fixed).has_shrink());
}

#[test]
fn inside_fixed_and_lost_only_look_at_fixed_faces() {
    let d = Domain::with_faces(
        DVec3::ZERO,
        DVec3::ONE,
        [
            [Boundary::Fixed, Boundary::Fixed],
            [Boundary::Periodic, Boundary::Periodic],
            [Boundary::Fixed, Boundary::Shrink],
        ],
    )
    .unwrap();
    // Faces, edges and corners of the fixed faces are inside.
    for p in [
        v(0.0, 0.5, 0.0),
        v(1.0, 0.5, 0.0),
        v(1.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
    ] {
        assert!(d.check_inside_fixed(p).is_ok(), "{p}");
        assert!(!d.is_lost(p), "{p}");
    }
    // Periodic axis: anything (remapped later); shrink face: anything beyond it.
    assert!(d.check_inside_fixed(v(0.5, -7.0, 0.5)).is_ok());
    assert!(d.check_inside_fixed(v(0.5, 0.5, 5.0)).is_ok());
    assert!(!d.is_lost(v(0.5, 12.0, 5.0)));
    // Just beyond a fixed face.
    match d.check_inside_fixed(v(up(1.0), 0.5, 0.5)) {
        Err(Error::OutsideBox {
            axis, lo, hi, x, ..
        }) => {
            assert_eq!((axis, lo, hi, x), ('x', 0.0, 1.0, up(1.0)));
        }
        other => panic!("expected OutsideBox, got {other:?}"),
    }
    match d.check_inside_fixed(v(0.5, 0.5, down(0.0))) {
        Err(Error::OutsideBox { axis, .. }) => assert_eq!(axis, 'z'),
        other => panic!("expected OutsideBox, got {other:?}"),
    }
    assert!(d.is_lost(v(up(1.0), 0.5, 0.5)));
    assert!(d.is_lost(v(down(0.0), 0.5, 0.5)));
    assert!(d.is_lost(v(0.5, 0.5, down(0.0))));
    assert!(!d.is_lost(v(0.5, 0.5, 2.0)));
}

#[test]
fn periodic_check_is_twice_the_contact_distance() {
    let d = Domain::new(
        DVec3::ZERO,
        v(1.0, 0.3, 5.0),
        [Boundary::Periodic, Boundary::Fixed, Boundary::Periodic],
    )
    .unwrap();
    assert!(d.check_periodic_contact(0.5).is_ok());
    match d.check_periodic_contact(up(0.5)) {
        Err(Error::PeriodicBoxTooSmall { axis, len, contact }) => {
            assert_eq!((axis, len, contact), ('x', 1.0, up(0.5)));
        }
        other => panic!("expected PeriodicBoxTooSmall, got {other:?}"),
    }
    // Short for a cutoff above half a length: the half of the shortest such length.
    assert_eq!(d.short_periodic_half(0.5), None);
    assert_eq!(d.short_periodic_half(up(0.5)), Some(0.5));
    assert_eq!(d.short_periodic_half(2.6), Some(0.5));
    let z_only = Domain::new(
        DVec3::ZERO,
        v(1.0, 0.3, 5.0),
        [Boundary::Fixed, Boundary::Fixed, Boundary::Periodic],
    )
    .unwrap();
    assert_eq!(z_only.short_periodic_half(2.0), None);
    assert_eq!(z_only.short_periodic_half(2.6), Some(2.5));
}
