//! `fix pour` (LAMMPS' and LIGGGHTS 1.x's particle pouring). The batch size, interval and
//! last insertion step must be LAMMPS' (its line "Particle insertion: n every m steps, N
//! by step s", recorded from the Debian `lammps` package with the scripts in
//! tests/data/pour/, same regions, sizes, fractions and gravity); batches come at the same
//! steps (LAMMPS' atom counts every 50 steps); every sphere lies wholly in the region
//! without overlaps, with the z velocity of a fall from the region's top
//! −√(vz² + 2 g (top − z)) to 1e-12, and diameters from the law asked for.

use crate::common;

use std::path::PathBuf;

/// The LIGGGHTS 3.x head of every test script: box, materials, gravity.
fn head(box_hi: [f64; 3], dt: f64) -> String {
    format!(
        "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region box block 0 {} 0 {} 0 {} units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep {dt}
fix grav all gravity 9.81 vector 0 0 -1
",
        box_hi[0], box_hi[1], box_hi[2]
    )
}

fn run(name: &str, script: &str) -> (PathBuf, String, String, bool) {
    let (dir, out) = common::run_kept(name, script, &[], None);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (dir, stdout, stderr, out.status.success())
}

/// Rows of the last snapshot of a dump.
fn last_snapshot(text: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut inside = false;
    for l in text.lines() {
        if l.starts_with("ITEM: ATOMS") {
            inside = true;
            rows.clear();
        } else if l.starts_with("ITEM:") {
            inside = false;
        } else if inside {
            rows.push(l.split_whitespace().map(|w| w.parse().unwrap()).collect());
        }
    }
    rows
}

const DUMP: &str = "fix integr all nve/sphere
dump d all custom 1 dump.pour id x y z vx vy vz radius
dump_modify d first no format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 1
";

/// Checks the snapshot after the first batch: `n` spheres, wholly in the block
/// `lo..hi` (or the z-cylinder of `axis_r` = (cx, cy, R)), no overlaps, the fall
/// velocity from `top` with `vz`, radii in `radii`.
#[allow(clippy::too_many_arguments)]
fn check_batch(
    rows: &[Vec<f64>],
    n: usize,
    lo: [f64; 3],
    hi: [f64; 3],
    cylinder: Option<(f64, f64, f64)>,
    vz: f64,
    radii: (f64, f64),
) {
    assert_eq!(rows.len(), n);
    let g = 9.81;
    // Inserted in the step's pre-exchange stage, a sphere then gets the second half-step
    // kick of that step only (gravity alone: no contacts between non-overlapping spheres).
    let dt = 1e-5;
    for r in rows {
        let (x, y, z, rad) = (r[1], r[2], r[3], r[7]);
        assert!(rad >= radii.0 && rad <= radii.1, "radius {rad}");
        let (v0, z0) = (r[6] + 0.5 * g * dt, z);
        let want = -(vz * vz + 2.0 * g * (hi[2] - z0)).sqrt();
        assert!((v0 - want).abs() <= 1e-12 * want.abs(), "vz {v0} vs {want}");
        assert_eq!((r[4], r[5]), (0.0, 0.0));
        assert!(z0 - rad >= lo[2] - 1e-12 && z0 + rad <= hi[2] + 1e-12);
        match cylinder {
            Some((cx, cy, radius)) => {
                assert!(((x - cx).powi(2) + (y - cy).powi(2)).sqrt() + rad <= radius + 1e-12)
            }
            None => {
                assert!(x - rad >= lo[0] && x + rad <= hi[0]);
                assert!(y - rad >= lo[1] && y + rad <= hi[1]);
            }
        }
    }
    for (i, a) in rows.iter().enumerate() {
        for b in &rows[i + 1..] {
            let d = ((a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2) + (a[3] - b[3]).powi(2)).sqrt();
            assert!(d >= a[7] + b[7] - 1e-12, "overlap {d}");
        }
    }
}

#[test]
fn a_block_batch_matches_lammps() {
    // LAMMPS (data/pour/in.lmp): "Particle insertion: 64457 every 14655 steps, 500 by step
    // 1" (a block's y extent 0.06 counts as 1, LAMMPS' quasi-2d rule).
    let script = head([0.06, 0.06, 0.2], 1e-5)
        + "region bc block 0.0 0.06 0.0 0.06 0.08 0.2 units box
fix ins all pour 500 1 12345 vol 0.3 1000 diam uniform 0.003 0.004 dens uniform 2650 2650 vel uniform 0 0 0 0 -0.1 region bc
"
        + DUMP;
    let (dir, stdout, stderr, ok) = run("pour_block", &script);
    assert!(ok, "{stdout}{stderr}");
    assert!(
        stdout.contains("Particle insertion: 64457 every 14655 steps, 500 by step 1\n"),
        "{stdout}"
    );
    let rows = last_snapshot(&std::fs::read_to_string(dir.join("dump.pour")).unwrap());
    check_batch(
        &rows,
        500,
        [0.0, 0.0, 0.08],
        [0.06, 0.06, 0.2],
        None,
        -0.1,
        (0.0015, 0.002),
    );
    // Uniform diameters in [3, 4] mm: mean 3.5 mm, σ of the mean 0.29/√500 mm.
    let mean = rows.iter().map(|r| 2.0 * r[7]).sum::<f64>() / 500.0;
    assert!(
        (mean - 0.0035).abs() < 4.0 * 0.000289 / 500f64.sqrt(),
        "{mean}"
    );
}

