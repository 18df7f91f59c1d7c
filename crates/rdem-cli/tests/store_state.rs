//! `fix store/state` (LIGGGHTS 3.8): five colliding spheres, periodic along x; one fix
//! stores `xu yu zu vx` with `com yes` once, at its definition, another (on a group of
//! three) stores `c_ke v_sp x radius` at the first run's set-up and every 300 steps; an
//! atom-style variable reads them back. The reference is LIGGGHTS 3.8's dump of
//! `tests/data/store_state/in.ss` every 200 steps (%.12g): rdem prints the same digits.

use crate::common;

use std::path::Path;

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/store_state")
}

#[test]
fn stored_values_match_liggghts() {
    let script = common::index_vars(&[("tn", "x")])
        + &std::fs::read_to_string(data().join("in.ss")).unwrap();
    let (dir, _) = common::run_kept_ok("store_state", &script, &[], None);
    let text = std::fs::read_to_string(dir.join("d_x.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let got: Vec<Vec<f64>> = common::dump_rows_with_step(&text);
    let want = common::reference_rows(&data().join("ref.txt"));
    common::assert_columns(&got, &want, 1, 1e-10, "store/state");
}

#[test]
fn store_state_errors_are_located() {
    let head =
        "atom_style granular\nregion r block 0 1 0 1 0 1\ncreate_box 1 r\nvariable e equal 1\n";
    for (line, message) in [
        ("fix s all store/state 0", "needs at least one input"),
        ("fix s all store/state 0 xx", "unknown input 'xx'"),
        (
            "fix s all store/state 0 v_e",
            "variable e is not atom-style",
        ),
        ("fix s all store/state 0 x com maybe", "'yes'"),
    ] {
        let out = common::run_script_raw(&format!("{head}{line}\n"), None);
        assert!(!out.status.success(), "{line}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{line}: {err}");
        assert!(err.contains("in.test:5"), "{line}: {err}");
    }
}
