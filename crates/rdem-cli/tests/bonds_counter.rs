//! `compute bond/counter` on breaking bonds, and bonds that survive re-neighboring, sorting,
//! periodic wrap and (feature `mpi`) migration between ranks. Scripts in
//! `tests/data/bonds/`.

use crate::common;

use std::path::{Path, PathBuf};

use common::rdem_in;

/// A fresh scratch directory.
fn scratch() -> PathBuf {
    common::scratch_dir("bonds")
}

/// Runs `tests/data/bonds/<script>` serially (`ranks` None) or on MPI ranks, one thread
/// each, and returns the thermo rows (every number of each row after the header).
fn thermo(script: &str, ranks: Option<usize>, extra: &[&str]) -> (Vec<Vec<f64>>, String) {
    let dir = scratch();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bonds");
    std::fs::copy(src.join(script), dir.join(script)).unwrap();
    let out = rdem_in(&dir, script, ranks)
        .args(extra)
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{script} ({ranks:?} ranks): {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
    let mut rows = Vec::new();
    let mut on = false;
    for line in text.lines() {
        if line.trim_start().starts_with("Step") {
            on = true;
            continue;
        }
        if line.starts_with("Loop time") {
            on = false;
        }
        if on {
            let r: Vec<f64> = line
                .split_whitespace()
                .map(|w| w.parse().unwrap())
                .collect();
            rows.push(r);
        }
    }
    assert!(!rows.is_empty(), "no thermo rows in\n{text}");
    (rows, text)
}

// Columns of in.agglomerate: step atoms ke bc1..bc6 (3..=8) snb (9).
const CREATED: usize = 3;

/// A bonded ball of 150 spheres hits a floor that bonds too (`createBondAlways on`):
/// pair bonds are created at step 1 and broken on impact, wall bonds are created and
/// broken. At every thermo line the counter is exact: intact(t) = intact(t−1) + created −
/// broken, for pairs and for walls, where created and broken count the events since the
/// previous line; and the intact counts agree with an independent count, the per-particle
/// bond numbers of `compute nbond/atom` summed: Σ n_i = 2 N_pair + N_wall.
#[test]
fn counter_is_exact_on_a_breaking_agglomerate() {
    let (rows, _) = thermo("in.agglomerate", None, &[]);
    check_counter(&rows);
}

/// The checks of [`counter_is_exact_on_a_breaking_agglomerate`]; returns the totals
/// (pair created, pair broken, wall created, wall broken).
fn check_counter(rows: &[Vec<f64>]) -> [f64; 4] {
    let mut totals = [0.0; 4];
    let (mut pair, mut wall) = (0.0, 0.0);
    for r in rows {
        let b = &r[CREATED..CREATED + 6];
        assert_eq!(
            b[2],
            pair + b[0] - b[1],
            "pair bonds at step {}: {r:?}",
            r[0]
        );
        assert_eq!(
            b[5],
            wall + b[3] - b[4],
            "wall bonds at step {}: {r:?}",
            r[0]
        );
        assert_eq!(r[9], 2.0 * b[2] + b[5], "nbond/atom sum at step {}", r[0]);
        pair = b[2];
        wall = b[5];
        totals[0] += b[0];
        totals[1] += b[1];
        totals[2] += b[3];
        totals[3] += b[4];
    }
    // The ball (150 spheres on a simple cubic lattice of touching spheres) has 345
    // nearest-neighbour pairs, all bonded at step 1; the impact must break some, and the
    // floor must make and break some.
    assert_eq!(totals[0], 345.0, "pair bonds created");
    assert!(totals[1] > 50.0, "pair bonds broken: {}", totals[1]);
    assert!(
        totals[2] > 10.0 && totals[3] > 10.0,
        "wall bonds: {totals:?}"
    );
    totals
}

// Columns of in.periodic: step atoms ke rke bc1 bc2 bc3 d.

/// A bonded pair drifts at 2 m/s (1.5 box lengths) and spins at 100 rad/s about z across
/// the periodic x faces, with the neighbor list rebuilt and the particles sorted at every
/// step. The bond is made once and never breaks or is made anew, and in this rigid motion
/// it only carries the centripetal force: the centre distance stays 2 mm + m ω² (d/2) /
/// (k_n A) = 2 mm + 0.67 nm (checked within 0.1 nm whenever the pair is not split by the
/// periodic face); translational energy is conserved to 1e-9 and rotational energy to
/// 1e-5 (relative).
#[test]
fn bond_survives_periodic_wrap_sorting_and_rebuilds() {
    let (rows, _) = thermo("in.periodic", None, &[]);
    check_periodic(&rows);
}

fn check_periodic(rows: &[Vec<f64>]) {
    let (ke0, rke0) = (rows[0][2], rows[0][3]);
    let stretch = {
        let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-9;
        let ka = 5.0e10 * std::f64::consts::PI * 1e-6;
        m * 100.0f64.powi(2) * 1e-3 / ka
    };
    let mut wrapped = 0;
    let mut created = 0.0;
    for r in &rows[1..] {
        created += r[4];
        assert_eq!(
            (r[5], r[6]),
            (0.0, 1.0),
            "bond lost at step {}: {r:?}",
            r[0]
        );
        assert!(
            (r[2] - ke0).abs() < 1e-9 * ke0,
            "translational energy {r:?}"
        );
        assert!((r[3] - rke0).abs() < 1e-5 * rke0, "rotational energy {r:?}");
        if r[7] > 0.01 {
            wrapped += 1;
        } else {
            assert!(
                (r[7] - 0.002 - stretch).abs() < 1e-10,
                "distance {} at step {} (want {})",
                r[7],
                r[0],
                0.002 + stretch
            );
        }
    }
    assert_eq!(created, 1.0);
    assert!(wrapped >= 1, "the pair never straddled the periodic face");
}

/// Serial and 2-rank runs of the breaking agglomerate (the default 1 × 2 × 1 grid splits
/// the ball at y = 0) report the same six counter values at every line, and the 2-rank
/// counter passes the same exactness checks.
#[cfg(feature = "mpi")]
#[test]
fn counter_totals_are_the_same_on_two_ranks() {
    if !common::have_mpirun() {
        eprintln!("skipped: mpirun not found");
        return;
    }
    let (serial, _) = thermo("in.agglomerate", None, &[]);
    let (two, text) = thermo("in.agglomerate", Some(2), &[]);
    assert!(text.contains("1 by 2 by 1"), "grid: {text}");
    let t1 = check_counter(&serial);
    let t2 = check_counter(&two);
    assert_eq!(t1, t2);
    assert_eq!(serial.len(), two.len());
    for (a, b) in serial.iter().zip(&two) {
        assert_eq!(
            a[CREATED..CREATED + 7],
            b[CREATED..CREATED + 7],
            "step {}",
            a[0]
        );
    }
}

/// The spinning pair of [`bond_survives_periodic_wrap_sorting_and_rebuilds`] on two ranks
/// (x split at 0.01): the bond follows its particles from rank to rank and across the
/// periodic face with the same checks.
#[cfg(feature = "mpi")]
#[test]
fn bond_migrates_between_ranks() {
    if !common::have_mpirun() {
        eprintln!("skipped: mpirun not found");
        return;
    }
    let (rows, text) = thermo("in.periodic", Some(2), &[]);
    assert!(text.contains("2 by 1 by 1"), "grid: {text}");
    check_periodic(&rows);
}

/// Runs `tests/data/bonds/<script>` on `threads` threads; returns the screen's thermo
/// rows and the files of `post/` by name.
fn run_threads(script: &str, threads: usize) -> (String, Vec<(String, Vec<u8>)>) {
    let dir = scratch();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bonds");
    std::fs::copy(src.join(script), dir.join(script)).unwrap();
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let out = rdem_in(&dir, script, None)
        .arg("--threads")
        .arg(threads.to_string())
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{threads} threads: {text}");
    let rows: String = text
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("Step"))
        .take_while(|l| !l.starts_with("Loop time"))
        .map(|l| format!("{l}\n"))
        .collect();
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir.join("post"))
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).unwrap())
        })
        .collect();
    files.sort();
    let _ = std::fs::remove_dir_all(&dir);
    (rows, files)
}

/// A 2120-sphere bonded ball (enough particles for the parallel force passes) breaking on
/// a bonding floor: thermo (bond counter included) and full-precision dumps of positions,
/// velocities, spins, forces, torques and bond numbers are byte-identical on 1, 2 and 4
/// threads.
#[test]
fn bonds_do_not_depend_on_the_thread_count() {
    let (rows1, files1) = run_threads("in.threads", 1);
    assert_eq!(files1.len(), 5, "dump files");
    assert!(rows1.contains("5771"), "all bonds created:\n{rows1}");
    for threads in [2, 4] {
        let (rows, files) = run_threads("in.threads", threads);
        assert_eq!(rows, rows1, "{threads} threads: thermo");
        assert!(files == files1, "{threads} threads: dumps differ");
    }
}
