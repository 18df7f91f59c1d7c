//! `fix mesh/surface ... element_exclusion_list read|write FILE`: the triangles a list
//! leaves out, the lists rdem writes, and the lists it refuses.
//!
//! The expectations were measured on LIGGGHTS 3.8.0 (Debian build, `liggghts -in in.x
//! -log none`, 2026-12-04) with the same STL files and lists, the kept triangles read off
//! a `dump mesh/stl` at `run 0`.

use std::path::Path;

use rdem::DVec3;
use rdem_script::Interpreter;

use crate::common;
use common::render;

const HEAD: &str = "atom_style granular
atom_modify map array sort 0 0
boundary f f f
units si
newton off
communicate single vel yes
region domain block -1 4 -1 4 -1 2 units box
create_box 1 domain
fix m1 all property/global youngsModulus peratomtype 7.e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
";

type Tri = [[f64; 3]; 3];

/// The four triangles of `c.stl`: two of the floor z = 0, two of the wall y = 0.
const FOUR: [Tri; 4] = [
    [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.]],
    [[0., 0., 0.], [1., 1., 0.], [0., 1., 0.]],
    [[0., 0., 0.], [1., 0., 0.], [1., 0., 1.]],
    [[0., 0., 0.], [1., 0., 1.], [0., 0., 1.]],
];

/// ASCII STL of `tris` as LIGGGHTS was given it: `solid m` on line 1, then 7 lines per
/// facet, so facet k (0-based) begins on line 2 + 7 k.
fn ascii(tris: &[Tri]) -> String {
    let mut s = String::from("solid m\n");
    for t in tris {
        s.push_str(" facet normal 0 0 0\n  outer loop\n");
        for p in t {
            s.push_str(&format!("   vertex {:?} {:?} {:?}\n", p[0], p[1], p[2]));
        }
        s.push_str("  endloop\n endfacet\n");
    }
    s + "endsolid m\n"
}

/// Binary STL of `tris`.
fn binary(tris: &[Tri]) -> Vec<u8> {
    let mut b = b"binary".to_vec();
    b.resize(80, b' ');
    b.extend((tris.len() as u32).to_le_bytes());
    for t in tris {
        for x in [0f32, 0., 1.] {
            b.extend(x.to_le_bytes());
        }
        for p in t {
            for x in p {
                b.extend((*x as f32).to_le_bytes());
            }
        }
        b.extend([0, 0]);
    }
    b
}

/// Runs `HEAD` and the fix line `fix` (with `{d}` the test folder).
fn run(d: &Path, fix: &str) -> Result<Interpreter, String> {
    let src = format!("{HEAD}{}\n", fix.replace("{d}", &d.display().to_string()));
    common::try_run("in.x", &src)
}

/// The corners of each triangle of mesh `mesh`, in order.
fn triangles(i: &Interpreter, mesh: &str) -> Vec<[DVec3; 3]> {
    let w = i.sim.world.as_ref().expect("box");
    let m = &w.meshes[w.mesh_index(mesh).expect("mesh")].mesh;
    (0..m.tris.len() as u32).map(|t| m.corners(t)).collect()
}

fn tris(list: &[Tri]) -> Vec<[DVec3; 3]> {
    list.iter().map(|t| t.map(DVec3::from_array)).collect()
}

/// `16` and `2` (any order) leave out the 3rd and the 1st facet of an ASCII file; in a
/// binary file the numbers are positions. LIGGGHTS 3.8 keeps the same triangles: the 2nd
/// and 4th for lists `16 2` (ASCII) and `3 1` (binary), one number per line.
#[test]
fn mesh_exclusion_read_leaves_out_the_listed_facets() {
    let d = common::scratch_dir("mesh-exclusion-read");
    std::fs::write(d.join("c.stl"), ascii(&FOUR)).unwrap();
    std::fs::write(d.join("cb.stl"), binary(&FOUR)).unwrap();
    std::fs::write(d.join("ex.txt"), "16\n2\n").unwrap();
    std::fs::write(d.join("exb.txt"), "3\n  1  \n").unwrap();
    std::fs::write(d.join("empty.txt"), "").unwrap();
    let want = tris(&[FOUR[1], FOUR[3]]);
    let i = run(
        &d,
        "fix mesh all mesh/surface file {d}/c.stl type 1 element_exclusion_list read {d}/ex.txt",
    )
    .unwrap();
    assert_eq!(triangles(&i, "mesh"), want);
    let out = common::screen(&i);
    assert!(out.contains("2 triangle(s) of"), "{out}");
    let i = run(
        &d,
        "fix mesh all mesh/surface/stress file {d}/cb.stl type 1 element_exclusion_list read {d}/exb.txt",
    )
    .unwrap();
    assert_eq!(triangles(&i, "mesh"), want);
    // An empty list leaves out nothing (LIGGGHTS 3.8 too).
    let i = run(
        &d,
        "fix mesh all mesh/surface file {d}/c.stl type 1 element_exclusion_list read {d}/empty.txt",
    )
    .unwrap();
    assert_eq!(triangles(&i, "mesh"), tris(&FOUR));
    std::fs::remove_dir_all(&d).ok();
}

