//! The small commands every script has: `processors` on fewer ranks than asked for,
//! `dimension`, `thermo_log`, seeds LIGGGHTS 3.8 refuses, `clear`, `units cgs|micro`.

use rdem_script::{Interpreter, Sim};

use crate::common;
use common::render;

/// Runs `src` (a script named `in.t`) and returns the interpreter and its output.
fn run(src: &str) -> (Interpreter, Result<(), String>, String) {
    let mut i = common::interpreter();
    let r = i.run_source("in.t", src).map_err(|e| render(&e));
    let out = common::screen(&i);
    (i, r, out)
}

/// LIGGGHTS 3.8 stops at `processors 2 2 2` on one process ("ERROR: Specified processors
/// != physical processors"); rdem warns, naming both grids, and runs on 1 x 1 x 1.
#[test]
fn processors_grid_that_does_not_fit_warns_and_runs() {
    let (i, r, out) = run("processors 2 2 2 grid onelevel map cart\n\
         region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n");
    r.unwrap();
    assert!(
        out.contains(
            "WARNING: line 1: processors 2 x 2 x 2 does not fit the 1 process of this run \
             (LIGGGHTS stops here): rdem uses 1 x 1 x 1"
        ),
        "{out}"
    );
    assert_eq!(i.sim.setup.procs, [0, 0, 0]);
    // A grid that fits is kept, without a warning.
    let (i, r, out) = run("processors 1 * 1 map xyz\n");
    r.unwrap();
    assert!(!out.contains("WARNING"), "{out}");
    assert_eq!(i.sim.setup.procs, [1, 0, 1]);
    // `grid twolevel` and `numa` say how ranks group onto nodes: read, and laid out as
    // onelevel; a process count that is not a multiple of the cores per node is a
    // warning (LAMMPS stops), a core grid that does not fit them an error.
    let (i, r, out) = run("processors * * 1 grid twolevel 24 * * 1\n");
    r.unwrap();
    assert!(
        out.contains(
            "WARNING: line 1: processors grid twolevel: 1 process is not a multiple of 24 \
             cores per node (LAMMPS stops here): rdem lays the ranks out as grid onelevel"
        ),
        "{out}"
    );
    assert_eq!(i.sim.setup.procs, [0, 0, 1]);
    let (_, r, out) = run("processors * * * grid numa\n");
    r.unwrap();
    assert!(!out.contains("WARNING"), "{out}");
    // Keywords rdem does not run are errors at the word.
    for (src, msg) in [
        (
            "processors * * * grid custom grid.txt\n",
            "processors grid custom is not supported yet",
        ),
        (
            "processors * * * grid twolevel 4 2 2 2\n",
            "processors grid twolevel: the core grid 2 x 2 x 2 does not fit 4 cores per node",
        ),
        (
            "processors * * * grid twolevel 4 3 * 1\n",
            "processors grid twolevel: the core grid 3 x * x 1 does not fit 4 cores per node",
        ),
        (
            "processors * * * part 1 2 multiple\n",
            "processors part is not supported yet",
        ),
        (
            "processors * * * file grid.txt\n",
            "processors file is not supported yet",
        ),
        (
            "processors * * * mapp xyz\n",
            "unknown processors keyword 'mapp'",
        ),
    ] {
        let (_, r, _) = run(src);
        let e = r.unwrap_err();
        assert!(e.contains(msg) && e.contains("in.t:1:"), "{e}");
    }
}

const BOX: &str = "region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n";

