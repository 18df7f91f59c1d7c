//! The pre-3.0 granular syntax (LIGGGHTS 1.x and 2.x, which LIGGGHTS 3.8 refuses): each
//! old command must run exactly as the 3.x command it translates to. The same small
//! scene (27 spheres thrown against plane and cylinder walls under gravity, with contacts
//! between them) is written in the old syntax and in the 3.x syntax, and the two dumps
//! (every position, velocity and spin at %.17g) must be byte-identical. The note line of
//! each translated command is asserted word for word, and the old keywords that have no
//! 3.x counterpart in rdem stop with a located error.

use crate::common;
use common::render;

/// 27 spheres (d = 10 mm, 2500 kg/m³) on a 12 mm lattice, thrown sideways and down.
const HEAD: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.01 0.07 -0.01 0.07 -0.01 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.05
fix m6 all property/global cohesionEnergyDensity peratomtypepair 1 3000
fix m7 all property/global characteristicVelocity scalar 1.0
";

const BODY: &str = "\
timestep 0.00001
lattice sc 0.012 origin 0.5 0.5 0.5
region start block 0.012 0.048 0.012 0.048 0.012 0.048 units box
create_atoms 1 region start
set group all diameter 0.01 density 2500
variable vx atom 0.8*sin(17*id)
variable vy atom 0.6*cos(11*id)
velocity all set v_vx v_vy -1.0
fix grav all gravity 9.81 vector 0 0 -1
";

const TAIL: &str = "\
fix integr all nve/sphere
dump d all custom 500 DUMP id x y z vx vy vz omegax omegay omegaz
dump_modify d format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 3000
";

fn run_text(name: &str, script: &str) -> (String, String) {
    let path = std::env::temp_dir().join(format!("rdem-old-{name}-{}.dump", std::process::id()));
    let src = script.replace("DUMP", &path.display().to_string());
    let i = common::run("in.old", &src);
    let dump = std::fs::read_to_string(&path).expect("dump written");
    let _ = std::fs::remove_file(&path);
    (dump, common::screen(&i))
}

/// Runs the scene with `models` (the pair style and walls) in the old and the new syntax;
/// the dumps must be the same bytes. Returns the old run's screen text.
fn same_run(name: &str, old: &str, new: &str) -> String {
    let (a, screen) = run_text(&format!("{name}-old"), &format!("{HEAD}{old}{BODY}{TAIL}"));
    let (b, _) = run_text(&format!("{name}-new"), &format!("{HEAD}{new}{BODY}{TAIL}"));
    assert!(
        a.lines().count() > 6 * 27,
        "{name}: the dump has all its steps"
    );
    // The particles did touch the walls and each other: some spin.
    assert!(
        a.lines()
            .filter(|l| l.split_whitespace().count() == 10)
            .any(|l| l
                .split_whitespace()
                .nth(7)
                .unwrap()
                .parse::<f64>()
                .unwrap()
                .abs()
                > 1e-3),
        "{name}: no particle spins, so no contact was tested"
    );
    if a != b {
        let d = a
            .lines()
            .zip(b.lines())
            .find(|(x, y)| x != y)
            .map(|(x, y)| format!("old: {x}\nnew: {y}"));
        panic!("{name}: the dumps differ\n{}", d.unwrap_or_default());
    }
    screen
}

/// The note lines of a run (what each old command became).
fn notes(screen: &str) -> Vec<&str> {
    screen
        .lines()
        .filter(|l| l.contains(" runs as: "))
        .collect()
}

#[test]
fn liggghts_1x_flags_run_as_the_3x_models() {
    let old = "\
pair_style gran/hertz/history 1 0
pair_coeff * *
fix zwalls all wall/gran/hertz/history 1 0 zplane 0.0 NULL 1
fix xwalls all wall/gran/hertz/history 1 0 xplane 0.0 0.06 1
fix ywalls all wall/gran/hertz/history 1 0 yplane 0.0 0.06 1
";
    let new = "\
pair_style gran model hertz tangential history
pair_coeff * *
fix zwalls all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix xwalls all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix xwalls_hi all wall/gran model hertz tangential history primitive type 1 xplane 0.06
fix ywalls all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix ywalls_hi all wall/gran model hertz tangential history primitive type 1 yplane 0.06
";
    let screen = same_run("v1", old, new);
    assert_eq!(
        notes(&screen),
        [
            "pair_style gran/hertz/history 1 0 (LIGGGHTS 1.x syntax) runs as: pair_style gran model hertz tangential history",
            "fix zwalls all wall/gran/hertz/history 1 0 zplane 0.0 NULL 1 (LIGGGHTS 1.x syntax) runs as: fix zwalls all wall/gran model hertz tangential history primitive type 1 zplane 0",
            "fix xwalls all wall/gran/hertz/history 1 0 xplane 0.0 0.06 1 (LIGGGHTS 1.x syntax) runs as: fix xwalls all wall/gran model hertz tangential history primitive type 1 xplane 0 and fix xwalls_hi all wall/gran model hertz tangential history primitive type 1 xplane 0.06",
            "fix ywalls all wall/gran/hertz/history 1 0 yplane 0.0 0.06 1 (LIGGGHTS 1.x syntax) runs as: fix ywalls all wall/gran model hertz tangential history primitive type 1 yplane 0 and fix ywalls_hi all wall/gran model hertz tangential history primitive type 1 yplane 0.06",
        ]
    );
}

