//! Helpers shared by the CLI tests.
#![allow(dead_code)]

use std::path::Path;

/// Copies the directory `from` (recursively) to `to`.
pub fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let t = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_dir(&e.path(), &t);
        } else {
            std::fs::copy(e.path(), &t).unwrap();
        }
    }
}

/// True when `mpirun` can be started; otherwise prints a note (the caller skips its MPI
/// test).
pub fn have_mpirun() -> bool {
    let ok = std::process::Command::new("mpirun")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        eprintln!("note: mpirun not found; MPI test skipped");
    }
    ok
}

/// The rdem binary under test: run directly (`ranks: None`) or on `ranks` MPI ranks with
/// `mpirun --oversubscribe` (so that 4 ranks run on 2 cores).
pub fn rdem_command(ranks: Option<usize>) -> std::process::Command {
    let bin = env!("CARGO_BIN_EXE_rdem");
    match ranks {
        None => std::process::Command::new(bin),
        Some(n) => {
            let mut c = std::process::Command::new("mpirun");
            c.args(["--allow-run-as-root", "--oversubscribe", "-np"])
                .arg(n.to_string())
                .arg(bin);
            c
        }
    }
}