/// `fix_modify energy` is accepted on any fix (warning where LIGGGHTS would add an energy
/// rdem does not); `temp`, `press`, `virial` and unknown keywords or IDs stop, at the word.
#[test]
fn fix_modify_generic_keywords() {
    let src = format!(
        "{BOX}fix gr all gravity 9.81 vector 0 0 -1\nfix integr all nve/sphere\n\
         fix_modify integr energy yes\nfix_modify gr energy no\nfix_modify gr energy yes\n"
    );
    let (i, r, out) = run(&src);
    r.unwrap();
    let energy: Vec<bool> = i.sim.defs.fixes.iter().map(|f| f.energy).collect();
    assert_eq!(energy, [true, true]);
    assert_eq!(
        out.matches("WARNING").count(),
        1,
        "one warning, for gravity:\n{out}"
    );
    assert!(
        out.contains(
            "line 7: fix_modify energy yes: rdem does not add the energy of fix gr (gravity)"
        ),
        "{out}"
    );
    for (tail, msg, col) in [
        (
            "fix_modify gr temp thermo_temp",
            "fix gr (gravity) computes no temperature",
            15,
        ),
        (
            "fix_modify gr press thermo_temp",
            "fix gr (gravity) computes no pressure",
            15,
        ),
        (
            "fix_modify gr virial yes",
            "fix_modify virial is not a LIGGGHTS 3.8 keyword",
            15,
        ),
        ("fix_modify gr energy maybe", "unknown energy 'maybe'", 22),
        (
            "fix_modify gr enrgy yes",
            "unknown fix_modify keyword 'enrgy'",
            15,
        ),
        ("fix_modify gravi energy yes", "no fix 'gravi'", 12),
        ("fix_modify gr", "fix_modify: missing keyword", 14),
    ] {
        let (_, r, _) = run(&format!(
            "{BOX}fix gr all gravity 9.81 vector 0 0 -1\n{tail}\n"
        ));
        let e = r.unwrap_err();
        assert!(
            e.contains(msg) && e.contains(&format!("in.t:4:{col}")),
            "{tail}: {e}"
        );
    }
}

/// A style that takes its own `fix_modify` keyword (as the servo wall's `integrate
/// start|stop` will): the hook sees it before the generic keywords.
#[derive(Default)]
struct Servo {
    integrate: Option<bool>,
}

impl rdem_script::fixes::ScriptFix for Servo {
    fn modify(
        &mut self,
        _sim: &mut Sim,
        _head: &rdem_script::fixes::FixHead,
        keyword: &str,
        a: &mut rdem_script::args::Args,
    ) -> rdem_script::args::CmdResult<bool> {
        if keyword != "integrate" {
            return Ok(false);
        }
        self.integrate = Some(a.keyword("integrate", &["start", "stop"])? == "start");
        Ok(true)
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &rdem_script::fixes::FixHead) {}
}

#[test]
fn fix_modify_reaches_a_style_keyword_first() {
    let mut i = common::interpreter();
    i.sim.defs.fixes.push(rdem_script::fixes::FixEntry {
        head: rdem_script::fixes::FixHead {
            id: "servo".into(),
            style: "servo",
            groupbit: 1,
        },
        stages: rdem_script::fixes::Stages::NONE,
        origin: None,
        energy: false,
        imp: Box::new(Servo::default()),
        seconds: 0.0,
    });
    i.run_source("in.t", "fix_modify servo integrate stop energy yes\n")
        .unwrap();
    let f = &i.sim.defs.fixes[0];
    assert_eq!(f.downcast::<Servo>().unwrap().integrate, Some(false));
    assert!(f.energy);
    let e = i
        .run_source("in.t", "fix_modify servo integrate go\n")
        .map_err(|e| render(&e))
        .unwrap_err();
    assert!(
        e.contains("unknown integrate 'go'") && e.contains("in.t:1:28"),
        "{e}"
    );
}

/// `dimension 3` runs before the box; other values than 2 and 3 and a late `dimension`
/// stop at the word (2d runs: tests/dim2.rs).
#[test]
fn dimension_two_or_three() {
    let (_, r, _) = run(&format!("dimension 3\n{BOX}"));
    r.unwrap();
    for (src, msg, at) in [
        (
            "dimension 4\n".to_string(),
            "dimension must be 2 or 3, not '4'",
            "in.t:1:11",
        ),
        (
            format!("{BOX}dimension 3\n"),
            "dimension after the simulation box is defined",
            "in.t:3:1",
        ),
        ("dimension 3 x\n".to_string(), "", "in.t:1:13"),
    ] {
        let (_, r, _) = run(&src);
        let e = r.unwrap_err();
        assert!(e.contains(msg) && e.contains(at), "{src}: {e}");
    }
}

