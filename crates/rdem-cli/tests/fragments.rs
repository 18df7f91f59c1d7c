//! `fix insert/fragments` (LIGGGHTS-INL) with a relative, bonded `multiplespheres`
//! template and `cohesion bond`: two rigid rods of three spheres (one along x, one
//! turned to z) fly into a band, where each is replaced by three bonded fragments of its
//! own shape, which then hit a plane (`tests/data/fragments/in.fragments`, written for
//! these tests). Reference: the same script run by LIGGGHTS-INL d69df36 built here (its
//! thermo without `v_nf`, which the fork refuses beside `fix multisphere`):
//!
//! - both replace the first rod at step 15051 and the second at step 15101, and make 4
//!   bonds, which hold to the end;
//! - kinetic energy after the replacement (step 15100): the fork 0.00084822999, and 6 · ½ (4/3 π ρ r³) v²;
//! - at step 40000, after the bounce: the fork 0.00017367913. The rods start at random
//!   points of two small slabs (±0.1 mm in x, ±1 mm across) in each program, so the
//!   bounce differs a little (measured: rdem 0.00017327541, 0.23 % off).

use crate::common;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/fragments");

/// The fork's kinetic energy at step 40000.
const FORK_KE_END: f64 = 0.00017367913;

/// Runs the script with `threads` threads; returns the directory and the screen output.
fn run(threads: &str) -> (std::path::PathBuf, String) {
    run_on(threads, None)
}

/// [`run`] on `ranks` MPI ranks (`None`: serially).
fn run_on(threads: &str, ranks: Option<usize>) -> (std::path::PathBuf, String) {
    let dir = common::scratch_dir("fragments");
    std::fs::copy(format!("{DATA}/in.fragments"), dir.join("in.fragments")).unwrap();
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let out = common::rdem_in(&dir, "in.fragments", ranks)
        .env("RDEM_THREADS", threads)
        .output()
        .unwrap();
    let text = common::success("in.fragments", &out);
    (dir, text)
}

/// The rows of the last snapshot of the dump file `path`.
fn dump_rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    common::dump_frames(&text).pop().expect("a snapshot").1
}

#[test]
fn rods_become_bonded_fragments_as_in_the_fork() {
    let (dir, out) = run("1");
    // Step, atoms, ke, fragments (group of the template), created, broken, intact, wall.
    let rows: Vec<Vec<f64>> = common::thermo_rows(&out)
        .into_iter()
        .filter(|r| r.len() == 8)
        .collect();
    let row = |step: f64| {
        rows.iter()
            .find(|r| r[0] == step)
            .unwrap_or_else(|| panic!("no thermo row at step {step}"))
            .clone()
    };
    for step in [15051, 15101] {
        let line = format!(
            "Particle replacement: replaced 1 particle templates (mass 0.000849) at step {step}"
        );
        assert!(out.contains(&line), "{line}\n{out}");
    }
    assert_eq!(out.matches("Particle replacement:").count(), 2);
    let before = row(15000.0);
    assert_eq!((before[1], before[3], before[6]), (6.0, 0.0, 0.0));
    let after = row(15500.0);
    assert_eq!(&after[1..2], &[6.0]);
    assert_eq!(&after[3..8], &[6.0, 0.0, 0.0, 4.0, 0.0]);
    // Bonds made and broken (the counter gives them since its last evaluation).
    let sum = |k: usize| rows.iter().map(|r| r[k]).sum::<f64>();
    assert_eq!((sum(4), sum(5)), (4.0, 0.0));
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.003f64.powi(3);
    let ke = 6.0 * 0.5 * m;
    // Thermo prints 8 significant digits.
    assert!((after[2] - ke).abs() <= 1e-7 * ke, "{} vs {ke}", after[2]);
    assert!((after[2] - 0.00084822999).abs() <= 1e-10);
    let end = row(40000.0);
    assert_eq!(&end[3..8], &[6.0, 0.0, 0.0, 4.0, 0.0]);
    assert!(
        (end[2] - FORK_KE_END).abs() <= 0.01 * FORK_KE_END,
        "kinetic energy after the bounce {} vs the fork's {FORK_KE_END}",
        end[2]
    );

    // The fragments where the rods were: per bond ID three spheres of r = 0.003 in a
    // row, 0.006 apart, one row along x (at y ≈ 0.02), one along z (at y ≈ −0.02). The
    // first rod's fragments were made 50 steps before the second's: the second
    // replacement shifted their indices, and their bonds held (rdem once lost them so).
    let frag = dump_rows(&dir.join("post/frag15101.txt"));
    assert_eq!(frag.len(), 6);
    // The dump prints 6 digits of the bond IDs: the two rods' rows are told apart by y.
    for upper in [true, false] {
        let mut s: Vec<&Vec<f64>> = frag.iter().filter(|r| (r[3] > 0.0) == upper).collect();
        assert_eq!(s.len(), 3);
        // Bond IDs: the step of the replacement and a fraction.
        let step = if upper { 15051.0 } else { 15101.0 };
        assert!(
            s.iter().all(|r| r[9] > step && r[9] < step + 1.0),
            "bond IDs {s:?}"
        );
        assert!(s.iter().all(|r| r[1] == 2.0 && r[5] == 0.003));
        let along_x = upper;
        let axis = if along_x { 2 } else { 4 };
        s.sort_by(|a, b| a[axis].total_cmp(&b[axis]));
        let y = s[1][3];
        assert!(
            (y - if along_x { 0.02 } else { -0.02 }).abs() < 1.1e-3,
            "row at y = {y}"
        );
        for w in s.windows(2) {
            let d: f64 = (2..5)
                .map(|k| (w[1][k] - w[0][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            // The dump's 6 significant digits: 1e-7 m here.
            assert!((d - 0.006).abs() < 3e-7, "spacing {d}");
            for k in (2..5).filter(|&k| k != axis) {
                assert!((w[1][k] - w[0][k]).abs() < 3e-7, "not in a row: {w:?}");
            }
        }
        // Each fragment moves with its rod's velocity.
        assert!(s
            .iter()
            .all(|r| (r[6] - 1.0).abs() < 1e-12 && r[7] == 0.0 && r[8] == 0.0));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fragments_do_not_depend_on_the_thread_count() {
    let (d1, _) = run("1");
    let (d2, _) = run("2");
    let a = std::fs::read_to_string(d1.join("post/end.txt")).unwrap();
    let b = std::fs::read_to_string(d2.join("post/end.txt")).unwrap();
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(&d1);
    let _ = std::fs::remove_dir_all(&d2);
}

/// On two MPI ranks (the box split at x = 0, which the fragments cross after their
/// replacement on the first rank) the end state is the serial one, to the dump's digits
/// (measured: the same bytes once sorted by ID).
#[cfg(feature = "mpi")]
#[test]
fn fragments_on_two_ranks_end_as_serial() {
    let sorted = |d: &std::path::Path| {
        let mut rows = dump_rows(&d.join("post/end.txt"));
        rows.sort_by(|a, b| a[0].total_cmp(&b[0]));
        rows
    };
    let (d1, _) = run("1");
    let (d2, out) = run_on("1", Some(2));
    assert!(out.contains("on 2 procs"), "{out}");
    let (a, b) = (sorted(&d1), sorted(&d2));
    assert_eq!(a.len(), 6);
    assert_eq!(a, b);
    let _ = std::fs::remove_dir_all(&d1);
    let _ = std::fs::remove_dir_all(&d2);
}
