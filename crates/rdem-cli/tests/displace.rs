//! `displace_atoms` (LIGGGHTS 3.8): `move` in box and lattice units, `ramp`, `random`
//! (LAMMPS' per-particle seeded generator) and `rotate` on a 4×4×4 lattice periodic
//! along x, some particles crossing the periodic face. The reference is LIGGGHTS 3.8's
//! (the Debian package) `write_dump` of `tests/data/displace/in.disp` (%.15g): rdem
//! gives the same positions and image flags to 1e-15, on 1 and 2 MPI ranks.
//!
//! Two LIGGGHTS 3.8 behaviours its manual does not state, measured there: the default
//! units are `box` (the manual says `lattice`), and `rotate` turns the positions in the
//! box, not the unwrapped ones.

use crate::common;

use std::path::Path;

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/displace")
}

fn positions(ranks: Option<usize>) -> Vec<Vec<f64>> {
    let script = std::fs::read_to_string(data().join("in.disp")).unwrap();
    let (dir, out) = common::run_kept_ok("displace", &script, &[], ranks);
    assert_eq!(out.matches("Displacing atoms ...").count(), 7, "{out}");
    let text = std::fs::read_to_string(dir.join("d.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    common::dump_frames(&text).remove(0).1
}

#[test]
fn displacements_match_liggghts() {
    let want = common::reference_rows(&data().join("ref.txt"));
    common::assert_columns(&positions(None), &want, 1, 1e-14, "1 rank");
}

#[cfg(feature = "mpi")]
#[test]
fn random_displacements_do_not_depend_on_the_ranks() {
    if common::have_mpirun() {
        let want = common::reference_rows(&data().join("ref.txt"));
        common::assert_columns(&positions(Some(2)), &want, 1, 1e-14, "2 ranks");
    }
}

/// A sphere moved beyond a fixed face stays until the next run loses it, as in
/// LIGGGHTS 3.8 (its run starts with 1 atom of 2).
#[test]
fn a_sphere_moved_out_is_lost_at_the_next_run() {
    let script = std::fs::read_to_string(data().join("in.outside")).unwrap();
    let (dir, out) = common::run_kept_ok("displace_out", &script, &[], None);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.contains("displace_atoms moved 1 particle(s) outside a fixed face"),
        "{out}"
    );
    let rows = common::thermo_rows(&out[out.rfind("Step").unwrap()..]);
    assert_eq!(rows, vec![vec![0.0, 1.0], vec![1.0, 1.0]], "{out}");
}

#[test]
fn displace_errors_are_located() {
    let head = "atom_style granular\nboundary p f f\nunits si\nregion reg block 0 1 0 1 0 1 units box\ncreate_box 1 reg\ncreate_atoms 1 single 0.1 0.5 0.5 units box\n";
    for (line, message) in [
        (
            "displace_atoms all move 1 0 0 units lattice",
            "no lattice is defined",
        ),
        ("displace_atoms all shift 1 0 0", "'rotate'"),
        (
            "displace_atoms all rotate 0 0 0 0 0 0 10",
            "the axis vector is zero",
        ),
        ("displace_atoms nobody move 1 0 0", "no group 'nobody'"),
        ("displace_atoms all ramp w 0 1 z 0 1", "'x'"),
    ] {
        let out = common::run_script_raw(&format!("{head}{line}\n"), None);
        assert!(!out.status.success(), "{line}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{line}: {err}");
        assert!(err.contains("in.test:7"), "{line}: {err}");
    }
}
