//! LIGGGHTS-PFM's `fix remove` against the fork itself (ParticulateFlow/LIGGGHTS-PFM
//! d075b977, built here as `lmp_rdemref`), on `tests/data/remove/in.rm`: 300 spheres of
//! two sizes at rest on a lattice, removed in a region every 10 steps, in five settings:
//!
//! - `a`: `delete` at 2 kg/s, `compress no`; `b`: the same of type 1 only (`atomtype 1`,
//!   compress by default);
//! - `c`: `shrink` at 0.5 kg/s; `d`: `shrink` with `delete_below` (the small type deleted
//!   first) and `integrated_error no`; `e`: `shrink` at the rate of an equal-style
//!   variable (0.02·step kg/s).
//!
//! Measured: the shrink settings follow the fork bit for bit (the dumps' 12 digits and
//! the thermo's 15) at every removal step. `delete` draws particles at random with the
//! fork's generator and rule: the first removal step takes the fork's particles; later
//! ones draw from rdem's list in ID order where the fork's list is in its storage order,
//! which its deletions reorder, so `a` follows the fork's removed mass to step 40 and
//! then other particles (the same total at step 60: the integrated rate), and `b` (one
//! size) follows it at every step.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/remove")
}

/// The variables of each setting, as `-var` gave them to the fork.
fn setting(tag: &'static str) -> [(&'static str, &'static str); 5] {
    let (kw, rate, style, extra) = match tag {
        "a" => ("massrate", "2", "delete", "compress no"),
        "b" => ("massrate", "2", "delete", "atomtype 1"),
        "c" => (
            "massrate",
            "0.5",
            "shrink delete_below 0.002",
            "compress no",
        ),
        "d" => (
            "massrate",
            "3",
            "shrink delete_below 0.0037",
            "atomtype 1 integrated_error no",
        ),
        _ => (
            "massratevariable",
            "vr",
            "shrink delete_below 0.002",
            "compress no",
        ),
    };
    [
        ("tag", tag),
        ("ratekw", kw),
        ("rate", rate),
        ("style", style),
        ("extra", extra),
    ]
}

/// The script of a setting as one text (string variables quoted where they have spaces).
fn script(tag: &'static str) -> String {
    let vars: String = setting(tag)
        .iter()
        .map(|(k, v)| format!("variable {k} string \"{v}\"\n"))
        .collect();
    vars + &std::fs::read_to_string(data().join("in.rm")).unwrap()
}

/// rdem's thermo rows and dump rows (step first) of `text` run with `ranks` processes
/// and `threads` threads.
fn run_text(text: &str, ranks: Option<usize>, threads: &str) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let dir = common::scratch_dir("remove");
    std::fs::write(dir.join("in.test"), text).unwrap();
    let out = common::rdem_in(&dir, "in.test", ranks)
        .env("RDEM_THREADS", threads)
        .output()
        .unwrap();
    let screen = common::success("fix remove", &out);
    let tag = text
        .lines()
        .find_map(|l| l.strip_prefix("variable tag string \""))
        .unwrap()
        .trim_end_matches('"')
        .to_string();
    let dump = std::fs::read_to_string(dir.join(format!("d_{tag}.txt"))).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (
        common::thermo_rows(&screen),
        common::dump_rows_with_step(&dump),
    )
}

fn run(tag: &'static str) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    run_text(&script(tag), None, "1")
}

fn fork_thermo(tag: &str) -> Vec<Vec<f64>> {
    common::reference_rows(&data().join(format!("pfm_{tag}_thermo.txt")))
}

/// Dump rows (step id type x y z radius mass) without their IDs, ordered by step and
/// place: `compress yes` renumbers in rdem's ID order and in the fork's storage order.
fn by_place(rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut v: Vec<Vec<f64>> = rows.iter().map(|r| [&r[..1], &r[2..]].concat()).collect();
    v.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    v
}

/// Shrinking follows the fork at every removal step: radii, masses, the particles
/// deleted below `delete_below`, the removed mass; a variable rate is read at the
/// removal step.
#[test]
fn shrink_follows_the_fork() {
    for tag in ["c", "d", "e"] {
        let (thermo, dump) = run(tag);
        common::assert_columns(&thermo, &fork_thermo(tag), 1, 1e-13, tag);
        let want = common::reference_rows(&data().join(format!("pfm_{tag}.txt")));
        common::assert_columns(&by_place(&dump), &by_place(&want), 1, 1e-11, tag);
    }
    // c takes 0.5 kg/s · 1e-3 s at each of its six removal steps, exactly.
    let (thermo, _) = run("c");
    for r in &thermo {
        assert!((r[2] - 0.5 * r[0] * 1e-4).abs() < 1e-15, "{r:?}");
    }
}

