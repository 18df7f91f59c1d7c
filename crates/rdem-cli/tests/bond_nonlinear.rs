//! `cohesion bond/nonlinear` (LIGGGHTS-INL) against LIGGGHTS-INL itself.
//!
//! The fork (idaholab/LIGGGHTS-INL d69df36) was built here (`make mpi_no_vtk`) and ran
//! `tests/data/bond_nonlinear/in.pair`, written for these tests: three free spheres in
//! an L, bonded at step 1, stretched, pressed, bent and twisted by their start
//! velocities, undamped, damped (`-var damp 0.1`) and breaking by stress with a lower
//! tensile strength (`-var brk on`). Its thermo rows are the `inl_pair*.txt` files. rdem
//! agrees with every row to 1.2e-9 of each column's scale at worst (measured: the
//! velocity of sphere 2 and the force on it, which the rounding of 20000 steps of a
//! stiff oscillation moves most; 1e-14 on the positions); the tests allow 1e-7. Each of
//! the eight unloading and retracting stiffnesses changes these rows by 16 % to 114 % of
//! a column's scale when set equal to (or well below) its loading stiffness (measured),
//! so every branch of the laws is taken.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bond_nonlinear")
}

/// `in.pair` with index variables set first (as `-var NAME VALUE` would).
fn script(vars: &[(&str, &str)]) -> String {
    common::index_vars(vars) + &std::fs::read_to_string(data().join("in.pair")).unwrap()
}

const CASES: [(&str, &str, &str, &str); 4] = [
    ("inl_pair.txt", "0.0", "off", "0.8"),
    ("inl_pair_damp.txt", "0.1", "off", "0.8"),
    ("inl_pair_break.txt", "0.0", "on", "0.8"),
    ("inl_pair_tension.txt", "0.0", "on", "0.5"),
];

/// rdem's thermo rows of `in.pair` with damping `damp`, `stressBreak brk` and the
/// tension-to-compression strength ratio `rtc`.
fn rows(damp: &str, brk: &str, rtc: &str) -> Vec<Vec<f64>> {
    common::thermo_rows(&common::run_script(
        &script(&[("damp", damp), ("brk", brk), ("rtc", rtc)]),
        None,
    ))
}

/// Undamped, damped and breaking, the bonded spheres follow the fork.
#[test]
fn bonded_spheres_follow_the_fork() {
    for (file, damp, brk, rtc) in CASES {
        let want = common::reference_rows(&data().join(file));
        common::assert_columns(&rows(damp, brk, rtc), &want, 1, 1e-7, file);
    }
}

/// With `stressBreak on` a bond breaks, and the rows part from the unbroken run's,
/// between steps 2000 and 2250 (by its compressive or bending stress: the same step with
/// the tensile strength lowered to 0.8 or not at all); with the tensile strength halved
/// by `ratioTensionCompressionBond`, in tension, between steps 500 and 750, as in the
/// fork.
#[test]
fn bonds_break_by_stress_where_the_fork_breaks_them() {
    let whole = rows("0.0", "off", "0.8");
    let parted = |r: &[Vec<f64>]| whole.iter().zip(r).find(|(a, b)| a != b).map(|(a, _)| a[0]);
    assert_eq!(parted(&rows("0.0", "on", "0.8")), Some(2250.0));
    assert_eq!(parted(&rows("0.0", "on", "1.0")), Some(2250.0));
    assert_eq!(parted(&rows("0.0", "on", "0.5")), Some(750.0));
}

/// A column of touching bonded spheres, bent in two runs, follows the fork (measured:
/// 1e-14 of each column's scale). Three things of the fork's are needed for it, each
/// measured by leaving it out: while a bond holds it takes the place of the normal
/// contact force (else 0.038 of a column's scale); a pair apart forgets its tangential
/// spring (else 7e-4); and the set-up of the second run moves the bonds' extremes (else
/// 2.7e-8).
#[test]
fn touching_bonded_spheres_follow_the_fork() {
    let text = std::fs::read_to_string(data().join("in.chain")).unwrap();
    let got = common::thermo_rows(&common::run_script(&text, None));
    let want = common::reference_rows(&data().join("inl_chain.txt"));
    // Column 7 is the spin of sphere 3 about the column's axis: rounding (1e-15 rad/s)
    // in both programs.
    let keep = |rows: &[Vec<f64>]| -> Vec<Vec<f64>> {
        rows.iter()
            .map(|r| {
                r.iter()
                    .enumerate()
                    .filter(|(k, _)| *k != 7)
                    .map(|(_, v)| *v)
                    .collect()
            })
            .collect()
    };
    common::assert_columns(&keep(&got), &keep(&want), 1, 1e-10, "in.chain");
}

/// A square floor of two triangles whose common edge passes under the sphere of
/// `in.wall`.
const FLOOR: &str = "solid floor
facet normal 0 0 1
outer loop
vertex -0.004 -0.004 0
vertex 0.004 -0.004 0
vertex 0.004 0.004 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex -0.004 -0.004 0
vertex 0.004 0.004 0
vertex -0.004 0.004 0
endloop
endfacet
endsolid floor
";

