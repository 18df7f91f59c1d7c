//! `store_force yes` of `fix wall/gran` (and of the 2.x `wall/gran/hertz/history`): the
//! wall's force on each particle as the per-atom vector `f_force_ID[1..3]`; and
//! `dump_modify region`. Five spheres touch a floor plane, a drum (zcylinder) and a mesh
//! plate, and each other, for 20 steps (tests/data/store_force/in.store_force, with the
//! command that recorded LIGGGHTS 3.8's dumps in its header). Every position, force and
//! stored wall force of rdem equals LIGGGHTS 3.8's to 1e-10 relative (zeros exactly);
//! the resting sphere's floor force at step 0 is Hertz's 4/3 E* √R δ^1.5.

use crate::common;

use std::path::{Path, PathBuf};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/store_force")
}

/// Runs `script` in a scratch folder with the plate mesh; returns the folder and the
/// output.
fn run(name: &str, script: &str) -> (PathBuf, std::process::Output) {
    let plate = std::fs::read_to_string(data().join("plate.stl")).unwrap();
    common::run_kept(name, script, &[("plate.stl", &plate)], None)
}

fn script() -> String {
    std::fs::read_to_string(data().join("in.store_force")).unwrap()
}

/// Each snapshot's rows (after `ITEM: ATOMS`).
fn snapshots(text: &str) -> Vec<Vec<Vec<f64>>> {
    let mut out: Vec<Vec<Vec<f64>>> = Vec::new();
    let mut inside = false;
    for l in text.lines() {
        if l.starts_with("ITEM: ATOMS") {
            inside = true;
            out.push(Vec::new());
        } else if l.starts_with("ITEM:") {
            inside = false;
        } else if inside {
            let row = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            out.last_mut().unwrap().push(row);
        }
    }
    out
}

fn assert_same(ours: &str, theirs: &str, snaps: usize, what: &str) {
    let (a, b) = (snapshots(ours), snapshots(theirs));
    assert_eq!(a.len(), snaps, "{what}: snapshots\n{ours}");
    assert_eq!(a.len(), b.len(), "{what}: snapshots\n{ours}");
    for (s, (sa, sb)) in a.iter().zip(&b).enumerate() {
        assert_eq!(sa.len(), sb.len(), "{what} snapshot {s}: rows\n{ours}");
        for (ra, rb) in sa.iter().zip(sb) {
            assert_eq!(ra.len(), 16, "{what}: columns");
            for (c, (x, y)) in ra.iter().zip(rb).enumerate() {
                let ok = if *y == 0.0 {
                    *x == 0.0
                } else {
                    (x - y).abs() <= 1e-10 * y.abs()
                };
                assert!(
                    ok,
                    "{what} snapshot {s} particle {} column {}: rdem {x}, LIGGGHTS {y}",
                    ra[0],
                    c + 1
                );
            }
        }
    }
}

fn ok(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn stored_wall_forces_match_liggghts() {
    let (dir, out) = run("store_force", &script());
    ok(&out);
    let ours = std::fs::read_to_string(dir.join("dump.walls")).unwrap();
    let theirs = std::fs::read_to_string(data().join("dump.walls.liggghts")).unwrap();
    assert_same(&ours, &theirs, 5, "store_force");

    // Particle 5 rests on the floor only: at step 0 its stored floor force is the Hertz
    // force 4/3 E* √R δ^1.5 (E* = E / (2 (1 − ν²)), R = 0.01, δ = 0.0015) and its total
    // force that minus its weight.
    let row = &snapshots(&ours)[0][4];
    assert_eq!(row[0], 5.0);
    let e_star = 5.0e6 / (2.0 * (1.0 - 0.45f64 * 0.45));
    let hertz = 4.0 / 3.0 * e_star * 0.01f64.sqrt() * 0.0015f64.powf(1.5);
    assert!(
        (row[9] - hertz).abs() <= 1e-12 * hertz,
        "{} vs {hertz}",
        row[9]
    );
    let weight = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-6 * 9.81;
    assert!((row[6] - (hertz - weight)).abs() <= 1e-12 * hertz);
    assert_eq!(&row[10..16], &[0.0; 6]);
}

#[test]
fn dump_region_writes_the_particles_inside_at_each_snapshot() {
    let text = script().replace(
        "run 20",
        "region half block -0.1 0.0 -0.1 0.1 -0.1 0.1 units box\ndump_modify d region half\nrun 20",
    );
    let (dir, out) = run("store_force_region", &text);
    ok(&out);
    let ours = std::fs::read_to_string(dir.join("dump.walls")).unwrap();
    let theirs = std::fs::read_to_string(data().join("dump.region.liggghts")).unwrap();
    // 4 particles at x <= 0 at step 0, then 2: particles 1 and 4 move to x > 0.
    let counts: Vec<usize> = snapshots(&ours).iter().map(Vec::len).collect();
    assert_eq!(counts, [4, 2, 2, 2, 2]);
    assert_same(&ours, &theirs, 5, "region");
}

#[test]
fn old_syntax_walls_store_the_same_forces() {
    // The 2.x walls (LIGGGHTS 3.8 refuses them; rdem runs them as the 3.x walls).
    let text = script()
        .replace(
            "fix floor all wall/gran model hertz tangential history primitive type 1 zplane -0.05 store_force yes",
            "fix floor all wall/gran/hertz/history primitive type 1 zplane -0.05 store_force yes",
        )
        .replace(
            "fix side all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate store_force yes",
            "fix side all wall/gran/hertz/history mesh n_meshes 1 meshes plate store_force yes",
        );
    assert_eq!(text.matches("wall/gran/hertz/history").count(), 2);
    let (dir, out) = run("store_force_old", &text);
    ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("runs as: fix floor all wall/gran model hertz tangential history primitive type 1 zplane -0.05 store_force yes"),
        "{stdout}"
    );
    let (new_dir, new_out) = run("store_force_new", &script());
    ok(&new_out);
    let ours = std::fs::read_to_string(dir.join("dump.walls")).unwrap();
    let new = std::fs::read_to_string(new_dir.join("dump.walls")).unwrap();
    assert_eq!(ours, new);
}

#[test]
fn bad_store_force_lines_are_located_errors() {
    for (from, to, message) in [
        (
            "zplane -0.05 store_force yes",
            "zplane -0.05 store_force_contact yes",
            "store_force_contact yes is not supported",
        ),
        (
            "zplane -0.05 store_force yes",
            "zplane -0.05 store_force maybe",
            "maybe",
        ),
        (
            "zplane -0.05 store_force yes",
            "zplane -0.05",
            "no fix 'force_floor'",
        ),
        (
            "dump_modify d sort id",
            "dump_modify d region nowhere sort id",
            "no region 'nowhere'",
        ),
    ] {
        let text = script().replace(from, to);
        let (_, out) = run("store_force_bad", &text);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{to}: should fail");
        assert!(err.contains(message), "{to}: {err}");
        assert!(err.contains("in.test:"), "{to}: located: {err}");
    }
}
