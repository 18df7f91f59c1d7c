//! Helpers shared by the CLI tests.
#![allow(dead_code)]

use std::path::Path;

/// The material block of one atom type most scripts here use: E = 5·10⁶ Pa, ν = 0.45,
/// e = 0.6, μ = 0.5.
///
/// A macro, so that `concat!` can build a `const` script around it; [`MATERIALS`] is the
/// same text for `format!`.
macro_rules! materials {
    () => {
        "\
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.6
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
"
    };
}
#[allow(unused_imports)]
pub(crate) use materials;

/// The text of [`materials!`].
pub const MATERIALS: &str = materials!();

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

/// `rdem -in <input> -log none`, run directly (`ranks: None`) or on MPI ranks
/// ([`rdem_command`]), in the directory `dir`; the caller adds the thread count and any
/// other argument.
pub fn rdem_in(dir: &Path, input: &str, ranks: Option<usize>) -> std::process::Command {
    let mut c = rdem_command(ranks);
    c.args(["-in", input, "-log", "none"]).current_dir(dir);
    c
}

/// Where Debian's liggghts-doc package puts LIGGGHTS 3.8's tutorials (scripts/test.sh
/// installs it).
pub const TUTORIALS: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public";

/// The tutorial folder `folder`, checked to hold `script`, and a scratch copy of it (named
/// after `prefix`) whose `post/` is empty, as the tutorial scripts expect.
pub fn tutorial_copy(
    folder: &str,
    script: &str,
    prefix: &str,
) -> (std::path::PathBuf, std::path::PathBuf) {
    let src = Path::new(TUTORIALS).join(folder);
    assert!(
        src.join(script).exists(),
        "{} is missing: install the liggghts-doc package (scripts/test.sh does)",
        src.join(script).display()
    );
    let dir = scratch_dir(prefix);
    copy_dir(&src, &dir);
    let _ = std::fs::remove_dir_all(dir.join("post"));
    std::fs::create_dir_all(dir.join("post")).unwrap();
    (src, dir)
}

/// The case `case` of the real users' scripts, `<repo>/../shared/wild/`, if its file
/// `script` is there; else `None`, with a note that the test is skipped.
pub fn wild_case(case: &str, script: &str) -> Option<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/wild")
        .join(case);
    if dir.join(script).exists() {
        Some(dir)
    } else {
        eprintln!("note: {} is absent; skipped", dir.join(script).display());
        None
    }
}

