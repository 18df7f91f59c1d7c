//! The `rdem` binary on bad scripts: a few fixtures of the parser error suite
//! (`crates/rdem-script/tests/data/errors`) copied to a temporary directory and run with
//! `rdem -in in.NAME -log none` stop with exit code 1 and the report on standard error
//! (file:line:col, the message, never a panic); a missing script, a bad option, `--help`
//! and `--version` exit as documented.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common;

fn fixture_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rdem-script/tests/data/errors")
}

fn run(dir: &Path, args: &[&str]) -> Output {
    common::rdem_command(None)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run rdem")
}

/// The value of `# expect-KEY: value` in a fixture header.
fn expect<'a>(src: &'a str, key: &str) -> &'a str {
    let tag = format!("# expect-{key}:");
    src.lines()
        .find_map(|l| l.strip_prefix(&tag))
        .map(str::trim)
        .unwrap_or_else(|| panic!("fixture has no {tag}"))
}

/// Text with white space and the report's gutter bars removed, so that a message that
/// miette wrapped at the terminal width still compares equal.
fn squeeze(s: &str) -> String {
    s.chars()
        .filter(|c| !c.is_whitespace() && *c != '│')
        .collect()
}

#[test]
fn bad_scripts_exit_1_with_the_report_on_stderr() {
    let dir = common::scratch_dir("cli-errors-fixtures");
    for stem in [
        "001_units_lj",
        "027_pair_order",
        "082_jump_missing_label",
        "086_fix_style",
        "109_run_particle_lost",
    ] {
        let src =
            std::fs::read_to_string(fixture_dir().join(format!("{stem}.in"))).expect("fixture");
        let name = format!("in.{stem}");
        std::fs::write(dir.join(&name), &src).unwrap();
        let out = run(&dir, &["-in", &name, "-log", "none"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stem}: exit code\n{stderr}");
        let loc = format!("{name}:{}:{}", expect(&src, "line"), expect(&src, "col"));
        assert!(stderr.contains(&loc), "{stem}: no {loc} in\n{stderr}");
        let message = expect(&src, "message");
        assert!(
            squeeze(&stderr).contains(&squeeze(message)),
            "{stem}: no '{message}' in\n{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stem}: panic\n{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_script_is_a_clear_error() {
    let dir = common::scratch_dir("cli-errors-missing");
    let out = run(&dir, &["-in", "missing.file", "-log", "none"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0), "{stderr}");
    assert!(
        squeeze(&stderr).contains(&squeeze("cannot open input script 'missing.file'")),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn options_exit_codes() {
    let dir = common::scratch_dir("cli-errors-options");
    let out = run(&dir, &["--bogus"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown option '--bogus'"));
    let out = run(&dir, &["--help"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: rdem"));
    let out = run(&dir, &["--version"]);
    assert_eq!(out.status.code(), Some(0));
    let version = String::from_utf8_lossy(&out.stdout);
    assert!(version.starts_with("rdem "));
    // The benchmark script tells from it whether the 2-rank runs can be made.
    assert_eq!(
        version.contains("(with MPI)"),
        cfg!(feature = "mpi"),
        "{version}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
