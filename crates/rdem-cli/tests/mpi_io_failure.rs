//! MPI (feature `mpi`): a file that rank 0 cannot write in the middle of a run — a
//! `fix print` file, a dump, a restart file — stops every rank with one report, and
//! the job ends (each case is killed and fails if it runs for two minutes).
//!
//! The failures are real ones made by the script itself: `/dev/full` (every write fails
//! with "No space left on device") as the file a `fix print` appends to, and an output
//! folder replaced by a plain file between two runs (`shell` acts on rank 0 only), so that
//! the next dump or restart file cannot be made. Only rank 0 writes files, so only rank 0
//! sees these failures; without the ranks' agreement rank 1 would go on stepping into the
//! next collective call and wait there forever.
#![cfg(feature = "mpi")]

use crate::common;

use std::time::{Duration, Instant};

use common::{have_mpirun, rdem_in, scratch_dir};

/// 300 spheres falling in a box split in two along x: both ranks own particles and
/// meet in collective calls every step (exchange, thermo).
const SETUP: &str = concat!("atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
processors 2 1 1
region box block -0.05 0.05 -0.05 0.05 0 0.1 units box
create_box 1 box
neighbor 0.002 bin
neigh_modify delay 0
", common::materials!(), "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
region ins block -0.045 0.045 -0.045 0.045 0.01 0.09 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 300 region ins
fix integr all nve/sphere
thermo 10
");

/// Runs `script` on 2 ranks; returns (exit code, stderr), or fails if the job is still
/// running after two minutes (a hung rank).
fn run_2(tag: &str, script: &str) -> (Option<i32>, String) {
    let dir = scratch_dir(tag);
    std::fs::write(dir.join("in.test"), script).unwrap();
    let mut child = rdem_in(&dir, "in.test", Some(2))
        .env("RDEM_THREADS", "1")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            let _ = child.wait();
            let _ = std::fs::remove_dir_all(&dir);
            panic!("{tag}: still running after 120 s: a rank waits forever");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut err = String::new();
    use std::io::Read;
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (status.code(), err)
}

/// The job failed with exit code 1 and one report, whose message `what` is there once,
/// with `why`; no `MPI_Abort` (every rank stopped by itself, in agreement). (mpirun adds
/// its own note that a process returned a non-zero exit code.)
fn assert_one_report(tag: &str, (code, err): (Option<i32>, String), what: &str, why: &str) {
    assert_eq!(code, Some(1), "{tag}: {err}");
    assert_eq!(err.matches(what).count(), 1, "{tag}: one report:\n{err}");
    assert!(err.contains(why), "{tag}: the reason:\n{err}");
    assert!(
        !err.contains("MPI_ABORT"),
        "{tag}: ranks stopped in agreement:\n{err}"
    );
    assert!(!err.contains("stopped alone"), "{tag}:\n{err}");
}

#[test]
fn a_fix_print_file_that_cannot_be_written_stops_every_rank() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{SETUP}fix p all print 30 \"step $(step)\" append /dev/full title none screen no\nrun 100\n"
    );
    let out = run_2("iofail-print", &script);
    assert_one_report(
        "print",
        out,
        "cannot append to '/dev/full'",
        "No space left on device",
    );
}

#[test]
fn a_dump_that_cannot_be_written_stops_every_rank() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{SETUP}dump d all custom 20 out/d_*.txt id x y z\nrun 40\nshell mv out moved\nshell touch out\nrun 40\n"
    );
    let out = run_2("iofail-dump", &script);
    assert_one_report(
        "dump",
        out,
        "dump d: cannot create directory 'out': File exists",
        "found during the run of line 31",
    );
}

#[test]
fn a_restart_file_that_cannot_be_written_stops_every_rank() {
    if !have_mpirun() {
        return;
    }
    let script = format!(
        "{SETUP}restart 20 out/a.restart out/b.restart\nrun 40\nshell mv out moved\nshell touch out\nrun 40\n"
    );
    let out = run_2("iofail-restart", &script);
    assert_one_report(
        "restart",
        out,
        "cannot create directory 'out': File exists",
        "found during the run of line 31",
    );
}
