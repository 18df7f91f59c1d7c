//! Tests of the parent module.

use super::*;

const GOOD: &str = "title line 3 atoms\n\n3 atoms # count\n2 atom types\n\n\
    0 1 xlo xhi\n-1 1.5 ylo yhi\n\
    0 2 zlo zhi\n\nAtoms # granular\n\n1 1 0.1 2500 0.2 0.3 0.5 0 0 0\n\
    3 2 0.12 2600 0.7 0.3 0.5 -1 0 2  # comment\n2 1 0.1 2500 0.5 0.7 1.2 0 0 0\n\n\n\
    Velocities\n\n3 -0.1 0.2 0 0 0 0\n1 0.1 0 0 0 0 1.5\n2 0 0 -0.3 0.25 0 0\n";

#[test]
fn parses_a_granular_file() {
    let f = parse_data(GOOD).unwrap();
    assert_eq!(f.title, "title line 3 atoms");
    assert_eq!(f.natoms, 3);
    assert_eq!(f.ntypes, 2);
    assert_eq!(f.lo, DVec3::new(0.0, -1.0, 0.0));
    assert_eq!(f.hi, DVec3::new(1.0, 1.5, 2.0));
    assert_eq!(f.atoms.len(), 3);
    let a = &f.atoms[1];
    assert_eq!((a.id, a.ty, a.diameter, a.density), (3, 2, 0.12, 2600.0));
    assert_eq!(a.x, DVec3::new(0.7, 0.3, 0.5));
    assert_eq!(a.image, [-1, 0, 2]);
    assert_eq!(a.line, 13);
    assert_eq!(f.velocities.len(), 3);
    assert_eq!(f.velocities[1].id, 1);
    assert_eq!(f.velocities[1].omega, DVec3::new(0.0, 0.0, 1.5));
    assert_eq!(f.velocities[0].line, 19);
    let ps = f.new_particles();
    assert_eq!(ps[1].0.v, DVec3::new(-0.1, 0.2, 0.0));
    assert_eq!(ps[1].0.radius, 0.06);
    assert_eq!(ps[1].1, [-1, 0, 2]);
    assert_eq!(ps[2].0.v, DVec3::new(0.0, 0.0, -0.3));
    assert_eq!(ps[2].0.omega, DVec3::new(0.25, 0.0, 0.0));
    assert_eq!(ps[2].0.tag, 2);
    // Without a Velocities section the particles are at rest.
    let cut = GOOD.find("Velocities").unwrap();
    let f = parse_data(&GOOD[..cut]).unwrap();
    assert!(f.velocities.is_empty());
    let ps = f.new_particles();
    assert_eq!(ps[0].0.omega, DVec3::ZERO);
    assert_eq!(ps[1].0.v, DVec3::ZERO);
}

#[test]
fn defaults_without_box_or_atoms() {
    let f = parse_data("empty\n\n0 atoms\n").unwrap();
    assert_eq!(f.lo, DVec3::splat(-0.5));
    assert_eq!(f.hi, DVec3::splat(0.5));
    assert!(f.atoms.is_empty());
    let f = parse_data("only a title").unwrap();
    assert_eq!(f.natoms, 0);
}

/// (file, line, offending word, message fragment)
fn check_err(text: &str, line: usize, word: &str, msg: &str) {
    check_err_as(text, &AtomLayout::Granular, line, word, msg);
}

/// [`check_err`] for a file of `layout`.
fn check_err_as(text: &str, layout: &AtomLayout, line: usize, word: &str, msg: &str) {
    let e = parse_data_as(text, layout).unwrap_err();
    let l = text.lines().nth(line - 1).unwrap_or("");
    assert_eq!(e.line, line, "{e}");
    assert_eq!(&l[e.col_range.clone()], word, "{e}");
    assert!(e.message.contains(msg), "'{}' lacks '{msg}'", e.message);
}

