//! `compute wall/gran/local` and `dump local`: two spheres (r 1 mm and 1.1 mm) pressed
//! 0.1 mm and 0.15 mm into a mesh plate of two triangles, sliding,
//! a third free and a fourth on a primitive plane (which LIGGGHTS 3.8 leaves out), Hertz
//! with tangential history, two steps. Every number of the dumps must equal LIGGGHTS
//! 3.8's (`tests/data/wall_local/`, recorded with the command in each script's header) to
//! the 6 digits it prints, and the contact area and overlap must be their closed forms.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/wall_local")
}

fn read(p: PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The rows of numbers after `ITEM: ENTRIES`.
fn rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .skip_while(|l| !l.starts_with("ITEM: ENTRIES"))
        .skip(1)
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// The header lines must be the same and every number within 2e-6 relative (LIGGGHTS
/// prints 6 digits) or 1e-15 absolute (its rounding residues, e.g. 1.1e-16 N across the
/// normal where rdem has 0, and a shear history of 5.9e-39 m where rdem has 0).
fn assert_same(ours: &str, theirs: &str, what: &str) {
    let head = |t: &str| {
        t.lines()
            .take_while(|l| !l.starts_with("ITEM: ENTRIES"))
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    assert_eq!(head(ours), head(theirs), "{what}: header");
    let (a, b) = (rows(ours), rows(theirs));
    assert_eq!(a.len(), b.len(), "{what}: rows\n{ours}");
    for (r, (ra, rb)) in a.iter().zip(&b).enumerate() {
        assert_eq!(ra.len(), rb.len(), "{what}: row {r} columns");
        for (c, (x, y)) in ra.iter().zip(rb).enumerate() {
            assert!(
                (x - y).abs() <= 2e-6 * y.abs() + 1e-15,
                "{what}: row {r} column {}: rdem {x}, LIGGGHTS {y}",
                c + 1
            );
        }
    }
}

#[test]
fn default_columns_match_liggghts() {
    let (dir, out) = common::run_data_script("wall_local", &data(), "in.wall", &["plate.stl"]);
    assert!(
        out.contains("primitive walls found"),
        "the primitive wall is reported, as LIGGGHTS warns: {out}"
    );
    for f in ["wall0.txt", "wall2.txt"] {
        assert_same(&read(dir.join("post").join(f)), &read(data().join(f)), f);
    }
}

#[test]
fn keyword_order_is_liggghts_order() {
    // Keywords given as delta contactArea force_tangential force_normal; LIGGGHTS writes
    // force_normal, force_tangential, contactArea, delta.
    let (dir, _) = common::run_data_script("wall_local", &data(), "in.wall_split", &["plate.stl"]);
    for f in ["split0.txt", "split2.txt"] {
        assert_same(&read(dir.join("post").join(f)), &read(data().join(f)), f);
    }
    // Closed forms at step 0 (positions as created): sphere 2 (r 1.1 mm, centre 0.95 mm
    // above the plate) then sphere 1 (r 1 mm, 0.9 mm): area π (r² − d²), overlap r − d;
    // the normal force along z only.
    let r = rows(&read(dir.join("post/split0.txt")));
    let pi = std::f64::consts::PI;
    for (row, (rad, d)) in r.iter().zip([(0.0011f64, 0.00095f64), (0.001, 0.0009)]) {
        let area = pi * (rad * rad - d * d);
        assert!((row[6] - area).abs() < 1e-6 * area, "{} vs {area}", row[6]);
        assert!((row[7] - (rad - d)).abs() < 1e-6 * (rad - d), "{}", row[7]);
        assert_eq!((row[0], row[1]), (0.0, 0.0));
        assert!(row[2] > 0.0);
    }
}

#[test]
fn contact_point_is_zero_for_walls_as_in_liggghts() {
    // LIGGGHTS 3.8 leaves a wall contact's point at 0 0 0 (point2.txt) and draws it as a
    // third point in the force chains (point2.vtk: 6 points, 6 lines for 2 contacts).
    let (dir, _) = common::run_data_script("wall_local", &data(), "in.wall_point", &["plate.stl"]);
    let ours = read(dir.join("post/point2.txt"));
    assert_same(&ours, &read(data().join("point2.txt")), "point2.txt");
    for row in rows(&ours) {
        assert_eq!(row.len(), 13, "pos id delta contactPoint");
        assert_eq!(&row[10..], &[0.0, 0.0, 0.0]);
    }
    assert_eq!(
        read(dir.join("post/point2.vtk")),
        read(data().join("point2.vtk")),
        "point2.vtk differs from LIGGGHTS 3.8's"
    );
}

#[test]
fn wall_local_needs_a_mesh_wall() {
    let script = "atom_style granular\nboundary f f f\nregion b block 0 1 0 1 0 1\n\
                  create_box 1 b\nfix m1 all property/global youngsModulus peratomtype 1e7\n\
                  fix m2 all property/global poissonsRatio peratomtype 0.3\n\
                  fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
                  fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
                  fix w all wall/gran model hertz tangential history primitive type 1 zplane 0\n\
                  compute c all wall/gran/local pos\n";
    let out = common::run_script_raw(script, None);
    let text =
        String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    assert!(
        text.contains("needs a fix wall/gran with mesh walls"),
        "{text}"
    );
    assert!(
        text.contains("wall/gran/local pos"),
        "the line is shown: {text}"
    );
}

#[test]
/// `heatFlux` without `fix heat/gran` stops the run, as LIGGGHTS 3.8 does (the values
/// themselves are checked in heat_local.rs).
fn heat_flux_needs_heat_conduction() {
    let (dir, _) = common::run_data_script("wall_local", &data(), "in.wall", &["plate.stl"]);
    let script = read(dir.join("in.wall")).replace(
        "compute wgl all wall/gran/local",
        "compute wgl all wall/gran/local pos vel id force torque history contactArea heatFlux",
    );
    std::fs::write(dir.join("in.heat"), script).unwrap();
    let out = common::rdem_command(None)
        .current_dir(&dir)
        .args(["-in", "in.heat", "-log", "none"])
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    assert!(
        text.contains("heatFlux needs the heat flows of a fix heat/gran"),
        "{text}"
    );
}