/// Lists LIGGGHTS 3.8 reads wrongly or refuses stop with the list's file and line, the
/// caret under the list's name in the script.
#[test]
fn mesh_exclusion_bad_lists_are_located_errors() {
    let d = common::scratch_dir("mesh-exclusion-bad");
    std::fs::write(d.join("c.stl"), ascii(&FOUR)).unwrap();
    std::fs::write(d.join("cb.stl"), binary(&FOUR)).unwrap();
    // LIGGGHTS 3.8 on these lists with c.stl: `2 3 16` leaves out only facet 1 (3 ends the
    // exclusions), `2 16` and a blank line leaves out nothing, `2 16` on one line and `x`
    // stop with "Expected integer parameter", a missing file stops with "can not open
    // file".
    let cases: [(&str, Option<&str>, &str, &str); 7] = [
        (
            "three.txt",
            Some("2\n3\n16\n"),
            "line 2: 3 is not the line number of a 'facet normal' line of the ASCII STL file",
            "every larger number",
        ),
        (
            "zero.txt",
            Some("0\n"),
            "line 1: 0 is not",
            "one number per line",
        ),
        (
            "blank.txt",
            Some("2\n16\n\n"),
            "line 3 is blank",
            "would exclude nothing",
        ),
        (
            "two.txt",
            Some("2 16\n"),
            "line 1 holds more than one word",
            "one number per line",
        ),
        (
            "word.txt",
            Some("2\nx\n"),
            "line 2: 'x' is not an integer",
            "one number per line",
        ),
        (
            "float.txt",
            Some("2.0\n"),
            "line 1: '2.0' is not an integer",
            "one number per line",
        ),
        (
            "missing.txt",
            None,
            "cannot read element exclusion list",
            "one number per line",
        ),
    ];
    for (name, text, message, help) in cases {
        if let Some(text) = text {
            std::fs::write(d.join(name), text).unwrap();
        }
        let path = d.join(name).display().to_string();
        let fix = format!(
            "fix mesh all mesh/surface file {}/c.stl type 1 element_exclusion_list read {path}",
            d.display()
        );
        let mut i = common::interpreter();
        let r = i
            .run_source("in.x", &format!("{HEAD}{fix}\n"))
            .expect_err(name);
        let text = render(&r);
        let col = fix.find(&path).unwrap() + 1;
        assert!(text.contains(&format!("in.x:15:{col}")), "{name}: {text}");
        assert!(
            text.contains(&format!("element exclusion list {path}")),
            "{name}: {text}"
        );
        assert!(text.contains(message), "{name}: {text}");
        let help_line = text
            .lines()
            .find(|l| l.trim_start().starts_with("help:"))
            .unwrap_or("");
        assert!(help_line.contains(help), "{name}: {text}");
    }
    // A binary file's numbers are positions: 5 of 4 triangles is none.
    std::fs::write(d.join("five.txt"), "5\n").unwrap();
    let e = run(
        &d,
        "fix mesh all mesh/surface file {d}/cb.stl type 1 element_exclusion_list read {d}/five.txt",
    )
    .err()
    .unwrap();
    assert!(
        e.contains("5 is not the number (1 to 4) of a triangle of the binary STL file"),
        "{e}"
    );
    std::fs::remove_dir_all(&d).ok();
}

