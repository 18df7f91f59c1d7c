//! LIGGGHTS-PFM's `model jkr` (rdem's `jkr/pfm`, which `model jkr` becomes when
//! `cohesionEnergyDensity` is defined and `workOfAdhesion` is not) against the fork
//! itself. The fork (ParticulateFlow/LIGGGHTS-PFM d075b977) was built here and ran
//! `tests/data/jkr_pfm/in.pj`: an oblique spinning pair and a sphere dropped on a jkr
//! plane, in two settings, dumped every 200 steps:
//!
//! - `a`: slow (0.05 m/s), damped (e = 0.5), γ = 0.5 J/m², `tangential history`: the pair
//!   and the sphere on the wall stick;
//! - `b`: fast (0.3 m/s), e = 0.9, γ = 0.05 J/m², `tangential no_history`: they rebound.
//!
//! Measured: 1.2e-13 of a column's scale at worst (a), bit for bit (b). The tests allow
//! 1e-11.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/jkr_pfm")
}

/// rdem's dump rows (step first) of `in.pj` with the variables `vars`, run with `edit`
/// applied to the script.
fn run(vars: &[(&str, &str)], edit: impl Fn(String) -> String) -> Vec<Vec<f64>> {
    let script =
        common::index_vars(vars) + &edit(std::fs::read_to_string(data().join("in.pj")).unwrap());
    let (dir, _) = common::run_kept_ok("jkr_pfm", &script, &[], None);
    let tag = vars.iter().find(|(k, _)| *k == "tag").unwrap().1;
    let text = std::fs::read_to_string(dir.join(format!("d_{tag}.txt"))).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    common::dump_rows_with_step(&text)
}

fn setting(tag: &'static str) -> [(&'static str, &'static str); 5] {
    match tag {
        "a" => [
            ("tag", "a"),
            ("v", "0.05"),
            ("e", "0.5"),
            ("gam", "0.5"),
            ("tan", "history"),
        ],
        _ => [
            ("tag", "b"),
            ("v", "0.3"),
            ("e", "0.9"),
            ("gam", "0.05"),
            ("tan", "no_history"),
        ],
    }
}

#[test]
fn impacts_follow_the_fork() {
    for tag in ["a", "b"] {
        let got = run(&setting(tag), |s| s);
        let want = common::reference_rows(&data().join(format!("pfm_{tag}.txt")));
        common::assert_columns(&got, &want, 2, 1e-11, tag);
    }
    // Setting a sticks: at the end the pair's relative velocity along x is below 2 % of
    // the approach speed (0.1 m/s) and the sphere on the plane has stopped falling.
    let got = run(&setting("a"), |s| s);
    let last = &got[got.len() - 3..];
    assert!((last[0][5] - last[1][5]).abs() < 2e-3, "{last:?}");
    assert!(last[2][7].abs() < 2e-3, "{last:?}");
}

/// The explicit name `jkr/pfm` is the same law; with γ = 0 it is Hertz's, bit for bit.
/// (The fork with γ = 0 differs from its own Hertz by up to 1.7e-3 of the force of a
/// wall contact at a small overlap, 6.5e-7 of the column's scale, measured: its 10 Newton
/// steps from a = R* fall short of the root there; rdem solves it.)
#[test]
fn explicit_name_and_no_adhesion() {
    let named = run(&setting("a"), |s| s.replace("model jkr", "model jkr/pfm"));
    let want = common::reference_rows(&data().join("pfm_a.txt"));
    common::assert_columns(&named, &want, 2, 1e-11, "jkr/pfm");
    let vars = [
        ("tag", "c"),
        ("v", "0.1"),
        ("e", "0.7"),
        ("gam", "0"),
        ("tan", "history"),
    ];
    let jkr = run(&vars, |s| s);
    let hertz = run(&vars, |s| s.replace("model jkr", "model hertz"));
    assert_eq!(jkr, hertz);
    // The pair and the wall did touch: forces were felt.
    assert!(jkr.iter().any(|r| r[8] != 0.0 || r[10] != 0.0));
}

/// `model jkr` with neither workOfAdhesion nor cohesionEnergyDensity names both.
#[test]
fn missing_adhesion_names_both_laws() {
    let script = common::index_vars(&setting("a"))
        + &std::fs::read_to_string(data().join("in.pj"))
            .unwrap()
            .replace("fix m6 all property/global cohesionEnergyDensity", "#");
    let out = common::run_script_raw(&script, None);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("workOfAdhesion") && err.contains("cohesionEnergyDensity"),
        "{err}"
    );
}

/// `in.pj` of setting `a` with its variables set, as a script text.
fn script_a() -> String {
    common::index_vars(&setting("a")) + &std::fs::read_to_string(data().join("in.pj")).unwrap()
}

/// The dump rows of `script` run in a scratch directory on `threads` threads, and the
/// directory.
fn run_threads(d: &Path, name: &str, script: &str, threads: &str) -> Vec<Vec<f64>> {
    std::fs::write(d.join(name), script).unwrap();
    let out = common::rdem_in(d, name, None)
        .arg("--threads")
        .arg(threads)
        .output()
        .unwrap();
    common::success(name, &out);
    common::dump_rows_with_step(&std::fs::read_to_string(d.join("d_a.txt")).unwrap())
}

/// 1 and 2 threads give the same digits. A restart written at step 3000 and read back
/// continues exactly as the run split there in one process (`run 3000` twice: the
/// set-up of the second evaluates the damping with the full-step velocities, as in
/// LIGGGHTS, so neither is the unbroken run).
#[test]
fn threads_and_a_restart_give_the_same_run() {
    let d = common::scratch_dir("jkr-pfm-threads");
    let s = script_a();
    let one = run_threads(&d, "in.one", &s, "1");
    assert_eq!(run_threads(&d, "in.two", &s, "2"), one);
    let split = run_threads(
        &d,
        "in.split",
        &s.replace("run 6000", "run 3000\nrun 3000"),
        "1",
    );
    let first = s.replace("run 6000", "run 3000\nwrite_restart pj.restart");
    run_threads(&d, "in.first", &first, "1");
    let second: String = s
        .lines()
        .filter(|l| !l.starts_with("create_atoms") && !l.starts_with("set "))
        .map(|l| match l {
            "create_box 1 reg" => "read_restart pj.restart\n".to_string(),
            "run 6000" => "run 3000\n".to_string(),
            _ => format!("{l}\n"),
        })
        .collect();
    let after = |rows: Vec<Vec<f64>>| -> Vec<Vec<f64>> {
        rows.into_iter().filter(|r| r[0] > 3000.0).collect()
    };
    let resumed = after(run_threads(&d, "in.second", &second, "1"));
    assert_eq!(resumed.len(), 45);
    assert_eq!(resumed, after(split));
    let _ = std::fs::remove_dir_all(&d);
}

/// On 2 and 4 MPI ranks (the pair straddles x = 0, where the box is split: a contact with
/// a ghost) the dumps are the serial ones to 1e-12 of each column's scale.
#[cfg(feature = "mpi")]
#[test]
fn ranks_give_the_serial_run() {
    if !common::have_mpirun() {
        return;
    }
    let serial = run(&setting("a"), |s| s);
    for ranks in [2, 4] {
        let script = script_a();
        let (dir, _) = common::run_kept_ok("jkr_pfm_mpi", &script, &[], Some(ranks));
        let text = std::fs::read_to_string(dir.join("d_a.txt")).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let got = common::dump_rows_with_step(&text);
        common::assert_columns(&got, &serial, 2, 1e-12, &format!("{ranks} ranks"));
    }
}
