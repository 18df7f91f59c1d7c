//! A fix definition has three steps: its style's parser reads the words with the script
//! state read-only, the fix is installed (an engine fix handed to the world, a property
//! table, a template, a mesh), and `unfix` takes it out again. So a definition whose words
//! are wrong changes nothing — not even when it would replace a fix of the same ID — and
//! a good redefinition replaces the old one everywhere.

use rdem_script::Interpreter;

use crate::common;

const SETUP: &str = "units si\n\
    atom_style granular\n\
    boundary f f f\n\
    region box block 0 1 0 1 0 1 units box\n\
    create_box 1 box\n\
    fix m all property/global youngsModulus peratomtype 5e6\n\
    fix g all gravity 9.81 vector 0 0 -1\n\
    fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.01\n";

fn interpreter() -> Interpreter {
    common::run("in.setup", SETUP)
}

fn engine_fix_ids(i: &Interpreter) -> Vec<String> {
    let w = i.sim.world.as_ref().expect("box");
    w.fixes.iter().map(|f| f.id.clone()).collect()
}

#[test]
fn a_wrong_redefinition_keeps_the_old_fix() {
    let mut i = interpreter();
    // The engine fix: a vector with two components.
    i.run_source("in.bad", "fix g all gravity 9.81 vector 0 0\n")
        .expect_err("two components");
    assert_eq!(engine_fix_ids(&i), ["g"]);
    assert!(i.sim.fix_index("g").is_some());
    // A property table: a value that is not a number.
    i.run_source(
        "in.bad",
        "fix m all property/global youngsModulus peratomtype x\n",
    )
    .expect_err("not a number");
    assert_eq!(i.sim.defs.properties["youngsModulus"].values, [5e6]);
    // A template: no radius.
    i.run_source(
        "in.bad",
        "fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500\n",
    )
    .expect_err("no radius");
    assert!(i.sim.defs.templates.contains_key("pts"));
    assert_eq!(i.sim.defs.fixes.len(), 3);
}

#[test]
fn a_good_redefinition_replaces_the_old_fix_everywhere() {
    let mut i = interpreter();
    i.run_source(
        "in.good",
        "fix g all gravity 1.0 vector 0 0 -1\n\
         fix m all property/global youngsModulus peratomtype 7e6\n",
    )
    .expect("redefinitions run");
    assert_eq!(engine_fix_ids(&i), ["g"]);
    assert_eq!(i.sim.defs.properties["youngsModulus"].values, [7e6]);
    assert_eq!(i.sim.defs.fixes.len(), 3);
    i.run_source("in.unfix", "unfix g\nunfix m\nunfix pts\n")
        .expect("unfix runs");
    assert!(engine_fix_ids(&i).is_empty());
    assert!(i.sim.defs.properties.is_empty() && i.sim.defs.templates.is_empty());
    assert!(i.sim.defs.fixes.is_empty());
}

/// LIGGGHTS 3.8 reads template weights with C's atof: `1./6.` and `5./6.` are 1 and 5,
/// normalized to 1/6 and 5/6 (it printed mass shares 16.666667 % and 83.333333 %). rdem
/// reads them so, with a warning naming each; a weight with no number at its start is
/// still an error.
#[test]
fn template_weights_are_read_as_liggghts_reads_them() {
    let two = format!(
        "{SETUP}fix pts2 all particletemplate/sphere 15485867 atom_type 1 density constant 2500 radius constant 0.02\n"
    );
    let out = common::run_screen(
        "in.w",
        &format!(
            "{two}fix pdd all particledistribution/discrete 32452843 2 pts 1./6. pts2 5./6.\n"
        ),
    );
    assert!(out.contains("template weight '1./6.' read as 1,"), "{out}");
    assert!(out.contains("template weight '5./6.' read as 5,"), "{out}");
    assert!(out.contains("weights sum to 6, not 1; normalised"), "{out}");
    let e = common::error(
        "in.w",
        &format!("{two}fix pdd all particledistribution/discrete 32452843 2 pts half pts2 0.5\n"),
    );
    assert!(
        e.contains("template weight must be a number, not 'half'"),
        "{e}"
    );
}

/// The forks' radius distributions (LIGGGHTS 3.8's ParScale tutorial writes
/// `radius gaussian number MU SIGMA`): `number` forms are read, `mass` is refused as the
/// forks refuse it, and `lognormal` needs the basis word.
#[test]
fn the_forks_radius_distributions() {
    use rdem::insert::template::RadiusDist;
    let mut i = interpreter();
    i.run_source(
        "in.forks",
        "fix g1 all particletemplate/sphere 15485867 atom_type 1 density constant 1000 radius gaussian number 0.008 2.5e-3\n\
         fix g2 all particletemplate/sphere 32452843 atom_type 1 density constant 1000 radius lognormal number -6 0.2\n\
         fix g3 all particletemplate/sphere 32452867 atom_type 1 density constant 1000 radius uniform number 0.001 0.002\n",
    )
    .expect("the forks' number forms");
    let t = &i.sim.defs.templates;
    assert_eq!(t["g1"].radius, RadiusDist::GaussianWithin3(0.008, 2.5e-3));
    assert_eq!(t["g2"].radius, RadiusDist::Lognormal(-6.0, 0.2));
    assert_eq!(t["g3"].radius, RadiusDist::Uniform(0.001, 0.002));
    for (src, needle) in [
        (
            "radius gaussian mass 0.008 2.5e-3",
            "mass-based radius distribution",
        ),
        ("radius lognormal -6 0.2", "takes 'number mu sigma'"),
        (
            "radius gaussian number 0.002 0.001",
            "3 standard deviations",
        ),
    ] {
        let e = i
            .run_source(
                "in.bad",
                &format!("fix b all particletemplate/sphere 15485863 atom_type 1 density constant 1000 {src}\n"),
            )
            .expect_err(src);
        assert!(format!("{e:?}").contains(needle), "{src}: {e:?}");
    }
}
