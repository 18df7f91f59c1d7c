//! `modify_timing on|verbose` (LIGGGHTS 3.8): after a run, each fix's time as LIGGGHTS
//! prints it (`Fix ID style time (%) = t (pct)`, the Modify line as `Modfy`; `verbose`
//! adds each rank's), measured while the post-force fixes act one at a time. Acting one
//! at a time must not change a single bit of the trajectory.

use crate::common;

use std::path::Path;

/// `fix momentum`'s five colliding spheres (tests/data/momentum/in.mom, N 3), with a
/// primitive wall and a viscous drag among the post-force fixes, and `timing` before
/// the run.
fn script(timing: &str) -> String {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/momentum/in.mom"),
    )
    .unwrap();
    let text = text.replace(
        "fix integr all nve/sphere",
        "fix visc all viscous 0.0001\nfix wall all wall/gran model hertz tangential history primitive type 1 zplane 0.024\nfix integr all nve/sphere",
    );
    let text = text.replace("run 6000", &format!("{timing}\nrun 6000"));
    common::index_vars(&[
        ("every", "3"),
        ("lx", "1"),
        ("ly", "0"),
        ("lz", "1"),
        ("ang", "angular"),
        ("tn", "x"),
    ]) + &text
}

fn run(timing: &str, ranks: Option<usize>) -> (String, String) {
    let (dir, out) = common::run_kept_ok("modify_timing", &script(timing), &[], ranks);
    let dump = std::fs::read_to_string(dir.join("d_x.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (out, dump)
}

/// The time of each `Fix ID style time (%) = t (pct)` line, in order.
fn fix_lines(out: &str) -> Vec<(String, f64, f64)> {
    out.lines()
        .filter(|l| l.starts_with("Fix ") && l.contains(" time (%) = "))
        .map(|l| {
            let (head, rest) = l.split_once(" time (%) = ").unwrap();
            let (t, pct) = rest.split_once(" (").unwrap();
            (
                head.to_string(),
                t.parse().unwrap(),
                pct.trim_end_matches(')').parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn each_fix_is_timed_and_the_trajectory_is_the_same() {
    let (plain, plain_dump) = run("", None);
    assert!(plain.contains("Modify time (%)"), "{plain}");
    assert!(fix_lines(&plain).is_empty(), "{plain}");
    let (out, dump) = run("modify_timing on", None);
    assert_eq!(dump, plain_dump, "modify_timing changed the trajectory");
    assert!(out.contains("Modfy time (%) = "), "{out}");
    let lines = fix_lines(&out);
    let names: Vec<&str> = lines.iter().map(|l| l.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "Fix m1 property/global",
            "Fix m2 property/global",
            "Fix m3 property/global",
            "Fix m4 property/global",
            "Fix gr gravity",
            "Fix visc viscous",
            "Fix wall wall/gran",
            "Fix integr nve/sphere",
            "Fix mom momentum",
        ],
        "{out}"
    );
    let modify: f64 = out
        .lines()
        .find_map(|l| l.strip_prefix("Modfy time (%) = "))
        .and_then(|r| r.split_whitespace().next())
        .unwrap()
        .parse()
        .unwrap();
    for (name, t, pct) in &lines {
        assert!(
            *t >= 0.0 && *pct >= 0.0 && *pct <= 100.0,
            "{name}: {t} {pct}"
        );
    }
    // The fixes that act every step took some time, within the Modify stage.
    for (name, t, _) in &lines[4..] {
        assert!(*t > 0.0, "{name}: {out}");
    }
    let sum: f64 = lines.iter().map(|l| l.1).sum();
    assert!(
        sum <= modify * 1.0001 + 1e-6,
        "fixes {sum} s, Modify {modify} s"
    );
}

#[cfg(feature = "mpi")]
#[test]
fn verbose_gives_each_rank() {
    if !common::have_mpirun() {
        return;
    }
    let (_, serial) = run("", None);
    let (out, dump) = run("modify_timing verbose", Some(2));
    let (_, plain) = run("", Some(2));
    assert_eq!(
        dump, plain,
        "modify_timing changed the trajectory on 2 ranks"
    );
    assert_eq!(
        common::dump_frames(&dump).len(),
        common::dump_frames(&serial).len()
    );
    for r in 0..2 {
        assert!(
            out.contains(&format!("  Modify   time [{r}] (%) = ")),
            "{out}"
        );
        assert!(
            out.contains(&format!("  [{r}] Fix mom momentum time ")),
            "{out}"
        );
    }
}

#[test]
fn a_wrong_setting_is_a_located_error() {
    let out = common::run_script_raw("modify_timing maybe\n", None);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("unknown modify_timing 'maybe'"), "{err}");
    assert!(err.contains("'verbose'"), "{err}");
    assert!(err.contains("in.test:1"), "{err}");
}
