//! `group ID type|id|variable`: the value lists, sequences and logicals of LIGGGHTS'
//! group command. The counts are LIGGGHTS 3.8's for the same script (200 atoms on a
//! simple cubic lattice, IDs 1–200, atoms 5–20 of type 2).

use crate::common;

const HEAD: &str = "units si\n\
    atom_style granular\n\
    atom_modify map array\n\
    boundary f f f\n\
    region box block 0 1 0 1 0 1 units box\n\
    create_box 2 box\n\
    lattice sc 0.1\n\
    region r block 0 1 0 1 0 0.1 units box\n\
    create_atoms 1 region r\n\
    set atom 5*20 type 2\n";

/// The count that the screen gives for `group`.
fn count(screen: &str, group: &str) -> usize {
    let tail = format!(" atoms in group {group}");
    let line = screen
        .lines()
        .find(|l| l.ends_with(&tail))
        .unwrap_or_else(|| panic!("no count for {group}:\n{screen}"));
    line.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn value_lists_sequences_and_logicals_select_as_liggghts() {
    let cases = [
        ("a", "id <= 15", 15),
        ("b", "id > 95", 105),
        ("c", "id <> 10 20", 11),
        ("e", "id == 7", 1),
        ("f", "id >= 100", 101),
        ("g", "id < 2", 1),
        ("h", "id 100:10000:10", 11),
        ("i", "id 10 25 50 500:1000", 3),
        ("j", "type == 2", 16),
        ("k", "type 1:2:1", 200),
        ("m", "id 1:20:7", 3),
    ];
    let mut src = HEAD.to_string();
    for (g, args, _) in cases {
        src += &format!("group {g} {args}\n");
    }
    src += "variable v atom \"x < 0.35 && type == 1\"\ngroup l variable v\n";
    let s = common::run_screen("in.groups", &src);
    for (g, args, n) in cases {
        assert_eq!(count(&s, g), n, "group {g} {args}");
    }
    assert_eq!(count(&s, "l"), 76, "group l variable v");
}

/// LIGGGHTS 3.8 printed "1 atoms in group d" for `group d id != 3` and 0 for `type != 2`
/// with every atom of type 1: its `!=` selects the equal values. rdem does what the
/// manual says, and warns.
#[test]
fn not_equal_selects_the_other_values_with_a_warning() {
    let s = common::run_screen(
        "in.ne",
        &format!("{HEAD}group d id != 3\ngroup t type != 2\n"),
    );
    assert_eq!(count(&s, "d"), 199);
    assert_eq!(count(&s, "t"), 184);
    assert_eq!(
        s.matches("LIGGGHTS 3.8 selects the equal ones instead")
            .count(),
        2,
        "{s}"
    );
}

#[test]
fn bad_group_values_are_located_errors() {
    let line = HEAD.lines().count() + 1;
    // (arguments, column of the caret, message)
    for (args, col, msg) in [
        (
            "id <> 20 10",
            18,
            "the upper value 10 is below the lower 20",
        ),
        ("id 1:9:0", 12, "'1:9:0' is not a number or range a:b"),
        ("id <= 3 4", 17, "4"),
        ("id >", 13, "missing"),
        ("variable nov", 18, "no variable 'nov'"),
    ] {
        let e = common::error("in.bad", &format!("{HEAD}group x {args}\n"));
        assert!(e.contains(msg), "{args}: {e}");
        assert!(e.contains(&format!("in.bad:{line}:{col}")), "{args}: {e}");
    }
}

/// Inserted particles join the inserting fix's group, the template fix's and the
/// distribution fix's, as in LIGGGHTS 3.8 (measured with this script: 10 atoms in each of
/// g2, g3 and g4 after the insertion).
#[test]
fn inserted_particles_join_the_template_and_distribution_groups() {
    let src = "atom_style granular\n\
        atom_modify map array\n\
        boundary f f f\n\
        units si\n\
        region reg block 0 1 0 1 0 1 units box\n\
        create_box 2 reg\n\
        neighbor 0.01 bin\n\
        fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n\
        fix m2 all property/global poissonsRatio peratomtype 0.45 0.45\n\
        fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3\n\
        fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n\
        pair_style gran model hertz tangential history\n\
        pair_coeff * *\n\
        timestep 1e-5\n\
        group g2 region reg\n\
        group g3 region reg\n\
        group g4 region reg\n\
        group g5 region reg\n\
        fix pts1 g2 particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.02\n\
        fix pdd g4 particledistribution/discrete 15485867 1 pts1 1.0\n\
        region ins block 0.1 0.9 0.1 0.9 0.1 0.9 units box\n\
        fix ins g3 insert/pack seed 32452843 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 10 region ins\n\
        run 1\n\
        group c2 intersect g2 all\n\
        group c3 intersect g3 all\n\
        group c4 intersect g4 all\n\
        group c5 intersect g5 all\n";
    let s = common::run_screen("in.template_groups", src);
    assert_eq!(
        ["c2", "c3", "c4", "c5"].map(|g| count(&s, g)),
        [10, 10, 10, 0]
    );
}
