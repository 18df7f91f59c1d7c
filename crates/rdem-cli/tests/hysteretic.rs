//! `model hysteretic/nonlinear1` and `hysteretic/nonlinear2` (LIGGGHTS-INL) against
//! LIGGGHTS-INL itself.
//!
//! The fork (idaholab/LIGGGHTS-INL d69df36) was built here (`make mpi_no_vtk`) and ran the
//! scripts of `tests/data/hysteretic/`, written for these tests: `in.press` (two spheres
//! pressed together by a ramped force, held, unloaded, pressed harder, unloaded, then
//! pulled apart) with either law, `limitForce` on and off and with a `pullOffForce`, and
//! `in.drop` (a sphere thrown obliquely at a plane `fix wall/gran` with the same law,
//! sliding and spinning up). Its thermo rows are the `inl_*.txt` files. rdem agrees with
//! every row to 1e-12 of each column's scale at worst (measured 9.6e-13, the velocity of
//! nonlinear2 with `limitForce off`; 3e-14 elsewhere); the tests allow 1e-10.
//!
//! The spheres start 1 µm apart. Started exactly touching, the fork sees an overlap of
//! one rounding unit at set-up and writes its history there, as it does at every
//! evaluation; rdem does not write history at set-up, and the two then differ by 5e-5
//! of the overlap (measured, nonlinear1).

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/hysteretic")
}

fn read(name: &str) -> String {
    std::fs::read_to_string(data().join(name)).unwrap()
}

/// The thermo rows of a reference file (comment lines skipped).
fn reference(name: &str) -> Vec<Vec<f64>> {
    common::reference_rows(&data().join(name))
}

/// A data script with index variables set first (as `-var NAME VALUE` would).
fn with_vars(name: &str, vars: &[(&str, &str)]) -> String {
    common::index_vars(vars) + &read(name)
}

const PRESS_CASES: [(&str, &str, &str); 6] = [
    ("1", "on", "0"),
    ("2", "on", "0"),
    ("1", "off", "0"),
    ("2", "off", "0"),
    ("1", "off", "1e-4"),
    ("2", "on", "1e-4"),
];

fn press(law: &str, lim: &str, pull: &str) -> String {
    with_vars("in.press", &[("law", law), ("lim", lim), ("pull", pull)])
}

/// Loading, holding, unloading, reloading to a higher force and pulling apart follow the
/// fork with either law, with `limitForce` on (the laws' default) and off, and with a
/// constant `pullOffForce`.
#[test]
fn press_cycles_follow_the_fork() {
    for (law, lim, pull) in PRESS_CASES {
        let what = format!("law {law} limitForce {lim} pullOffForce {pull}");
        let got = common::thermo_rows(&common::run_script(&press(law, lim, pull), None));
        let want = reference(&format!("inl_press_law{law}_lim{lim}_pull{pull}.txt"));
        common::assert_columns(&got, &want, 1, 1e-10, &what);
    }
}

/// The cycles are what the laws say: the second loading reaches a larger overlap, and
/// after each unloading the spheres keep a plastic overlap; with `limitForce off`
/// nonlinear1's adhesive branch holds the pulled sphere a while, with it on the pulled
/// sphere leaves at once.
#[test]
fn press_cycles_are_elasto_plastic() {
    let rows = reference("inl_press_law1_limon_pull0.txt");
    let at = |step: f64| rows.iter().find(|r| r[0] == step).unwrap()[1];
    // Overlap (column 1) at the end of the first loading, its unloading, the second
    // loading and its unloading.
    let (l1, u1, l2, u2) = (at(50000.0), at(100000.0), at(150000.0), at(200000.0));
    assert!(l2 > 1.5 * l1, "{l1} {l2}");
    assert!(u1 > 0.8 * l1 && u1 < l1, "{u1} {l1}");
    assert!(u2 > 0.8 * l2 && u2 < l2, "{u2} {l2}");
    let got = common::thermo_rows(&common::run_script(&press("1", "on", "0"), None));
    assert_eq!(got.len(), rows.len());
    let gone = |rows: &[Vec<f64>]| rows.last().unwrap()[1] < 0.0;
    assert!(gone(&got), "limitForce on: the pulled sphere leaves");
    let held = reference("inl_press_law1_limoff_pull0.txt");
    assert!(!gone(&held), "limitForce off: the adhesive branch holds it");
}

/// A sphere thrown at a plane wall with friction: the bounce, the slip and the spin-up
/// follow the fork with either law.
#[test]
fn a_sphere_thrown_at_a_wall_follows_the_fork() {
    for law in ["1", "2"] {
        let got = common::thermo_rows(&common::run_script(
            &with_vars("in.drop", &[("law", law)]),
            None,
        ));
        let want = reference(&format!("inl_drop_law{law}.txt"));
        common::assert_columns(&got, &want, 1, 1e-10, &format!("drop, law {law}"));
        // It bounced (rising at the end, much slower than it came) and spins.
        let last = want.last().unwrap();
        assert!(last[3] > 0.0 && last[3] < 0.3 * 0.5, "{last:?}");
        assert!(last[4].abs() > 10.0, "{last:?}");
    }
}

