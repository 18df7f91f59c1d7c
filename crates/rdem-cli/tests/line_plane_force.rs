//! `fix lineforce` and `fix planeforce` (LIGGGHTS 3.8): two pairs of spheres fall under
//! a slanted gravity onto a wall and onto each other, one pair's forces kept along a
//! line, the other's in a plane (the wall, defined after them, pushes unprojected). The
//! reference is LIGGGHTS 3.8's dump of `tests/data/line_plane_force/in.lf` every 4000
//! of 20000 steps (%.12g): rdem prints the same digits.

use crate::common;

use std::path::Path;

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/line_plane_force")
}

fn rows(script: &str) -> Vec<Vec<f64>> {
    let (dir, _) = common::run_kept_ok("line_plane_force", script, &[], None);
    let text = std::fs::read_to_string(dir.join("d_x.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    common::dump_rows_with_step(&text)
}

#[test]
fn projected_forces_match_liggghts() {
    let script = common::index_vars(&[("tn", "x")])
        + &std::fs::read_to_string(data().join("in.lf")).unwrap();
    let want = common::reference_rows(&data().join("ref.txt"));
    common::assert_columns(&rows(&script), &want, 1, 1e-10, "line and plane");
    // Without the projections the spheres end elsewhere.
    let free: String = script
        .lines()
        .filter(|l| !l.starts_with("fix lf") && !l.starts_with("fix pf"))
        .map(|l| format!("{l}\n"))
        .collect();
    let got = rows(&free);
    assert!((got.last().unwrap()[2] - want.last().unwrap()[2]).abs() > 1e-3);
}

#[test]
fn a_zero_direction_is_an_error() {
    let out = common::run_script_raw(
        "atom_style granular\nregion r block 0 1 0 1 0 1\ncreate_box 1 r\nfix l all lineforce 0 0 0\n",
        None,
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the direction is zero"), "{err}");
    assert!(err.contains("in.test:4"), "{err}");
}
