//! `fix heat/gran` on a packing of 256 spheres against LIGGGHTS 3.8: the scripts in
//! tests/data/heat/ (an fcc packing on a mesh floor at 400 K beside a primitive side wall at
//! 350 K, two atom types, a heat source in one corner), run there by `regenerate.sh`, which
//! kept LIGGGHTS' thermo table (`*.liggghts.thermo`: thermal energy `f_heattransfer`, mean
//! and maximum temperature, total heat flow by `compute reduce`) and its dump of `Temp`
//! and `heatFlux` per particle (`*.liggghts.dump`).
//!
//! At the first row of a run LIGGGHTS 3.8 prints a total heat flow that rdem does not
//! (the walls add their heat to `heatFlux` in the set-up of every run after the first,
//! on top of the previous step's values; it is zeroed before the next step, so no
//! temperature depends on it): that one value is not compared.

use crate::common;

use std::collections::HashMap;
use std::path::Path;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/heat");

/// Runs `in.NAME` of tests/data/heat in a scratch copy of the folder (one thread);
/// returns the thermo rows of its last run and its dump (step → tag → [type, z, Temp,
/// heatFlux]).
fn run(name: &str) -> (Vec<Vec<f64>>, Dump) {
    let dir = common::scratch_dir("heat");
    common::copy_dir(Path::new(DIR), &dir);
    let input = format!("in.{name}");
    let out = common::rdem_in(&dir, &input, None)
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    let text = common::success(&input, &out);
    let dump = read_dump(&std::fs::read_to_string(dir.join(format!("dump.{name}"))).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
    (last_table(&text), dump)
}

type Dump = HashMap<u64, HashMap<u64, Vec<f64>>>;

/// The rows of the last thermo table of a screen output.
fn last_table(out: &str) -> Vec<Vec<f64>> {
    let start = out.rfind("Step").expect("a thermo table");
    common::thermo_rows(&out[start..])
}

/// A `dump custom` text file: step → tag → the other columns.
fn read_dump(text: &str) -> Dump {
    let lines: Vec<&str> = text.lines().collect();
    let mut snaps = HashMap::new();
    let mut k = 0;
    while k < lines.len() {
        if lines[k].starts_with("ITEM: TIMESTEP") {
            let step: u64 = lines[k + 1].trim().parse().unwrap();
            let n: usize = lines[k + 3].trim().parse().unwrap();
            let rows = lines[k + 9..k + 9 + n]
                .iter()
                .map(|l| {
                    let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
                    (v[0] as u64, v[1..].to_vec())
                })
                .collect();
            snaps.insert(step, rows);
            k += 9 + n;
        } else {
            k += 1;
        }
    }
    snaps
}

fn liggghts(name: &str) -> (Vec<Vec<f64>>, Dump) {
    let thermo = std::fs::read_to_string(format!("{DIR}/{name}.liggghts.thermo")).unwrap();
    let dump = std::fs::read_to_string(format!("{DIR}/{name}.liggghts.dump")).unwrap();
    (common::thermo_rows(&thermo), read_dump(&dump))
}

/// Compares the thermo tables column by column within `rel` (relative) per column.
fn compare_thermo(got: &[Vec<f64>], want: &[Vec<f64>], rel: [f64; 6]) {
    assert_eq!(got.len(), want.len(), "rows: {got:?}");
    for (r, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.len(), 6, "{g:?}");
        assert_eq!(g[0], w[0], "step");
        assert_eq!(g[1], w[1], "atoms");
        for c in 2..6 {
            if r == 0 && c == 5 {
                continue; // LIGGGHTS' set-up heat flow (see the module's doc)
            }
            let tol = rel[c] * w[c].abs();
            assert!(
                (g[c] - w[c]).abs() <= tol,
                "step {}, column {c}: rdem {} vs LIGGGHTS {} (tolerance {tol})",
                g[0],
                g[c],
                w[c]
            );
        }
    }
}

