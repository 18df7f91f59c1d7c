//! LIGGGHTS-PFM's `general_plane`, `general_cylinder` and `general_cone` primitive walls
//! (`fix wall/gran ... primitive type T general_...`). An oblique, spinning impact on a
//! tilted general plane (inside a tilted general cylinder) is the impact on `zplane`
//! (inside `zcylinder`) turned by the same rotation, within 1e-9 of the box size: the
//! walls' geometry (distance and normal) is all that differs. The normals and axes are
//! given unnormalised, as the manual allows. The cone's geometry is checked against
//! closed forms in `rdem::wall::primitive`'s unit tests.
//!
//! Against the fork: LIGGGHTS-PFM d075b97, built here (FFT_NONE), ran
//! `tests/data/general_walls/in.{plane,cylinder,cone}` (an oblique spinning impact on a
//! tilted plane, inside a tilted cylinder and inside a tilted cone, 20000 steps); its dumps
//! are stored beside them as `pfm.dump.*`.

use glam::{DMat3, DVec3};

use crate::common;

/// Box ±0.2 m, fixed faces; one sphere of radius 5 mm (Hertz, friction 0.5, e 0.5).
const HEAD: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block -0.2 0.2 -0.2 0.2 -0.2 0.2 units box
create_box 1 box
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix integr all nve/sphere
";

fn words(v: DVec3) -> String {
    format!("{:.17e} {:.17e} {:.17e}", v.x, v.y, v.z)
}

/// Runs one sphere at `x` with velocity `v` and spin `w` against `wall` for 20 ms; the
/// last row of its dump (id x y z vx vy vz wx wy wz).
fn run(wall: &str, x: DVec3, v: DVec3, w: DVec3) -> Vec<f64> {
    let script = format!(
        "{HEAD}fix wall all wall/gran model hertz tangential history primitive type 1 {wall}
create_atoms 1 single {} units box
set atom 1 diameter 0.01 density 2500
velocity all set {}
set atom 1 omegax {} omegay {} omegaz {}
dump d all custom 20000 d.txt id x y z vx vy vz omegax omegay omegaz
dump_modify d format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 20000
",
        words(x),
        words(v),
        w.x,
        w.y,
        w.z
    );
    let (dir, out) = common::run_kept("general-walls", &script, &[], None);
    common::success("general wall", &out);
    let text = std::fs::read_to_string(dir.join("d.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    common::dump_frames(&text).pop().unwrap().1.remove(0)
}

/// Checks that `got` is `want` turned by `r` (positions, velocities and spins).
fn assert_turned(got: &[f64], want: &[f64], r: DMat3, what: &str) {
    for k in [1, 4, 7] {
        let g = DVec3::new(got[k], got[k + 1], got[k + 2]);
        let w = r * DVec3::new(want[k], want[k + 1], want[k + 2]);
        let scale = if k == 1 { 0.2 } else { 1.0 + w.length() };
        assert!(
            (g - w).length() < 1e-9 * scale,
            "{what}: columns {k}..{}: {g} against {w}",
            k + 2
        );
    }
}

#[test]
fn tilted_general_walls_are_the_axis_walls_turned() {
    let r = DMat3::from_rotation_x(0.6) * DMat3::from_rotation_z(0.3);
    let (x, v, w) = (
        DVec3::new(0.01, 0.0, 0.012),
        DVec3::new(0.3, 0.1, -1.0),
        DVec3::new(0.0, 5.0, 0.0),
    );
    // The plane: z = 0 against the plane through the origin turned (normal ×3).
    let want = run("zplane 0.0", x, v, w);
    assert!(want[6] > 0.0, "no bounce: {want:?}");
    let n = r * DVec3::Z * 3.0;
    let got = run(
        &format!("general_plane 0 0 0 {}", words(n)),
        r * x,
        r * v,
        r * w,
    );
    assert_turned(&got, &want, r, "general_plane");
    // The cylinder: radius 2 cm about the z axis, the sphere inside moving out.
    let (x, v) = (DVec3::new(0.005, 0.002, 0.0), DVec3::new(1.0, 0.2, 0.3));
    let want = run("zcylinder 0.02 0.0 0.0", x, v, w);
    assert!(want[4] < 0.0, "no bounce: {want:?}");
    let axis = r * DVec3::Z * -0.5;
    let got = run(
        &format!("general_cylinder 0.02 0 0 0 {}", words(axis)),
        r * x,
        r * v,
        r * w,
    );
    assert_turned(&got, &want, r, "general_cylinder");
}

#[test]
fn general_walls_reject_what_they_cannot_be() {
    let out = common::run_script_raw(
        &format!("{HEAD}fix wall all wall/gran model hertz tangential history primitive type 1 general_plane 0 0 0 0 0 0\n"),
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("has no direction"), "{err}");
    let out = common::run_script_raw(
        &format!("{HEAD}fix wall all wall/gran model hertz tangential history primitive type 1 general_cone 0.1 0 0 0 0 0 0 0.2\n"),
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("rim centres must differ"), "{err}");
    let out = common::run_script_raw(
        &format!("{HEAD}fix wall all wall/gran model hertz tangential history primitive type 1 general_plane 0 0 0 0 0 1 shear x 1.0\n"),
        None,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("'shear' with a general_plane"), "{err}");
}

#[test]
fn general_walls_match_liggghts_pfm() {
    let data = std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/general_walls"
    ));
    for wall in ["plane", "cylinder", "cone"] {
        let script = format!("in.{wall}");
        let (dir, _) = common::run_data_script("general-walls-pfm", data, &script, &[]);
        let got = common::dump_frames(
            &std::fs::read_to_string(dir.join(format!("dump.{wall}"))).unwrap(),
        );
        let _ = std::fs::remove_dir_all(&dir);
        let want = common::dump_frames(
            &std::fs::read_to_string(data.join(format!("pfm.dump.{wall}"))).unwrap(),
        );
        assert_eq!(got.len(), 11, "{wall}: frames");
        assert_eq!(got.len(), want.len(), "{wall}: frames");
        let rows = |f: &[(u64, Vec<Vec<f64>>)]| -> Vec<Vec<f64>> {
            f.iter()
                .map(|(step, r)| {
                    std::iter::once(*step as f64)
                        .chain(r[0][1..].iter().copied())
                        .collect()
                })
                .collect()
        };
        let (g, w) = (rows(&got), rows(&want));
        // Positions, velocities and spins within 1e-12 of each column's scale (measured:
        // 2e-14); the impact turned the velocity round.
        common::assert_columns(
            &g,
            &w,
            1,
            1e-12,
            &format!("general_{wall} against LIGGGHTS-PFM"),
        );
        let (v0, v1) = (
            glam::DVec3::new(w[0][4], w[0][5], w[0][6]),
            glam::DVec3::new(w[10][4], w[10][5], w[10][6]),
        );
        assert!(
            v0.dot(v1) < 0.5 * v0.length_squared(),
            "{wall}: {v0} then {v1}"
        );
    }
}