/// `write` lists slivers, all copies but the last of a repeated triangle and triangles
/// with more than 5 edge neighbours, one number a line, increasing.
///
/// LIGGGHTS 3.8 wrote `37 2 2` for `m.stl` (the four facets, facet 1 again at line 30, a
/// sliver at line 37), then stopped on the sliver; read back, that list keeps lines 9,
/// 16, 23 and 30. For a fan of 7 triangles about one edge it listed all 7, for 6 none;
/// with `heal auto_remove_duplicates` it listed no duplicate; it listed a right-angled
/// sliver of 0.05729 degrees and not one of 0.0573.
#[test]
fn mesh_exclusion_write_lists_bad_triangles() {
    let d = common::scratch_dir("mesh-exclusion-write");
    let sliver: Tri = [[2., 0., 0.], [3., 0., 0.], [2.5, 1e-9, 0.]];
    let m = [FOUR[0], FOUR[1], FOUR[2], FOUR[3], FOUR[0], sliver];
    std::fs::write(d.join("m.stl"), ascii(&m)).unwrap();
    let list = d.join("excl.txt");
    // Without heal, rdem stops on the repeated triangle after writing the list.
    let e = run(
        &d,
        "fix mesh all mesh/surface file {d}/m.stl type 1 element_exclusion_list write {d}/excl.txt",
    )
    .err()
    .unwrap();
    assert!(e.contains("repeat an earlier one"), "{e}");
    assert!(e.contains("'element_exclusion_list read"), "{e}");
    assert_eq!(std::fs::read_to_string(&list).unwrap(), "2\n37\n");
    let i = run(
        &d,
        "fix mesh all mesh/surface file {d}/m.stl type 1 element_exclusion_list read {d}/excl.txt",
    )
    .unwrap();
    assert_eq!(triangles(&i, "mesh"), tris(&m[1..5]));
    // LIGGGHTS' own list reads the same.
    std::fs::write(d.join("liggghts.txt"), "37\n2\n2\n").unwrap();
    let i = run(
        &d,
        "fix mesh all mesh/surface file {d}/m.stl type 1 element_exclusion_list read {d}/liggghts.txt",
    )
    .unwrap();
    assert_eq!(triangles(&i, "mesh"), tris(&m[1..5]));
    // With heal the copies are no longer listed (nor in LIGGGHTS 3.8); the mesh imports.
    run(
        &d,
        "fix mesh all mesh/surface file {d}/m.stl type 1 heal auto_remove_duplicates element_exclusion_list write {d}/excl.txt",
    )
    .unwrap();
    assert_eq!(std::fs::read_to_string(&list).unwrap(), "37\n");
    // Fans about the edge (0,0,0)-(1,0,0): 7 triangles have 6 neighbours each, 6 have 5.
    for (n, want) in [(7, "2\n9\n16\n23\n30\n37\n44\n"), (6, "")] {
        let fan: Vec<Tri> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                [[0., 0., 0.], [1., 0., 0.], [0.5, a.cos(), a.sin()]]
            })
            .collect();
        std::fs::write(d.join("fan.stl"), ascii(&fan)).unwrap();
        run(
            &d,
            "fix mesh all mesh/surface file {d}/fan.stl type 1 element_exclusion_list write {d}/excl.txt",
        )
        .unwrap();
        assert_eq!(std::fs::read_to_string(&list).unwrap(), want, "fan of {n}");
    }
    // Right-angled slivers: listed below 1e-3 rad (0.0572958 degrees).
    let slivers: Vec<Tri> = [0.0574, 0.0573, 0.05729, 0.0572]
        .iter()
        .enumerate()
        .map(|(k, deg)| {
            let y = 0.1 * k as f64;
            [
                [0., y, 0.],
                [1., y, 0.],
                [1., y + f64::to_radians(*deg).tan(), 0.],
            ]
        })
        .collect();
    std::fs::write(d.join("s.stl"), ascii(&slivers)).unwrap();
    run(
        &d,
        "fix mesh all mesh/surface file {d}/s.stl type 1 element_exclusion_list write {d}/excl.txt",
    )
    .unwrap();
    assert_eq!(std::fs::read_to_string(&list).unwrap(), "16\n23\n");
    // A good mesh gives an empty list.
    std::fs::write(d.join("c.stl"), ascii(&FOUR)).unwrap();
    run(
        &d,
        "fix mesh all mesh/surface file {d}/c.stl type 1 element_exclusion_list write {d}/excl.txt",
    )
    .unwrap();
    assert_eq!(std::fs::read_to_string(&list).unwrap(), "");
    std::fs::remove_dir_all(&d).ok();
}