/// Threads give the same digits.
#[test]
fn threads_give_the_same_cycles() {
    let d = common::scratch_dir("hysteretic-threads");
    std::fs::write(d.join("in.script"), press("2", "off", "0")).unwrap();
    let run = |threads: &str| {
        let out = common::rdem_in(&d, "in.script", None)
            .arg("--threads")
            .arg(threads)
            .output()
            .unwrap();
        common::thermo_rows(&common::success(threads, &out))
    };
    assert_eq!(run("2"), run("1"));
    let _ = std::fs::remove_dir_all(&d);
}

/// A missing property of the laws stops the run with its name, as in the fork.
#[test]
fn a_missing_property_is_named() {
    for (line, name) in [
        ("fix q1 all property/global alphaCustom", "alphaCustom"),
        (
            "fix p5 all property/global LoadingStiffness",
            "LoadingStiffness",
        ),
        (
            "fix p8 all property/global coefficientPlasticityDepth",
            "coefficientPlasticityDepth",
        ),
    ] {
        let s: String = press("1", "on", "0")
            .lines()
            .filter(|l| !l.starts_with(line))
            .map(|l| format!("{l}\n"))
            .collect();
        let out = common::run_script_raw(&s, None);
        assert!(!out.status.success(), "{name}");
        let text = String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
        assert!(text.contains(name), "{name}: {text}");
    }
}

/// Written to a restart file after the first unloading and read back, the contact
/// history carries the cycle on: the rows after the restart are the uninterrupted run's.
#[test]
fn a_restart_continues_the_cycle_exactly() {
    let full = press("1", "off", "0");
    let lines: Vec<&str> = full.lines().collect();
    let runs: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].starts_with("run "))
        .collect();
    // First part: up to the end of the second stage, then the restart file.
    let mut first = lines[..=runs[1]].join("\n");
    first.push_str("\nwrite_restart press.restart\n");
    // Second part: the same set-up with the box and atoms from the file, then the rest.
    let mut second = String::new();
    for l in &lines[..runs[1]] {
        let stage = ["run ", "unfix push", "variable F", "fix push"]
            .iter()
            .any(|p| l.starts_with(p));
        if l.starts_with("create_box") {
            second.push_str("read_restart press.restart\n");
        } else if !(stage || l.starts_with("create_atoms") || l.starts_with("set group")) {
            second.push_str(&format!("{l}\n"));
        }
    }
    // The rest, without the `unfix` and `variable delete` of a stage that is not defined.
    let rest = lines[runs[1] + 1..].join("\n");
    second.push_str(
        rest.replacen("unfix push\nvariable F delete\n", "", 1)
            .as_str(),
    );
    let d = common::scratch_dir("hysteretic-restart");
    std::fs::write(d.join("in.first"), &first).unwrap();
    std::fs::write(d.join("in.second"), &second).unwrap();
    let run = |name: &str| {
        let out = common::rdem_in(&d, name, None).output().unwrap();
        common::thermo_rows(&common::success(name, &out))
    };
    run("in.first");
    let resumed = run("in.second");
    let whole = common::thermo_rows(&common::run_script(&full, None));
    // The whole run's rows from its set-up of the third stage on.
    let from = whole.iter().position(|r| r[0] == 100000.0).unwrap() + 1;
    assert!(resumed.len() > 40);
    assert_eq!(resumed, whole[from..]);
    let _ = std::fs::remove_dir_all(&d);
}

/// The same throw at an STL floor (`mesh/surface/stress`) bounces as off the primitive
/// plane, to the fork's rows; with a rolling spring too (the widest mesh-wall history:
/// 10 normal values, tangential and rolling springs, the stress values) it runs.
#[test]
fn a_mesh_wall_gives_the_primitive_walls_bounce() {
    let stl = "solid floor\n\
        facet normal 0 0 1\nouter loop\nvertex -0.01 -0.01 0\nvertex 0.01 -0.01 0\nvertex 0.01 0.01 0\nendloop\nendfacet\n\
        facet normal 0 0 1\nouter loop\nvertex -0.01 -0.01 0\nvertex 0.01 0.01 0\nvertex -0.01 0.01 0\nendloop\nendfacet\n\
        endsolid floor\n";
    let mesh = |roll: &str| {
        let s = with_vars("in.drop", &[("law", "2")]);
        let line = s
            .lines()
            .find(|l| l.starts_with("fix floor all wall/gran"))
            .unwrap()
            .to_string();
        s.replace(
            &line,
            &format!(
                "fix fl all mesh/surface/stress file floor.stl type 2\n\
                 fix r1 all property/global coefficientRollingFriction peratomtypepair 2 0.1 0.1 0.1 0.1\n\
                 fix r2 all property/global coefficientRollingViscousDamping peratomtypepair 2 0.1 0.1 0.1 0.1\n\
                 fix floor all wall/gran model hysteretic/nonlinear2 tangential history \
                 rolling_friction {roll} mesh n_meshes 1 meshes fl"
            ),
        )
    };
    let got = common::thermo_rows(&common::run_with_files(
        &mesh("off"),
        &[("floor.stl", stl)],
        None,
    ));
    common::assert_columns(
        &got,
        &reference("inl_drop_law2.txt"),
        1,
        1e-10,
        "mesh floor",
    );
    let spring = common::thermo_rows(&common::run_with_files(
        &mesh("epsd"),
        &[("floor.stl", stl)],
        None,
    ));
    assert_eq!(spring.len(), got.len());
}
