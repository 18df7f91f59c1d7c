//! `region prism` (stock LIGGGHTS 3.8): a parallelepiped, against LIGGGHTS 3.8 (the
//! Debian package, run here on `tests/data/region_prism/`).

use crate::common;

use std::path::Path;

fn read(name: &str) -> String {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/region_prism");
    std::fs::read_to_string(d.join(name)).unwrap()
}

/// The points of a simple cubic lattice (spacing 0.5, many on the prisms' faces) that
/// prisms tilted along one and along three pairs of axes hold, side in and out, and in
/// lattice units: LIGGGHTS 3.8 counts 8883, 4414, 42242 and 20.
#[test]
fn prisms_hold_the_lattice_points_liggghts_counts() {
    let out = common::run_script(&read("in.counts"), None);
    assert!(out.contains("COUNTS 8883 4414 42242 20\n"), "{out}");
}

/// The spheres and their clearance to the faces of the prism
/// 0 0.1 0 0.1 0 0.1 0.03 -0.02 0.04 (distance to each face plane minus the radius).
fn inserted(fill: &str) -> (usize, f64) {
    let script = format!("variable fill index \"{fill}\"\n{}", read("in.insert"));
    let (dir, _) = common::run_kept_ok("region_prism", &script, &[], None);
    let text = std::fs::read_to_string(dir.join("pos.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let frames = common::dump_frames(&text);
    let rows = &frames.last().unwrap().1;
    let (h, xy, xz, yz) = (0.1f64, 0.03, -0.02, 0.04);
    let inv = [
        [1.0 / h, -xy / (h * h), (xy * yz - h * xz) / (h * h * h)],
        [0.0, 1.0 / h, -yz / (h * h)],
        [0.0, 0.0, 1.0 / h],
    ];
    let mut clearance = f64::INFINITY;
    for r in rows {
        for row in inv {
            let u: f64 = (0..3).map(|k| row[k] * r[1 + k]).sum();
            let g = row.iter().map(|v| v * v).sum::<f64>().sqrt();
            clearance = clearance.min((u / g).min((1.0 - u) / g) - r[4]);
        }
    }
    (rows.len(), clearance)
}

/// `insert/pack ... all_in yes` in a tilted prism: every sphere lies wholly inside
/// after the step (LIGGGHTS 3.8 also inserts all 300); `volumefraction_region 0.2`
/// inserts 0.2 × 1e-3 m³ / (4/3 π (4 mm)³) = 746 spheres from the prism's exact volume
/// (LIGGGHTS 3.8 estimates it by Monte Carlo and inserts 744).
#[test]
fn insertion_fills_a_prism_with_whole_spheres() {
    let (n, c) = inserted("particles_in_region 300");
    assert_eq!(n, 300);
    assert!(c > 0.0, "a sphere pokes out by {}", -c);
    let (n, c) = inserted("volumefraction_region 0.2");
    assert_eq!(n, 746);
    assert!(c > 0.0, "a sphere pokes out by {}", -c);
}

/// A tilted prism cannot make the simulation box (a triclinic box), and a tilt may not
/// pair with a dimension that is infinite at both ends, as in LAMMPS.
#[test]
fn prisms_rdem_refuses() {
    let head = "atom_style granular\nunits si\n";
    let out = common::run_script_raw(
        &format!("{head}region b prism 0 1 0 1 0 1 0.2 0 0 units box\ncreate_box 1 b\n"),
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("makes a triclinic box"), "{err}");
    let out = common::run_script_raw(
        &format!("{head}region b prism 0 1 -INF INF 0 1 0.2 0 0 units box\n"),
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the tilt xy is not 0"), "{err}");
    // Untilted, it is a block.
    let out = common::run_script(
        &format!("{head}region b prism 0 1 0 2 0 3 0 0 0 units box\ncreate_box 1 b\n"),
        None,
    );
    assert!(
        out.contains("Created orthogonal box = (0 0 0) to (1 2 3)"),
        "{out}"
    );
}