/// A sphere bonded to a plane and thrown at it follows the fork through the normal
/// law's compression and tension branches, with the plane given as a primitive wall and
/// as a mesh (the fork's rows, measured against both: 4e-14 of the velocity's scale, the
/// rest exact).
#[test]
fn wall_bonds_follow_the_fork() {
    let text = std::fs::read_to_string(data().join("in.wall")).unwrap();
    let want = common::reference_rows(&data().join("inl_wall.txt"));
    let (zmin, zmax) = want
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), r| (a.min(r[1]), b.max(r[1])));
    assert!(zmin < 0.000525 && zmax > 0.000525, "{zmin} {zmax}");
    let plane = common::thermo_rows(&common::run_script(&text, None));
    common::assert_columns(&plane, &want, 1, 1e-12, "primitive wall");
    let mesh = text
        .replace(
            "fix             floor",
            "fix             mesh all mesh/surface file floor.stl type 1\nfix             floor",
        )
        .replace("primitive type 1 zplane 0.0", "mesh n_meshes 1 meshes mesh");
    let got = common::thermo_rows(&common::run_with_files(
        &mesh,
        &[("floor.stl", FLOOR)],
        None,
    ));
    common::assert_columns(&got, &want, 1, 1e-12, "mesh wall");
}

/// Two threads give the same rows as one; two MPI ranks (the box split at x = 0, with
/// sphere 1 on one side and its bond's partner on the other, so the bond's history is
/// kept from both sides) give the serial rows.
#[test]
fn threads_and_ranks_give_the_serial_rows() {
    let s = script(&[("damp", "0.1"), ("brk", "off")]);
    let one = common::run_script(&s, None);
    let dir = common::scratch_dir("bond-nonlinear-threads");
    std::fs::write(dir.join("in.test"), &s).unwrap();
    let out = common::rdem_in(&dir, "in.test", None)
        .env("RDEM_THREADS", "2")
        .output()
        .unwrap();
    let two = common::success("2 threads", &out);
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(common::thermo_rows(&one), common::thermo_rows(&two));
    #[cfg(feature = "mpi")]
    if common::have_mpirun() {
        let ranks = common::run_script(&s, Some(2));
        assert!(ranks.contains("on 2 procs"), "{ranks}");
        common::assert_columns(
            &common::thermo_rows(&ranks),
            &common::thermo_rows(&one),
            1,
            1e-12,
            "2 ranks",
        );
    }
}

/// Split by `write_restart` at step 10000 and continued by `read_restart` in a new
/// process, the run ends with the rows of two runs in one process, bit for bit: the
/// bonds' angles and the extremes of their cycles come back. (Two runs, as LIGGGHTS: the
/// set-up of a run evaluates the bonds again, with the angle's increment not kept.)
#[test]
fn a_restart_continues_bit_for_bit() {
    let s = script(&[("damp", "0.1"), ("brk", "off")]);
    let whole = common::run_script(
        &s.replace(
            "run             20000",
            "run 10000
run 10000",
        ),
        None,
    );
    let first = s.replace(
        "run             20000",
        "run 10000\nwrite_restart state.restart",
    );
    let (d1, _) = common::run_kept_ok("bond-nonlinear-first", &first, &[], None);
    // The continuing script: the same settings, the particles from the restart file.
    let second: String = s
        .lines()
        .filter(|l| {
            ![
                "region",
                "create_box",
                "create_atoms",
                "set ",
                "group",
                "velocity",
            ]
            .iter()
            .any(|w| l.starts_with(w))
        })
        .map(|l| match l {
            l if l.starts_with("soft_particles") => format!(
                "{l}\nread_restart ../{}/state.restart\n",
                d1.file_name().unwrap().to_string_lossy()
            ),
            l if l.starts_with("run") => "run 10000\n".to_string(),
            l => format!("{l}\n"),
        })
        .collect();
    let (d2, out) = common::run_kept_ok("bond-nonlinear-second", &second, &[], None);
    let last = |o: &str| common::thermo_rows(o).last().unwrap().clone();
    assert_eq!(last(&out), last(&whole));
    let _ = std::fs::remove_dir_all(d1);
    let _ = std::fs::remove_dir_all(d2);
}

/// A missing stiffness table and a keyword of `cohesion bond` that the nonlinear model
/// does not have are located errors that name what is needed.
#[test]
fn missing_tables_and_foreign_keywords_are_errors() {
    let s = script(&[("damp", "0.0"), ("brk", "off")]);
    let out = common::run_script_raw(
        &s.replace(
            "fix             b23 all property/global stiffnessPerUnitAreaKc_tt peratomtypepair 1 0.5e10\n",
            "",
        ),
        None,
    );
    // The message without miette's line breaks.
    let flat = |o: &std::process::Output| {
        String::from_utf8_lossy(&o.stderr)
            .split_whitespace()
            .filter(|w| *w != "│")
            .collect::<Vec<_>>()
            .join(" ")
    };
    let err = flat(&out);
    assert!(!out.status.success());
    assert!(
        err.contains("cohesion bond/nonlinear needs 'fix ID all property/global stiffnessPerUnitAreaKc_tt peratomtypepair 1 ...'"),
        "{err}"
    );
    let out = common::run_script_raw(
        &s.replace(
            "stressBreak ${brk}",
            "dissipationBond on stressBreak ${brk}",
        ),
        None,
    );
    let err = flat(&out);
    assert!(!out.status.success());
    assert!(
        err.contains("'dissipationBond' is not a keyword of the bond model given")
            && err.contains("it is a keyword of 'cohesion bond'")
            && err.contains("in.test:"),
        "{err}"
    );
}