/// Deleting: the fork's particles at the first removal step (counts and removed mass
/// to step 40 in `a`, every step in `b`); the integrated rate keeps the removed mass
/// within one particle of rate · time at every step.
#[test]
fn delete_follows_the_fork() {
    let (thermo, _) = run("a");
    let want = fork_thermo("a");
    common::assert_columns(&thermo[..5], &want[..5], 1, 1e-13, "a");
    // Type 1: 2500 kg/m³, 8 mm.
    let m1 = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.004f64.powi(3);
    for r in &thermo {
        let due = 2.0 * r[0] * 1e-4;
        assert!(r[2] >= due - 1e-6 && r[2] < due + m1, "{r:?}");
    }
    assert_eq!(thermo.last().unwrap()[1], want.last().unwrap()[1]);
    let (thermo, dump) = run("b");
    common::assert_columns(&thermo, &fork_thermo("b"), 1, 1e-13, "b");
    // compress yes: the IDs run 1..N at every dumped step.
    for step in [0.0, 30.0, 60.0] {
        let ids: Vec<f64> = dump.iter().filter(|r| r[0] == step).map(|r| r[1]).collect();
        assert!(
            ids.iter().enumerate().all(|(k, &id)| id == k as f64 + 1.0),
            "{step}"
        );
    }
}

/// The script of a setting with the lattice made by `create_atoms single`, one sphere
/// per line: the IDs are then the same on any number of ranks (`create_atoms region`
/// numbers them rank by rank, as LAMMPS does).
fn script_with_ids(tag: &'static str) -> String {
    let mut lines = String::new();
    for k in 0..3 {
        for j in 0..10 {
            for i in 0..10 {
                let (x, y, z) = (0.01 * i as f64, 0.01 * j as f64, 0.01 * k as f64);
                lines.push_str(&format!("create_atoms 1 single {x} {y} {z} units box\n"));
            }
        }
    }
    script(tag).replace("create_atoms 1 region fill\n", &lines)
}

/// The same removals on 2 threads and on 2 and 4 ranks: rdem draws from all ranks'
/// particles in ID order.
#[test]
fn removal_does_not_depend_on_ranks_or_threads() {
    for tag in ["a", "b"] {
        let text = script_with_ids(tag);
        let one = run_text(&text, None, "1");
        assert!(one.0.last().unwrap()[1] < 290.0, "{:?}", one.0);
        assert_eq!(run_text(&text, None, "2"), one, "{tag}: 2 threads");
        if common::have_mpirun() {
            for ranks in [2, 4] {
                let (thermo, dump) = run_text(&text, Some(ranks), "1");
                common::assert_columns(&thermo, &one.0, 0, 0.0, tag);
                assert_eq!(dump, one.1, "{tag}: {ranks} ranks");
            }
        }
    }
}

/// A restart between removal steps continues as the unbroken run (the generator, the
/// schedule and the integrated rate are kept; LIGGGHTS-PFM keeps the removed mass but
/// not the integrated rate, so after a restart it removes nothing until the rate has
/// integrated again all that was removed before); `restart_read no` starts afresh.
#[test]
fn restart_continues_the_removal() {
    let (thermo, dump) = run("a");
    let text = script("a");
    let first = text.replace("run 60", "run 35\nwrite_restart post/rm.restart");
    let second = text
        .replace(
            "create_box 2 reg",
            "read_restart post/rm.restart\nregion reg2 block 0 0.1 0 0.1 0 0.05 units box",
        )
        .replace("region reg block 0 0.1 0 0.1 0 0.05 units box\n", "")
        .replace("create_atoms 1 region fill\n", "")
        .replace("set region half type 2\n", "")
        .replace("set type 1 diameter 0.008 density 2500\n", "")
        .replace("set type 2 diameter 0.006 density 2500\n", "")
        .replace("run 60", "run 25");
    let dir = common::scratch_dir("remove_restart");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    std::fs::write(dir.join("in.first"), &first).unwrap();
    std::fs::write(dir.join("in.second"), &second).unwrap();
    let out = common::rdem_in(&dir, "in.first", None).output().unwrap();
    common::success("first half", &out);
    let out = common::rdem_in(&dir, "in.second", None).output().unwrap();
    let screen = common::success("second half", &out);
    let rows = common::thermo_rows(&screen);
    let dump2 = common::dump_rows_with_step(&std::fs::read_to_string(dir.join("d_a.txt")).unwrap());
    // The second half's rows (steps 40, 50, 60) are the unbroken run's.
    let common_rows: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] >= 40.0).collect();
    assert_eq!(common_rows.len(), 3, "{rows:?}");
    for r in common_rows {
        assert_eq!(Some(r), thermo.iter().find(|w| w[0] == r[0]));
    }
    let at60: Vec<&Vec<f64>> = dump.iter().filter(|r| r[0] == 60.0).collect();
    let got60: Vec<&Vec<f64>> = dump2.iter().filter(|r| r[0] == 60.0).collect();
    assert_eq!(got60, at60);
    // restart_read no: the removal starts afresh at the definition step (35): nothing
    // removed before step 45, and the removed mass counts from 0 (at step 50: two
    // removal steps' worth, 2 kg/s · 1e-3 s each, within a particle).
    let fresh = second.replace("compress no", "compress no restart_read no");
    std::fs::write(dir.join("in.fresh"), fresh).unwrap();
    let out = common::rdem_in(&dir, "in.fresh", None).output().unwrap();
    let rows = common::thermo_rows(&common::success("restart_read no", &out));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(rows[0][2], 0.0, "{rows:?}");
    let at50 = rows.iter().find(|r| r[0] == 50.0).unwrap();
    assert!(at50[2] >= 2e-3 - 1e-6 && at50[2] < 2e-3 + 7e-4, "{rows:?}");
    assert!(
        rows.iter().filter(|r| r[0] < 45.0).all(|r| r[2] == 0.0),
        "{rows:?}"
    );
}

