//! The `rdem` command line: a script from standard input, `-var`, `-echo`, `-log`,
//! `-screen`, and the report after a run.

use std::io::Write;
use std::process::Stdio;

use crate::common;

const SCRIPT: &str = "\
units si
boundary f f f
region reg block 0 1 0 1 0 1 units box
create_box 1 reg
variable n index 7
print \"n is ${n} and m is ${m}\"
run 3
";

#[test]
fn script_from_stdin_with_vars_echo_and_log() {
    let d = common::scratch_dir("cli-stdin");
    let mut child = common::rdem_command(None)
        .args([
            "-var", "m", "five", "-var", "n", "3", "-echo", "screen", "-log", "run.log",
        ])
        .current_dir(&d)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(SCRIPT.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // -var n 3 wins over the script's index variable (LIGGGHTS' rule).
    assert!(stdout.contains("n is 3 and m is five"), "{stdout}");
    // -echo screen: the commands appear on the screen.
    assert!(
        stdout.contains("region reg block 0 1 0 1 0 1 units box"),
        "{stdout}"
    );
    assert!(stdout.contains("Loop time of "), "{stdout}");
    assert!(
        stdout.contains(" on 1 procs for 3 steps with 0 atoms"),
        "{stdout}"
    );
    for stage in ["Pair ", "Neigh ", "Comm ", "Outpt ", "Modify ", "Other "] {
        assert!(stdout.contains(stage), "no {stage} line: {stdout}");
    }
    let log = std::fs::read_to_string(d.join("run.log")).unwrap();
    assert!(log.contains("n is 3 and m is five"), "{log}");
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn screen_none_and_default_log() {
    let d = common::scratch_dir("cli-screen");
    std::fs::write(d.join("in.s"), SCRIPT).unwrap();
    let out = common::rdem_command(None)
        .args(["-in", "in.s", "-screen", "none", "-var", "m", "x"])
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    // The default log file, as LIGGGHTS names it.
    let log = std::fs::read_to_string(d.join("log.liggghts")).unwrap();
    assert!(log.contains("n is 7 and m is x"), "{log}");
    let _ = std::fs::remove_dir_all(d);
}

#[test]
fn threads_flag_and_env() {
    let d = common::scratch_dir("cli-threads");
    std::fs::write(d.join("in.s"), SCRIPT).unwrap();
    let ok = common::rdem_command(None)
        .args([
            "-in",
            "in.s",
            "--threads",
            "2",
            "-log",
            "none",
            "-var",
            "m",
            "x",
        ])
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(ok.status.success());
    assert!(String::from_utf8_lossy(&ok.stdout).contains("using 2 threads"));
    let bad = common::rdem_command(None)
        .args(["-in", "in.s", "-log", "none"])
        .env("RDEM_THREADS", "zero")
        .current_dir(&d)
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("RDEM_THREADS"));
    let _ = std::fs::remove_dir_all(d);
}
