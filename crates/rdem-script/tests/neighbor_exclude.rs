//! `neigh_modify exclude type M N | group G1 G2 | none`: excluded pairs are left out of
//! the neighbor list and never interact (as in LAMMPS and LIGGGHTS: "exclude if one atom
//! in pair is type M, other is type N"), the others do.

use rdem_script::Interpreter;

use crate::common;

/// Three overlapping spheres at rest, no gravity: 1 and 2 of type 1, 3 of type 2, all
/// pairs overlapping by 2 mm. `tail` is read before a 10-step run.
fn run(tail: &str) -> Interpreter {
    let src = format!(
        "units si
atom_style granular
boundary f f f
region box block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 2 box
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0.018 0 0 units box
create_atoms 2 single 0.009 0.0156 0 units box
set atom * diameter 0.02 density 2500
neighbor 0.002 bin
fix m1 all property/global youngsModulus peratomtype 5e6 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.9 0.9 0.9 0.9
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
fix integr all nve/sphere
timestep 1e-6
{tail}
run 10
"
    );
    common::run("in.exclude", &src)
}

/// Speeds of atoms 1, 2, 3 after the run.
fn speeds(i: &Interpreter) -> [f64; 3] {
    let p = &i.sim.world.as_ref().unwrap().particles;
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        *o = p.v[p.find_tag(k as u64 + 1).unwrap()].length();
    }
    out
}

#[test]
fn excluded_pairs_never_touch() {
    // Without exclusion all three push apart.
    let s = speeds(&run(""));
    assert!(s.iter().all(|&v| v > 1e-4), "{s:?}");
    // Type 1–1 excluded: 1 and 2 feel only 3, symmetrically.
    let s = speeds(&run("neigh_modify exclude type 1 1"));
    let all = speeds(&run(""));
    assert!((s[0] - s[1]).abs() <= 1e-12 * s[0], "{s:?}");
    assert!(s[0] < all[0], "{s:?} vs {all:?}");
    // Every pair excluded (types 1–1 and 1–2, given either way round): nothing moves.
    let s = speeds(&run("neigh_modify exclude type 1 1 exclude type 2 1"));
    assert_eq!(s, [0.0; 3]);
    // By group: 3 alone in g3; its pairs with the rest excluded; 1 and 2 still repel.
    let i = run("group g3 id 3\ngroup g12 id 1 2\nneigh_modify exclude group g3 g12");
    let s = speeds(&i);
    assert_eq!(s[2], 0.0);
    assert!(s[0] > 1e-4 && (s[0] - s[1]).abs() <= 1e-12 * s[0], "{s:?}");
    // `none` clears the list.
    let s = speeds(&run(
        "neigh_modify exclude type 1 1\nneigh_modify exclude none",
    ));
    assert_eq!(s, all);
}

#[test]
fn bad_exclusions_are_located_errors() {
    let mut i = run("");
    for (line, want) in [
        (
            "neigh_modify exclude type 1 3\n",
            "atom type 3 is out of range",
        ),
        ("neigh_modify exclude group g9 all\n", "no group 'g9'"),
        ("neigh_modify exclude molecule all\n", "molecule IDs"),
        (
            "neigh_modify exclude bogus\n",
            "unknown exclude style 'bogus'",
        ),
    ] {
        let e = i.run_source("in.bad", line).expect_err(line);
        let text = format!("{e:?}");
        assert!(text.contains(want), "{line}: {text}");
    }
    // A wrong word changes nothing: the delay given before it is not kept.
    let before = i.sim.setup.neighbor;
    assert!(i
        .run_source("in.bad", "neigh_modify delay 5 exclude type 1 3\n")
        .is_err());
    assert_eq!(i.sim.setup.neighbor, before);
    assert!(i.sim.setup.exclude.is_empty());
}
