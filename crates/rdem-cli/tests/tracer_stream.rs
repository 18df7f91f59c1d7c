//! `fix property/atom/tracer/stream` (LIGGGHTS 3.8) against LIGGGHTS 3.8 itself, on
//! `tests/data/tracer_stream/in.ts`: 500 small spheres per packet every 500 steps through
//! a square face, and a tracer marking `n_tracer` of them from `mark_step` on. LIGGGHTS
//! printed, every 500 steps, how many were marked since the last print (`f_tracer`):
//!
//! - mark_step 600, n_tracer 7, every 300: 7 7 14 7 0 0 (windows 600, 900, 1200 and 1500
//!   together, 1800; 2100 never: it starts after the last packet's next step);
//! - mark_step 1001, n_tracer 5, every 250: 0 5 5 5 0 0 (1001, 1251, 1751; 1501 and 2001
//!   skipped: a window at a packet's own step or past the next packet's is not taken);
//! - mark_step 20, n_tracer 3, once: 3 0 0 0 0 0.
//!
//! rdem's insertion draws differ from LIGGGHTS', so the particles differ, but the counts
//! do not: rdem prints the same lines, and the particles it marks are, in each window, the
//! first of their packet to be released at or after the window's start.

use crate::common;

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tracer_stream")
}

fn script(ms: &str, nt: &str, ev: &str) -> String {
    common::index_vars(&[("ms", ms), ("nt", nt), ("ev", ev)])
        + &std::fs::read_to_string(data().join("in.ts")).unwrap()
}

fn face() -> String {
    std::fs::read_to_string(data().join("face.stl")).unwrap()
}

/// The `marked STEP N` lines of a run's screen.
fn marked_lines(out: &str) -> Vec<(u64, u64)> {
    out.lines()
        .filter_map(|l| l.strip_prefix("marked "))
        .map(|l| {
            let mut w = l.split_whitespace().map(|x| x.parse().unwrap());
            (w.next().unwrap(), w.next().unwrap())
        })
        .collect()
}

/// Per particle ID: (the step of the packet that brought it, its release step, marked).
fn particles(dir: &Path) -> HashMap<u64, (u64, u64, bool)> {
    let mut all = HashMap::new();
    for step in (100..=3000).step_by(100) {
        let text = std::fs::read_to_string(dir.join(format!("post/dump{step}.t"))).unwrap();
        for (_, rows) in common::dump_frames(&text) {
            for r in rows {
                // Packets come at steps 1, 501, ...: first seen in the dump 99 steps on.
                let e = all
                    .entry(r[0] as u64)
                    .or_insert((step - 99, r[5] as u64, false));
                e.2 |= r[4] != 0.0;
            }
        }
    }
    all
}

const CASES: [(&str, &str, &str, [u64; 6]); 3] = [
    ("600", "7", "300", [7, 7, 14, 7, 0, 0]),
    ("1001", "5", "250", [0, 5, 5, 5, 0, 0]),
    ("20", "3", "once", [3, 0, 0, 0, 0, 0]),
];

#[test]
fn counts_and_windows_as_liggghts() {
    for (ms, nt, ev, want) in CASES {
        let what = format!("mark_step {ms} n_tracer {nt} every {ev}");
        let (dir, out) = common::run_kept_ok(
            "tracer_stream",
            &script(ms, nt, ev),
            &[("face.stl", &face())],
            None,
        );
        let lines = marked_lines(&out);
        let steps: Vec<u64> = (1..=6).map(|k| 500 * k).collect();
        assert_eq!(
            lines.iter().map(|l| l.0).collect::<Vec<_>>(),
            steps,
            "{what}"
        );
        assert_eq!(
            lines.iter().map(|l| l.1).collect::<Vec<_>>(),
            want,
            "{what}"
        );
        // Each marked particle belongs to the latest window started at or before its
        // release; within its packet no unmarked particle was released in that window
        // before it (ties aside).
        let all = particles(&dir);
        let _ = std::fs::remove_dir_all(&dir);
        let (ms, nt): (u64, u64) = (ms.parse().unwrap(), nt.parse().unwrap());
        let every = ev.parse::<u64>().unwrap_or(u64::MAX / 4);
        let window = |r: u64| ms + (r - ms) / every * every;
        let mut per_window: BTreeMap<u64, Vec<(u64, u64)>> = BTreeMap::new();
        for (&id, &(packet, release, marked)) in &all {
            if marked {
                assert!(release >= ms, "{what}: {id} released at {release}");
                per_window
                    .entry(window(release))
                    .or_default()
                    .push((packet, release));
            }
        }
        for (w, marks) in &per_window {
            assert_eq!(marks.len() as u64, nt, "{what}: window {w}: {marks:?}");
            let packet = marks[0].0;
            assert!(marks.iter().all(|m| m.0 == packet), "{what}: {marks:?}");
            let last = marks.iter().map(|m| m.1).max().unwrap();
            let skipped = all
                .values()
                .filter(|p| p.0 == packet && !p.2 && p.1 >= *w && p.1 < last)
                .count();
            assert_eq!(skipped, 0, "{what}: window {w}");
        }
    }
}