/// The packing held in place (no integration): only the temperatures change, so rdem
/// follows LIGGGHTS 3.8 to round-off: every thermo value within 1e-12 (relative), every
/// particle's temperature within 1e-12 and heat flow within 1e-9 (relative, or 1e-12 W).
#[test]
fn frozen_packing_as_liggghts() {
    let (thermo, dump) = run("heat_frozen");
    let (lt, ld) = liggghts("heat_frozen");
    compare_thermo(&thermo, &lt, [0.0, 0.0, 1e-12, 1e-12, 1e-12, 1e-12]);
    assert_eq!(dump.len(), ld.len());
    for (step, want) in &ld {
        let got = &dump[step];
        assert_eq!(got.len(), 256);
        for (tag, w) in want {
            let g = &got[tag];
            assert!(
                (g[2] - w[2]).abs() <= 1e-12 * w[2],
                "step {step} tag {tag}: T {g:?} vs {w:?}"
            );
            if *step > 0 {
                let tol = (1e-9 * w[3].abs()).max(1e-12);
                assert!(
                    (g[3] - w[3]).abs() <= tol,
                    "step {step} tag {tag}: Q {g:?} vs {w:?}"
                );
            }
        }
    }
}

/// The packing settling under gravity for 5000 steps (the overlaps, so the contact areas,
/// change every step). The settling itself drifts from LIGGGHTS' (positions up to 2e-6 m
/// apart after 5000 steps, measured), so the temperatures agree less closely: thermal
/// energy and mean temperature within 1e-6 (measured 7e-8), maximum temperature within
/// 1e-4 (measured 8e-6), total heat flow within 1e-3 (measured 1.5e-4), and every
/// particle's temperature within 0.05 K of LIGGGHTS' (measured 0.013 K at step 5000, of a
/// rise up to 13 K).
#[test]
fn settling_packing_as_liggghts() {
    let (thermo, dump) = run("heat_bed");
    let (lt, ld) = liggghts("heat_bed");
    compare_thermo(&thermo, &lt, [0.0, 0.0, 1e-6, 1e-6, 1e-4, 1e-3]);
    for (step, want) in &ld {
        let got = &dump[step];
        assert_eq!(got.len(), want.len());
        for (tag, w) in want {
            let g = &got[tag];
            assert!(
                (g[2] - w[2]).abs() <= 0.05,
                "step {step} tag {tag}: T {g:?} vs {w:?}"
            );
        }
    }
    // The heat reached the particles: the bottom layer warmed by more than 5 K.
    let last = &dump[&5000];
    let bottom: Vec<f64> = last
        .values()
        .filter(|v| v[1] < 0.008)
        .map(|v| v[2])
        .collect();
    assert!(
        !bottom.is_empty() && bottom.iter().all(|&t| t > 305.0),
        "{bottom:?}"
    );
}

/// `temperature T` at the end of a mesh `fix wall/gran` line: LIGGGHTS 3.8 reads it and
/// ignores it (each mesh has its `fix mesh/surface` temperature). For
/// `tests/data/heat_mesh_wall/in.w` (a sphere on a 500 K floor) it printed the summed
/// temperature 300.70995 at steps 1500 and 2000 with T = 500 and with T = 900. rdem runs
/// both to those digits and warns where T differs from the mesh's.
#[test]
fn mesh_wall_temperature_is_ignored_as_liggghts() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/heat_mesh_wall");
    let script = std::fs::read_to_string(data.join("in.w")).unwrap();
    let floor = std::fs::read_to_string(data.join("floor.stl")).unwrap();
    for t in ["500", "900"] {
        let s = common::index_vars(&[("T", t)]) + &script;
        let out = common::run_with_files_raw(&s, &[("floor.stl", &floor)], None);
        let stdout = common::success(t, &out);
        let rows = common::thermo_rows(&stdout);
        let last = rows.last().unwrap();
        assert_eq!(last[0], 2000.0);
        assert!((last[1] - 300.70995).abs() < 1e-5, "T {t}: {last:?}");
        let text = stdout + &String::from_utf8_lossy(&out.stderr);
        assert_eq!(text.contains("is ignored"), t == "900", "T {t}: {text}");
    }
}