#[test]
fn liggghts_1x_damping_off_cohesion_on_and_hooke_without_history() {
    // dampflag 0 is tangential_damping off, cohesionflag 1 the linear cohesion (sjkr);
    // gran/hooke has no tangential spring (tangential no_history: its only tangential
    // force is the damping, so the walls without damping exert none and the spins come
    // from the pair contacts); zcylinder's axis is x = y = 0 in 1.x.
    let old = "\
pair_style gran/hooke 1 1
pair_coeff * *
fix zwalls all wall/gran/hooke 0 1 zplane 0.0 NULL 1
fix cyl all wall/gran/hooke 0 1 zcylinder 0.075 1 shear z 0.2
";
    let new = "\
pair_style gran model hooke tangential no_history cohesion sjkr
pair_coeff * *
fix zwalls all wall/gran model hooke tangential no_history cohesion sjkr primitive type 1 zplane 0.0 tangential_damping off
fix cyl all wall/gran model hooke tangential no_history cohesion sjkr primitive type 1 zcylinder 0.075 0 0 shear z 0.2 tangential_damping off
";
    let screen = same_run("v1-hooke", old, new);
    assert_eq!(
        notes(&screen)[0],
        "pair_style gran/hooke 1 1 (LIGGGHTS 1.x syntax) runs as: pair_style gran model hooke tangential no_history cohesion sjkr"
    );
    assert_eq!(
        notes(&screen)[2],
        "fix cyl all wall/gran/hooke 0 1 zcylinder 0.075 1 shear z 0.2 (LIGGGHTS 1.x syntax) runs as: fix cyl all wall/gran model hooke tangential no_history cohesion sjkr tangential_damping off primitive type 1 zcylinder 0.075 0 0 shear z 0.2"
    );
}

#[test]
fn liggghts_2x_keywords_run_as_the_3x_models() {
    let old = "\
pair_style gran/hooke/history tangential_damping off cohesion sjkr rolling_friction cdt viscous off
pair_coeff * *
fix floor all wall/gran/hooke/history primitive type 1 zplane 0.0 store_force no rolling_friction cdt cohesion sjkr tangential_damping off viscous off
fix side all wall/gran/hooke/history tangential_damping on primitive type 1 xplane 0.06 shear y 0.1
fix cyl all wall/gran/hooke/history primitive type 1 zcylinder 0.04 0.03 0.03 rolling_friction cdt
";
    let new = "\
pair_style gran model hooke tangential history cohesion sjkr rolling_friction cdt tangential_damping off
pair_coeff * *
fix floor all wall/gran model hooke tangential history cohesion sjkr rolling_friction cdt primitive type 1 zplane 0.0 tangential_damping off
fix side all wall/gran model hooke tangential history primitive type 1 xplane 0.06 shear y 0.1
fix cyl all wall/gran model hooke tangential history rolling_friction cdt primitive type 1 zcylinder 0.04 0.03 0.03
";
    let screen = same_run("v2", old, new);
    assert_eq!(
        notes(&screen),
        [
            "pair_style gran/hooke/history tangential_damping off cohesion sjkr rolling_friction cdt viscous off (LIGGGHTS 2.x syntax) runs as: pair_style gran model hooke tangential history cohesion sjkr rolling_friction cdt tangential_damping off",
            "fix floor all wall/gran/hooke/history primitive type 1 zplane 0.0 store_force no rolling_friction cdt cohesion sjkr tangential_damping off viscous off (LIGGGHTS 2.x syntax) runs as: fix floor all wall/gran model hooke tangential history cohesion sjkr rolling_friction cdt tangential_damping off primitive type 1 zplane 0",
            "fix side all wall/gran/hooke/history tangential_damping on primitive type 1 xplane 0.06 shear y 0.1 (LIGGGHTS 2.x syntax) runs as: fix side all wall/gran model hooke tangential history primitive type 1 xplane 0.06 shear y 0.1",
            "fix cyl all wall/gran/hooke/history primitive type 1 zcylinder 0.04 0.03 0.03 rolling_friction cdt (LIGGGHTS 2.x syntax) runs as: fix cyl all wall/gran model hooke tangential history rolling_friction cdt primitive type 1 zcylinder 0.04 0.03 0.03",
        ]
    );
}

