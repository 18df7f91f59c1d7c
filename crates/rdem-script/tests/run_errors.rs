//! Errors found during a run point at the word that introduced what failed, with a miette
//! error code: a thermo column (`rdem::run::thermo`), a variable's formula
//! (`rdem::run::variable`), a dump (`rdem::run::dump`), a fix (`rdem::run::fix`); what
//! belongs to no word (a particle lost through a fixed face) stays
//! at the `run` command (`rdem::run::engine`). Before, every one of them was reported at
//! `run`.

use rdem_script::ScriptReport;

use crate::common;
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
    let mut i = common::interpreter();
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
    let r = report(&script(
        "thermo_modify lost error\nvelocity all set 0 0 -1000\nrun 100\n",
    ));
    let text = render(&r);
    assert_eq!(r.code(), Some("rdem::run::engine"), "{text}");
    assert!(text.contains("in.rt:13:1"), "{text}");
    assert!(text.contains("lost"), "{text}");
}

/// A thin mesh plate at x = 0.01 (two triangles), written into `dir`, and a box
/// x −0.02..0.05 with a 1 mm sphere at (0, 0.001, 0) of velocity `vel`, walls of the
/// plate, and `tail` before its `run`.
fn plate_script(dir: &std::path::Path, vel: &str, tail: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let stl = dir.join("plate.stl");
    let facet = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        format!(
            "facet normal 0 0 0\nouter loop\nvertex {} {} {}\nvertex {} {} {}\nvertex {} {} {}\nendloop\nendfacet\n",
            a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]
        )
    };
    let (p0, p1, p2, p3) = (
        [0.01, -0.02, -0.02],
        [0.01, 0.02, -0.02],
        [0.01, 0.02, 0.02],
        [0.01, -0.02, 0.02],
    );
    std::fs::write(
        &stl,
        format!(
            "solid plate\n{}{}endsolid plate\n",
            facet(p0, p1, p2),
            facet(p0, p2, p3)
        ),
    )
    .unwrap();
    format!(
        "units si\n\
         atom_style sphere\n\
         atom_modify map array\n\
         boundary f f f\n\
         newton off\n\
         communicate single vel yes\n\
         region box block -0.02 0.05 -0.02 0.02 -0.02 0.02 units box\n\
         create_box 2 box\n\
         neighbor 0.001 bin\n\
         fix m1 all property/global youngsModulus peratomtype 1.e7 1.e7\n\
         fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n\
         pair_style gran model hertz tangential history\n\
         pair_coeff * *\n\
         timestep 1e-5\n\
         fix plate all mesh/surface file {} type 2\n\
         fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate\n\
         create_atoms 1 single 0.0 0.001 0.0 units box\n\
         set atom 1 diameter 0.002 density 2500 {vel}\n\
         fix integr all nve/sphere\n\
         {tail}",
        stl.display()
    )
}

/// A particle that tunnels through a thin mesh plate (5 mm a step against a 1 mm
/// radius) and leaves the box: the report names its tag, where it was found, its
/// velocity, and the plate's triangle that its path traced back crosses, with the
/// crossing point (x = 0.01, y = 0.001 + 0.01 · 3/500 = 0.00106 on the straight path).
/// It never touched the plate (its centre went from 0.005 to 0.01, on the plate, where
/// no normal exists, to 0.015), and the report says so.
#[test]
fn a_lost_particle_names_the_wall_its_path_crossed() {
    let dir = std::env::temp_dir().join(format!("rdem-lost-{}", std::process::id()));
    let src = plate_script(&dir, "vx 500 vy 3", "thermo_modify lost error\nrun 100\n");
    let r = report(&src);
    std::fs::remove_dir_all(&dir).ok();
    let text = render(&r);
    let words = text
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert_eq!(r.code(), Some("rdem::run::engine"), "{text}");
    // Found at the first re-neighboring after it left (x = 0.1 at step 20).
    assert!(
        words.contains("first lost tag 1 at (0.1, 0.0016, 0)"),
        "{text}"
    );
    assert!(words.contains("with velocity (500, 3, 0)"), "{text}");
    assert!(
        words.contains(
            "its path crosses mesh 'plate' triangle 0 of wall 'walls' at (0.01, 0.00106, 0)"
        ),
        "{text}"
    );
    assert!(words.contains("it has touched no wall"), "{text}");
}

/// The step of the last touch in a report ("at step S (N steps before)").
fn touch_step(text: &str) -> u64 {
    let at = text.find("last touched").expect("a last touch");
    let rest = &text[at..];
    let s = rest.find("at step ").expect("its step") + "at step ".len();
    rest[s..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// A particle that bounces off the plate and leaves the box through its far face (x =
/// −0.02): the report names the plate's triangle it last touched, and the step. It
/// meets the plate at step 90 (0.009 m at 10 m/s, dt 1e-5) and leaves it after a Hertz
/// contact of about 15 steps (t_c = 2.87 (m²/(R E*² v))^(1/5) = 1.5e-4 s for E* =
/// 5.5e6 Pa, R = 1 mm, m = 1.05e-5 kg), so the last touch lies in steps 95..120 (it
/// was 105); it leaves the box about 0.03 m / 5 m/s = 600 steps later.
///
/// LIGGGHTS' default (`lost ignore`) drops it and goes on; so does rdem's, with one
/// warning holding the report; `lost ignore` gives none, `lost error` stops with it.
#[test]
fn a_lost_particle_names_the_wall_it_last_touched() {
    let dir = std::env::temp_dir().join(format!("rdem-lost-touch-{}", std::process::id()));
    let tail = "thermo_style custom step atoms\nthermo 1000\nrun 2000\n";
    // Default: the run goes on without it, with one warning.
    let (_, out) = common::try_run_screen("in.rt", &plate_script(&dir, "vx 10", tail)).unwrap();
    let warnings: Vec<&str> = out.lines().filter(|l| l.starts_with("WARNING")).collect();
    assert_eq!(warnings.len(), 1, "{out}");
    let w = warnings[0];
    assert!(w.contains("1 particle(s) lost"), "{w}");
    assert!(w.contains("it last touched mesh 'plate' triangle"), "{w}");
    assert!(w.contains("of wall 'walls' at step"), "{w}");
    let step = touch_step(w);
    assert!((95..=120).contains(&step), "last touch at step {step}: {w}");
    let last_row = out
        .lines()
        .rfind(|l| l.trim_start().starts_with("2000 "))
        .unwrap_or_else(|| panic!("{out}"));
    assert_eq!(last_row.split_whitespace().nth(1), Some("0"), "{out}");
    // lost ignore: silent, same end.
    let src = plate_script(&dir, "vx 10", &format!("thermo_modify lost ignore\n{tail}"));
    let (_, out) = common::try_run_screen("in.rt", &src).unwrap();
    assert!(!out.contains("WARNING"), "{out}");
    // lost error: stops, with the same last touch.
    let src = plate_script(&dir, "vx 10", &format!("thermo_modify lost error\n{tail}"));
    let r = report(&src);
    std::fs::remove_dir_all(&dir).ok();
    let text = render(&r).replace('│', " ");
    let words = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        words.contains("it last touched mesh 'plate' triangle"),
        "{text}"
    );
    assert_eq!(touch_step(&words), step, "{text}");
}
