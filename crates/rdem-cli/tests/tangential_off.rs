//! `pair_style gran` and `fix wall/gran` without a `tangential` model: LIGGGHTS 3.8
//! applies no tangential force (its default `off`; `tangential off` says so), and
//! needs no `coefficientFriction`. rdem applied `tangential history` there before.
//!
//! The reference figures are LIGGGHTS 3.8's (the Debian package, `liggghts`) for the
//! scripts of `tests/data/tangential_off/`, the final line of each dump (%.10g).

use crate::common;

use std::path::Path;

fn read(name: &str) -> String {
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tangential_off");
    std::fs::read_to_string(d.join(name)).unwrap()
}

/// Runs the data script `name` with `vars` (index variables set first); returns the
/// last row of its dump `dump`.
fn last_row(name: &str, vars: &[(&str, &str)], dump: &str) -> Vec<f64> {
    let mut script: String = vars
        .iter()
        .map(|(k, v)| format!("variable {k} index \"{v}\"\n"))
        .collect();
    script.push_str(&read(name));
    let (dir, _) = common::run_kept_ok("tangential_off", &script, &[], None);
    let text = std::fs::read_to_string(dir.join(dump)).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let frames = common::dump_frames(&text);
    frames.last().unwrap().1.last().unwrap().clone()
}

fn assert_row(got: &[f64], want: &[f64], what: &str) {
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= 1e-9 * w.abs().max(1e-3),
            "{what}: {got:?} against LIGGGHTS 3.8's {want:?}"
        );
    }
}

/// An oblique impact of two spheres: without `tangential` (and with `tangential off`)
/// no spin and LIGGGHTS 3.8's velocities to 10 digits; `no_history` spins them.
#[test]
fn pairs_without_a_tangential_model_have_no_tangential_force() {
    // id vx vy vz omegaz of sphere 2 after 0.02 s.
    let none = [2.0, 0.7852852547, 0.1075725653, 0.0, 0.0];
    for tan in ["", "tangential off"] {
        let row = last_row("in.pair", &[("tan", tan), ("tn", "x")], "d_x.txt");
        assert_row(&row, &none, tan);
    }
    let row = last_row(
        "in.pair",
        &[("tan", "tangential no_history"), ("tn", "x")],
        "d_x.txt",
    );
    assert_row(
        &row,
        &[2.0, 0.7792463008, 0.1588266065, 0.0, -2.499953542],
        "no_history",
    );
}

/// A sphere spinning and sliding on a wall: without `tangential` (and without
/// `coefficientFriction`) it keeps its speed and spin, as in LIGGGHTS 3.8; with
/// `tangential history` friction slows it and spins it up, also as LIGGGHTS 3.8.
#[test]
fn walls_without_a_tangential_model_have_no_friction() {
    // id z vx vz omegay after 0.02 s.
    let row = last_row(
        "in.wall",
        &[("tan", ""), ("fric", ""), ("tn", "x")],
        "w_x.txt",
    );
    assert_row(
        &row,
        &[1.0, 0.04978549318, 1.0, -0.03117393575, 3.0],
        "none",
    );
    let fric = "fix m4 all property/global coefficientFriction peratomtypepair 1 0.5";
    let row = last_row(
        "in.wall",
        &[("tan", "tangential history"), ("fric", fric), ("tn", "x")],
        "w_x.txt",
    );
    assert_row(
        &row,
        &[
            1.0,
            0.04978549318,
            0.8962123201,
            -0.03117393575,
            8.169769481,
        ],
        "history",
    );
}
