//! The mesh tutorial cases of liggghts-doc (meshGran, conveyor, insert_stream,
//! chute_wear, movingMeshGran) run unmodified by the `rdem` binary and end with the
//! particle count LIGGGHTS 3.8 ends with, within 5 %.
//!
//! The LIGGGHTS figures are the last rows of `tests/data/mesh_tutorials/<case>.log`, the
//! screen output of LIGGGHTS 3.8 running the tutorial followed by `include stats.in`
//! (`regenerate.sh` there has the exact commands). rdem runs the same wrapper on a
//! temporary copy of the tutorial directory.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::copy_dir;

const TUTORIALS: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public";
/// Largest allowed relative difference of the final particle counts.
const TOLERANCE: f64 = 0.05;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mesh_tutorials")
}

/// (step, atoms, mean z) of the stats row of a screen output.
fn stats_row(out: &str) -> (u64, u64, f64) {
    let lines: Vec<&str> = out.lines().collect();
    let h = lines
        .iter()
        .rposition(|l| l.contains("rdemZave"))
        .expect("stats header");
    let w: Vec<&str> = lines[h + 1].split_whitespace().collect();
    (
        w[0].parse().unwrap(),
        w[1].parse().unwrap(),
        w[2].parse().unwrap(),
    )
}

/// Runs the tutorial `case` (file `in.<case>`) and returns its screen output and the
/// files it wrote under `post/`.
fn run(case: &str) -> (String, Vec<String>) {
    let src = Path::new(TUTORIALS).join(case);
    let file = format!("in.{case}");
    assert!(
        src.join(&file).exists(),
        "{} is missing: install the liggghts-doc package (scripts/test.sh does)",
        src.join(&file).display()
    );
    let tmp =
        std::env::temp_dir().join(format!("rdem-mesh-tutorial-{case}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    copy_dir(&src, &tmp);
    let _ = std::fs::remove_dir_all(tmp.join("post"));
    std::fs::create_dir_all(tmp.join("post")).unwrap();
    std::fs::copy(data().join("stats.in"), tmp.join("stats.in")).unwrap();
    std::fs::write(
        tmp.join("wrapper.in"),
        format!("include {file}\ninclude stats.in\n"),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rdem"))
        .args(["-in", "wrapper.in", "-log", "none"])
        .current_dir(&tmp)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{case} failed:\n{}\n{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut files: Vec<String> = std::fs::read_dir(tmp.join("post"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let _ = std::fs::remove_dir_all(&tmp);
    (stdout, files)
}

/// Runs `case` and checks its final step and particle count against LIGGGHTS'.
fn check(case: &str) -> (String, Vec<String>) {
    let lig = std::fs::read_to_string(data().join(format!("{case}.log"))).unwrap();
    let (lig_step, lig_atoms, lig_z) = stats_row(&lig);
    let (out, files) = run(case);
    let (step, atoms, z) = stats_row(&out);
    assert_eq!(step, lig_step, "{case}: final step");
    let rel = (atoms as f64 - lig_atoms as f64).abs() / lig_atoms as f64;
    eprintln!(
        "{case}: {atoms} particles (LIGGGHTS {lig_atoms}, {:+.2} %), mean height {z:.5} (LIGGGHTS {lig_z:.5})",
        100.0 * (atoms as f64 / lig_atoms as f64 - 1.0)
    );
    assert!(
        rel <= TOLERANCE,
        "{case}: {atoms} particles at the end, LIGGGHTS {lig_atoms}"
    );
    (out, files)
}

#[test]
fn conveyor() {
    check("conveyor");
}

#[test]
fn insert_stream() {
    let (out, _) = check("insert_stream");
    // Packets of 300 at steps 1, 30001, 60001 and 90001, as LIGGGHTS inserts them.
    let packets: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("INFO: Particle insertion ins: inserted"))
        .collect();
    assert_eq!(packets.len(), 4, "{packets:?}");
    assert!(
        packets.iter().all(|l| l.contains("inserted 300 ")),
        "{packets:?}"
    );
}

#[test]
fn mesh_gran() {
    let (_, files) = check("meshGran");
    assert!(files.iter().any(|f| f.ends_with(".stl")), "{files:?}");
}

#[test]
fn moving_mesh_gran() {
    let (_, files) = check("movingMeshGran");
    assert!(files.iter().any(|f| f.ends_with(".stl")), "{files:?}");
}

#[test]
fn chute_wear() {
    check("chute_wear");
}
