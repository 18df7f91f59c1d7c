//! `restart N root` and `restart N file1 file2`: which files appear at which steps, and
//! that `read_restart` reads them back. LIGGGHTS 3.8 ran the same schedule
//! (tests/data/units/si.in with `restart 100 r.*.rst`, `restart 150 ta.rst tb.rst`,
//! `run 250`, `run 100`, `restart 100 plain`, `run 100`) and wrote r.100.rst, r.200.rst,
//! r.300.rst, plain.400, ta.rst (steps 150, then 450) and tb.rst (step 300): no file at a
//! run's first step, none at a run's last step unless a multiple of N, and a new one-name
//! `restart` replaces the old one-name schedule only.

use std::path::Path;

use rdem_script::Interpreter;

use crate::common;

const SI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/units/si.in");

fn run_in(dir: &Path, src: &str) -> Interpreter {
    common::run("in.r", &src.replace("DIR", &dir.display().to_string()))
}

/// The step in a restart file's title line, and its atom count, through `read_restart`.
fn read_back(file: &Path) -> (u64, u64, rdem_script::Sim) {
    let src = format!("read_restart {}\n", file.display());
    let mut i = common::interpreter();
    i.run_source("in.read", &src).unwrap();
    let w = i.sim.world.as_ref().unwrap();
    (w.step, w.natoms(), i.sim)
}

#[test]
fn files_at_the_steps_liggghts_writes() {
    let dir = common::scratch_dir("restart-steps");
    let base = std::fs::read_to_string(SI).unwrap();
    let (head, _) = base.split_once("run 10000").unwrap();
    let src = format!(
        "{head}restart 100 DIR/r.*.rst\nrestart 150 DIR/ta.rst DIR/tb.rst\nrun 250\nrun 100\n\
         restart 100 DIR/plain\nrun 100\n"
    );
    let i = run_in(&dir, &src);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "plain.400",
            "r.100.rst",
            "r.200.rst",
            "r.300.rst",
            "ta.rst",
            "tb.rst"
        ]
    );
    for (f, step) in [
        ("r.100.rst", 100),
        ("r.200.rst", 200),
        ("r.300.rst", 300),
        ("plain.400", 400),
        ("ta.rst", 450),
        ("tb.rst", 300),
    ] {
        let (s, n, _) = read_back(&dir.join(f));
        assert_eq!((s, n), (step, 2), "{f}");
    }
    // The last file holds the state at its step: ta.rst is the end of the run.
    let (_, _, back) = read_back(&dir.join("ta.rst"));
    let (w, b) = (i.sim.world.as_ref().unwrap(), back.world.as_ref().unwrap());
    for k in 0..2 {
        let (a, c) = (&w.particles, &b.particles);
        let kb = (0..2).find(|&j| c.tag[j] == a.tag[k]).unwrap();
        for (u, v) in [(a.x[k], c.x[kb]), (a.v[k], c.v[kb])] {
            assert!(
                (u - v).length() <= 1e-15 * u.length().max(1e-300),
                "{u} vs {v}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `restart 0` stops both schedules; unsupported forms are located errors.
#[test]
fn restart_zero_and_errors() {
    let dir = common::scratch_dir("restart-zero");
    let base = std::fs::read_to_string(SI).unwrap();
    let (head, _) = base.split_once("run 10000").unwrap();
    run_in(
        &dir,
        &format!("{head}restart 10 DIR/r\nrestart 10 DIR/a DIR/b\nrestart 0\nrun 30\n"),
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
    for (src, msg) in [
        (
            "restart 100 r.% \n",
            "'%' in the name) are not supported yet",
        ),
        (
            "restart 100 a b fileper 2\n",
            "restart fileper is not supported yet",
        ),
        (
            "restart v_n r\n",
            "restart with a variable N is not supported yet",
        ),
        ("restart 100\n", "restart N needs a file name"),
    ] {
        let mut i = common::interpreter();
        let e = i.run_source("in.t", src).unwrap_err();
        let text = format!("{:?}", miette::Report::new(*e));
        assert!(text.contains(msg), "{src}: {text}");
    }
}
