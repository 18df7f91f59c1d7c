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

/// A clump's spheres are not moved (their positions are their body's): LIGGGHTS 3.8
/// moves them and its `fix multisphere` puts them back at the next step (measured on
/// LIGGGHTS-PFM's `cornerghost` example); rdem says so in a warning. A free sphere of the
/// same group moves.
#[test]
fn clumps_stay_with_a_warning() {
    let script = "\
units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block 0 0.1 0 0.1 0 0.1 units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix pts all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 nspheres 2 ntry 100000 spheres 0 0 0 0.002 0.0032 0 0 0.0016 type 1
fix pdd all particledistribution/discrete 15485867 1 pts 1.0
region ins block 0.04 0.06 0.04 0.06 0.04 0.06 units box
fix ins all insert/pack seed 32452843 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 1 region ins
fix ms all multisphere allow_group_and_set yes
run 1
create_atoms 1 single 0.01 0.01 0.01 units box
set atom 3 diameter 0.004 density 2500
variable x1 equal x[1]
variable x3 equal x[3]
print \"BEFORE ${x1} ${x3}\"
displace_atoms all move 0.01 0 0 units box
run 1
print \"AFTER ${x1} ${x3}\"
";
    let (dir, out) = common::run_kept_ok("displace_clump", script, &[], None);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        out.contains("2 sphere(s) of clumps (fix multisphere) not moved"),
        "{out}"
    );
    let nums = |key: &str| -> Vec<f64> {
        let l = out.lines().find(|l| l.starts_with(key)).unwrap();
        l.split_whitespace()
            .skip(1)
            .map(|w| w.parse().unwrap())
            .collect()
    };
    let (before, after) = (nums("BEFORE"), nums("AFTER"));
    assert!((after[0] - before[0]).abs() < 1e-6, "{out}");
    assert!((after[1] - before[1] - 0.01).abs() < 1e-6, "{out}");
}
