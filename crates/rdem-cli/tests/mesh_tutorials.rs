//! The mesh tutorial cases of liggghts-doc (meshGran, conveyor, insert_stream,
//! chute_wear, movingMeshGran) run unmodified by the `rdem` binary and end with the
//! particle count LIGGGHTS 3.8 ends with, within 5 %.
//!
//! The LIGGGHTS figures are the last rows of `tests/data/mesh_tutorials/<case>.log`, the
//! screen output of LIGGGHTS 3.8 running the tutorial followed by `include stats.in`
//! (`regenerate.sh` there has the exact commands). rdem runs the same wrapper on a
//! temporary copy of the tutorial directory.

use std::path::{Path, PathBuf};

use crate::common;
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
/// files it wrote under `post/` (name and, for `keep`, contents).
fn run(case: &str, keep: &str) -> (String, Vec<(String, String)>) {
    let src = Path::new(TUTORIALS).join(case);
    let file = format!("in.{case}");
    assert!(
        src.join(&file).exists(),
        "{} is missing: install the liggghts-doc package (scripts/test.sh does)",
        src.join(&file).display()
    );
    let tmp = common::scratch_dir(&format!("mesh-tutorial-{case}"));
    copy_dir(&src, &tmp);
    let _ = std::fs::remove_dir_all(tmp.join("post"));
    std::fs::create_dir_all(tmp.join("post")).unwrap();
    std::fs::copy(data().join("stats.in"), tmp.join("stats.in")).unwrap();
    std::fs::write(
        tmp.join("wrapper.in"),
        format!("include {file}\ninclude stats.in\n"),
    )
    .unwrap();
    let out = common::rdem_in(&tmp, "wrapper.in", None).output().unwrap();
    let stdout = common::success(&format!("{case} failed"), &out);
    let mut files: Vec<(String, String)> = std::fs::read_dir(tmp.join("post"))
        .unwrap()
        .map(|e| {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            let text = if name == keep {
                std::fs::read_to_string(tmp.join("post").join(&name)).unwrap()
            } else {
                String::new()
            };
            (name, text)
        })
        .collect();
    files.sort();
    let _ = std::fs::remove_dir_all(&tmp);
    (stdout, files)
}

/// Runs `case` and checks its final step and particle count against LIGGGHTS'.
fn check(case: &str, keep: &str) -> (String, Vec<(String, String)>) {
    let lig = std::fs::read_to_string(data().join(format!("{case}.log"))).unwrap();
    let (lig_step, lig_atoms, lig_z) = stats_row(&lig);
    let (out, files) = run(case, keep);
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
    check("conveyor", "");
}

#[test]
fn insert_stream() {
    let (out, _) = check("insert_stream", "");
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
    let (_, files) = check("meshGran", "");
    assert!(files.iter().any(|f| f.0.ends_with(".stl")), "{files:?}");
}

#[test]
fn moving_mesh_gran() {
    let (_, files) = check("movingMeshGran", "");
    assert!(files.iter().any(|f| f.0.ends_with(".stl")), "{files:?}");
}

/// Triangle centroids and one cell array of a legacy VTK mesh file (as dump mesh/vtk
/// and LIGGGHTS write it: three points per triangle).
fn mesh_field(text: &str, name: &str) -> (Vec<[f64; 3]>, Vec<f64>) {
    let lines: Vec<&str> = text.lines().collect();
    let numbers = |from: usize, count: usize| -> Vec<f64> {
        lines[from..]
            .iter()
            .flat_map(|l| l.split_whitespace().map(|w| w.parse::<f64>().unwrap()))
            .take(count)
            .collect()
    };
    let p = lines.iter().position(|l| l.starts_with("POINTS")).unwrap();
    let np: usize = lines[p].split_whitespace().nth(1).unwrap().parse().unwrap();
    let pts = numbers(p + 1, 3 * np);
    let cent = pts
        .chunks(9)
        .map(|c| [0, 1, 2].map(|a| (c[a] + c[3 + a] + c[6 + a]) / 3.0))
        .collect();
    let f = lines
        .iter()
        .position(|l| l.starts_with(&format!("{name} ")))
        .unwrap_or_else(|| panic!("no array {name}"));
    (cent, numbers(f + 1, np / 3))
}

/// The wear-weighted centroid and the mean centroid of the ten most worn triangles.
fn wear_figures(cent: &[[f64; 3]], wear: &[f64]) -> (f64, [f64; 3], [f64; 3]) {
    let total: f64 = wear.iter().sum();
    let centroid =
        [0, 1, 2].map(|a| cent.iter().zip(wear).map(|(c, w)| c[a] * w).sum::<f64>() / total);
    let mut order: Vec<usize> = (0..wear.len()).collect();
    order.sort_by(|&a, &b| wear[b].total_cmp(&wear[a]));
    let top = [0, 1, 2].map(|a| order[..10].iter().map(|&t| cent[t][a]).sum::<f64>() / 10.0);
    (total, centroid, top)
}

/// chute_wear: the particle count, and the wear where LIGGGHTS puts it. LIGGGHTS' last
/// wear dump (`data/mesh_tutorials/chute_wear_wear.txt`) has its wear-weighted centroid
/// at (-0.0645, 0.0021, -0.1334) and its ten most worn triangles around
/// (-0.018, -0.004, -0.115): the stream's impact zone. rdem's must be within 1 cm and
/// 2 cm of those, and the total wear within 10 %.
#[test]
fn chute_wear() {
    let (_, files) = check("chute_wear", "mesh_100000.vtk");
    let text = &files
        .iter()
        .find(|f| f.0 == "mesh_100000.vtk")
        .expect("the last wear dump")
        .1;
    let (cent, wear) = mesh_field(text, "wear");
    assert_eq!(cent.len(), 1616);
    let (total, centroid, top) = wear_figures(&cent, &wear);
    let reference = std::fs::read_to_string(data().join("chute_wear_wear.txt")).unwrap();
    let nums = |prefix: &str| -> Vec<Vec<f64>> {
        reference
            .lines()
            .filter_map(|l| l.strip_prefix(prefix))
            .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
            .collect()
    };
    let lig_total = nums("total ")[0][0];
    let lig_centroid = &nums("centroid ")[0];
    let lig_top: Vec<f64> = (0..3)
        .map(|a| nums("top ").iter().map(|r| r[2 + a]).sum::<f64>() / 10.0)
        .collect();
    let dist = |a: &[f64], b: &[f64]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    eprintln!(
        "chute_wear: total wear {total:.1} (LIGGGHTS {lig_total:.1}), centroid {centroid:?} \
         (LIGGGHTS {lig_centroid:?}), ten most worn around {top:?} (LIGGGHTS {lig_top:?})"
    );
    assert!(
        (total / lig_total - 1.0).abs() < 0.10,
        "total wear {total} vs {lig_total}"
    );
    assert!(
        dist(&centroid, lig_centroid) < 0.01,
        "{centroid:?} vs {lig_centroid:?}"
    );
    assert!(dist(&top, &lig_top) < 0.02, "{top:?} vs {lig_top:?}");
}