/// A fresh, empty directory under the system temp directory, named after `prefix`, the
/// process and a counter.
pub fn scratch_dir(prefix: &str) -> std::path::PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!(
        "rdem-{prefix}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `script` (written as `in.test` in a scratch directory) with `-log none` and one
/// thread per process, serially (`ranks: None`) or on MPI ranks; the directory is removed.
pub fn run_script_raw(script: &str, ranks: Option<usize>) -> std::process::Output {
    run_with_files_raw(script, &[], ranks)
}

/// [`run_script_raw`] with `files` (name, contents) written beside the script.
pub fn run_with_files_raw(
    script: &str,
    files: &[(&str, &str)],
    ranks: Option<usize>,
) -> std::process::Output {
    let (dir, out) = run_kept("script", script, files, ranks);
    let _ = std::fs::remove_dir_all(&dir);
    out
}

/// Writes `script` as `in.test` and `files` (name, contents) into a fresh scratch
/// directory named after `prefix`, and runs it there with `-log none` and one thread per
/// process; returns the directory (kept, with what the run wrote) and the output.
pub fn run_kept(
    prefix: &str,
    script: &str,
    files: &[(&str, &str)],
    ranks: Option<usize>,
) -> (std::path::PathBuf, std::process::Output) {
    let dir = scratch_dir(prefix);
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = rdem_in(&dir, "in.test", ranks)
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    (dir, out)
}

/// [`run_kept`] for a script that must succeed: the directory and the screen output
/// (the failure message has the standard error too).
pub fn run_kept_ok(
    prefix: &str,
    script: &str,
    files: &[(&str, &str)],
    ranks: Option<usize>,
) -> (std::path::PathBuf, String) {
    let (dir, out) = run_kept(prefix, script, files, ranks);
    (dir, success(prefix, &out))
}

/// Runs the script file `script` of the directory `data` in a fresh scratch directory
/// named after `prefix`, with `files` of `data` copied beside it and an empty `post/`,
/// with `-log none` and one thread; the script must succeed. Returns the directory
/// (kept) and the screen output, standard error after it.
pub fn run_data_script(
    prefix: &str,
    data: &std::path::Path,
    script: &str,
    files: &[&str],
) -> (std::path::PathBuf, String) {
    let dir = scratch_dir(prefix);
    std::fs::create_dir_all(dir.join("post")).unwrap();
    for f in std::iter::once(&script).chain(files) {
        std::fs::copy(data.join(f), dir.join(f)).unwrap();
    }
    let out = rdem_in(&dir, script, None)
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    let text = success(script, &out) + &String::from_utf8_lossy(&out.stderr);
    (dir, text)
}

/// The standard output of a run that must have succeeded (`what` names it in the
/// failure message, with the standard error).
pub fn success(what: &str, out: &std::process::Output) -> String {
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{what}: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// [`run_script_raw`] for a script that must succeed; returns the screen output.
pub fn run_script(script: &str, ranks: Option<usize>) -> String {
    run_with_files(script, &[], ranks)
}

/// [`run_with_files_raw`] for a script that must succeed; returns the screen output.
pub fn run_with_files(script: &str, files: &[(&str, &str)], ranks: Option<usize>) -> String {
    let out = run_with_files_raw(script, files, ranks);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{ranks:?} ranks: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// Every thermo row of a screen output (the lines of numbers after each `Step ...`
/// header, across `INFO` and ` - ` note lines), in order.
pub fn thermo_rows(out: &str) -> Vec<Vec<f64>> {
    let mut all = Vec::new();
    let mut in_table = false;
    for l in out.lines() {
        if l.trim_start().starts_with("Step") {
            in_table = true;
            continue;
        }
        if in_table {
            let v: Result<Vec<f64>, _> = l.split_whitespace().map(str::parse).collect();
            match v {
                Ok(v) if !v.is_empty() => all.push(v),
                _ => in_table = l.starts_with("INFO") || l.starts_with(" - "),
            }
        }
    }
    all
}

/// The floor z = 0, −0.1..0.1 in x and y, as four ASCII STL triangles meeting at the
/// centre (each of area 0.01 m²).
pub fn floor_stl() -> String {
    let v = |x: f64, y: f64| format!("vertex {x} {y} 0\n");
    let c = [(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)];
    let mut s = String::from("solid floor\n");
    for k in 0..4 {
        let (a, b) = (c[k], c[(k + 1) % 4]);
        s += &format!(
            "facet normal 0 0 1\nouter loop\n{}{}{}endloop\nendfacet\n",
            v(a.0, a.1),
            v(b.0, b.1),
            v(0.0, 0.0)
        );
    }
    s + "endsolid floor\n"
}

/// The rows of numbers of a reference file (thermo rows a program printed), lines
/// starting with `#` (its source) skipped.
pub fn reference_rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// Index-variable lines setting `vars` ahead of a script, as `-var NAME VALUE` would.
pub fn index_vars(vars: &[(&str, &str)]) -> String {
    vars.iter()
        .map(|(k, v)| format!("variable {k} index {v}\n"))
        .collect()
}

/// Every value of `got`, from column `first` on, within `rel` of the largest magnitude of
/// its column in `want` (columns of velocity or spin pass through zero); the rows have
/// `want`'s length. Column 0 names the row (the step) in the failure message.
pub fn assert_columns(got: &[Vec<f64>], want: &[Vec<f64>], first: usize, rel: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: row count");
    let cols = want[0].len();
    for k in first..cols {
        let scale = want.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
        for (g, w) in got.iter().zip(want) {
            assert_eq!(g.len(), cols, "{what}: {g:?}");
            assert!(
                (g[k] - w[k]).abs() <= rel * scale,
                "{what}: row {} column {k}: {} against the reference's {} (scale {scale})",
                w[0],
                g[k],
                w[k]
            );
        }
    }
}

/// The snapshots of a `dump custom` or `dump local` file: per `ITEM: TIMESTEP`, the step
/// and the rows of numbers after its `ITEM: ATOMS` or `ITEM: ENTRIES` line, in file order.
pub fn dump_frames(text: &str) -> Vec<(u64, Vec<Vec<f64>>)> {
    text.split("ITEM: TIMESTEP")
        .skip(1)
        .map(|snap| {
            let mut lines = snap.lines().skip_while(|l| l.trim().is_empty());
            let step = lines.next().unwrap().trim().parse().unwrap();
            let rows = lines
                .skip_while(|l| !l.starts_with("ITEM: ATOMS") && !l.starts_with("ITEM: ENTRIES"))
                .skip(1)
                .filter(|l| !l.trim().is_empty())
                .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
                .collect();
            (step, rows)
        })
        .collect()
}

/// The rows of every snapshot of a `dump custom` file (see [`dump_frames`]), each with
/// its step in front, in file order: the layout of the reference files that hold a
/// whole LIGGGHTS dump.
pub fn dump_rows_with_step(text: &str) -> Vec<Vec<f64>> {
    dump_frames(text)
        .into_iter()
        .flat_map(|(s, rows)| {
            rows.into_iter().map(move |r| {
                let mut v = vec![s as f64];
                v.extend(r);
                v
            })
        })
        .collect()
}
