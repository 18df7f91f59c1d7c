//! Errors found during a run point at the word that introduced what failed, with a miette
//! error code: a thermo column (`rdem::run::thermo`), a variable's formula
//! (`rdem::run::variable`), a dump (`rdem::run::dump`), a fix (`rdem::run::fix`); what
//! belongs to no word (a particle lost through a fixed face) stays
//! at the `run` command (`rdem::run::engine`). Before, every one of them was reported at
//! `run`.

use rdem_script::{Interpreter, Output, ScriptReport, Sim};

mod common;
use common::render;

/// One particle falling in a box, and `tail` after it.
fn script(tail: &str) -> String {
    format!(
        "units si\n\
         atom_style granular\n\
         boundary f f f\n\
         region box block 0 1 0 1 0 1 units box\n\
         create_box 1 box\n\
         create_atoms 1 single 0.5 0.5 0.5 units box\n\
         set atom 1 diameter 0.1 density 1000\n\
         fix integr all nve/sphere\n\
         fix g all gravity 9.81 vector 0 0 -1\n\
         timestep 1e-5\n\
         {tail}"
    )
}

fn report(src: &str) -> Box<ScriptReport> {
    let mut i = Interpreter::new(Sim::new(Output::captured()));
    i.run_source("in.rt", src)
        .expect_err("the script must fail")
}

#[test]
fn a_thermo_column_that_fails_is_reported_at_its_word() {
    // Line 11 is thermo_style; `f_g` starts at column 32; the run is line 12.
    let r = report(&script("thermo_style custom step atoms f_g\nrun 10\n"));
    let text = render(&r);
    assert_eq!(r.code(), Some("rdem::run::thermo"), "{text}");
    assert!(text.contains("in.rt:11:32"), "{text}");
    assert!(
        text.contains("fix g (gravity) computes no global values"),
        "{text}"
    );
    assert!(text.contains("found during the run of line 12"), "{text}");
}

#[test]
fn a_variable_that_fails_is_reported_at_its_formula() {
    // Line 11 defines the variable; its formula `f_g` starts at column 18; thermo uses
    // it on line 12; the run is line 13.
    let r = report(&script(
        "variable e equal f_g\nthermo_style custom step v_e\nrun 10\n",
    ));
    let text = render(&r);
    assert_eq!(r.code(), Some("rdem::run::variable"), "{text}");
    assert!(text.contains("in.rt:11:18"), "{text}");
    assert!(text.contains("computes no global values"), "{text}");
    assert!(text.contains("found during the run of line 13"), "{text}");
}

#[test]
fn a_fix_whose_stage_fails_is_reported_at_its_style_word() {
    // fix ave/time reads f_g at its first sample (step 1): line 11, `ave/time` at 12.
    let r = report(&script("fix at all ave/time 1 1 1 f_g\nrun 10\n"));
    let text = render(&r);
    assert_eq!(r.code(), Some("rdem::run::fix"), "{text}");
    assert!(text.contains("in.rt:11:12"), "{text}");
    assert!(text.contains("computes no global values"), "{text}");
}

#[test]
fn a_dump_that_fails_is_reported_at_its_style_word() {
    // The dump's directory cannot be made (a file is in the way): line 12, `custom` at 12.
    let dir = std::env::temp_dir().join(format!("rdem_run_errors_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let blocker = dir.join("blocker");
    std::fs::write(&blocker, "a file, not a directory").unwrap();
    let tail = format!(
        "thermo 5\ndump d all custom 5 {}/d_*.txt id x y z\nrun 10\n",
        blocker.display()
    );
    let r = report(&script(&tail));
    let text = render(&r);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(r.code(), Some("rdem::run::dump"), "{text}");
    assert!(text.contains("in.rt:12:12"), "{text}");
    assert!(text.contains("dump d"), "{text}");
}

#[test]
fn a_lost_particle_is_reported_at_the_run() {
    let r = report(&script("velocity all set 0 0 -1000\nrun 100\n"));
    let text = render(&r);
    assert_eq!(r.code(), Some("rdem::run::engine"), "{text}");
    assert!(text.contains("in.rt:12:1"), "{text}");
    assert!(text.contains("lost"), "{text}");
}