#[test]
fn a_cylinder_and_a_poly_mix_match_lammps() {
    // data/pour/in.cyl: "Particle insertion: 1054 every 13546 steps, 300 by step 1".
    let script = head([0.06, 0.06, 0.2], 1e-5)
        + "region bc cylinder z 0.03 0.03 0.025 0.1 0.19 units box
fix ins all pour 300 1 777 vol 0.2 100 diam one 0.004 dens 2650 2650 region bc
" + DUMP;
    let (dir, stdout, stderr, ok) = run("pour_cyl", &script);
    assert!(ok, "{stdout}{stderr}");
    assert!(
        stdout.contains("Particle insertion: 1054 every 13546 steps, 300 by step 1\n"),
        "{stdout}"
    );
    let rows = last_snapshot(&std::fs::read_to_string(dir.join("dump.pour")).unwrap());
    check_batch(
        &rows,
        300,
        [0.005, 0.005, 0.1],
        [0.055, 0.055, 0.19],
        Some((0.03, 0.03, 0.025)),
        0.0,
        (0.002, 0.002),
    );
    // data/pour/in.poly: "Particle insertion: 90665 every 14655 steps, 100 by step 1";
    // half the spheres of each diameter by number.
    let script = head([0.06, 0.06, 0.2], 1e-5)
        + "region bc block 0.0 0.06 0.0 0.06 0.08 0.2 units box
fix ins all pour 100 1 4242 vol 0.3 200 diam poly 2 0.003 0.5 0.004 0.5 dens 2650 2650 vel 0 0 0 0 -0.1 region bc
"
        + DUMP;
    let (dir, stdout, stderr, ok) = run("pour_poly", &script);
    assert!(ok, "{stdout}{stderr}");
    assert!(
        stdout.contains("Particle insertion: 90665 every 14655 steps, 100 by step 1\n"),
        "{stdout}"
    );
    let rows = last_snapshot(&std::fs::read_to_string(dir.join("dump.pour")).unwrap());
    let small = rows.iter().filter(|r| r[7] == 0.0015).count();
    let large = rows.iter().filter(|r| r[7] == 0.002).count();
    assert_eq!((small, large), (50, 50));
}

#[test]
fn batches_come_at_lammps_steps() {
    // data/pour/in.batch: "Particle insertion: 3 every 452 steps, 100 by step 14917";
    // LAMMPS' atom counts every 50 steps to 1000: 3 from step 1, 6 from 453, 9 from 905.
    // No floor: the box reaches down far enough for free fall through step 1000.
    let script = head([2.0, 2.0, 4.0], 1e-3).replace("0 2 0 2 0 4", "0 2 0 2 -10 4")
        + "region bc block 0.0 2 0.0 2 3 4 units box
fix ins all pour 100 1 12345 vol 0.0005 100 diam one 0.1 dens 1000 1000 region bc
fix integr all nve/sphere
thermo_style custom step atoms
thermo 50
run 1000
";
    let (_, stdout, stderr, ok) = run("pour_batch", &script);
    assert!(ok, "{stdout}{stderr}");
    assert!(
        stdout.contains("Particle insertion: 3 every 452 steps, 100 by step 14917\n"),
        "{stdout}"
    );
    let counts = common::thermo_rows(&stdout);
    let want: Vec<Vec<f64>> = (0..=20)
        .map(|k| {
            let step = 50 * k;
            let n = match step {
                0 => 0,
                s if s < 453 => 3,
                s if s < 905 => 6,
                _ => 9,
            };
            vec![step as f64, n as f64]
        })
        .collect();
    assert_eq!(counts, want, "{stdout}");
}

#[test]
fn what_pour_cannot_do_is_a_located_error() {
    let base = head([0.06, 0.06, 0.2], 1e-5) + "region bc block 0.0 0.06 0.0 0.06 0.08 0.2 units box\nregion s sphere 0.03 0.03 0.1 0.01 units box\n";
    for (line, message) in [
        (
            "fix ins all pour 10 1 1 region bc dens 2000 2650",
            "a spread of densities",
        ),
        (
            "fix ins all pour 10 1 1 region bc rate 0.1",
            "a moving insertion volume",
        ),
        ("fix ins all pour 10 1 1 region s", "needs a block region"),
        (
            "fix ins all pour 10 1 1 diam one 0.002",
            "needs 'region ID'",
        ),
        ("fix ins all pour 10 2 1 region bc", "atom type 2 is not"),
    ] {
        let (_, stdout, stderr, ok) = run("pour_bad", &format!("{base}{line}\n"));
        assert!(!ok, "{line}: {stdout}");
        assert!(stderr.contains(message), "{line}: {stderr}");
        assert!(stderr.contains("in.test:"), "{line}: located: {stderr}");
    }
    // Gravity must exist and point along -z.
    let no_gravity = base.replace("fix grav all gravity 9.81 vector 0 0 -1\n", "");
    let (_, _, stderr, ok) = run(
        "pour_bad",
        &format!("{no_gravity}fix ins all pour 10 1 1 region bc\n"),
    );
    assert!(!ok && stderr.contains("needs fix gravity"), "{stderr}");
    let sideways = base.replace("vector 0 0 -1", "vector 1 0 0");
    let (_, _, stderr, ok) = run(
        "pour_bad",
        &format!("{sideways}fix ins all pour 10 1 1 region bc\n"),
    );
    assert!(!ok && stderr.contains("needs gravity along -z"), "{stderr}");
}
