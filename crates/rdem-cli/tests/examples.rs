//! The scripts in `examples/` run to completion with the `rdem` binary and leave the files
//! they promise: a VTK series whose last snapshot holds every particle, and what each
//! script prints at its end (checked against what the physics allows).

use std::path::Path;

use crate::common;

/// Runs `examples/<dir>/<file>` in a temporary copy; returns (stdout, the copy's path).
fn run(dir: &str, file: &str) -> (String, std::path::PathBuf) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(dir);
    let tmp = common::scratch_dir(&format!("example-{dir}"));
    std::fs::copy(src.join(file), tmp.join(file)).unwrap();
    let out = common::rdem_in(&tmp, file, None).output().unwrap();
    let stdout = common::success(&format!("{dir}/{file}"), &out);
    (stdout, tmp)
}

/// Number of points in the VTK file of the latest step of `post/<prefix>*.vtk`.
fn last_vtk_points(dir: &Path, prefix: &str) -> (u64, usize) {
    let mut files: Vec<(u64, std::path::PathBuf)> = std::fs::read_dir(dir.join("post"))
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            let n = p.file_name()?.to_str()?.to_string();
            let step = n.strip_prefix(prefix)?.strip_suffix(".vtk")?.parse().ok()?;
            Some((step, p))
        })
        .collect();
    files.sort();
    let (step, path) = files.last().expect("a VTK snapshot").clone();
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        text.starts_with("# vtk DataFile Version"),
        "not a legacy VTK file"
    );
    let n = text
        .lines()
        .find_map(|l| l.strip_prefix("POINTS "))
        .and_then(|l| l.split_whitespace().next()?.parse().ok())
        .expect("POINTS line");
    (step, n)
}

fn printed(stdout: &str, prefix: &str) -> Vec<f64> {
    let line = stdout
        .lines()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting '{prefix}'"));
    line.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter_map(|w| w.parse().ok())
        .collect()
}

/// The pour: all 2500 beads arrive, the pile's top is below the inlet and above a single
/// layer of the largest beads.
#[test]
fn pour() {
    let (out, dir) = run("pour", "in.pour");
    let v = printed(&out, "poured");
    assert_eq!(v[0], 2500.0, "{out}");
    assert!(v[1] > 0.0044 && v[1] < 0.09, "pile top {}", v[1]);
    assert_eq!(last_vtk_points(&dir, "pour_"), (30000, 2500));
    let _ = std::fs::remove_dir_all(dir);
}

/// The settling column: the particles come to rest (kinetic energy tiny), at a mean height
/// no lower than a radius and with a few contacts per particle.
#[test]
fn settling_cylinder() {
    let (out, dir) = run("settling_cylinder", "in.settle");
    let v = printed(&out, "settled");
    assert!(v[0] > 0.0012 && v[0] < 0.05, "mean height {}", v[0]);
    assert!(v[1] > 2.0 && v[1] < 12.0, "contacts per particle {}", v[1]);
    let (step, n) = last_vtk_points(&dir, "settle_");
    assert_eq!(step, 30000);
    assert!(n > 1000, "{n} particles in the last snapshot");
    let text = std::fs::read_to_string(dir.join("height.txt")).unwrap();
    assert_eq!(text.lines().filter(|l| !l.starts_with('#')).count(), 30);
    let _ = std::fs::remove_dir_all(dir);
}

/// Growth packing: the packing fraction rises stage by stage to a dense random packing
/// (frictionless spheres jam near 0.64; the flat walls keep it below that).
#[test]
fn growth_packing() {
    let (out, dir) = run("growth_packing", "in.grow");
    let stages: Vec<f64> = out
        .lines()
        .filter(|l| l.starts_with("stage "))
        .map(|l| *printed(l, "stage").last().unwrap())
        .collect();
    assert_eq!(stages.len(), 3, "{out}");
    assert!(stages.windows(2).all(|w| w[1] > w[0]), "{stages:?}");
    let fin = printed(&out, "final packing fraction")[0];
    assert!(fin > 0.55 && fin < 0.66, "final packing fraction {fin}");
    let (_, n) = last_vtk_points(&dir, "grow_");
    assert!(n > 1000);
    let _ = std::fs::remove_dir_all(dir);
}

/// The bonded agglomerate: all 1176 nearest-neighbour pairs of the 461-sphere ball are
/// bonded at step 1, the impact breaks a part of them (at 5 m/s about 30 %; between 5 %
/// and 95 % here), and the last snapshot colours every particle by its intact bonds:
/// the field `c_nb` sums to twice the intact pair bonds printed at the end.
#[test]
fn bonded_agglomerate() {
    let (out, dir) = run("bonded_agglomerate", "in.agglomerate");
    let intact = printed(&out, "intact pair bonds at the end:")[0];
    assert!(intact > 0.05 * 1176.0 && intact < 0.95 * 1176.0, "{out}");
    assert!(out.contains("1176"), "all bonds created: {out}");
    assert_eq!(last_vtk_points(&dir, "agglomerate_"), (15000, 461));
    let text = std::fs::read_to_string(dir.join("post/agglomerate_15000.vtk")).unwrap();
    let mut lines = text.lines().skip_while(|l| !l.starts_with("c_nb "));
    assert!(lines.next().is_some(), "no c_nb field");
    let nb: Vec<f64> = lines
        .take_while(|l| !l.chars().next().is_some_and(|c| c.is_alphabetic()))
        .flat_map(|l| l.split_whitespace().map(|w| w.parse::<f64>().unwrap()))
        .collect();
    assert_eq!(nb.len(), 461);
    assert_eq!(nb.iter().sum::<f64>(), 2.0 * intact);
    let _ = std::fs::remove_dir_all(dir);
}