#[test]
fn errors_point_at_the_word() {
    let head = "t\n2 atoms\n1 atom types\n0 1 xlo xhi\n\nAtoms\n\n";
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n2 1 0.1 abc 0.5 0.5 0.5\n"),
        9,
        "abc",
        "density",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n2 2 0.1 1 0.5 0.5 0.5\n"),
        9,
        "2",
        "outside 1..1",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n1 1 0.1 1 0.5 0.5 0.5\n"),
        9,
        "1",
        "used twice (first on line 8)",
    );
    check_err(
        &format!("{head}1 1 0 2500 0.5 0.5 0.5\n"),
        8,
        "0",
        "diameter must be > 0",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5 0 0 0\n2 1 0.1 1 0.5 0.5 0.5\n"),
        9,
        "2 1 0.1 1 0.5 0.5 0.5",
        "on all atom lines or on none",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5 7\n"),
        8,
        "7",
        "found 8",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5 0 1.5 0\n"),
        8,
        "1.5",
        "iy",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 nan\n"),
        8,
        "nan",
        "finite",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n"),
        9,
        "",
        "ends after 1 of the 2",
    );
    check_err(
        &format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n\n2 1 0.1 1 0.5 0.5 0.5\n"),
        9,
        "",
        "announces 2 atoms",
    );
    check_err(
        "t\n1 atoms\n1 atom types\nAtoms\n1 1 0.1 2500 0.5 0.5 0.5\n",
        5,
        "1",
        "expected an empty line after 'Atoms'",
    );
    check_err("t\n1 atoms\n1 atom types\n", 4, "", "no 'Atoms' section");
    check_err("t\n1 atoms\n", 3, "", "no 'atom types'");
    check_err("t\n3 atomz\n", 2, "atomz", "unknown header keyword 'atomz'");
    check_err("t\n1 2 atoms\n", 2, "2", "takes 1 value(s), found 2");
    check_err("t\n1 xlo xhi\n", 2, "xlo", "takes 2 value(s), found 1");
    check_err("t\n1 0 xlo xhi\n", 2, "1 0", "must be below");
    check_err("t\n1.5 atoms\n", 2, "1.5", "integer");
    check_err("t\n0 0 0 xy xz yz\n", 2, "xy xz yz", "triclinic");
    check_err("t\n4 bonds\n", 2, "bonds", "not supported");
    check_err("t\n1 atoms\n2 atoms\n", 3, "atoms", "given twice");
    check_err(
        "t\n0 atoms\n\nMasses\n\n1 1.0\n",
        4,
        "Masses",
        "diameter and density",
    );
    check_err("t\n0 atoms\n\nBonds\n", 4, "Bonds", "not supported");
    check_err(
        "t\n0 atoms\n\nAtomz\n",
        4,
        "Atomz",
        "unknown section keyword",
    );
    check_err(
        "t\n0 atoms\nAtoms\n\n4 bonds\n",
        5,
        "4 bonds",
        "header line after",
    );
    check_err(
        "t\n0 atoms\n\nVelocities\n\n",
        4,
        "Velocities",
        "after the 'Atoms'",
    );
    let vhead = format!("{head}1 1 0.1 2500 0.5 0.5 0.5\n2 1 0.1 1 0.5 0.5 0.5\n\nVelocities\n\n");
    check_err(
        &format!("{vhead}1 0 0 0 0 0 0\n5 0 0 0 0 0 0\n"),
        14,
        "5",
        "not in the Atoms",
    );
    check_err(
        &format!("{vhead}1 0 0 0 0 0 0\n1 0 0 0 0 0 0\n"),
        14,
        "1",
        "second velocity",
    );
    check_err(&format!("{vhead}1 0 0 0 0 0\n"), 13, "0", "found 6");
    check_err(&format!("{vhead}1 0 0 0 0 0 x\n"), 13, "x", "omegaz");
    check_err("", 1, "", "empty");
    let e = parse_data("t\n3 atomz\n").unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 2, column 3: unknown header keyword 'atomz'"
    );
}

#[test]
fn round_trip_is_exact() {
    let mut f = parse_data(GOOD).unwrap();
    f.atoms[0].x = DVec3::new(0.1 + 0.2, 1.0 / 3.0, -0.0);
    f.atoms[1].density = 1e-300;
    f.atoms[2].diameter = 5e-324;
    f.velocities[0].v = DVec3::new(1e22, -123_456_789.123_456_79, f64::MIN_POSITIVE);
    f.lo.x = -1e-7;
    let text = format_data(&f);
    let g = parse_data(&text).unwrap();
    assert_eq!(f, g);
    assert!(g.atoms[0].x.z.is_sign_negative());
    // Written numbers stay short.
    assert!(text.contains("\n1 1 0.1 2500 0.30000000000000004 0.3333333333333333 -0 0 0 0\n"));
    assert!(text.contains("-1e-7 1 xlo xhi"));
}

fn hybrid() -> AtomLayout {
    AtomLayout::Hybrid(vec![SubStyle::Sphere, SubStyle::BondGran])
}

