//! `cohesion easo/capillary/viscous` against LIGGGHTS 3.8: the scripts of
//! tests/data/liquid/ run here and their numbers are compared with what LIGGGHTS wrote for
//! them (item40.liggghts.txt, item41.liggghts.txt; regenerate.sh there makes them).

use crate::common;

const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/liquid");

/// Runs tests/data/liquid/`name` with `from` replaced by `to` in its text; returns the
/// screen output.
fn run(name: &str, from: &str, to: &str) -> String {
    let src = std::fs::read_to_string(format!("{DIR}/{name}"))
        .unwrap()
        .replace(from, to);
    common::run_screen(name, &src)
}

/// The numeric rows of a `fix print` file (comment lines skipped).
fn rows(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

/// Item 40: two spheres (radii 1 mm and 0.8 mm), one wiggling in x and y through contact
/// and back beyond the bridge's rupture distance twice, the other turning in place.
/// Every step: the force on sphere 2, the torques on both, both liquid contents.
///
/// It covers the approach (no bridge: no force), the contact (Hertz, tangential history,
/// and the bridge's capillary force at zero gap and viscous normal and tangential forces,
/// the spin of sphere 2 entering the tangential velocity), the bridge holding apart
/// (capillary force decaying with the gap, viscous forces at the gap), its rupture at
/// (1 + θ/2)∛V (step 1154: the liquid shared out in proportion to the volumes, so that the
/// contents change to 0.00505445671720171 and 0.00489363922421541) and a second
/// contact with the new contents.
///
/// Tolerance: LIGGGHTS prints 15 significant digits; both evaluate the same formulas, so
/// every force and torque must agree to 1e-9 of the column's largest magnitude and every
/// content to 1e-12 relative. Measured: see the assertion messages.
#[test]
fn two_spheres_bridge_forms_pulls_and_breaks() {
    let path = std::env::temp_dir().join(format!("rdem-liquid40-{}.txt", std::process::id()));
    run(
        "item40.in",
        "file item40.txt",
        &format!("file {}", path.display()),
    );
    let ours = rows(&std::fs::read_to_string(&path).unwrap());
    let _ = std::fs::remove_file(&path);
    let theirs = rows(&std::fs::read_to_string(format!("{DIR}/item40.liggghts.txt")).unwrap());
    assert_eq!(ours.len(), theirs.len(), "one row per step");
    assert_eq!(theirs.len(), 2600);
    // Column scales: the largest magnitude of each force/torque column in LIGGGHTS' run.
    let scale: Vec<f64> = (0..7)
        .map(|c| theirs.iter().map(|r| r[c].abs()).fold(0.0, f64::max))
        .collect();
    let mut worst = [0.0f64; 7];
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a[0], b[0], "step");
        for c in 1..7 {
            let err = if c <= 4 {
                (a[c] - b[c]).abs() / scale[c]
            } else {
                (a[c] - b[c]).abs() / b[c].abs()
            };
            worst[c] = worst[c].max(err);
            let tol = if c <= 4 { 1e-9 } else { 1e-12 };
            assert!(
                err <= tol,
                "step {}: column {c} is {} in rdem, {} in LIGGGHTS (error {err:e})",
                b[0],
                a[c],
                b[c]
            );
        }
    }
    // The scenario reaches each phase: a contact force of several mN, a bridge pulling
    // apart, and the rupture with its liquid transfer.
    assert!(scale[1] > 5e-3, "peak contact force {}", scale[1]);
    let pulls_apart = theirs.iter().any(|r| r[0] > 1000.0 && r[1] < -7e-5);
    assert!(pulls_apart, "the bridge pulls after the contact");
    let last = theirs.last().unwrap();
    assert!(
        last[5] > 0.00505 && last[6] < 0.0049,
        "liquid moved: {last:?}"
    );
    eprintln!(
        "worst relative errors (fx fy tq1 tq2 l1 l2): {:?}",
        &worst[1..]
    );
}

/// Item 41: 252 wet spheres (two sizes) thrown about in a box settle into a bed; bridges
/// break in the first collisions and move liquid between the sizes. The run is chaotic,
/// so only the state the bed settles into is compared with LIGGGHTS' thermo at step
/// 10000: mean coordination number, mean height, total and extreme liquid contents.
#[test]
fn wet_bed_settles_as_in_liggghts() {
    let out = run("item41.in", "thermo_modify format float %.12g\n", "");
    let last = |text: &str| -> Vec<f64> {
        text.lines()
            .rfind(|l| l.split_whitespace().next() == Some("10000"))
            .unwrap_or_else(|| panic!("no row 10000 in\n{text}"))
            .split_whitespace()
            .map(|w| w.parse().unwrap())
            .collect()
    };
    let ours = last(&out);
    let theirs = last(&std::fs::read_to_string(format!("{DIR}/item41.liggghts.txt")).unwrap());
    // LIGGGHTS: step atoms ke liquidtransfer coord zbar lmax lmin at step 10000.
    assert_eq!(theirs[1], 252.0);
    assert_eq!(ours[1], 252.0);
    let close = |k: usize, what: &str, tol: f64| {
        let rel = (ours[k] - theirs[k]).abs() / theirs[k].abs();
        assert!(
            rel <= tol,
            "{what}: rdem {} LIGGGHTS {} (relative {rel:e})",
            ours[k],
            theirs[k]
        );
    };
    close(3, "total liquid content", 1e-3);
    close(4, "mean coordination number", 0.05);
    close(5, "mean height", 0.02);
    close(6, "largest liquid content", 0.01);
    close(7, "smallest liquid content", 0.01);
    // Settled: the kinetic energy dropped by five orders from the start.
    assert!(ours[2] < 1e-9, "kinetic energy {}", ours[2]);
}
