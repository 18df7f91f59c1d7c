//! `region mesh/tet` in the engine: a unit cube split into five and into six
//! tetrahedra. The volume is the sum of the tetrahedra's, exactly 1; a point is inside
//! when it is strictly inside one tetrahedron, so points on the cube's faces and on the
//! faces shared inside are out (LIGGGHTS 3.8 counts 15 and 6 of the 5³ lattice points
//! of step 1/4, measured in `rdem-cli/tests/data/mesh_tet`); samples drawn by volume are
//! uniform in the cube; the whole-ball test keeps the ball's distance to the surface.

use rdem::region::{Region, Shape, TetMesh};
use rdem::DVec3;

/// Corner k of the unit cube: x = bit 0, y = bit 1, z = bit 2.
fn corners() -> Vec<DVec3> {
    (0..8)
        .map(|k| DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64))
        .collect()
}

/// Four corner tetrahedra and the central one (corners 1, 2, 4, 7).
fn five() -> TetMesh {
    TetMesh::new(
        corners(),
        vec![
            [0, 1, 2, 4],
            [3, 2, 1, 7],
            [5, 4, 7, 1],
            [6, 7, 4, 2],
            [1, 2, 4, 7],
        ],
    )
    .unwrap()
}

/// The six tetrahedra around the diagonal 0–7, one per order of the axes.
fn six() -> TetMesh {
    let mut cells = Vec::new();
    for p in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let mut c = 0usize;
        let mut cell = [0; 4];
        for (k, axis) in p.iter().enumerate() {
            c |= 1 << axis;
            cell[k + 1] = c;
        }
        cells.push(cell);
    }
    TetMesh::new(corners(), cells).unwrap()
}

fn lattice_count(m: &TetMesh, step: f64, n: i32) -> usize {
    let mut count = 0;
    for k in -1..=n + 1 {
        for j in -1..=n + 1 {
            for i in -1..=n + 1 {
                if m.contains(DVec3::new(i as f64, j as f64, k as f64) * step) {
                    count += 1;
                }
            }
        }
    }
    count
}

#[test]
fn cube_volume_is_exact_and_faces_are_outside() {
    for (m, lattice) in [(five(), 15), (six(), 6)] {
        assert_eq!(m.volume(), 1.0);
        assert_eq!(m.bounding_box(), (DVec3::ZERO, DVec3::ONE));
        // The cube's surface: 2 triangles per face.
        assert_eq!(m.surface().len(), 12);
        assert_eq!(lattice_count(&m, 0.25, 4), lattice);
        // Inside, off every inner face; outside; on a face of the cube.
        assert!(m.contains(DVec3::new(0.1, 0.2, 0.13)));
        assert!(m.contains(DVec3::new(0.9, 0.85, 0.8)));
        assert!(!m.contains(DVec3::new(1.01, 0.5, 0.52)));
        assert!(!m.contains(DVec3::new(-1e-12, 0.5, 0.52)));
        assert!(!m.contains(DVec3::new(0.0, 0.3, 0.61)));
    }
    // The central tetrahedron's faces x + y + z = 1 are inner faces of `five`: out.
    assert!(!five().contains(DVec3::new(0.5, 0.25, 0.25)));
    assert!(five().contains(DVec3::new(0.5, 0.25, 0.26)));
    assert!(five().contains(DVec3::new(0.5, 0.25, 0.24)));
    // The six share the diagonal planes x = y etc.
    assert!(!six().contains(DVec3::new(0.5, 0.5, 0.3)));
    assert!(six().contains(DVec3::new(0.5, 0.51, 0.3)));
}

/// A region of the five-tetrahedra cube, as `region ... mesh/tet` makes it.
fn region() -> Region {
    Region::new(Shape::TetMesh(std::sync::Arc::new(five()))).unwrap()
}

fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// 80 000 samples over the 27 cells of a 3×3×3 split of the cube: each cell holds 1/27
/// of them within 4 standard deviations (the five tetrahedra have volumes 1/6 and 1/3,
/// and the cells cut across them, so a wrong choice of tetrahedron or a non-uniform
/// point inside one shows), and χ² over the 27 cells stays under the 99.9 % quantile
/// of 26 degrees of freedom (54.1).
#[test]
fn samples_are_uniform_in_the_volume() {
    let r = region();
    let mut u = rng(7);
    let n = 80_000;
    let mut cells = [0usize; 27];
    let clip = (DVec3::splat(-5.0), DVec3::splat(5.0));
    for _ in 0..n {
        let x = r.sample(clip, &mut u, 10).expect("a point");
        assert!(r.contains(x), "{x}");
        let c = (x * 3.0).floor();
        cells[(c.x + 3.0 * c.y + 9.0 * c.z) as usize] += 1;
    }
    let expect = n as f64 / 27.0;
    let sigma = (expect * (1.0 - 1.0 / 27.0)).sqrt();
    let mut chi2 = 0.0;
    for (k, &c) in cells.iter().enumerate() {
        assert!((c as f64 - expect).abs() < 4.0 * sigma, "cell {k}: {c}");
        chi2 += (c as f64 - expect).powi(2) / expect;
    }
    assert!(chi2 < 54.1, "chi2 = {chi2}");
    // Clipped to the lower half: every sample there.
    let half = (DVec3::splat(-5.0), DVec3::new(5.0, 5.0, 0.5));
    for _ in 0..1000 {
        assert!(r.sample(half, &mut u, 100).unwrap().z <= 0.5);
    }
    // The volume is the mesh's when the clip holds it, Monte Carlo otherwise.
    assert_eq!(r.volume(clip, 0, &mut u), 1.0);
    let v = r.volume(half, 100_000, &mut u);
    assert!((v - 0.5).abs() < 0.01, "{v}");
}

/// The whole-ball test (insertion `all_in yes`): a ball fits when its centre is inside
/// and it stays clear of the six faces; the inner faces do not count.
#[test]
fn whole_balls() {
    let r = region();
    assert!(r.contains_sphere(DVec3::splat(0.5), 0.49));
    assert!(!r.contains_sphere(DVec3::splat(0.5), 0.51));
    assert!(r.contains_sphere(DVec3::new(0.2, 0.5, 0.5), 0.19));
    assert!(!r.contains_sphere(DVec3::new(0.2, 0.5, 0.5), 0.21));
    // Near an edge: distance √(0.1² + 0.1²) ≈ 0.141 to the edge, 0.1 to the faces.
    assert!(!r.contains_sphere(DVec3::new(0.1, 0.1, 0.5), 0.11));
    assert!(r.contains_sphere(DVec3::new(0.1, 0.1, 0.5), 0.099));
    // side out: the whole ball out of the mesh's box.
    let out = region().side_out();
    assert!(out.contains_sphere(DVec3::new(1.5, 0.5, 0.5), 0.49));
    assert!(!out.contains_sphere(DVec3::new(1.5, 0.5, 0.5), 0.51));
    assert!(out.contains(DVec3::new(1.0, 0.5, 0.5)));
}

/// Moved by a pose (a dynamic region), inside and sampling follow.
#[test]
fn posed_mesh_moves() {
    let pose = rdem::region::Pose::new(DVec3::new(2.0, 0.0, 0.0), DVec3::ZERO, DVec3::Z, 0.0);
    let r = region().posed(pose);
    assert!(r.contains(DVec3::new(2.5, 0.5, 0.52)) && !r.contains(DVec3::new(0.5, 0.5, 0.52)));
    let mut u = rng(3);
    let clip = (DVec3::splat(-5.0), DVec3::splat(5.0));
    for _ in 0..100 {
        let x = r.sample(clip, &mut u, 10).unwrap();
        assert!(x.x > 2.0 && x.x < 3.0, "{x}");
    }
}
