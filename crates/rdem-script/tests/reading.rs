//! How scripts are read, checked against LIGGGHTS 3.8 (`liggghts -in in.x -log none`):
//! script files are bytes (comments and quoted text in any encoding), CRLF line ends,
//! numbers written as LIGGGHTS reads them, and the default units of `region` and
//! `create_atoms`. Each test's doc comment records what LIGGGHTS 3.8 did with the same
//! script.

use rdem_script::{Interpreter, Output, Sim};

/// The first lines of every script here: a granular SI set-up.
const PRE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
";

/// Materials, contact model and time step after `create_box`.
const POST: &str = "\
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
";

/// Runs `script`; the screen text, or the rendered error report.
fn try_run(script: &str) -> Result<String, String> {
    let mut i = Interpreter::new(Sim::new(Output::captured()));
    let r = i.run_source("in.test", script);
    let screen = i.sim.out.captured.clone().unwrap_or_default();
    match r {
        Ok(()) => Ok(screen),
        Err(e) => Err(render(&e)),
    }
}

/// Runs `script`, which must succeed; the screen text.
fn run(script: &str) -> String {
    try_run(script).unwrap_or_else(|e| panic!("{e}"))
}

/// A report as plain text.
fn render(r: &rdem_script::ScriptReport) -> String {
    let mut out = String::new();
    miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
        .with_width(200)
        .render_report(&mut out, r)
        .unwrap();
    out
}

/// Lines of `screen` starting with `prefix`.
fn lines_with<'s>(screen: &'s str, prefix: &str) -> Vec<&'s str> {
    screen.lines().filter(|l| l.starts_with(prefix)).collect()
}

/// `region` without `units` and no `lattice`: LIGGGHTS 3.8 runs it and prints
/// `Created orthogonal box = (0 0 0) to (1 1 1)`; its manual gives `units = box` as the
/// default. After `lattice sc 2.0` the same command still gives `(0 0 0) to (1 1 1)`;
/// with `units lattice` it gives `(0 0 0) to (2 2 2)`. `units lattice` with no lattice
/// command gives `(0 0 0) to (1 1 1)` (the default lattice `none 1.0`), and after
/// `lattice none 2.0` it gives `(0 0 0) to (2 2 2)`.
#[test]
fn region_units_default_to_box_and_lattice_defaults_to_none_1() {
    let created = |setup: &str| {
        let s = run(&format!("{PRE}{setup}\ncreate_box 1 reg\n"));
        lines_with(&s, "Created orthogonal box")[0].to_string()
    };
    let unit = "Created orthogonal box = (0 0 0) to (1 1 1)";
    let two = "Created orthogonal box = (0 0 0) to (2 2 2)";
    assert_eq!(created("region reg block 0 1 0 1 0 1"), unit);
    assert_eq!(created("region reg block 0 1 0 1 0 1 units box"), unit);
    assert_eq!(created("region reg block 0 1 0 1 0 1 units lattice"), unit);
    assert_eq!(
        created("lattice sc 2.0\nregion reg block 0 1 0 1 0 1"),
        unit
    );
    assert_eq!(
        created("lattice sc 2.0\nregion reg block 0 1 0 1 0 1 units lattice"),
        two
    );
    assert_eq!(
        created("lattice none 2.0\nregion reg block 0 1 0 1 0 1 units lattice"),
        two
    );
}

/// The same packing in a region written without `units` and with `units box` (LIGGGHTS
/// 3.8: `units box` is the default, see above): the same particles and the same thermo.
#[test]
fn region_without_units_builds_what_units_box_builds() {
    let script = |units: &str| {
        format!(
            "{PRE}region reg block -0.05 0.05 -0.05 0.05 0. 0.15{units}\ncreate_box 1 reg\n{POST}\
             fix g all gravity 9.81 vector 0 0 -1\n\
             fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.002\n\
             fix pd all particledistribution/discrete 10009 1 pts 1.0\n\
             region inlet block -0.04 0.04 -0.04 0.04 0.08 0.14{units}\n\
             fix ins all insert/pack seed 10037 distributiontemplate pd maxattempt 100 insert_every 1000 \
             overlapcheck yes all_in yes vel constant 0.0 0.0 -0.5 region inlet particles_in_region 20 ntry_mc 10000\n\
             fix nve all nve/sphere\ncompute z all property/atom z\ncompute zs all reduce sum c_z\n\
             thermo_style custom step atoms c_zs\nrun 10\n"
        )
    };
    let a = run(&script(""));
    let b = run(&script(" units box"));
    let rows = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| l.trim_start().starts_with("10 ") || l.trim_start().starts_with("0 "))
            .map(String::from)
            .collect()
    };
    assert_eq!(rows(&a).len(), 2, "{a}");
    assert!(rows(&a)[1].contains(" 20 "), "{a}");
    assert_eq!(rows(&a), rows(&b));
}

/// `create_atoms single` without `units`: LIGGGHTS 3.8 places the atom in box units
/// (its manual: "the default for ... units = box"). After `lattice sc 2.0` and
/// `create_atoms 1 single 0.3 0.3 0.3` a sphere of radius 1 at the origin held that atom
/// (`1 atoms in group g`), so it was not moved to 0.6. `create_atoms 1 box` with no
/// lattice stops with `ERROR: Cannot create atoms with undefined lattice`.
#[test]
fn create_atoms_single_defaults_to_box_units() {
    let s = run(&format!(
        "{PRE}lattice sc 2.0\nregion reg block 0 4 0 4 0 4\ncreate_box 1 reg\n\
         create_atoms 1 single 0.3 0.3 0.3\ncreate_atoms 1 single 1.3 0.3 0.3 units box\n\
         region s sphere 0 0 0 1.0\ngroup g region s\n\
         region s3 sphere 0 0 0 1.0 units lattice\ngroup g3 region s3\n"
    ));
    assert!(s.contains("\n1 atoms in group g\n"), "{s}");
    assert!(s.contains("\n2 atoms in group g3\n"), "{s}");
    let e = try_run(&format!(
        "{PRE}region reg block 0 1 0 1 0 1\ncreate_box 1 reg\ncreate_atoms 1 box\n"
    ))
    .unwrap_err();
    assert!(e.contains("create_atoms box/region needs a lattice"), "{e}");
    let e = try_run(&format!(
        "{PRE}lattice none 1.0\nregion reg block 0 1 0 1 0 1\ncreate_box 1 reg\ncreate_atoms 1 box\n"
    ))
    .unwrap_err();
    assert!(e.contains("create_atoms box/region needs a lattice"), "{e}");
}