/// `thermo_log` writes thermo's lines (a header per run) to its file, truncating it
/// unless `append`, until `thermo_log none`: the files equal LIGGGHTS 3.8's byte for byte
/// (tests/data/settings/thermo_log_*.liggghts.txt, made by regenerate.sh).
#[test]
fn thermo_log_files_as_liggghts() {
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/settings");
    let dir = std::env::temp_dir().join(format!("rdem-thermo-log-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let d = dir.display().to_string();
    let src = std::fs::read_to_string(format!("{data}/thermo_log.in"))
        .unwrap()
        .replace("include ../parity/", &format!("include {data}/../parity/"))
        .replace(
            "thermo_log thermo_log_",
            &format!("thermo_log {d}/thermo_log_"),
        );
    let (_, r, out) = run(&src);
    r.unwrap_or_else(|e| panic!("{e}\n{out}"));
    for f in ["a", "b"] {
        let got = std::fs::read_to_string(dir.join(format!("thermo_log_{f}.txt"))).unwrap();
        let want = std::fs::read_to_string(format!("{data}/thermo_log_{f}.liggghts.txt")).unwrap();
        assert_eq!(got, want, "thermo_log_{f}.txt");
    }
    std::fs::remove_dir_all(&dir).unwrap();
    let (_, r, _) = run("thermo_log a.txt appnd\n");
    let e = r.unwrap_err();
    assert!(
        e.contains("unknown thermo_log keyword 'appnd'") && e.contains("in.t:1:18"),
        "{e}"
    );
    let (_, r, _) = run("thermo_log\n");
    assert!(r.unwrap_err().contains("missing thermo log file name"));
}

/// Seeds LIGGGHTS 3.8 refuses (not a prime > 10000: "It is required that the random
/// seed value is > 10000 and a prime number", for 12345 in each of these styles) run
/// with a warning naming the line; 0 stops.
#[test]
fn seeds_liggghts_refuses_warn() {
    let head = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/parity/head.in"
    ))
    .unwrap();
    let mat = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/parity/mat.in"
    ))
    .unwrap();
    let defs = "fix pts all particletemplate/sphere 12345 atom_type 1 density constant 2500 radius constant 0.0025\n\
         fix pdd all particledistribution/discrete 9973 1 pts 1.0\n\
         fix ins all insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 5 region box\n\
         fix ins2 all insert/pack seed 10008 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 5 region box\n";
    let pre = format!("{head}region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n{mat}");
    let line0 = pre.lines().count();
    let (_, r, out) = run(&format!("{pre}{defs}"));
    r.unwrap();
    assert_eq!(out.matches("WARNING").count(), 3, "{out}");
    for (n, seed) in [(1, 12345), (2, 9973), (4, 10008)] {
        let w = format!(
            "WARNING: line {}: seed {seed} is not a prime > 10000: LIGGGHTS 3.8 refuses it, rdem takes it",
            line0 + n
        );
        assert!(out.contains(&w), "{w}\n{out}");
    }
    let (_, r, _) = run(&format!(
        "{pre}fix pts all particletemplate/sphere 0 atom_type 1 density constant 2500 radius constant 0.0025\n"
    ));
    let e = r.unwrap_err();
    assert!(e.contains("seed must be a positive integer, not 0"), "{e}");
    let (_, r, _) = run(&format!(
        "{pre}fix pts all particletemplate/sphere -5 atom_type 1 density constant 2500 radius constant 0.0025\n"
    ));
    assert!(r
        .unwrap_err()
        .contains("seed must be a non-negative integer, not '-5'"));
}

