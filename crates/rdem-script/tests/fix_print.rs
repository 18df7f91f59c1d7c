//! `fix print`: the lines and files LIGGGHTS 3.8 writes for the same scripts, byte for
//! byte, and a `.csv` of `f_` values of `fix massflow/mesh` against the closed form.

use rdem_script::Interpreter;

use crate::common;
use common::render;

/// A 1 m box with one particle at rest and materials (the set-up of the LIGGGHTS runs).
const HEAD: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 1 0 1 0 1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m all property/global youngsModulus peratomtype 5e6
fix p all property/global poissonsRatio peratomtype 0.45
fix c all property/global coefficientRestitution peratomtypepair 1 0.3
fix f all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.001
create_atoms 1 single 0.5 0.5 0.5
";

/// The screen lines that are not thermo rows, run headers or the loop summary, with
/// the step of each thermo row as `@N` (to check where the prints fall).
fn printed(i: &Interpreter) -> Vec<String> {
    let s = common::screen(i);
    let mut out = Vec::new();
    let mut in_run = false;
    for l in s.lines() {
        if l.trim_start().starts_with("Step") {
            in_run = true;
            continue;
        }
        if l.starts_with("Loop time") {
            in_run = false;
            continue;
        }
        if !in_run {
            continue;
        }
        let first = l.split_whitespace().next().unwrap_or("");
        match first.parse::<u64>() {
            Ok(step) if l.split_whitespace().count() > 1 => out.push(format!("@{step}")),
            _ => out.push(l.to_string()),
        }
    }
    out
}

/// LIGGGHTS 3.8, `liggghts -in in.fp -log log.x` with `q.txt` holding `old line` before
/// (2026-11-24); its screen between the thermo rows of steps 0, 4, 7 / 7, 8, 12:
/// `step 6 hello v_a 7 time` (step 3), `z` (5), `step 12 hello v_a 13 time` (6) and
/// `step 18 bye v_a 19 time` (9), `z` (10), `step 24 bye v_a 25 time` (12): nothing at a
/// run's set-up, the text substituted at each print, `screen no` silent on the screen
/// and in the log. Its files:
/// - p.txt: `# Fix print output for fix pr` and the four `step` lines;
/// - q.txt (`append`): `old line`, `my title`, `x 4`, `x 8`, ..., `x 24`;
/// - r.txt (`title none`): `z`, `z`.
#[test]
fn prints_and_files_as_liggghts() {
    let d = common::scratch_dir("fixprint-files");
    let p = |f: &str| d.join(f).display().to_string();
    std::fs::write(p("q.txt"), "old line\n").unwrap();
    let script = format!(
        "{HEAD}\
         variable a equal step*2\n\
         variable s string hello\n\
         fix pr all print 3 \"step $a ${{s}} v_a $(v_a+1) time\" file {}\n\
         fix pr2 all print 2 \"x ${{a}}\" append {} title \"my title\" screen no\n\
         fix pr3 all print 5 \"z\" file {} title none\n\
         thermo 4\n\
         run 7\n\
         variable s string bye\n\
         run 5\n",
        p("p.txt"),
        p("q.txt"),
        p("r.txt")
    );
    let i = common::run("in.fp", &script);
    assert_eq!(
        printed(&i),
        [
            "@0",
            "step 6 hello v_a 7 time",
            "@4",
            "z",
            "step 12 hello v_a 13 time",
            "@7",
            "@7",
            "@8",
            "step 18 bye v_a 19 time",
            "z",
            "step 24 bye v_a 25 time",
            "@12",
        ]
    );
    let read = |f: &str| std::fs::read_to_string(p(f)).unwrap();
    assert_eq!(
        read("p.txt"),
        "# Fix print output for fix pr\nstep 6 hello v_a 7 time\nstep 12 hello v_a 13 time\n\
         step 18 bye v_a 19 time\nstep 24 bye v_a 25 time\n"
    );
    assert_eq!(
        read("q.txt"),
        "old line\nmy title\nx 4\nx 8\nx 12\nx 16\nx 20\nx 24\n"
    );
    assert_eq!(read("r.txt"), "z\nz\n");
}

/// LIGGGHTS 3.8, `liggghts -in in.fp2 -log none` (2026-11-24): runs that start at a
/// multiple of N print nothing at their set-up, `run 0` prints nothing, a fix redefined
/// with the same ID prints with its new N, `$(time)` is `%.20g`:
/// `s 3 t=0.0030000000000000000625`, `s 6 t=0.0060000000000000001249`,
/// `s 9 t=0.0090000000000000010547`, `s 12 t=0.01200000000000000025`, `re 14`, `[18]`,
/// and x.txt is `# Fix print output for fix pr2` then `[18]`.
#[test]
fn steps_of_the_prints_as_liggghts() {
    let d = common::scratch_dir("fixprint-steps");
    let x = d.join("x.txt");
    let script = format!(
        "{HEAD}\
         fix pr all print 3 \"s $(step) t=$(time)\" title \"a b\"\n\
         run 6\n\
         run 6\n\
         run 0\n\
         fix pr all print 2 \"re $(step)\"\n\
         run 3\n\
         unfix pr\n\
         fix pr2 all print 3 \"[$(step)]\" file {}\n\
         run 3\n",
        x.display()
    );
    let i = common::run("in.fp", &script);
    let lines: Vec<String> = printed(&i)
        .into_iter()
        .filter(|l| !l.starts_with('@'))
        .collect();
    assert_eq!(
        lines,
        [
            "s 3 t=0.0030000000000000000625",
            "s 6 t=0.0060000000000000001249",
            "s 9 t=0.0090000000000000010547",
            "s 12 t=0.01200000000000000025",
            "re 14",
            "[18]",
        ]
    );
    assert_eq!(
        std::fs::read_to_string(&x).unwrap(),
        "# Fix print output for fix pr2\n[18]\n"
    );
}

