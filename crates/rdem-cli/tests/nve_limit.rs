//! `fix nve/limit absolute|radius_ratio xmax` (stock LIGGGHTS 3.8): velocity Verlet for
//! translation with the speed capped at xmax/dt (xmax·r/dt). `tests/data/nve_limit/in.limit`
//! pushes three overlapped spheres apart (Hertz with friction, so that torques act on
//! spins the fix leaves alone); LIGGGHTS 3.8 ran it with both styles
//! (`liggghts_absolute.txt`: `-var style absolute -var xmax 1e-5`;
//! `liggghts_radius_ratio.txt`: `-var style radius_ratio -var xmax 2e-3`). rdem's dumps
//! agree within 1e-12 of each column's scale (measured: 1.6e-15 and 4.4e-14), and its
//! counts of velocity resets (`f_lim`) are LIGGGHTS' exactly, back at 0 in the second run.

use std::path::{Path, PathBuf};

use crate::common;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/nve_limit")
}

/// The frames of a dump (rows sorted by id), flattened.
fn frames(text: &str) -> Vec<Vec<f64>> {
    common::dump_frames(text)
        .into_iter()
        .flat_map(|(_, mut rows)| {
            rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
            rows
        })
        .collect()
}

fn check(style: &str, xmax: &str, counts: &[f64]) {
    let script = std::fs::read_to_string(data().join("in.limit")).unwrap();
    let dir = common::scratch_dir("nve-limit");
    std::fs::write(dir.join("in.limit"), script).unwrap();
    let out = common::rdem_in(&dir, "in.limit", None)
        .args(["-var", "style", style, "-var", "xmax", xmax])
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    let text = common::success("nve/limit", &out);
    let got = frames(&std::fs::read_to_string(dir.join(format!("d_{style}.txt"))).unwrap());
    let want =
        frames(&std::fs::read_to_string(data().join(format!("liggghts_{style}.txt"))).unwrap());
    assert_eq!(got.len(), want.len(), "{style}: rows");
    assert!(!want.is_empty());
    common::assert_columns(&got, &want, 1, 1e-12, style);
    // The moving spheres reached the cap and kept their spins (no torque integration).
    let resets: Vec<f64> = common::thermo_rows(&text).iter().map(|r| r[1]).collect();
    assert_eq!(resets, counts, "{style}: resets\n{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn nve_limit_caps_the_speed_as_liggghts() {
    // Thermo every 100 steps over `run 500` and `run 1000` (LIGGGHTS' columns step, f_lim).
    let second = [0.0; 11];
    let mut a = vec![0.0, 593.0, 1193.0, 1793.0, 2310.0, 2568.0];
    a.extend(second);
    check("absolute", "1e-5", &a);
    let mut r = vec![0.0, 585.0, 1185.0, 1354.0, 1354.0, 1354.0];
    r.extend(second);
    check("radius_ratio", "2e-3", &r);
}

#[test]
fn nve_limit_names_its_styles() {
    let out = common::run_script_raw(
        "region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\nfix lim all nve/limit 0.1\n",
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("absolute") && err.contains("radius_ratio"),
        "{err}"
    );
}
