//! Exact restarts: a run split by `write_restart` and `read_restart` (in a new process)
//! ends bit-identical to the unbroken run, as LIGGGHTS continues bit for bit.
//!
//! Each case is a script in parts: `head` (before the box), `make_box`, `defs` (what
//! both the writing and the continuing script define after the box: materials, pair
//! style, walls, fixes) and `init` (what only the writing script does: creating or
//! inserting particles). The unbroken run is `head make_box defs init run N1 run N2`;
//! the split run is `head make_box defs init run N1 write_restart` in one process and
//! `head read_restart defs run N2` in another. Both write every particle's state with 17
//! significant digits at the end, and the thermo rows of the second run; they must be
//! the same bytes.

mod common;
use common::run_kept;

/// One case.
struct Case {
    head: &'static str,
    make_box: &'static str,
    defs: &'static str,
    init: &'static str,
    n1: u64,
    n2: u64,
    /// Files (name, contents) beside the scripts.
    files: Vec<(&'static str, String)>,
}

/// The end state and the thermo rows of the last run.
const FINAL: &str = "write_dump all custom final.dump id type x y z vx vy vz omegax omegay omegaz radius mass modify sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n";

fn run_ok(prefix: &str, script: &str, files: &[(&str, &str)]) -> (std::path::PathBuf, String) {
    let (dir, out) = run_kept(prefix, script, files, None);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{prefix}: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, text)
}

/// Thermo rows after the last `Step` header, as printed.
fn last_rows(out: &str) -> Vec<String> {
    let start = out.rfind("Step").expect("a thermo header");
    out[start..]
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with("Loop time"))
        .map(str::to_string)
        .collect()
}

/// Runs `c` unbroken and split; asserts the same end state and thermo rows; returns the
/// end state's dump.
fn check_split(name: &str, c: &Case) -> String {
    let unbroken = format!(
        "{}{}{}{}run {}\nrun {}\n{FINAL}",
        c.head, c.make_box, c.defs, c.init, c.n1, c.n2
    );
    let files: Vec<(&str, &str)> = c.files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let (d0, out0) = run_ok(&format!("{name}-unbroken"), &unbroken, &files);
    let first = format!(
        "{}{}{}{}run {}\nwrite_restart state.restart\n",
        c.head, c.make_box, c.defs, c.init, c.n1
    );
    let (d1, _) = run_ok(&format!("{name}-first"), &first, &files);
    // The continuing script runs in a new process and directory with the restart file
    // beside its own files.
    let second = format!(
        "{}read_restart ../{}/state.restart\n{}run {}\n{FINAL}",
        c.head,
        d1.file_name().unwrap().to_string_lossy(),
        c.defs,
        c.n2
    );
    let (dir2, out2) = run_ok(&format!("{name}-second"), &second, &files);
    let a = std::fs::read_to_string(d0.join("final.dump")).unwrap();
    let b = std::fs::read_to_string(dir2.join("final.dump")).unwrap();
    let (ra, rb) = (last_rows(&out0), last_rows(&out2));
    for d in [d0, d1, dir2] {
        let _ = std::fs::remove_dir_all(d);
    }
    assert_eq!(ra, rb, "{name}: thermo rows of the continued run differ");
    if a != b {
        let diff = a
            .lines()
            .zip(b.lines())
            .find(|(x, y)| x != y)
            .map(|(x, y)| format!("unbroken: {x}\nsplit:    {y}"));
        panic!("{name}: end states differ, first difference:\n{diff:?}");
    }
    a
}

/// Particles in a dump's `ITEM: ATOMS` section.
fn atoms(dump: &str) -> usize {
    dump.lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .count()
}

const HEAD: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
";

/// A bed settling in a cylinder on a floor, rolling friction on: pair, wall and
/// rolling histories all carry over.
#[test]
fn settling_bed_with_walls_and_rolling_friction_continues_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: "region box block -0.05 0.05 -0.05 0.05 0 0.12 units box\ncreate_box 1 box\n",
        defs: "neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.6
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.1
pair_style gran model hertz tangential history rolling_friction cdt
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history rolling_friction cdt primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history rolling_friction cdt primitive type 1 zcylinder 0.045 0 0
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo 1000
thermo_modify format float %.17g
",
        init: "region ins cylinder z 0 0 0.04 0.005 0.11 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 250 region ins
",
        n1: 8000,
        n2: 4000,
        files: Vec::new(),
    };
    let end = check_split("bed", &c);
    assert_eq!(atoms(&end), 250);
}

/// A square of half-width `h` at height `z` (two triangles, normal +z), ASCII STL.
fn square_stl(h: f64, z: f64) -> String {
    let v = |x: f64, y: f64| format!("vertex {x} {y} {z}\n");
    let tri = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        format!(
            "facet normal 0 0 1\nouter loop\n{}{}{}endloop\nendfacet\n",
            v(a.0, a.1),
            v(b.0, b.1),
            v(c.0, c.1)
        )
    };
    format!(
        "solid sq\n{}{}endsolid sq\n",
        tri((-h, -h), (h, -h), (h, h)),
        tri((-h, -h), (h, h), (-h, h))
    )
}

/// A stream poured through a face onto a shaking floor mesh, counted by a massflow
/// face on the way: insertion generators and schedule, mesh motion phase, mesh wall
/// history and the flow counters all carry over (the continuing script defines the
/// templates, the stream, the meshes, their motion and the counter again, as CFDEM's
/// run scripts do).
#[test]
fn stream_on_a_moving_mesh_with_massflow_continues_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: "region box block -0.06 0.06 -0.06 0.06 -0.01 0.16 units box\ncreate_box 1 box\n",
        defs: "neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all mesh/surface file floor.stl type 1
fix face all mesh/surface file face.stl type 1
fix counter all mesh/surface file counter.stl type 1
fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor
fix side all wall/gran model hertz tangential history primitive type 1 zcylinder 0.05 0 0
fix shake all move/mesh mesh floor wiggle amplitude 0 0 0.002 period 0.01
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius gaussian 0.003 0.0003
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/stream seed 86028157 distributiontemplate pdd nparticles 400 particlerate 2000 insert_every 1000 overlapcheck yes vel constant 0 0 -0.5 insertion_face face
fix mf all massflow/mesh mesh counter count once vec_side 0 0 -1
fix integr all nve/sphere
thermo_style custom step atoms ke f_mf[1] f_mf[2] f_ins[1]
thermo 500
thermo_modify format float %.17g
",
        init: "",
        n1: 5000,
        n2: 4000,
        files: vec![
            ("floor.stl", square_stl(0.05, 0.0)),
            ("face.stl", square_stl(0.03, 0.14)),
            ("counter.stl", square_stl(0.05, 0.07)),
        ],
    };
    let end = check_split("stream", &c);
    assert!(
        atoms(&end) > 100 && atoms(&end) <= 400,
        "{} particles",
        atoms(&end)
    );
}