/// A line as the real scripts write it (`"${time},${in_mass_flow},..." screen no title
/// "t,..." file massflow.csv`): one particle of diameter 4 mm and density 2500 falls at
/// 1 m/s through a disk mesh 9.5 mm below it (at step 95 of 1e-4 s); the mass through it
/// is ρ·π·d³/6 = 8.3776e-5 kg, within 1e-12 relative.
#[test]
fn csv_of_massflow_values() {
    let d = common::scratch_dir("fixprint-csv");
    let mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/hopper/meshes/orifice_D25.stl"
    );
    let csv = d.join("post/massflow.csv");
    let script = format!(
        "atom_style granular\n\
         atom_modify map array\n\
         boundary f f f\n\
         newton off\n\
         communicate single vel yes\n\
         units si\n\
         region reg block -0.02 0.02 -0.02 0.02 -0.02 0.02 units box\n\
         create_box 1 reg\n\
         neighbor 0.001 bin\n\
         neigh_modify delay 0\n\
         fix m all property/global youngsModulus peratomtype 5e6\n\
         fix p all property/global poissonsRatio peratomtype 0.45\n\
         fix c all property/global coefficientRestitution peratomtypepair 1 0.3\n\
         fix f all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\n\
         pair_coeff * *\n\
         timestep 0.0001\n\
         fix orifice all mesh/surface file {mesh} type 1\n\
         fix mf all massflow/mesh mesh orifice vec_side 0 0 -1\n\
         create_atoms 1 single 0.001 0.002 0.0095\n\
         set atom 1 diameter 0.004 density 2500\n\
         velocity all set 0 0 -1\n\
         fix integr all nve/sphere\n\
         variable time equal time\n\
         variable in_mass_flow equal f_mf[1]\n\
         variable count equal f_mf[2]\n\
         fix out all print 50 \"${{time}},${{in_mass_flow}},${{count}}\" screen no title \"t,in_mass_flow,count\" file {}\n\
         run 150\n",
        csv.display()
    );
    let i = common::run("in.fp", &script);
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(text.lines().next(), Some("t,in_mass_flow,count"), "{text}");
    assert_eq!(rows.len(), 3, "{text}");
    let m = 2500.0 * std::f64::consts::PI * 0.004f64.powi(3) / 6.0;
    for (k, (t, mass, n)) in [(0.005, 0.0, 0.0), (0.01, m, 1.0), (0.015, m, 1.0)]
        .into_iter()
        .enumerate()
    {
        let r = &rows[k];
        assert!((r[0] - t).abs() < 1e-12, "{text}");
        assert!((r[1] - mass).abs() <= 1e-12 * m, "{text}");
        assert_eq!(r[2], n, "{text}");
    }
    // `screen no`: nothing on the screen.
    let s = common::screen(&i);
    assert!(!s.contains("e-05,"), "{s}");
}

/// `rdem -check` writes no file and reports a variable the text names that does not
/// exist (substituted once at each run's set-up).
#[test]
fn check_writes_nothing_and_finds_unknown_variables() {
    let d = common::scratch_dir("fixprint-check");
    let f = d.join("p.txt");
    let script = format!(
        "{HEAD}variable a equal 1\n\
         fix ok all print 1 \"$a\" file {}\n\
         fix bad all print 1 \"${{nope}}\"\n\
         run 2\n",
        f.display()
    );
    let mut i = common::interpreter();
    let c = i.check_source("in.fp", &script);
    assert!(!f.exists());
    assert_eq!(c.problems.len(), 1, "{c:?}");
    let msg = c.problems[0].report.to_string();
    assert!(msg.contains("nope"), "{msg}");
}

/// A file that cannot be made is an error at its name when the fix is defined; a write
/// that fails during the run (`/dev/full`) stops the run with an error at the fix.
#[test]
fn io_errors_are_located() {
    let d = common::scratch_dir("fixprint-io");
    std::fs::write(d.join("afile"), "x").unwrap();
    let bad = d.join("afile/p.txt");
    let script = format!("{HEAD}fix pr all print 1 \"x\" file {}\n", bad.display());
    let mut i = common::interpreter();
    let r = render(&i.run_source("in.fp", &script).unwrap_err());
    let line = HEAD.lines().count() + 1;
    assert!(r.contains(&format!("in.fp:{line}:29")), "{r}");
    assert!(r.contains("afile"), "{r}");

    if !std::path::Path::new("/dev/full").exists() {
        eprintln!("no /dev/full: the failing write during a run is not tested");
        return;
    }
    let script =
        format!("{HEAD}fix pr all print 2 \"x\" append /dev/full title none\nrun 1\nrun 1\n");
    let mut i = common::interpreter();
    let r = render(&i.run_source("in.fp", &script).unwrap_err());
    assert!(r.contains(&format!("in.fp:{line}:")), "{r}");
    assert!(r.contains("/dev/full"), "{r}");
    // The first run (step 1) printed nothing, so it ran through.
    let s = common::screen(&i);
    assert_eq!(s.matches("Loop time").count(), 1, "{s}");
}
