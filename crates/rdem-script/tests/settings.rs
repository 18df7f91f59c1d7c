//! The small commands every script has: `processors` on fewer ranks than asked for,
//! `dimension`, `thermo_log`, seeds LIGGGHTS 3.8 refuses, `clear`, `units cgs|micro`.

use rdem_script::{Interpreter, Output, Sim};

mod common;
use common::render;

/// Runs `src` (a script named `in.t`) and returns the interpreter and its output.
fn run(src: &str) -> (Interpreter, Result<(), String>, String) {
    let mut i = Interpreter::new(Sim::new(Output::captured()));
    let r = i.run_source("in.t", src).map_err(|e| render(&e));
    let out = i.sim.outputs.out.captured.clone().unwrap_or_default();
    (i, r, out)
}

/// LIGGGHTS 3.8 stops at `processors 2 2 2` on one process ("ERROR: Specified processors
/// != physical processors"); rdem warns, naming both grids, and runs on 1 x 1 x 1.
#[test]
fn processors_grid_that_does_not_fit_warns_and_runs() {
    let (i, r, out) = run("processors 2 2 2 grid onelevel map cart\n\
         region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n");
    r.unwrap();
    assert!(
        out.contains(
            "WARNING: line 1: processors 2 x 2 x 2 does not fit the 1 process of this run \
             (LIGGGHTS stops here): rdem uses 1 x 1 x 1"
        ),
        "{out}"
    );
    assert_eq!(i.sim.setup.procs, [0, 0, 0]);
    // A grid that fits is kept, without a warning.
    let (i, r, out) = run("processors 1 * 1 map xyz\n");
    r.unwrap();
    assert!(!out.contains("WARNING"), "{out}");
    assert_eq!(i.sim.setup.procs, [1, 0, 1]);
    // Keywords rdem does not run are errors at the word.
    for (src, msg) in [
        (
            "processors * * * grid numa\n",
            "processors grid numa is not supported yet",
        ),
        (
            "processors * * * part 1 2 multiple\n",
            "processors part is not supported yet",
        ),
        (
            "processors * * * file grid.txt\n",
            "processors file is not supported yet",
        ),
        (
            "processors * * * mapp xyz\n",
            "unknown processors keyword 'mapp'",
        ),
    ] {
        let (_, r, _) = run(src);
        let e = r.unwrap_err();
        assert!(e.contains(msg) && e.contains("in.t:1:"), "{e}");
    }
}