/// `clear` empties everything a script defined but its variables (as LIGGGHTS 3.8: a
/// variable defined before prints after `clear`), and the script goes on from scratch.
#[test]
fn clear_keeps_only_variables() {
    let head = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/parity/head.in"
    ))
    .unwrap();
    let mat = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/parity/mat.in"
    ))
    .unwrap();
    let setup = format!("{head}region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n{mat}");
    let src = format!(
        "variable a equal 5\nprocessors * * 1\n{setup}create_atoms 1 single 0.2 0.2 0.2 units box\n\
         group g region box\ncompute k all ke\nfix integr all nve/sphere\n\
         thermo_style custom step c_k\ntimestep 0.001\n\
         compute_modify thermo_temp extra 0\nclear\nprint \"a=${{a}}\"\n"
    );
    let (mut i, r, out) = run(&src);
    r.unwrap_or_else(|e| panic!("{e}\n{out}"));
    assert!(out.contains("a=5"), "{out}");
    let s = &i.sim;
    assert!(s.world.is_none());
    assert_eq!(s.defs.groups.names(), ["all"]);
    assert!(s.defs.regions.is_empty() && s.defs.fixes.is_empty() && s.defs.properties.is_empty());
    let computes: Vec<&str> = s.defs.computes.iter().map(|c| c.id()).collect();
    assert_eq!(computes, ["thermo_temp"]);
    assert_eq!(s.outputs.thermo.columns, ["step", "atoms", "ke", "cpu"]);
    assert_eq!((s.setup.dt, s.setup.procs), (1e-8, [0, 0, 0]));
    // The same definitions run again.
    i.run_source(
        "in.t2",
        &format!("{setup}create_atoms 1 single 0.2 0.2 0.2 units box\nrun 0\n"),
    )
    .unwrap();
    assert_eq!(i.sim.natoms(), 1);
    let (_, r, _) = run("clear now\n");
    assert!(r.unwrap_err().contains("in.t:1:7"));
}

/// The neighbor, exclusion, sort and lost-particle settings have one owner: the script's
/// set-up before the box exists, the world after. A command given after `create_box`
/// reaches the world at once (before, the world got them only when a run started, and
/// read stale values in between), and the settings given before the box carry over.
#[test]
fn settings_have_one_owner_before_and_after_the_box() {
    let (i, r, _) = run("units si\nneighbor 0.002 bin\nneigh_modify delay 3\n\
         thermo_modify lost warn\natom_modify sort 50 0.01\n\
         region box block 0 1 0 1 0 1 units box\ncreate_box 2 box\n");
    r.unwrap();
    let w = i.sim.world.as_ref().unwrap();
    assert_eq!(w.neighbor.settings.skin, 0.002);
    assert_eq!(w.neighbor.settings.delay, 3);
    assert_eq!(w.lost_policy, rdem::LostPolicy::Warn);
    assert_eq!((w.sort.every, w.sort.binsize), (50, 0.01));
    let (i, r, _) = run(
        "units si\nregion box block 0 1 0 1 0 1 units box\ncreate_box 2 box\n\
         neighbor 0.003 bin\nneigh_modify delay 8 every 2 check no exclude type 1 2\n\
         thermo_modify lost ignore\natom_modify sort 0 0\n",
    );
    r.unwrap();
    let w = i.sim.world.as_ref().unwrap();
    let s = w.neighbor.settings;
    assert_eq!((s.skin, s.delay, s.every, s.check), (0.003, 8, 2, false));
    assert!(!w.neighbor.exclude.is_empty());
    assert_eq!(i.sim.neighbor_settings(), s);
    assert_eq!(w.lost_policy, rdem::LostPolicy::Ignore);
    assert_eq!(w.sort.every, 0);
}

/// A template of weight 0 in `particledistribution/discrete`: LIGGGHTS 3.8 takes it
/// (mass% 0) and inserted all 50 particles of this script from the other template (0
/// atoms of type 1, 50 of type 2). Weights that sum to 0 gave LIGGGHTS NaN fractions;
/// rdem stops there.
#[test]
fn a_template_of_weight_zero_is_never_inserted() {
    let head = "units si\natom_style granular\nboundary f f f\n\
        region box block 0 0.1 0 0.1 0 0.1 units box\ncreate_box 2 box\n\
        neighbor 0.002 bin\n\
        fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n\
        fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n\
        fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n\
        fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n\
        pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 1e-5\n\
        fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2000 radius constant 0.0025\n\
        fix pts2 all particletemplate/sphere 32452867 atom_type 2 density constant 2000 radius constant 0.002\n";
    let rest = "fix integr all nve/sphere\n\
        region ins block 0.01 0.09 0.01 0.09 0.01 0.09 units box\n\
        fix ins all insert/pack seed 67867967 distributiontemplate pdd1 insert_every once \
        overlapcheck yes all_in yes particles_in_region 50 region ins\n\
        run 1\ngroup t1 type 1\ngroup t2 type 2\n";
    let (_, r, out) = run(&format!(
        "{head}fix pdd1 all particledistribution/discrete 49979687 2 pts1 0 pts2 1\n{rest}"
    ));
    r.unwrap();
    assert!(out.contains("\n0 atoms in group t1\n"), "{out}");
    assert!(out.contains("\n50 atoms in group t2\n"), "{out}");
    assert!(!out.contains("WARNING"), "{out}");
    let (_, r, _) = run(&format!(
        "{head}fix pdd1 all particledistribution/discrete 49979687 2 pts1 0 pts2 0\n"
    ));
    let e = r.unwrap_err();
    assert!(e.contains("sum of the template weights"), "{e}");
}