#[test]
fn unfix_of_a_1x_plane_pair_removes_both_walls() {
    // After `unfix xwalls` neither x wall acts: the run equals one without them.
    let old = "\
pair_style gran/hertz/history
pair_coeff * *
fix zwalls all wall/gran/hertz/history zplane 0.0 NULL 1
fix xwalls all wall/gran/hertz/history 1 0 xplane 0.0 0.06 1
unfix xwalls
";
    let new = "\
pair_style gran model hertz tangential history
pair_coeff * *
fix zwalls all wall/gran model hertz tangential history primitive type 1 zplane 0.0
";
    // The 2.x form with no model words needs 'primitive': the 1.x wall style without
    // its flags is an error, pointing at the style word.
    let mut i = common::interpreter();
    let e = i
        .run_source("in.old", &format!("{HEAD}{old}"))
        .expect_err("zplane without flags or primitive");
    let r = render(&e);
    assert!(
        r.contains("unknown keyword 'zplane' of the LIGGGHTS 2.x wall"),
        "{r}"
    );
    let old = old.replace(
        "wall/gran/hertz/history zplane",
        "wall/gran/hertz/history 1 0 zplane",
    );
    same_run("unfix", &old, new);
}

/// The error of `script` (after the head and a pair style), rendered.
fn error_of(line: &str) -> String {
    let src = format!("{HEAD}pair_style gran/hertz/history\npair_coeff * *\n{line}\n");
    common::error("in.bad", &src)
}

/// Asserts that the rendered error says `message` and points at `word` of its line (the
/// column of the report's `[file:line:column]` is where `word` starts).
fn located(r: &str, message: &str, word: &str) {
    assert!(r.contains(message), "message '{message}' missing in:\n{r}");
    let head = r.lines().find(|l| l.contains("─[in.")).expect("location");
    let inner = &head[head.find('[').unwrap() + 1..head.rfind(']').unwrap()];
    let mut parts = inner.rsplit(':');
    let col: usize = parts.next().unwrap().parse().unwrap();
    let line: usize = parts.next().unwrap().parse().unwrap();
    let src = r
        .lines()
        .find_map(|l| l.trim_start().strip_prefix(&format!("{line} │ ")))
        .expect("the source line");
    let at: String = src.chars().skip(col - 1).collect();
    assert!(at.starts_with(word), "not located at '{word}':\n{r}");
}

#[test]
fn old_keywords_without_a_3x_model_are_located_errors() {
    let r = error_of("fix w all wall/gran/hertz/history 1 0 zplane 0 NULL 1 wiggle z 0.01 0.1");
    located(
        &r,
        "wiggle (a wall oscillating in place, LIGGGHTS 1.x) is not supported",
        "wiggle",
    );
    let r = error_of("fix w all wall/gran/hertz/history 1 0 zplane 0 NULL 1 temperature 300");
    located(
        &r,
        "temperature (a wall's temperature for fix heat/gran) is not supported yet",
        "temperature",
    );
    let r = error_of("fix w all wall/gran/hertz/history primitive type 1 zplane 0 viscous on");
    located(&r, "viscous damping", "on");
    // `store_force yes` runs (tests/wall_store_force.rs in rdem-cli); a bad value does not.
    let r =
        error_of("fix w all wall/gran/hertz/history primitive type 1 zplane 0 store_force maybe");
    located(&r, "maybe", "maybe");
    let r = error_of("fix w all wall/gran/hertz/history 2 0 zplane 0 NULL 1");
    located(&r, "dampflag must be 0 or 1, not '2'", "2");
    let r = error_of("fix w all wall/gran/hertz/history 1 0 zplane NULL NULL 1");
    located(&r, "both lo and hi are NULL", "zplane");
    let r = error_of("fix w all wall/gran/hertz/history 1 0 zcylinder 0.1 1 shear x 1");
    located(&r, "only shear along the axis", "x");
    let r = error_of("fix w all wall/gran/hertz/history primitive type 1 zplane 0 cohesion easo");
    located(&r, "unknown cohesion model 'easo'", "easo");

    let e = common::interpreter()
        .run_source(
            "in.bad",
            &format!("{HEAD}pair_style gran/hertz/history 1000 500 10 5 0.5 1\n"),
        )
        .expect_err("LAMMPS' form");
    let r = render(&e);
    located(&r, "dampflag must be 0 or 1, not '1000'", "1000");
    assert!(
        r.contains("LAMMPS' 'Kn Kt gamma_n gamma_t xmu dampflag' form is not supported"),
        "{r}"
    );
    let e = common::interpreter()
        .run_source(
            "in.bad1",
            &format!("{HEAD}pair_style gran/hertz/history 1 0 1\n"),
        )
        .expect_err("three flags");
    located(&render(&e), "unexpected extra argument '1'", "1");
    let e = common::interpreter()
        .run_source(
            "in.bad2",
            &format!("{HEAD}pair_style gran/hertz/history rolling_friction epsd\n"),
        )
        .expect_err("epsd is 3.x");
    located(&render(&e), "unknown rolling friction model 'epsd'", "epsd");
    let e = common::interpreter()
        .run_source(
            "in.bad3",
            &format!("{HEAD}pair_style gran/hertz/history/stiffness\n"),
        )
        .expect_err("not translated");
    located(
        &render(&e),
        "not a LIGGGHTS pair style rdem knows",
        "gran/hertz/history/stiffness",
    );
}
