//! `fix nve/noforce` (LIGGGHTS 3.8): two spheres moved at their set velocity under
//! gravity (forces ignored, velocities and spin kept) push a free sphere integrated by
//! `nve/sphere`. The reference is LIGGGHTS 3.8's dump of `tests/data/nve_noforce/in.nf`
//! every 2000 of 10000 steps (%.12g): rdem prints the same digits.

use crate::common;

use std::path::Path;

#[test]
fn moved_spheres_ignore_forces_as_liggghts() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/nve_noforce");
    let script =
        common::index_vars(&[("tn", "x")]) + &std::fs::read_to_string(data.join("in.nf")).unwrap();
    let (dir, _) = common::run_kept_ok("nve_noforce", &script, &[], None);
    let text = std::fs::read_to_string(dir.join("d_x.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let got: Vec<Vec<f64>> = common::dump_rows_with_step(&text);
    let want = common::reference_rows(&data.join("ref.txt"));
    common::assert_columns(&got, &want, 1, 1e-10, "nve/noforce");
    // The movers kept their velocity under gravity and contact.
    let last = &got[got.len() - 3];
    assert_eq!((last[5], last[7]), (0.5, 0.1), "{last:?}");
}

#[test]
fn nve_noforce_takes_no_argument() {
    let out = common::run_script_raw(
        "atom_style granular\nregion r block 0 1 0 1 0 1\ncreate_box 1 r\nfix n all nve/noforce 1\n",
        None,
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("in.test:4"), "{err}");
}