const HYBRID: &str = "hybrid\n\n3 atoms\n1 atom types\n2 bonds\n1 bond types\n\
    2 extra bond per atom\n0 1 xlo xhi\n\nAtoms\n\n\
    1 1 0.2 0.3 0.5 0.1 2500 7 0 0 1\n2 1 0.4 0.3 0.5 0.12 2600 7 0 0 0\n\
    3 1 0.6 0.3 0.5 0.1 2500 8 0 0 0\n\nVelocities\n\n1 0.1 0 0 0 0 1\n2 0 0 0 0 0 0\n\
    3 0 0 0 0 0 0\n\nBonds\n\n1 1 1 2\n2 1 3 2\n";

fn check_hybrid_err(text: &str, line: usize, word: &str, msg: &str) {
    check_err_as(text, &hybrid(), line, word, msg);
}

/// `atom_style hybrid granular bond/gran`: `id type x y z diameter density molecule`,
/// bonds; the other sub-style order puts the molecule first.
#[test]
fn parses_a_hybrid_file_with_bonds() {
    let f = parse_data_as(HYBRID, &hybrid()).unwrap();
    let a = &f.atoms[1];
    assert_eq!(
        (a.id, a.diameter, a.density, a.molecule),
        (2, 0.12, 2600.0, 7)
    );
    assert_eq!(a.x, DVec3::new(0.4, 0.3, 0.5));
    assert_eq!(f.atoms[0].image, [0, 0, 1]);
    assert_eq!(f.velocities[0].omega, DVec3::new(0.0, 0.0, 1.0));
    assert_eq!(f.nbondtypes, 1);
    assert_eq!(
        f.bonds,
        vec![
            DataBond {
                id: 1,
                ty: 1,
                atoms: [1, 2]
            },
            DataBond {
                id: 2,
                ty: 1,
                atoms: [3, 2]
            }
        ]
    );
    let back = parse_data_as(&format_data(&f), &hybrid()).unwrap();
    assert_eq!(back, f);
    let other = AtomLayout::Hybrid(vec![SubStyle::BondGran, SubStyle::Sphere]);
    let g = parse_data_as(
        "t\n1 atoms\n1 atom types\nAtoms\n\n1 1 0 0 0 4 0.1 2500\n",
        &other,
    )
    .unwrap();
    assert_eq!((g.atoms[0].molecule, g.atoms[0].diameter), (4, 0.1));
    // Granular files have no bonds.
    check_err(HYBRID, 5, "bonds", "not supported by atom_style granular");
}

#[test]
fn hybrid_errors_point_at_the_word() {
    let bond = |to: &str| HYBRID.replace("2 1 3 2\n", to);
    check_hybrid_err(&bond("2 2 3 2\n"), 25, "2", "bond type 2 is outside 1..1");
    check_hybrid_err(
        &bond("2 1 3 9\n"),
        25,
        "9",
        "atom-ID 9 is not in the Atoms section",
    );
    check_hybrid_err(&bond("2 1 3 3\n"), 25, "3", "to itself");
    check_hybrid_err(&bond("2 1 3\n"), 25, "3", "a bond line has 4 values");
    check_hybrid_err(
        &HYBRID.replace("2 bonds", "3 bonds"),
        26,
        "",
        "the file ends after 2 of the 3 lines of 'Bonds'",
    );
    check_hybrid_err(
        &HYBRID.replace("7 0 0 1\n", "0 0 1\n"),
        12,
        "0",
        "an atom line has 8 values (atom-ID atom-type x y z diameter density molecule-ID) or 11",
    );
    check_hybrid_err(
        &HYBRID.replace("1 0.1 0 0 0 0 1\n", "1 0.1 0 0\n"),
        18,
        "0",
        "a velocity line has 7 values",
    );
    let cut = HYBRID.find("\nBonds").unwrap();
    check_hybrid_err(
        &HYBRID[..cut],
        21,
        "",
        "announces 2 bonds but there is no 'Bonds' section",
    );
    let moved = "t\n1 atoms\n1 atom types\n1 bonds\n1 bond types\nBonds\n\n1 1 1 1\n";
    check_hybrid_err(moved, 6, "Bonds", "after the 'Atoms' section");
    let no_bonds = AtomLayout::Hybrid(vec![SubStyle::Sphere]);
    let e = parse_data_as(HYBRID, &no_bonds).unwrap_err();
    assert!(
        e.message
            .contains("'bonds' is not supported by atom_style hybrid without bond/gran"),
        "{e}"
    );
}