/// `monitor_heat yes`: `f_ID[2]` is the heat of what was taken, m c T.
#[test]
fn monitor_heat_counts_m_c_t() {
    let text = script("c")
        .replace(
            "fix integr all nve/sphere",
            "fix m5 all property/global thermalConductivity peratomtype 1 1\n\
             fix m6 all property/global thermalCapacity peratomtype 800 900\n\
             fix heat all heat/gran initial_temperature 350\n\
             fix integr all nve/sphere",
        )
        .replace("compress no", "compress no monitor_heat yes")
        .replace(
            "variable m equal f_rm[1]",
            "variable m equal f_rm[1]\nvariable q equal f_rm[2]",
        )
        .replace("custom step atoms v_m", "custom step atoms v_m v_q");
    let (thermo, dump) = run_text(&text, None, "1");
    // Shrinking takes the same fraction of every eligible sphere (those in the region,
    // 0.02 <= x <= 0.08, at step 0): the heat is 350 K times the removed mass times
    // their mass-weighted capacity. Columns: step id type x y z radius mass.
    let (mut mc, mut m) = (0.0, 0.0);
    for r in dump
        .iter()
        .filter(|r| r[0] == 0.0 && r[3] >= 0.02 && r[3] <= 0.08)
    {
        mc += r[7] * if r[2] == 1.0 { 800.0 } else { 900.0 };
        m += r[7];
    }
    let c = mc / m;
    for r in &thermo {
        assert!(
            (r[3] - 350.0 * c * r[2]).abs() < 1e-6 * r[3].max(1e-12),
            "{r:?} {c}"
        );
    }
    assert!(thermo.last().unwrap()[3] > 0.0);
}

/// Located errors: the fork's fixed word order, an unknown keyword, a missing variable.
#[test]
fn errors_are_located() {
    let base = script("a");
    for (from, to, needle) in [
        ("nevery 10", "every 10", "nevery"),
        ("seed 1234567", "seeds 1234567", "seed"),
        (
            "region cut ${extra}",
            "region cut colour red",
            "fix remove keyword",
        ),
        (
            "region cut ${extra}",
            "region nowhere",
            "no region 'nowhere'",
        ),
    ] {
        let text = base.replace(from, to);
        let out = common::run_script_raw(&text, None);
        assert!(!out.status.success(), "{to}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(needle) && err.contains("in.test:"),
            "{to}: {err}"
        );
    }
    // Clumps are not supported yet: refused at the definition, or at the first removal
    // step when `fix multisphere` comes after.
    for (text, needle) in [
        (
            base.replace(
                "fix rm all remove",
                "fix ms all multisphere\nfix rm all remove",
            ),
            "fix remove with clumps",
        ),
        (
            base.replace(
                "variable m equal",
                "fix ms all multisphere\nvariable m equal",
            ),
            "removing clumps (fix multisphere)",
        ),
    ] {
        let out = common::run_script_raw(&text, None);
        assert!(!out.status.success(), "{needle}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let text = script("e").replace("variable vr equal 0.02*step\n", "");
    let out = common::run_script_raw(&text, None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no variable 'vr'"), "{err}");
}
