//! Residence-time tracers (LIGGGHTS 3.8): `fix property/atom/tracer`, `compute
//! nparticles/tracer/region` and `fix property/atom/regiontracer/time`. Six spheres move
//! up at 1 m/s (no gravity, no contact) through a mark region and a count region; one
//! leaves the box.
//!
//! The references are LIGGGHTS 3.8's (the Debian package) for
//! `tests/data/tracer/in.tracer`: the thermo rows (the marked count `f_tracer`, the four
//! counts of the compute, the mean times) and the dump every step (marker, domain time,
//! region time of each sphere). Case a: dirac at step 3, checks every 2 steps, markers
//! reset when counted; case b: heaviside from step 4, every 3 steps, no reset. rdem
//! matches every row, on 1 and 2 MPI ranks; the dump at a step where the compute unmarks
//! still shows the marker, as LIGGGHTS writes dumps before thermo.

use crate::common;

use std::path::Path;

fn data() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/tracer")
}

/// (ms, style, ce, reset, th, extra, case)
const CASES: [[&str; 7]; 2] = [
    ["3", "dirac", "2", "yes", "1", "\"\"", "a"],
    ["4", "heaviside", "3", "no", "3", "\"f_t2[1] f_t2[2]\"", "b"],
];

fn run(case: &[&str; 7], ranks: Option<usize>) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let names = ["ms", "style", "ce", "reset", "th", "extra"];
    let vars: Vec<(&str, &str)> = names.iter().copied().zip(case.iter().copied()).collect();
    let script =
        common::index_vars(&vars) + &std::fs::read_to_string(data().join("in.tracer")).unwrap();
    let (dir, out) = common::run_kept_ok("tracer", &script, &[], ranks);
    let text = std::fs::read_to_string(dir.join("d.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let thermo = common::thermo_rows(&out[out.find("Step").unwrap()..]);
    let dump = common::dump_rows_with_step(&text);
    (thermo, dump)
}

fn check(ranks: Option<usize>) {
    for case in &CASES {
        let c = case[6];
        let (thermo, dump) = run(case, ranks);
        let what = format!("case {c}, {ranks:?} ranks");
        let want = common::reference_rows(&data().join(format!("thermo_{c}.txt")));
        // Thermo prints 8 digits.
        common::assert_columns(&thermo, &want, 0, 1e-7, &format!("{what}: thermo"));
        let want = common::reference_rows(&data().join(format!("dump_{c}.txt")));
        common::assert_columns(&dump, &want, 0, 1e-5, &format!("{what}: dump"));
    }
}

#[test]
fn tracers_mark_count_and_time_as_liggghts() {
    check(None);
}

#[cfg(feature = "mpi")]
#[test]
fn tracers_on_two_ranks() {
    if common::have_mpirun() {
        check(Some(2));
    }
}

#[test]
fn tracer_errors_are_located() {
    let head = std::fs::read_to_string(data().join("in.tracer")).unwrap();
    let head: String = head
        .lines()
        .take_while(|l| !l.starts_with("fix tracer"))
        .map(|l| format!("{l}\n"))
        .collect();
    for (line, message) in [
        (
            "fix tracer all property/atom/tracer region_mark mark",
            "needs 'region_mark REGION' and 'mark_step S'",
        ),
        (
            "fix tracer all property/atom/tracer region_mark nowhere mark_step 3",
            "nowhere",
        ),
        (
            "fix tracer all property/atom/tracer region_mark mark mark_step 3 marker_style step",
            "'heaviside'",
        ),
        (
            "compute np all nparticles/tracer/region region_count cnt tracer integr",
            "no fix property/atom/tracer 'integr'",
        ),
        (
            "compute np all nparticles/tracer/region region_count cnt",
            "needs 'region_count REGION' and",
        ),
    ] {
        let out = common::run_script_raw(&format!("{head}{line}\n"), None);
        assert!(!out.status.success(), "{line}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{line}: {err}");
        assert!(err.contains("in.test:"), "{line}: {err}");
    }
}
