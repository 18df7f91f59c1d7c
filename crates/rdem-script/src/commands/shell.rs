//! `shell cmd args...`: `cd`, `mkdir` (`-p`), `rm` (`-f`, `-r`), `rmdir`, `mv` and `putenv` done natively
//! (`std::fs`, `std::env`), anything else run by `/bin/sh -c` with the words joined by
//! single spaces (quotes removed), as LAMMPS passes them to `system()`.
//!
//! What LIGGGHTS 3.8 does, checked on it (`liggghts -in in.x -log none`):
//! - `shell mkdir d1 d2/sub` makes `d1` and silently not `d2/sub` (no parents);
//!   `shell mkdir -p x/y` makes a folder named `-p`. rdem reads `-p` as `mkdir -p` does
//!   (parents are made), and an existing folder is no failure.
//! - `shell rm -r d` leaves the folder `d` as it is, without a word, and `shell rm -rf x`
//!   removes the file `x` (LIGGGHTS unlinks each word, options too). rdem reads `-r`,
//!   `-R`, `-f` and their joined forms as `rm` does: a folder goes with all it holds.
//! - `shell cd nonexist`, `shell rm nofile`, `shell rmdir full_dir`, `shell mv nofile x`,
//!   `shell false` and `shell exit 3` go on without a word; rdem goes on too but prints a
//!   warning for each failed action or non-zero exit status.
//! - `shell` alone, `shell cd` with no or two folders, `shell mkdir`, `shell rm`,
//!   `shell rmdir`, `shell putenv` with nothing, `shell mv` without exactly two names
//!   stop the script ("Illegal shell ... command"): rdem stops with a located error.
//! - `shell putenv A=1=2` sets `A` to `1=2`; `shell putenv NOEQ` leaves `NOEQ` empty
//!   (glibc's `putenv` removes it): rdem does the same.
//!
//! `cd` changes the process' working folder, so every later relative path (scripts,
//! data files, dumps, `print` files) is read and written from there; every MPI rank does
//! `cd` and `putenv`, only rank 0 makes, removes and moves files and runs other commands
//! (the interpreter's agreement after each command keeps the other ranks from going on
//! before rank 0 is done). Under `rdem -check` only `cd` and `putenv` act: no file is
//! made, removed or moved and no other command runs.

use std::path::Path;

use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The natively run sub-commands, for errors.
const NATIVE: &str = "cd, mkdir, rm, rmdir, mv, putenv, or any other command for /bin/sh";

/// `shell cmd args...`.
pub(super) fn shell(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let Some(cmd) = a.peek() else {
        return Err(a.error_at(1, "shell: missing command", Some(NATIVE.into())));
    };
    a.seek(2);
    let args: Vec<&str> = a.words()[2..].iter().map(|w| w.text.as_str()).collect();
    let rank0 = rdem::comm::process_rank_size().0 == 0;
    // Files are touched by one rank, and not at all by `rdem -check`.
    let acts = rank0 && !sim.script.check;
    match cmd {
        "cd" => {
            if args.len() != 1 {
                return Err(count_error(a, "shell cd takes one folder"));
            }
            if let Err(e) = std::env::set_current_dir(args[0]) {
                a.warn_at(2, &format!("shell cd: cannot change to '{}': {e}", args[0]));
            }
        }
        "mkdir" => {
            let parents = args.contains(&"-p");
            let dirs = names(a, cmd, &["-p"])?;
            if acts {
                for (k, d) in dirs {
                    let r = if parents {
                        std::fs::create_dir_all(d)
                    } else if Path::new(d).is_dir() {
                        Ok(())
                    } else {
                        std::fs::create_dir(d)
                    };
                    if let Err(e) = r {
                        a.warn_at(k, &format!("shell mkdir: cannot create folder '{d}': {e}"));
                    }
                }
            }
        }
        "rm" => {
            // `-f`, `-r` (`-R`) and their joined forms (`-rf`, `-fr`, `-Rf`, ...).
            let opts = rm_options(&args);
            let files = names(a, cmd, RM_OPTIONS)?;
            if acts {
                for (k, f) in files {
                    let path = Path::new(f);
                    let r = if opts.recursive && path.is_dir() && !path.is_symlink() {
                        std::fs::remove_dir_all(path)
                    } else {
                        std::fs::remove_file(path)
                    };
                    match r {
                        Err(e) if !(opts.force && e.kind() == std::io::ErrorKind::NotFound) => {
                            a.warn_at(k, &format!("shell rm: cannot remove '{f}': {e}"))
                        }
                        _ => {}
                    }
                }
            }
        }
        "rmdir" => {
            let dirs = names(a, cmd, &[])?;
            if acts {
                for (k, d) in dirs {
                    if let Err(e) = std::fs::remove_dir(d) {
                        a.warn_at(k, &format!("shell rmdir: cannot remove folder '{d}': {e}"));
                    }
                }
            }
        }
        "mv" => {
            if args.len() != 2 {
                return Err(count_error(a, "shell mv takes two names: old new"));
            }
            if acts {
                if let Err(e) = std::fs::rename(args[0], args[1]) {
                    a.warn_at(
                        2,
                        &format!("shell mv: cannot move '{}' to '{}': {e}", args[0], args[1]),
                    );
                }
            }
        }
        "putenv" => {
            if args.is_empty() {
                return Err(count_error(a, "shell putenv needs NAME=VALUE"));
            }
            for (k, def) in args.iter().enumerate() {
                let (name, value) = def.split_once('=').unwrap_or((def, ""));
                if name.is_empty() || def.contains('\0') {
                    a.warn_at(k + 2, &format!("shell putenv: cannot set '{def}'"));
                } else if !def.contains('=') {
                    // glibc's putenv("NAME") removes NAME.
                    std::env::remove_var(name);
                } else {
                    // Script commands run while no other thread reads the environment.
                    std::env::set_var(name, value);
                }
            }
        }
        _ => {
            if acts {
                let line: Vec<&str> = a.words()[1..].iter().map(|w| w.text.as_str()).collect();
                let line = line.join(" ");
                // What the script printed so far comes before the command's output.
                sim.outputs.out.flush();
                match std::process::Command::new("/bin/sh")
                    .arg("-c")
                    .arg(&line)
                    .status()
                {
                    Ok(s) if s.success() => {}
                    Ok(s) => a.warn_at(
                        1,
                        &format!(
                            "shell command '{line}' {}",
                            match s.code() {
                                Some(c) => format!("exited with status {c}"),
                                None => "was stopped by a signal".into(),
                            }
                        ),
                    ),
                    Err(e) => a.warn_at(1, &format!("shell command '{line}' did not run: {e}")),
                }
            }
        }
    }
    a.seek(a.words().len());
    Ok(())
}