/// `pair_style gran ...` before `create_box`, as LIGGGHTS 3.8 takes it (measured: it runs
/// such a script; wild/24 has one): the box gets the model, and two overlapping spheres
/// push each other apart as with the style given after the box.
#[test]
fn pair_style_before_the_box_is_the_boxs() {
    let tail = "region box block 0 0.1 0 0.1 0 0.1 units box
create_box 1 box
pair_coeff * *
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
create_atoms 1 single 0.05 0.05 0.05 units box
create_atoms 1 single 0.0595 0.05 0.05 units box
set group all diameter 0.01 density 2500
fix integr all nve/sphere
timestep 1e-6
run 10
";
    let style = "pair_style gran model hertz tangential history\n";
    let head = "atom_style granular\nunits si\n";
    let vx = |src: &str| {
        let (i, r, out) = run(src);
        r.unwrap_or_else(|e| panic!("{e}\n{out}"));
        let w = i.sim.world.as_ref().unwrap();
        let k = w.particles.find_tag(1).unwrap();
        w.particles.v[k].x
    };
    let before = vx(&format!("{head}{style}{tail}"));
    let after = vx(&format!(
        "{head}{}",
        tail.replacen("pair_coeff", &format!("{style}pair_coeff"), 1)
    ));
    assert!(before < 0.0, "{before}");
    assert_eq!(before, after);
}

/// `region ... volume_limit V` (LIGGGHTS 3.8 accepts it without documenting it; the
/// scripts of LIGGGHTS_CFDRC give it for their micrometre boxes): LIGGGHTS 3.8 needs it,
/// and the template's, to fill a 3.7e-11 m³ block to 20 % with 20 µm spheres (without
/// them it stops: "Unable to calculate region volume", "Volume expectancy too small"),
/// and inserts 221 of the 221.1 asked for; rdem checks the value and fills the block
/// the same (221 or 222: the fraction rounds up at random, as in LIGGGHTS).
#[test]
fn region_volume_limit_is_read() {
    let script = |limit: &str| {
        format!(
            "units si\natom_style granular\nboundary p p p\n\
             region domain block 0 4.2e-4 0 4.2e-4 0 2.1e-4 units box volume_limit {limit}\n\
             create_box 1 domain\nneighbor 1.9e-5 bin\nhard_particles yes\n\
             fix m1 all property/global youngsModulus peratomtype 8.7e9\n\
             fix m2 all property/global poissonsRatio peratomtype 0.3\n\
             fix m3 all property/global coefficientRestitution peratomtypepair 1 0.95\n\
             fix m4 all property/global coefficientFriction peratomtypepair 1 0.0\n\
             pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 1e-9\n\
             fix pts1 all particletemplate/sphere 15485863 atom_type 1 volume_limit 1e-18 \
             density constant 2500 radius constant 2e-5\n\
             fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0\n\
             fix ins all insert/pack seed 49979687 distributiontemplate pdd1 insert_every once \
             overlapcheck yes all_in yes region domain volumefraction_region 0.2\n\
             fix integr all nve/sphere\nrun 1\n"
        )
    };
    let (i, r, out) = run(&script("1e-16"));
    r.unwrap();
    let n = i.sim.world.as_ref().unwrap().particles.nlocal();
    assert!(n == 221 || n == 222, "{n} particles\n{out}");
    let (_, r, _) = run(&script("-1"));
    let e = r.unwrap_err();
    assert!(e.contains("volume_limit"), "{e}");
}
