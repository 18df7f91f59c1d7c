//! `thermo_temp`, `compute_modify` and thermo `ke` against LIGGGHTS 3.8: the scripts in
//! tests/data/settings/ ran there (`regenerate.sh`, outputs in `*.liggghts.txt`); the rows
//! LIGGGHTS printed are hard-coded below.

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/settings");

/// Runs `name` from tests/data/settings and returns its captured screen output.
fn run(name: &str) -> String {
    let src = std::fs::read_to_string(format!("{DIR}/{name}")).unwrap();
    // The scripts include ../parity/*.in relative to their folder.
    let src = src.replace("include ../parity/", &format!("include {DIR}/../parity/"));
    common::run_screen(name, &src)
}

/// The thermo rows (lines of numbers only) of an output, each as numbers.
fn rows(out: &str) -> Vec<Vec<f64>> {
    out.lines()
        .filter_map(|l| {
            let v: Option<Vec<f64>> = l.split_whitespace().map(|w| w.parse().ok()).collect();
            v.filter(|v| v.len() >= 4)
        })
        .collect()
}

/// Asserts each row equals LIGGGHTS' to a relative 1e-13 (the printed 15 digits).
fn assert_rows(got: &[Vec<f64>], want: &[[f64; 4]], out: &str) {
    assert_eq!(got.len(), want.len(), "row count in\n{out}");
    for (g, w) in got.iter().zip(want) {
        for (a, b) in g.iter().zip(w) {
            let tol = 1e-13 * b.abs();
            assert!(
                (a - b).abs() <= tol,
                "{a} vs LIGGGHTS {b} in row {g:?}\n{out}"
            );
        }
    }
}

/// `compute_modify thermo_temp extra N` changes c_thermo_temp as dof = 3N − extra (0 at
/// dof ≤ 0), and `temp` follows it; `ke` stays Σ ½ m v², also for a single particle.
#[test]
fn extra_dof_as_liggghts() {
    let out = run("temp_extra.in");
    // LIGGGHTS 3.8 (temp_extra.liggghts.txt): step atoms ke c_thermo_temp per `run 0`,
    // extra 3 (default), 0, 5, 12, -2, then one particle with extra 3 and 0.
    let want = [
        [0.0, 4.0, 0.00212712002586809, 3.42370044641133e+19],
        [0.0, 4.0, 0.00212712002586809, 2.56777533480849e+19],
        [0.0, 4.0, 0.00212712002586809, 4.40190057395742e+19],
        [0.0, 4.0, 0.00212712002586809, 0.0],
        [0.0, 4.0, 0.00212712002586809, 2.20095028697871e+19],
        [0.0, 1.0, 9.16297857297023e-05, 0.0],
        [0.0, 1.0, 9.16297857297023e-05, 4.42447442305464e+18],
    ];
    let got = rows(&out);
    assert_rows(&got, &want, &out);
    // The closed form: KE = Σ ½ m v², T = 2 KE / ((3·4 − extra) k_B).
    let m = 2500.0 * std::f64::consts::PI / 6.0 * 1e-6;
    let vs = [
        [1.5, 0.2, 0.3],
        [0.1, -0.7, 0.3],
        [0.1, 0.2, 0.3],
        [0.1, 0.2, 0.3],
    ];
    let ke: f64 = vs
        .iter()
        .map(|v| 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
        .sum();
    let t5 = 2.0 * ke / (7.0 * 1.3806504e-23);
    assert!((got[2][3] - t5).abs() <= 1e-13 * t5);
    assert!((got[0][2] - ke).abs() <= 1e-13 * ke);
}

/// Without `dynamic yes` the particle count is the one at the run's set-up: a pour that
/// starts empty prints 0; `dynamic yes` counts at each evaluation; `dynamic no` again
/// keeps the count of the set-up (30) while 10 more particles arrive.
#[test]
fn dynamic_as_liggghts() {
    let out = run("temp_dynamic.in");
    // LIGGGHTS 3.8 (temp_dynamic.liggghts.txt): step atoms ke c_thermo_temp.
    let want = [
        [0.0, 0.0, 0.0, 0.0],
        [2.0, 20.0, 0.000229074464324256, 0.0],
        [4.0, 20.0, 0.000229074464324256, 0.0],
        [4.0, 20.0, 0.000229074464324256, 5.82167687244031e+17],
        [6.0, 20.0, 0.000229074464324256, 5.82167687244031e+17],
        [6.0, 20.0, 0.000229074464324256, 5.82167687244031e+17],
        [8.0, 30.0, 0.000343611696486384, 5.72130313326031e+17],
        [10.0, 30.0, 0.000343611696486384, 5.72130313326031e+17],
        [10.0, 30.0, 0.000343611696486384, 5.72130313326031e+17],
        [12.0, 40.0, 0.000458148928648512, 7.62840417768041e+17],
        [14.0, 40.0, 0.000458148928648512, 7.62840417768041e+17],
    ];
    assert_rows(&rows(&out), &want, &out);
}

/// `temp` is `c_thermo_temp`; an unknown compute ID is a located error with the nearest
/// ID; a keyword a style does not use warns.
#[test]
fn compute_modify_errors_and_warnings() {
    let head = std::fs::read_to_string(format!("{DIR}/../parity/head.in")).unwrap();
    let mut i = common::interpreter();
    let src = format!(
        "{head}region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\ncompute k all ke\n\
         compute_modify k dynamic yes\ncompute_modify thermo_tmp dynamic yes\n"
    );
    let e = i.run_source("in.t", &src).unwrap_err();
    let text = format!("{:?}", miette::Report::new(*e));
    assert!(text.contains("no compute 'thermo_tmp'"), "{text}");
    assert!(text.contains("thermo_temp"), "{text}");
    let out = common::screen(&i);
    assert!(
        out.contains("compute_modify dynamic has no effect on compute k (style ke)"),
        "{out}"
    );
    let mut i = common::interpreter();
    let e = i
        .run_source("in.t", "compute_modify thermo_temp extra 4.5\n")
        .unwrap_err();
    let text = format!("{:?}", miette::Report::new(*e));
    assert!(
        text.contains("extra must be an integer, not '4.5'"),
        "{text}"
    );
    let mut i = common::interpreter();
    let e = i
        .run_source("in.t", "compute_modify thermo_temp extra 1 bogus 2\n")
        .unwrap_err();
    let text = format!("{:?}", miette::Report::new(*e));
    assert!(
        text.contains("unknown compute_modify keyword 'bogus'"),
        "{text}"
    );
}
