//! `heatFlux` of `compute pair/gran/local` and `compute wall/gran/local`: three spheres
//! at 300, 400 and 300 K (two types, conductivities 10 and 20) touching each other and a
//! 500 K mesh floor, ten steps. Every per-contact heat flow, overlap, contact area and
//! temperature must equal LIGGGHTS 3.8's (tests/data/heat_local/, recorded with the
//! command in the script's header; printed with 15 digits) to 1e-8 relative: the flows
//! are from the temperatures at the time of output (step 0 included), which is what
//! LIGGGHTS gives. Closed form at step 0: the 1–2 pair conducts
//! 4 k₁k₂/(k₁+k₂) √A (T₂ − T₁).

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

fn run(script_text: &str) -> (PathBuf, std::process::Output) {
    let floor = std::fs::read_to_string(data().join("heat/floor.stl")).unwrap();
    common::run_kept("heat_local", script_text, &[("floor.stl", &floor)], None)
}

/// Each snapshot's rows after `ITEM: ENTRIES` / `ITEM: ATOMS`, sorted (the order of
/// contacts is not part of the format).
fn snapshots(text: &str) -> Vec<Vec<Vec<f64>>> {
    let mut out: Vec<Vec<Vec<f64>>> = Vec::new();
    let mut inside = false;
    for l in text.lines() {
        if l.starts_with("ITEM: ENTRIES") || l.starts_with("ITEM: ATOMS") {
            inside = true;
            out.push(Vec::new());
        } else if l.starts_with("ITEM:") {
            inside = false;
        } else if inside {
            let row = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            out.last_mut().unwrap().push(row);
        }
    }
    for s in &mut out {
        s.sort_by(|a: &Vec<f64>, b| a.partial_cmp(b).unwrap());
    }
    out
}

fn assert_same(ours: &str, theirs: &str, what: &str) {
    let (a, b) = (snapshots(ours), snapshots(theirs));
    assert_eq!(a.len(), 3, "{what}: snapshots at 0, 5, 10\n{ours}");
    assert_eq!(a.len(), b.len(), "{what}: snapshots\n{ours}");
    for (s, (sa, sb)) in a.iter().zip(&b).enumerate() {
        assert_eq!(sa.len(), sb.len(), "{what} snapshot {s}: rows\n{ours}");
        for (ra, rb) in sa.iter().zip(sb) {
            for (c, (x, y)) in ra.iter().zip(rb).enumerate() {
                assert!(
                    (x - y).abs() <= 1e-8 * y.abs(),
                    "{what} snapshot {s} column {}: rdem {x}, LIGGGHTS {y}",
                    c + 1
                );
            }
        }
    }
}

#[test]
fn contact_heat_flows_match_liggghts() {
    let dir = data().join("heat_local");
    let script = std::fs::read_to_string(dir.join("in.heat_local")).unwrap();
    let (out_dir, out) = run(&script);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for f in ["pair", "wall", "atoms"] {
        let ours = std::fs::read_to_string(out_dir.join(format!("dump.{f}"))).unwrap();
        let theirs = std::fs::read_to_string(dir.join(format!("{f}.liggghts"))).unwrap();
        assert_same(&ours, &theirs, f);
    }
    // Step 0, pair 1–2 (types 1 and 2, 300 and 400 K): the closed form from its area.
    let pair = snapshots(&std::fs::read_to_string(out_dir.join("dump.pair")).unwrap());
    let row = &pair[0][0];
    assert_eq!((row[0], row[1]), (1.0, 2.0));
    let expect = 4.0 * 10.0 * 20.0 / 30.0 * row[3].sqrt() * (400.0 - 300.0);
    assert!(
        (row[5] - expect).abs() < 1e-12 * expect,
        "{} vs {expect}",
        row[5]
    );
}

#[test]
fn heat_flux_without_heat_conduction_is_an_error() {
    let dir = data().join("heat_local");
    let script = std::fs::read_to_string(dir.join("in.heat_local"))
        .unwrap()
        .lines()
        .filter(|l| !l.contains("heat/gran") && !l.contains("Temp") && !l.contains("d3"))
        .map(|l| l.replace(" temperature 500", "") + "\n")
        .collect::<String>();
    let (_, out) = run(&script);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("heatFlux needs the heat flows of a fix heat/gran"),
        "{err}"
    );
}
