//! `compute coord/atom` against closed forms on a lattice and against LIGGGHTS 3.8.
//!
//! tests/data/coord_atom/in.fff and in.ppp: a 5 × 5 × 5 simple cubic lattice (spacing a =
//! 0.02, diameter 0.01, skin 0.02, so the neighbor cutoff is 0.03), sites 1..60 of type 2;
//! cutoff 0.025 reaches the 6 nearest sites (a), 0.029 also the 12 at a√2 (not the 8 at
//! a√3 = 0.0346). `*.liggghts.dump` are LIGGGHTS 3.8's dumps of the same scripts
//! (`liggghts -in in.fff -log none`).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/coord_atom");

/// The lines after `ITEM: ATOMS` of a dump, trimmed.
fn atoms(dump: &str) -> Vec<String> {
    dump.lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| l.trim().to_string())
        .collect()
}

fn lattice(bound: &str) -> Vec<Vec<f64>> {
    let dir = std::env::temp_dir().join(format!("rdem-coord-{bound}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dump = dir.join(format!("{bound}.dump"));
    let src = std::fs::read_to_string(format!("{DIR}/in.{bound}"))
        .unwrap()
        .replace(&format!("{bound}.dump"), &dump.display().to_string());
    common::try_run(&format!("in.{bound}"), &src).unwrap_or_else(|e| panic!("{e}"));
    let ours = atoms(&std::fs::read_to_string(&dump).unwrap());
    let theirs = atoms(&std::fs::read_to_string(format!("{DIR}/{bound}.liggghts.dump")).unwrap());
    assert_eq!(ours.len(), 125);
    // The same numbers, line by line, as LIGGGHTS printed them.
    assert_eq!(
        ours, theirs,
        "{bound}: rdem's dump differs from LIGGGHTS 3.8's"
    );
    let _ = std::fs::remove_dir_all(&dir);
    ours.iter()
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Periodic: every site has 6 sites at a and 12 at a√2 (closed form); `mix yes` and the
/// type columns split the 18 by type; particles outside the group `half` get 0.
#[test]
fn periodic_lattice_closed_form_and_liggghts() {
    for row in lattice("ppp") {
        // id type all25 all29 mix t12[1] t12[2] t12[3]
        let (id, ty) = (row[0] as u64, row[1]);
        assert_eq!(row[2], 6.0, "{row:?}");
        assert_eq!(row[3], 18.0, "{row:?}");
        if id <= 60 {
            assert_eq!(ty, 2.0);
            assert_eq!(row[5] + row[6], 18.0, "{row:?}");
            assert_eq!(row[7], 18.0, "{row:?}");
            // Type 1 neighbours are the other type: mix counts them.
            assert_eq!(row[4], row[5], "{row:?}");
        } else {
            assert_eq!(&row[5..8], &[0.0, 0.0, 0.0], "{row:?}");
        }
    }
}

/// Fixed faces: the count of site (i, j, k) is the number of offsets d ∈ {−1, 0, 1}³ with
/// 0 < |d|² ≤ 2 (cutoff 0.029) or |d|² = 1 (0.025) that stay inside the 5³ sites.
#[test]
fn bounded_lattice_closed_form_and_liggghts() {
    let rows = lattice("fff");
    for row in &rows {
        let id = row[0] as i64 - 1;
        let s = [id % 5, (id / 5) % 5, id / 25];
        let (mut near, mut both) = (0.0, 0.0);
        for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let d2 = dx * dx + dy * dy + dz * dz;
                    let t = [s[0] + dx, s[1] + dy, s[2] + dz];
                    if d2 == 0 || t.iter().any(|&v| !(0..5).contains(&v)) {
                        continue;
                    }
                    near += f64::from(d2 == 1);
                    both += f64::from(d2 <= 2);
                }
            }
        }
        assert_eq!(row[2], near, "{row:?}");
        assert_eq!(row[3], both, "{row:?}");
    }
}

const POLY: &str = "\
units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region domain block 0 0.1 0 0.1 0 0.1 units box
create_box 2 domain
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
create_atoms 1 single 0.05 0.05 0.05 units box
create_atoms 1 single 0.02 0.02 0.02 units box
create_atoms TYPE single XJ 0.02 0.02 units box
set atom 1 diameter 0.01 density 1000
set atom 2 diameter 0.002 density 1000
set atom 3 diameter 0.002 density 1000
compute c all coord/atom CUT
compute s all reduce sum c_c
variable n equal c_s
run 0
print \"counted ${n}\"
";

/// The reach of LIGGGHTS' neighbor list, measured with LIGGGHTS 3.8 (this script, a dump
/// of `c_c` after `run 0`; the pair counts for both, particle 1 for none): particle 2 (type 1, r 0.001) and 3 at distance d; radius
/// 0.005 is the largest of type 1 (particle 1, far away), 0.001 of type 2; skin 0.002.
/// Cutoff 0.01: with particle 3 of type 2 the pair counts at d = 0.0079, not at 0.0081
/// (0.005 + 0.001 + 0.002 = 0.008); of type 1 it counts at d = 0.0115, not at 0.0125
/// (0.012). A cutoff of 0.012 runs, 0.0120001 stops ("cutoff is longer than neigh
/// cutoff").
#[test]
fn reach_of_each_type_pair_as_liggghts() {
    for (ty, d, cut, want) in [
        (2, 0.0079, "0.01", "counted 2"),
        (2, 0.0081, "0.01", "counted 0"),
        (1, 0.0115, "0.012", "counted 2"),
        (1, 0.0125, "0.012", "counted 0"),
    ] {
        let src = POLY
            .replace("TYPE", &ty.to_string())
            .replace("XJ", &format!("{}", 0.02 + d))
            .replace("CUT", cut);
        let i = common::try_run("in.poly", &src).unwrap_or_else(|e| panic!("{e}"));
        let out = common::screen(&i);
        assert!(
            out.lines().any(|l| l.trim() == want),
            "type {ty} d {d}: want '{want}' in\n{out}"
        );
    }
    let src = POLY
        .replace("TYPE", "2")
        .replace("XJ", "0.025")
        .replace("CUT", "0.0120001");
    let e = common::try_run("in.poly", &src)
        .err()
        .expect("cutoff beyond the neighbor cutoff");
    assert!(e.contains("longer than the neighbor cutoff 0.012"), "{e}");
}

/// Bad input: located errors as LIGGGHTS 3.8 stops on (`mix` only as the two words after
/// the cutoff, types 1..N, non-empty ranges).
#[test]
fn errors() {
    let head = POLY
        .split("compute c")
        .next()
        .unwrap()
        .replace("TYPE", "2")
        .replace("XJ", "0.025");
    for (words, want) in [
        ("0.01 mix maybe", "mix"),
        ("0.01 mix yes 1 2", "'mix' is not an atom type"),
        ("0.01 1 mix yes", "'mix' is not an atom type"),
        (
            "0.01 3",
            "type 3 is out of range: the box has 2 atom type(s)",
        ),
        ("0.01 0", "type 0 is out of range"),
        ("0.01 2*1", "empty type range '2*1'"),
        ("-1", "coord/atom cutoff"),
        ("", "coord/atom cutoff"),
    ] {
        let e = common::try_run(
            "in.bad",
            &format!("{head}compute c all coord/atom {words}\n"),
        )
        .err()
        .unwrap_or_else(|| panic!("'{words}' must stop"));
        assert!(e.contains(want), "{words}: {e}");
        assert!(e.contains("in.bad"), "{words}: not located: {e}");
    }
}
