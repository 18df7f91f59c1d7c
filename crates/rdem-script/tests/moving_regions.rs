//! Moving regions (`region ... move v_x v_y v_z rotate v_theta P R`): placed by their
//! equal-style variables each time they are used. Checked against LIGGGHTS 3.8 on
//! tests/data/regions/in.moving (a sphere that travels, a block that turns about z, a
//! side-out block that both moves and turns about (1, 1, 0), their union; `count`,
//! `mass`, `xcm`, `vcm`, `ke`, `bound` with a region; `group`, `delete_atoms` and `set`
//! with a moving region after a run). LIGGGHTS' lines are in moving.liggghts.txt with
//! the command that made them.

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/regions");

fn run(src: &str) -> Result<String, String> {
    common::try_screen("in.moving", src)
}

/// Every thermo line and every count LIGGGHTS printed, exactly (`%.12g`): the particles
/// in each region at each step depend on the region's pose at that step.
#[test]
fn counts_and_sums_follow_the_regions_as_liggghts() {
    let src = std::fs::read_to_string(format!("{DIR}/in.moving")).unwrap();
    let out = run(&src).unwrap();
    let liggghts = std::fs::read_to_string(format!("{DIR}/moving.liggghts.txt")).unwrap();
    let mut n = 0;
    for l in liggghts.lines().filter(|l| !l.starts_with('#')) {
        let l = l.trim_end();
        assert!(
            out.lines().any(|o| o.trim_end() == l),
            "LIGGGHTS printed '{l}', rdem did not:\n{out}"
        );
        n += 1;
    }
    assert_eq!(n, 18);
}

const HEAD: &str = "units si
atom_style granular
boundary f f f
region domain block 0 1 0 1 0 1 units box
create_box 1 domain
variable dx equal 0.1*step
create_atoms 1 single 0.55 0.5 0.5 units box
set atom * diameter 0.02 density 2500
";

/// A region moved by `move` is found by `group` where the variables put it at the time
/// of the command, not where it was defined.
#[test]
fn a_group_takes_the_region_where_it_is_now() {
    let out = run(&format!(
        "{HEAD}region r sphere 0.05 0.5 0.5 0.1 move v_dx NULL NULL
variable n equal count(all,r)
print \"at0=${{n}}\"
run 5
group g region r
print \"at5=${{n}} g=$(count(g))\""
    ))
    .unwrap();
    // Step 0: centre 0.05, the particle at 0.55 is outside; step 5: centre 0.55.
    assert!(out.contains("at0=0") && out.contains("at5=1 g=1"), "{out}");
}

#[test]
fn insertion_union_and_bad_motion_are_errors() {
    let e = run(&format!(
        "{HEAD}region r block 0 0.2 0 0.2 0 0.2 move v_dx NULL NULL
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.01
fix pdd all particledistribution/discrete 15485867 1 pts 1.0
fix ins all insert/pack seed 32452843 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 5 region r"
    ))
    .unwrap_err();
    assert!(e.contains("dynamic regions are not allowed"), "{e}");
    let e = run(&format!(
        "{HEAD}region a sphere 0 0 0 0.1
region u union 1 a move v_dx NULL NULL"
    ))
    .unwrap_err();
    assert!(e.contains("region union cannot move"), "{e}");
    let e = run(&format!(
        "{HEAD}region a sphere 0 0 0 0.1 move dx NULL NULL"
    ))
    .unwrap_err();
    assert!(
        e.contains("must be an equal-style variable v_name or NULL"),
        "{e}"
    );
    let e = run(&format!(
        "{HEAD}region a sphere 0 0 0 0.1 rotate v_th 0 0 0 0 0 0"
    ))
    .unwrap_err();
    assert!(e.contains("rotation axis must not be 0 0 0"), "{e}");
    // The variable is looked up at the first use, as LAMMPS does at run set-up.
    let e = run(&format!(
        "{HEAD}region a sphere 0 0 0 0.1 move NULL v_nope NULL
group g region a"
    ))
    .unwrap_err();
    assert!(
        e.contains("region a moves with v_nope: no variable 'nope'"),
        "{e}"
    );
    let e = run(&format!(
        "{HEAD}variable s string abc
region a sphere 0 0 0 0.1 rotate v_s 0 0 0 0 0 1
variable n equal count(all,a)
print \"$n\""
    ))
    .unwrap_err();
    assert!(e.contains("variable 's' is not equal-style"), "{e}");
}
