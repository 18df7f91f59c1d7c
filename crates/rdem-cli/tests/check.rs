//! `rdem -check SCRIPT`: every line rdem cannot run is reported, nothing runs, nothing is
//! written.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common;
use common::{copy_dir, rdem_command, scratch_dir};

const TUTORIALS: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public";

/// Every file under `dir` with its size and modification time.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, (u64, std::time::SystemTime)> {
    let mut m = BTreeMap::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let e = e.unwrap();
            let meta = e.metadata().unwrap();
            if meta.is_dir() {
                todo.push(e.path());
            }
            m.insert(e.path(), (meta.len(), meta.modified().unwrap()));
        }
    }
    m
}

/// Runs `rdem ARGS` in `dir` and checks that nothing in `dir` changed.
fn check_in(dir: &Path, args: &[&str]) -> Output {
    let before = snapshot(dir);
    let out = rdem_command(None)
        .args(args)
        .env("RDEM_THREADS", "1")
        .current_dir(dir)
        .output()
        .unwrap();
    assert_eq!(
        snapshot(dir),
        before,
        "rdem {args:?} changed its folder:\n{}",
        String::from_utf8_lossy(&out.stdout)
    );
    out
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// The last line of standard output: the summary.
fn summary(out: &Output) -> String {
    text(&out.stdout).lines().last().unwrap_or("").to_string()
}

/// The real users' scripts, `<repo>/../shared/wild`.
fn wild() -> Option<PathBuf> {
    common::wild_case("", "MANIFEST.tsv")
}

/// Copies the wild case `case_dir` (its top folder) to a scratch directory, runs
/// `rdem -check main` there and returns the output.
fn check_wild(root: &Path, case_dir: &str, main: &str) -> Output {
    let top = case_dir.split('/').next().unwrap();
    let tmp = scratch_dir("check-wild");
    copy_dir(&root.join(top), &tmp.join(top));
    let out = check_in(&tmp.join(case_dir), &["-check", main]);
    let _ = std::fs::remove_dir_all(&tmp);
    out
}

/// Real scripts from `../shared/wild`, each line rdem cannot run counted by hand.
///
/// `34_scm_calibration_read_dump/in.cal_prim_30X` — 1 line:
/// - 40 `fix filtermesh ... primitive type 2 yplane_finite_porous ...`: a fork's porous
///   wall.
///
/// (Line 25, `pair_style gran ...` before `create_box`, runs: LIGGGHTS 3.8 takes it there
/// too. Line 75, `read_dump dump.atom_info_1 1 x y z radius vx vy vz box no add yes
/// replace no`, runs.)
///
#[test]
fn wild_scripts_list_exactly_the_lines_rdem_cannot_run() {
    let Some(root) = wild() else { return };
    let cases = [(
        "34_scm_calibration_read_dump",
        "in.cal_prim_30X",
        "in.cal_prim_30X: 1 line rdem cannot run: fix wall/gran (line 40)",
        &[0usize; 0][..],
    )];
    for (case, main, want, left_out) in cases {
        let out = check_wild(&root, case, main);
        let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
        assert_eq!(out.status.code(), Some(1), "{case}:\n{stdout}\n{stderr}");
        assert_eq!(summary(&out), want, "{case}:\n{stderr}");
        // Each line has its report, with file:line:column.
        let listed: Vec<usize> = want
            .split(['(', ')'])
            .filter_map(|s| s.trim_start_matches("line ").parse().ok())
            .collect();
        for l in &listed {
            assert!(
                stderr.contains(&format!("{main}:{l}:")),
                "{case}: no report for line {l}:\n{stderr}"
            );
        }
        assert_eq!(
            stderr.matches(&format!("[{main}:")).count(),
            listed.len(),
            "{case}: one report per line:\n{stderr}"
        );
        let note = stdout.lines().find(|l| l.contains("left out"));
        assert_eq!(
            note.is_some(),
            !left_out.is_empty(),
            "{case}: a note on the left-out errors, exactly when some are:\n{stdout}"
        );
        let note = note.unwrap_or("");
        for l in left_out {
            assert!(
                note.contains(&format!("{main}:{l} ")),
                "{case}: {l}: {note}"
            );
        }
    }
}

/// Every LIGGGHTS tutorial the tutorial tests run (`tutorials.rs`, `mesh_tutorials.rs`),
/// and the two heat transfer tutorials: `-check` reports nothing, exits 0 and writes
/// nothing.
#[test]
fn tutorials_check_clean() {
    let cases = [
        ("contactModels", "in.newModels"),
        ("cohesion", "in.noCohesion"),
        ("cohesion", "in.cohesion"),
        ("hysteresis", "in.noHysteresis"),
        ("hysteresis", "in.hysteresis"),
        ("packing", "in.packing"),
        ("conveyor", "in.conveyor"),
        ("insert_stream", "in.insert_stream"),
        ("meshGran", "in.meshGran"),
        ("movingMeshGran", "in.movingMeshGran"),
        ("chute_wear", "in.chute_wear"),
        ("heatTransfer_1", "in.heatGran"),
        ("heatTransfer_2", "in.heatGran"),
    ];
    for (dir, file) in cases {
        let src = Path::new(TUTORIALS).join(dir);
        assert!(
            src.join(file).exists(),
            "{} is missing: install the liggghts-doc package (scripts/test.sh does)",
            src.join(file).display()
        );
        let tmp = scratch_dir("check-tutorial");
        copy_dir(&src, &tmp);
        let out = check_in(&tmp, &["-check", file]);
        let _ = std::fs::remove_dir_all(&tmp);
        let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
        assert!(out.status.success(), "{dir}/{file}:\n{stdout}\n{stderr}");
        assert_eq!(
            stdout,
            format!("{file}: rdem can run every line\n"),
            "{dir}"
        );
        assert_eq!(stderr, "", "{dir}/{file}");
    }
}

/// Writes `script` as `in.test` (and `files`) in a scratch directory and runs `args` there
/// (the directory must not change); returns the output.
fn check_script(script: &str, files: &[(&str, &str)], args: &[&str]) -> Output {
    let dir = scratch_dir("check");
    std::fs::write(dir.join("in.test"), script).unwrap();
    for (n, t) in files {
        std::fs::write(dir.join(n), t).unwrap();
    }
    let out = check_in(&dir, args);
    let _ = std::fs::remove_dir_all(&dir);
    out
}

/// A script with two independent errors (a typo in a command name at line 9, a fix style
/// rdem does not have at line 14) and one that only follows from the second (line 16,
/// `unfix` of that fix): both are reported with their lines, the follow-on is not, exit 1;
/// every command that would write a file (log, print file, dump, fix ave/time file,
/// write_dump, write_data, write_restart) writes nothing.
#[test]
fn two_errors_both_reported_and_nothing_written() {
    let script = "\
log log.check
units si
atom_style granular
boundary f f f
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 units box
set atom 1 diameter 0.1 density 2500
neighbr 0.01 bin
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix heat all heat/gran/radiation initial_temperature 300
pair_style gran model hertz tangential history
unfix heat
pair_coeff * *
timestep 1e-5
fix integr all nve/sphere
variable z equal z[1]
fix ave all ave/time 1 1 1 v_z file ave.txt
print \"z = ${z}\" file printed.txt
dump d all custom 10 post/d*.txt id x y z
thermo_style custom step atoms v_z
run 100
write_dump all custom one.txt id x
write_data data.out
write_restart restart.out
";
    let want = "in.test: 2 lines rdem cannot run: neighbr (line 9), fix heat/gran/radiation (14)";
    for args in [
        &["-check", "in.test"][..],
        &["--check", "in.test"],
        &["-in", "in.test", "-check", "-log", "log.x"],
    ] {
        let out = check_script(script, &[], args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert_eq!(summary(&out), want, "{args:?}: {stderr}");
        assert!(stderr.contains("unknown command 'neighbr'"), "{stderr}");
        assert!(stderr.contains("in.test:9:1"), "{stderr}");
        assert!(
            stderr.contains("heat/gran/radiation needs the keyword 'cutoff'"),
            "{stderr}"
        );
        assert!(stderr.contains("in.test:14:"), "{stderr}");
        assert!(!stderr.contains("in.test:16:"), "{stderr}");
    }
    // -var reaches the script; the fixed script checks clean.
    let fixed = script
        .replace("neighbr", "neighbor")
        .replace(
            "fix heat all heat/gran/radiation initial_temperature 300\n",
            "",
        )
        .replace("unfix heat\n", "")
        + "unfix ${f}\n";
    let out = check_script(&fixed, &[], &["-check", "in.test", "-var", "f", "ave"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(text(&out.stdout), "in.test: rdem can run every line\n");
}

/// A `label`/`jump` loop over a `loop` variable is followed: a line in the body that fails
/// on every pass is reported once, and a line that only fails on the third pass is
/// reached.
#[test]
fn loops_are_followed_and_each_line_reported_once() {
    let script = "\
units si
region box block 0 1 0 1 0 1 units box
create_box 1 box
variable i loop 3
label top
create_bonds many all all 1 0.0 0.1
if \"$i == 3\" then \"bogus_on_the_last_pass\"
next i
jump SELF top
";
    let out = check_script(script, &[], &["-check", "in.test"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert_eq!(
        summary(&out),
        "in.test: 2 lines rdem cannot run: create_bonds (line 6), if (7)",
        "{stderr}"
    );
    assert_eq!(stderr.matches("[in.test:6:").count(), 1, "{stderr}");
    assert!(stderr.contains("bogus_on_the_last_pass"), "{stderr}");
}

/// A loop whose end depends on what the steps would do is cut after 1000 passes, with a
/// note, and the check goes on past it.
#[test]
fn loops_waiting_for_steps_end() {
    let script = "\
units si
region box block 0 1 0 1 0 1 units box
create_box 1 box
label wait
run 10
if \"$(atoms) < 5\" then \"jump SELF wait\"
bogus_after_the_loop
";
    let out = check_script(script, &[], &["-check", "in.test"]);
    let stdout = text(&out.stdout);
    assert_eq!(
        summary(&out),
        "in.test: 1 line rdem cannot run: bogus_after_the_loop (line 7)"
    );
    assert!(stdout.contains("followed 1000 times"), "{stdout}");
}

/// With no particles (no step runs) a formula over them that divides by zero is a note,
/// not a line rdem cannot run (CFDEM's small_hearth divides by a region's particle count
/// in a `run every` command); with particles, or before the box, it is still a problem.
#[test]
fn division_by_no_particles_is_a_note() {
    let head = "\
units si
region box block 0 1 0 1 0 1 units box
create_box 1 box
variable n equal count(all)
variable per equal 1/v_n
";
    let script = format!("{head}run 10 every 5 \"print 'per ${{per}}'\"\n");
    let out = check_script(&script, &[], &["-check", "in.test"]);
    assert_eq!(summary(&out), "in.test: rdem can run every line");
    assert!(
        text(&out.stdout).contains("in.test:6: not checked"),
        "{}",
        text(&out.stdout)
    );
    let with_one = script
        .replace("block 0 1 0 1 0 1", "block 0 10 0 10 0 10")
        .replace(
            "variable n equal count(all)",
            "create_atoms 1 single 5 5 5\nvariable n equal count(all)-1",
        );
    let out = check_script(&with_one, &[], &["-check", "in.test"]);
    assert!(
        summary(&out).contains("1 line rdem cannot run"),
        "{}",
        summary(&out)
    );
}

/// The cases of `../shared/wild` (MANIFEST.tsv) whose every line rdem can run, as
/// `rdem -check` says (exit 0). The list grows as the commands real scripts use land
/// (issue 17); each case not in it must have at least one line reported.
const WILD_FULLY_SUPPORTED: &[&str] = &[
    "02_cfdem_periodic_channel_init/DEM",
    "04_cfdem_fillcylinder_init/DEM",
    "06_cfdem_rbc_bonds_init/DEM",
    "08_cfdem_hopper_tracer_init/DEM",
    "10_pfm_servo_wall",
    "12_pfm_chung_normal_impact",
    "14_pfm_stress_box_euler",
    "16_pfm_rotary_kiln_init",
    "18_inl_chain_bending_bond_counter",
    "20_inl_chain_test_plate",
    "22_inl_bonds_from_multisphere",
    "24_fibers_cantilever_beam",
    "26_fibers_shear_box_insert",
    "28_seaice_bond_break",
    "30_seaice_column_pour",
    "36_thesis_screw_conveyor",
    "40_2x_conveyor_surface_vel_heat",
    "44_1x_giacomp_pour",
    "46_helix_read_data_hooke",
    "48_fluidised_bed_sjkr_init/DEM",
    "50_capillary_heat_init/DEM",
    "52_mcg_hourglass",
    "54_pici_jkr_rotating_drum",
    "56_2x_chute_cylinder_obstacle",
];

/// `rdem -check` on every case of `../shared/wild`: exactly the cases of
/// [`WILD_FULLY_SUPPORTED`] are clean; every other one names its lines.
#[test]
fn wild_cases_rdem_can_run_every_line_of() {
    let Some(root) = wild() else { return };
    let manifest = std::fs::read_to_string(root.join("MANIFEST.tsv")).unwrap();
    let mut clean = Vec::new();
    let mut report = String::new();
    for line in manifest.lines().skip(1) {
        let cols: Vec<&str> = line.split('\t').collect();
        let (case, main) = (cols[0], cols[1]);
        let out = check_wild(&root, case, main);
        match out.status.code() {
            Some(0) => clean.push(case.to_string()),
            Some(1) => report.push_str(&format!("{case}: {}\n", summary(&out))),
            other => panic!(
                "{case}: rdem -check exited with {other:?}:\n{}",
                text(&out.stderr)
            ),
        }
    }
    eprintln!("{report}");
    assert_eq!(clean, WILD_FULLY_SUPPORTED, "not clean:\n{report}");
}