/// On 2 MPI ranks (the release steps gathered from both) the counts are the same.
#[cfg(feature = "mpi")]
#[test]
fn two_ranks_mark_as_many() {
    if !common::have_mpirun() {
        return;
    }
    let (ms, nt, ev, want) = CASES[0];
    let s = script(ms, nt, ev).replace("boundary m m m", "boundary m m m\nprocessors 2 1 1");
    let (dir, out) =
        common::run_kept_ok("tracer_stream_mpi", &s, &[("face.stl", &face())], Some(2));
    let _ = std::fs::remove_dir_all(&dir);
    let got: Vec<u64> = marked_lines(&out).iter().map(|l| l.1).collect();
    assert_eq!(got, want);
}

/// A restart written at step 1000 (just after a print) and read back keeps the pending
/// windows: with n_tracer 300 a window takes parts of two packets, and the rest of the
/// run marks as the whole run did.
#[test]
fn a_restart_keeps_the_windows() {
    let whole = script("600", "300", "300");
    let d = common::scratch_dir("tracer-stream-restart");
    std::fs::write(d.join("face.stl"), face()).unwrap();
    std::fs::create_dir_all(d.join("post")).unwrap();
    std::fs::write(d.join("in.whole"), &whole).unwrap();
    let out = common::success(
        "whole",
        &common::rdem_in(&d, "in.whole", None).output().unwrap(),
    );
    let all: Vec<u64> = marked_lines(&out).iter().map(|l| l.1).collect();
    let first: String = whole
        .lines()
        .filter(|l| !l.starts_with("dump"))
        .map(|l| format!("{l}\n"))
        .collect::<String>()
        .replace("run 3000", "run 1000\nwrite_restart ts.restart");
    std::fs::write(d.join("in.first"), &first).unwrap();
    common::success(
        "first",
        &common::rdem_in(&d, "in.first", None).output().unwrap(),
    );
    let second: String = whole
        .lines()
        .map(|l| match l {
            "create_box 1 reg" => "read_restart ts.restart\n".to_string(),
            "run 3000" => "run 2000\n".to_string(),
            l if l.starts_with("dump") => String::new(),
            l => format!("{l}\n"),
        })
        .collect();
    std::fs::write(d.join("in.second"), &second).unwrap();
    let out = common::success(
        "second",
        &common::rdem_in(&d, "in.second", None).output().unwrap(),
    );
    let _ = std::fs::remove_dir_all(&d);
    let got: Vec<u64> = marked_lines(&out).iter().map(|l| l.1).collect();
    // Prints at 1500 ... 3000. (Without the windows restored the counts differ: checked.)
    assert_eq!(got, all[2..]);
    assert!(got.iter().sum::<u64>() > 0, "{all:?}");
}

#[test]
fn bad_definitions_are_located_errors() {
    for (from, to, says) in [
        (
            "insert_stream ins",
            "insert_stream integr",
            "no fix insert/stream 'integr'",
        ),
        ("every ${ev}", "", "needs"),
        ("every ${ev}", "every 0", "every"),
        (
            "f_release_fix_insert_stream[5]",
            "f_release_fix_insert_stream[3]",
            "column 5",
        ),
    ] {
        let s = script("600", "7", "300").replace(from, to);
        let (dir, out) = common::run_kept("tracer_stream_err", &s, &[("face.stl", &face())], None);
        let _ = std::fs::remove_dir_all(&dir);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{to}");
        assert!(
            err.contains(says) && err.contains("in.test:"),
            "{to}: {err}"
        );
    }
}