/// The options of `shell rm`: `-f` (no warning for a missing name) and `-r` or `-R`
/// (folders with everything in them), alone or joined.
const RM_OPTIONS: &[&str] = &[
    "-f", "-r", "-R", "-rf", "-fr", "-Rf", "-fR", "-rR", "-Rr", "-rfR", "-Rrf",
];

/// What the options of `shell rm` ask for.
struct RmOptions {
    force: bool,
    recursive: bool,
}

/// The options among `args` (the words after `rm`), any of [`RM_OPTIONS`].
fn rm_options(args: &[&str]) -> RmOptions {
    let opts = args.iter().filter(|w| RM_OPTIONS.contains(w));
    let has = |c: char| opts.clone().any(|w| w.contains(c));
    RmOptions {
        force: has('f'),
        recursive: has('r') || has('R'),
    }
}

/// The names after `shell mkdir|rm|rmdir` with their word index, the options in
/// `flags` left out; at least one is needed and other options are errors.
fn names<'a>(a: &Args<'a>, cmd: &str, flags: &[&str]) -> CmdResult<Vec<(usize, &'a str)>> {
    let mut out = Vec::new();
    for (k, w) in a.words().iter().enumerate().skip(2) {
        let w = w.text.as_str();
        if flags.contains(&w) {
            continue;
        }
        if w.starts_with('-') && w.len() > 1 {
            let valid = match flags {
                [] => "no options".to_string(),
                f => format!("only {}", f.join(", ")),
            };
            return Err(a.error_at(
                k,
                format!("shell {cmd}: option '{w}' is not supported"),
                Some(format!("rdem's shell {cmd} takes {valid}")),
            ));
        }
        out.push((k, w));
    }
    if out.is_empty() {
        let what = if cmd == "rm" { "file" } else { "folder" };
        return Err(count_error(
            a,
            &format!("shell {cmd} needs at least one {what}"),
        ));
    }
    Ok(out)
}

/// A wrong number of arguments: at the first one too many, or just past the last word.
fn count_error(a: &Args, message: &str) -> crate::diagnostic::ScriptError {
    let n = a.words().len();
    let at = match a.words()[1].text.as_str() {
        "cd" if n > 3 => 3,
        "mv" if n > 4 => 4,
        _ => n,
    };
    a.error_at(at, message.to_string(), Some(format!("shell {}", usage(a))))
}

/// The syntax of the sub-command of `a`.
fn usage(a: &Args) -> &'static str {
    match a.words()[1].text.as_str() {
        "cd" => "cd FOLDER",
        "mkdir" => "mkdir [-p] FOLDER ...",
        "rm" => "rm [-f] [-r] FILE|FOLDER ...",
        "rmdir" => "rmdir FOLDER ...",
        "mv" => "mv OLD NEW",
        _ => "putenv NAME=VALUE ...",
    }
}
