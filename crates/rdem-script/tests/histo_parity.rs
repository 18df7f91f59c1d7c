//! Parity of `fix ave/histo` with LIGGGHTS 3.8: tests/data/parity/item16.in, item17.in and
//! item18.in run in rdem, and their histogram files must equal LIGGGHTS' byte for byte
//! (itemN-K.liggghts.histo, made by regenerate.sh: `liggghts -in itemN.in -log none`,
//! its `itemN-K.histo` renamed), and their thermo rows (`f_ID[1..4]`) LIGGGHTS' (in
//! itemN.liggghts.txt) to 1e-6.

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/parity");

/// Runs item `n` with its histogram files in a scratch folder; returns the screen output
/// and the folder.
fn run_item(n: u32, files: u32) -> (String, std::path::PathBuf) {
    let read = |f: &str| std::fs::read_to_string(format!("{DIR}/{f}")).unwrap();
    let dir = std::env::temp_dir().join(format!("rdem-histo-{n}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut src = read(&format!("item{n}.in"))
        .replace("include head.in\n", &read("head.in"))
        .replace("include mat.in\n", &read("mat.in"));
    for k in 1..=files {
        let name = format!("item{n}-{k}.histo");
        src = src.replace(&name, &dir.join(&name).display().to_string());
    }
    (common::run_screen("item.in", &src), dir)
}

/// The thermo rows (lines of numbers after a `Step` header) of `out`.
fn thermo_rows(out: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut inside = false;
    for l in out.lines() {
        let first = l.split_whitespace().next();
        if first == Some("Step") {
            inside = true;
        } else if inside {
            match l
                .split_whitespace()
                .map(|w| w.parse::<f64>())
                .collect::<Result<Vec<_>, _>>()
            {
                Ok(r) if !r.is_empty() => rows.push(r),
                _ => inside = false,
            }
        }
    }
    rows
}

/// Runs item `n` and checks its `files` histogram files and its thermo rows.
fn check_item(n: u32, files: u32) {
    let (out, dir) = run_item(n, files);
    for k in 1..=files {
        let ours = std::fs::read_to_string(dir.join(format!("item{n}-{k}.histo"))).unwrap();
        let theirs = std::fs::read_to_string(format!("{DIR}/item{n}-{k}.liggghts.histo")).unwrap();
        assert_eq!(ours, theirs, "item{n}-{k}.histo differs from LIGGGHTS'");
    }
    let theirs =
        thermo_rows(&std::fs::read_to_string(format!("{DIR}/item{n}.liggghts.txt")).unwrap());
    let ours = thermo_rows(&out);
    assert_eq!(ours.len(), theirs.len(), "thermo rows:\n{out}");
    assert!(!ours.is_empty());
    for (r, l) in ours.iter().zip(&theirs) {
        assert_eq!(r.len(), l.len(), "{r:?} vs {l:?}");
        for (a, b) in r.iter().zip(l) {
            assert!(
                (a - b).abs() <= 1e-6 * b.abs().max(1e-12),
                "{r:?} vs LIGGGHTS {l:?}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// Item 16, mode vector of attributes: `x` of five particles over 5 samples (25 counts
/// per output: counts are summed, not averaged); `vx` of a group of three with `beyond
/// end` (−0.3 counted in the first bin, `hi` = 0.2 in the last); `v_xx x` with `beyond
/// extra` and `ave running` (7 bins, coordinates `lo` and `hi` for the extra ones,
/// counts 10, 20, 30, 40: sums; min 0 from the running start); `vx vz` with
/// `ave window 2` and three titles written as given (no `#`).
#[test]
fn vector_attributes_beyond_running_window() {
    check_item(16, 4);
}

/// Item 17, mode scalar: `v_s` (the step) over 3 samples, the value 250 on a bin
/// boundary goes into the upper bin; compute reduce elements, an equal variable and a
/// compute scalar with `ave running` (min 0); `ave running overwrite start 100` (one
/// block, 15 counts from step 100); mode vector of a global vector (`c_r`); window 3
/// with `start 60` (first output at 100; min over the window); two runs (no repeated
/// output at step 200).
#[test]
fn scalar_running_overwrite_start_window() {
    check_item(17, 5);
}

/// Item 18: `beyond ignore` (1 counted, 2 missing, left out of the total); an empty
/// group (0 counts, min 1e+20, max −1e+20, normalized 0); an atom-style variable with
/// `ave running` (max 0: the running max starts from 0); a per-atom compute (ke/atom).
#[test]
fn ignore_empty_group_atom_variable_compute() {
    check_item(18, 5);
}

/// Words LIGGGHTS 3.8 refuses stop with an error at the word (checked there:
/// `overwrite` without `ave running` is "Illegal fix ave/histo command", `x` without
/// `mode vector` "cannot input per-atom values in scalar mode").
#[test]
fn bad_words_are_located_errors() {
    let read = |f: &str| std::fs::read_to_string(format!("{DIR}/{f}")).unwrap();
    let src = read("item16.in")
        .replace("include head.in\n", &read("head.in"))
        .replace("include mat.in\n", &read("mat.in"));
    let setup = &src[..src.find("fix h1").unwrap()];
    for (line, word, expect) in [
        (
            "fix h all ave/histo 10 5 100 0 1 4 x mode vector overwrite",
            "overwrite",
            "needs ave running",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 x",
            "x",
            "needs mode vector",
        ),
        (
            "fix h all ave/histo 10 5 100 1 0 4 v_xx mode vector",
            "0",
            "must be above lo",
        ),
        (
            "fix h all ave/histo 10 11 100 0 1 4 x mode vector",
            "100",
            "Nfreq",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 x c_nope mode vector",
            "c_nope",
            "no compute 'nope'",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 x beyond far mode vector",
            "far",
            "ignore",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 x mode vector ave sliding",
            "sliding",
            "window",
        ),
    ] {
        let mut i = common::interpreter();
        let e = i
            .run_source("item.in", &format!("{setup}{line}\n"))
            .err()
            .unwrap_or_else(|| panic!("{line} ran"));
        let text = format!("{:?}", miette::Report::new(*e));
        assert!(text.contains(expect), "{line}: {text}");
        // The caret is under the word.
        let col = line.rfind(&format!(" {word}")).unwrap() + 2;
        let report = text.lines().find(|l| l.contains("item.in:")).unwrap_or("");
        assert!(
            report.ends_with(&format!(":{col}]")),
            "{line}: {report}\n{text}"
        );
    }
}
