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

use crate::common;
use common::{run_kept, MATERIALS};

/// One case.
struct Case {
    head: &'static str,
    make_box: &'static str,
    defs: &'static str,
    init: &'static str,
    /// What both scripts define after the particles exist (after `init` in the writing
    /// script, after `defs` in the continuing one).
    after: &'static str,
    n1: u64,
    n2: u64,
    /// Files (name, contents) beside the scripts.
    files: Vec<(&'static str, String)>,
    /// Files both runs write at the end, which must be the same bytes.
    compare: &'static [&'static str],
}

/// The end state and the thermo rows of the last run.
const FINAL: &str = "write_dump all custom final.dump id type x y z vx vy vz omegax omegay omegaz radius mass modify sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n";

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
/// end state's dump and the thermo rows of the continued run.
fn check_split(name: &str, c: &Case) -> (String, Vec<Vec<f64>>) {
    let unbroken = format!(
        "{}{}{}{}{}run {}\nrun {}\n{FINAL}",
        c.head, c.make_box, c.defs, c.init, c.after, c.n1, c.n2
    );
    let files: Vec<(&str, &str)> = c.files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let (d0, out0) = common::run_kept_ok(&format!("{name}-unbroken"), &unbroken, &files, None);
    let first = format!(
        "{}{}{}{}{}run {}\nwrite_restart state.restart\n",
        c.head, c.make_box, c.defs, c.init, c.after, c.n1
    );
    let (d1, _) = common::run_kept_ok(&format!("{name}-first"), &first, &files, None);
    // The continuing script runs in a new process and directory with the restart file
    // beside its own files.
    let second = format!(
        "{}read_restart ../{}/state.restart\n{}{}run {}\n{FINAL}",
        c.head,
        d1.file_name().unwrap().to_string_lossy(),
        c.defs,
        c.after,
        c.n2
    );
    let (dir2, out2) = common::run_kept_ok(&format!("{name}-second"), &second, &files, None);
    let a = std::fs::read_to_string(d0.join("final.dump")).unwrap();
    let b = std::fs::read_to_string(dir2.join("final.dump")).unwrap();
    let (ra, rb) = (last_rows(&out0), last_rows(&out2));
    for f in c.compare {
        let (x, y) = (std::fs::read(d0.join(f)), std::fs::read(dir2.join(f)));
        assert!(x.is_ok(), "{name}: the unbroken run wrote no {f}");
        assert!(x.unwrap() == y.unwrap_or_default(), "{name}: {f} differs");
    }
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
    let rows = ra
        .iter()
        .filter_map(|l| {
            l.split_whitespace()
                .map(str::parse)
                .collect::<Result<Vec<f64>, _>>()
                .ok()
        })
        .collect();
    (a, rows)
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

/// The settling beds' box: 0.1 × 0.1 × 0.12 m.
const BED_BOX: &str = "region box block -0.05 0.05 -0.05 0.05 0 0.12 units box\ncreate_box 1 box\n";

/// The settling beds' particles: 250 spheres of radius 4 mm packed in a cylinder.
const BED_INIT: &str = "region ins cylinder z 0 0 0.04 0.005 0.11 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 250 region ins
";

/// The settling beds' definitions for the extra properties `$props` and the contact
/// model `$model` (pair style, floor and cylinder wall alike).
macro_rules! bed_defs {
    ($props:literal, $model:literal) => {
        concat!(
            "neighbor 0.002 bin\nneigh_modify delay 0\n",
            common::materials!(),
            $props,
            "pair_style gran model ",
            $model,
            "
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model ",
            $model,
            " primitive type 1 zplane 0
fix cyl all wall/gran model ",
            $model,
            " primitive type 1 zcylinder 0.045 0 0
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo 1000
thermo_modify format float %.17g
"
        )
    };
}

/// A settling bed with definitions `defs`, split after 8000 of 12000 steps: the 250
/// spheres all stay; returns the thermo rows.
fn bed(name: &str, defs: &'static str) -> Vec<Vec<f64>> {
    let c = Case {
        head: HEAD,
        make_box: BED_BOX,
        defs,
        init: BED_INIT,
        after: "",
        n1: 8000,
        n2: 4000,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split(name, &c);
    assert_eq!(atoms(&end), 250);
    rows
}

/// A bed settling in a cylinder on a floor, rolling friction on: pair, wall and
/// rolling histories all carry over.
#[test]
fn settling_bed_with_walls_and_rolling_friction_continues_bit_for_bit() {
    bed(
        "bed",
        bed_defs!(
            "fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.1\n",
            "hertz tangential history rolling_friction cdt"
        ),
    );
}

/// The same bed with LIGGGHTS-PFM's `tangential incremental_history` (pair and walls):
/// its stored force, k_t and normal force of the step before carry over.
#[test]
fn incremental_history_bed_continues_bit_for_bit() {
    let rows = bed(
        "bed-incremental",
        bed_defs!("", "hertz tangential incremental_history"),
    );
    // Still moving at the split: the contacts' history matters to the continued run.
    assert!(rows.iter().any(|r| r[2] > 1e-6), "{rows:?}");
}

/// The same bed with `model jkr` (LIGGGHTS_Flexible_Fibers): the contact radius of each
/// contact (the solve's warm start and the sign of a neck, which holds apart) carries over.
#[test]
fn jkr_bed_continues_bit_for_bit() {
    let rows = bed(
        "bed-jkr",
        bed_defs!(
            "fix m5 all property/global workOfAdhesion peratomtypepair 1 2.0
fix m6 all property/global resolutionJKR scalar 1e-4
",
            "jkr tangential history"
        ),
    );
    assert!(rows.iter().any(|r| r[2] > 1e-6), "{rows:?}");
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
        after: "",
        n1: 5000,
        n2: 4000,
        files: vec![
            ("floor.stl", square_stl(0.05, 0.0)),
            ("face.stl", square_stl(0.03, 0.14)),
            ("counter.stl", square_stl(0.05, 0.07)),
        ],
        compare: &[],
    };
    let (end, rows) = check_split("stream", &c);
    // Insertions every 1000 steps from step 1 (40 each) go on after the split, and the
    // counter face has counted particles before and after it.
    let last = rows.last().unwrap();
    assert_eq!(
        (atoms(&end), last[1], last[5]),
        (360, 360.0, 360.0),
        "{last:?}"
    );
    assert!(rows[0][4] > 0.0 && last[4] > rows[0][4], "{rows:?}");
}

/// A bonded agglomerate (`cohesion bond`, bonds made at step 1 between touching
/// neighbours of a cubic block) dropped on a floor and breaking on impact: the bonds,
/// their forces and the broken ones carry over with the pair histories.
#[test]
fn bonded_agglomerate_breaking_on_a_floor_continues_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: "region box block -0.012 0.012 -0.012 0.012 0 0.02 units box\ncreate_box 1 box\n",
        defs: "neighbor 0.0002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix b1 all property/global radiusMultiplierBond peratomtypepair 1 1.0
fix b2 all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 2e10
fix b3 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 1e10
fix b4 all property/global maxDistanceBond peratomtypepair 1 0.002003
fix b5 all property/global createDistanceBond peratomtypepair 1 0.00201
fix b6 all property/global tsCreateBond scalar 1
fix d1 all property/global dampingNormalForceBond peratomtypepair 1 0.0
fix d2 all property/global dampingTangentialForceBond peratomtypepair 1 0.0
fix d3 all property/global dampingNormalTorqueBond peratomtypepair 1 0.0
fix d4 all property/global dampingTangentialTorqueBond peratomtypepair 1 0.0
pair_style gran model hertz tangential history cohesion bond
pair_coeff * *
timestep 2e-7
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix integr all nve/sphere
compute bc all bond/counter
thermo_style custom step atoms ke c_bc[3]
thermo 500
thermo_modify format float %.17g
",
        init: "lattice sc 0.002
region blk block -0.004 0.0041 -0.004 0.0041 0.0021 0.0102 units box
create_atoms 1 region blk
set group all diameter 0.002 density 2500
velocity all set 0.3 0 -4
",
        after: "",
        n1: 4600,
        n2: 1400,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split("bonds", &c);
    assert_eq!(atoms(&end), 100);
    // 235 bonds were made between the 100 touching neighbours; the impact (at step
    // ~3700) breaks 65 of them after the split.
    let intact: Vec<f64> = rows.iter().map(|r| r[3]).collect();
    assert_eq!(
        (intact[0], *intact.last().unwrap()),
        (235.0, 170.0),
        "{intact:?}"
    );
}

/// Particles growing by `fix adapt` (a diameter that follows the time) in a bed whose
/// mean kinetic energy a running `fix ave/time` follows: the time, the radii and
/// masses, and the running average carry over.
#[test]
fn growing_particles_with_a_running_average_continue_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: BED_BOX,
        defs: concat!("neighbor 0.002 bin
neigh_modify delay 0
", common::materials!(), "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history primitive type 1 zcylinder 0.045 0 0
variable d atom 0.006*(1+0.25*time/0.2)
fix grow all adapt 50 atom diameter v_d
variable k equal ke
fix at all ave/time 10 20 500 v_k ave running
fix integr all nve/sphere
thermo_style custom step atoms ke f_at
thermo 500
thermo_modify format float %.17g
"),
        init: "region ins cylinder z 0 0 0.04 0.005 0.11 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 250 region ins
",
        after: "",
        n1: 5000,
        n2: 5000,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split("adapt", &c);
    assert_eq!(atoms(&end), 250);
    // The last adaptation, in the last step (its pre-force stage, at the time of step
    // 9999): every diameter is 0.006 · (1 + 0.25 · 0.19998 / 0.2).
    let want = 0.5 * 0.006 * (1.0 + 0.25 * 0.19998 / 0.2);
    for l in end
        .lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
    {
        let r: f64 = l.split_whitespace().nth(11).unwrap().parse().unwrap();
        assert!((r - want).abs() < 1e-15, "{l}");
    }
    assert!(rows.iter().all(|r| r[3] > 0.0), "{rows:?}");
}

/// The settling bed with `fix ave/euler` and its `dump euler/vtk`: the cell averages of
/// the last step (velocities, volume fractions, the stress of the contacts) are the same
/// bytes after the split. ave/euler keeps no state between its samples; what it averages
/// (positions, velocities and the contact forces, recomputed at the continued run's
/// set-up from the restored histories) must all have carried over.
#[test]
fn ave_euler_of_a_settling_bed_continues_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: BED_BOX,
        defs: concat!(
            "neighbor 0.002 bin
neigh_modify delay 0
",
            common::materials!(),
            "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history primitive type 1 zcylinder 0.045 0 0
fix integr all nve/sphere
fix euler all ave/euler nevery 100 cell_size_relative 3 parallel no
dump e all euler/vtk 2000 euler_*.vtk
thermo_style custom step atoms ke
thermo 1000
thermo_modify format float %.17g
"
        ),
        init: BED_INIT,
        after: "",
        n1: 6000,
        n2: 4000,
        files: Vec::new(),
        compare: &["euler_10000.vtk"],
    };
    let (end, _) = check_split("euler", &c);
    assert_eq!(atoms(&end), 250);
}

/// Particles 1–20 wiggle (`fix move wiggle`) and 21–30 follow `fix move variable`
/// through a settling bed: the motions' time origin (the step of their definition in the
/// writing script), the last variable displacement and every particle's original
/// position carry over, so the prescribed particles are where the unbroken run has them.
#[test]
fn particles_moved_by_fix_move_continue_bit_for_bit() {
    let c = Case {
        head: HEAD,
        make_box: BED_BOX,
        defs: concat!("neighbor 0.002 bin
neigh_modify delay 0
", common::materials!(), "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history primitive type 1 zcylinder 0.045 0 0
thermo_style custom step atoms ke
thermo 1000
thermo_modify format float %.17g
"),
        init: "region ins cylinder z 0 0 0.04 0.005 0.11 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 250 region ins
run 500
",
        after: "group wig id 1:20
group var id 21:30
group free subtract all wig var
fix wiggle wig move wiggle 0.002 NULL NULL 0.05 units box
variable dx equal 0.002*sin(20*time)
variable vx equal 0.04*cos(20*time)
fix follow var move variable v_dx NULL NULL v_vx NULL NULL units box
fix integr free nve/sphere
",
        n1: 3000,
        n2: 3000,
        files: Vec::new(),
        compare: &[],
    };
    let (end, _) = check_split("move", &c);
    assert_eq!(atoms(&end), 250);
}

/// A bed packed by `insert/pack/dense` (once, at the first step) and settling: the
/// continuing script defines the fix again, and it does not pack the region again.
#[test]
fn a_dense_packing_is_not_inserted_again_after_a_restart() {
    let c = Case {
        head: HEAD,
        make_box: BED_BOX,
        defs: concat!("neighbor 0.002 bin
neigh_modify delay 0
", common::materials!(), "\
pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix cyl all wall/gran model hertz tangential history primitive type 1 zcylinder 0.045 0 0
region ins block -0.03 0.03 -0.03 0.03 0.02 0.08 units box
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
fix ins all insert/pack/dense seed 49979687 distributiontemplate pdd region ins volumefraction_region 0.3
fix integr all nve/sphere
thermo_style custom step atoms ke f_ins[1]
thermo 1000
thermo_modify format float %.17g
"),
        init: "",
        after: "",
        n1: 3000,
        n2: 3000,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split("dense", &c);
    let n = atoms(&end);
    assert!(n > 150, "{n} particles packed");
    // The fix's count of inserted particles carried over too.
    assert!(rows.iter().all(|r| r[3] == n as f64), "{rows:?}");
}

/// Heat conduction (`fix heat/gran`) in a packing settling on a heated mesh floor
/// beside a heated wall, with a heat source (a per-particle property set by the writing
/// script only): the temperatures, heat flows and sources carry over, and defining
/// `heat/gran` again with its `initial_temperature` does not reset them.
#[test]
fn heat_conduction_continues_bit_for_bit() {
    let floor = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/heat/floor.stl"),
    )
    .unwrap();
    let c = Case {
        head: HEAD,
        make_box: "region reg block -0.01 0.07 -0.01 0.07 -0.01 0.08 units box\ncreate_box 2 reg\n",
        defs: "neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
fix ftco all property/global thermalConductivity peratomtype 100. 40.
fix ftca all property/global thermalCapacity peratomtype 50. 80.
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix floor all mesh/surface file floor.stl type 2 move 0 0 0.00207 temperature 400.
fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes floor
fix side all wall/gran model hertz tangential history primitive type 1 xplane 0.00208 temperature 350.
fix side2 all wall/gran model hertz tangential history primitive type 1 xplane 0.0621
fix side3 all wall/gran model hertz tangential history primitive type 1 yplane 0.0015
fix side4 all wall/gran model hertz tangential history primitive type 1 yplane 0.0621
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix heattransfer all heat/gran initial_temperature 300.
fix integr all nve/sphere
compute tmean all reduce ave f_Temp
compute tmax all reduce max f_Temp
compute flux all reduce sum f_heatFlux
thermo_style custom step atoms f_heattransfer c_tmean c_tmax c_flux
thermo_modify format float %.17g
thermo 500
",
        init: "lattice fcc 0.0141421356237
region pack block 0.006 0.06 0.006 0.06 0.006 0.06 units box
create_atoms 1 region pack
region upper block INF INF INF INF 0.032 INF units box
set region upper type 2
set type 1 diameter 0.01 density 2500
set type 2 diameter 0.01 density 3000
run 0
region src block INF 0.02 INF 0.02 0.04 INF units box
set region src property/atom heatSource 0.05
",
        after: "",
        n1: 2500,
        n2: 2500,
        files: vec![("floor.stl", floor)],
        compare: &[],
    };
    let (end, rows) = check_split("heat", &c);
    assert_eq!(atoms(&end), 256);
    // The bed has warmed from its initial 300 K by the end (measured: mean 301.69 K,
    // maximum 312.94 K at step 5000).
    let last = rows.last().unwrap();
    assert!(last[3] > 301.0 && last[4] > 310.0, "{last:?}");
}

/// Bad restart files stop `read_restart` with a located error that names the file and
/// says what is wrong; never a panic.
#[test]
fn bad_restart_files_are_located_errors() {
    // A good file to damage.
    let script = format!(
        "{HEAD}region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\ncreate_atoms 1 single 0.5 0.5 0.5 units box\nwrite_restart good.restart\n"
    );
    let (dir, out) = run_kept("badrestart", &script, &[], None);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let good = std::fs::read(dir.join("good.restart")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let mut corrupt = good.clone();
    let k = good.len() - 3;
    corrupt[k] ^= 0x10;
    let mut later = good.clone();
    later[16] += 1;
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated", good[..good.len() / 2].to_vec(), "is truncated"),
        ("corrupted", corrupt, "is corrupted"),
        ("later", later, "written by a newer rdem"),
        (
            "data",
            b"LAMMPS data file\n\n1 atoms\n1 atom types\n0 1 xlo xhi\n".to_vec(),
            "read it with read_data",
        ),
        ("empty", Vec::new(), "it is empty"),
    ];
    for (name, bytes, want) in cases {
        let script = format!("{HEAD}read_restart r.restart\n");
        let dir = common::scratch_dir(&format!("badrestart-{name}"));
        std::fs::write(dir.join("r.restart"), &bytes).unwrap();
        std::fs::write(dir.join("in.test"), &script).unwrap();
        let out = common::rdem_command(None)
            .args(["-in", "in.test", "-log", "none"])
            .current_dir(&dir)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let _ = std::fs::remove_dir_all(&dir);
        assert_eq!(out.status.code(), Some(1), "{name}: {text}");
        assert!(
            text.contains(want) && text.contains("'r.restart'"),
            "{name}: {text}"
        );
        assert!(text.contains("in.test:7"), "{name}: not located: {text}");
        assert!(!text.contains("panicked"), "{name}: {text}");
    }
}

/// A run killed (SIGKILL) while it writes restart files every few steps, in turn to two
/// names, leaves every restart file it had written readable: each is written under a
/// temporary name and renamed only once complete.
#[test]
fn a_run_killed_while_writing_restart_files_leaves_them_readable() {
    let script = format!(
        "{HEAD}region box block 0 0.2 0 0.2 0 0.2 units box
create_box 1 box
lattice sc 0.005
region blk block 0.0025 0.1975 0.0025 0.1975 0.0025 0.0975 units box
create_atoms 1 region blk
set group all diameter 0.004 density 2500
{MATERIALS}pair_style gran model hertz tangential history
pair_coeff * *
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix integr all nve/sphere
restart 3 a.restart b.restart
run 100000000
"
    );
    let dir = common::scratch_dir("killed");
    std::fs::write(dir.join("in.test"), &script).unwrap();
    let mut child = common::rdem_command(None)
        .args(["-in", "in.test", "-log", "none"])
        .env("RDEM_THREADS", "1")
        .current_dir(&dir)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait until both files exist (the run is writing one every 3 steps), then kill.
    let t0 = std::time::Instant::now();
    while !(dir.join("a.restart").exists() && dir.join("b.restart").exists()) {
        assert!(t0.elapsed().as_secs() < 60, "no restart files after 60 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(150));
    child.kill().unwrap();
    child.wait().unwrap();
    let (mut counts, mut steps) = (Vec::new(), Vec::new());
    for f in ["a.restart", "b.restart"] {
        let read = format!(
            "{HEAD}read_restart {f}\nvariable n equal count(all)\nprint \"ATOMS ${{n}} STEP $(step)\"\n"
        );
        std::fs::write(dir.join("in.read"), &read).unwrap();
        let out = common::rdem_command(None)
            .args(["-in", "in.read", "-log", "none"])
            .current_dir(&dir)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "{f}: {text}{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let line = text.lines().find(|l| l.starts_with("ATOMS ")).unwrap();
        let w: Vec<&str> = line.split_whitespace().collect();
        counts.push(w[1].parse::<u64>().unwrap());
        steps.push(w[3].parse::<u64>().unwrap());
    }
    let _ = std::fs::remove_dir_all(&dir);
    // Every particle of the lattice (39 × 39 × 19) in both files, which hold steps 3
    // apart (the last two written), in either order.
    assert_eq!(counts, [28899, 28899], "{steps:?}");
    assert_eq!(steps[0].abs_diff(steps[1]), 3, "{steps:?}");
}

/// A block of 294 spheres bonded by `bond_style gran` (LIGGGHTS_Flexible_Fibers) dropped
/// on a floor, some bonds breaking after the split: every bond (partners, L₀, the stored shear force and
/// torques, broken ones until they are dropped) carries over.
#[test]
fn bonded_block_continues_bit_for_bit() {
    let c = Case {
        head: "atom_style hybrid granular bond/gran n_bondtypes 1 bonds_per_atom 6
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
",
        make_box: BED_BOX,
        defs: concat!(
            "neighbor 0.002 bin\nneigh_modify delay 0\n",
            common::materials!(),
            "pair_style gran model hertz tangential history
pair_coeff * *
bond_style gran
bond_coeff 1 1.0 0.0 1.0e7 4.0e6 1 0.5 1 4.0e4 4.0e4
timestep 2e-5
fix gravi all gravity 9.81 vector 0 0 -1
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0
fix integr all nve/sphere
thermo_style custom step atoms numbonds ke
thermo 500
thermo_modify format float %.17g
"
        ),
        init: "region blk block -0.024 0.024 -0.024 0.024 0.02 0.068 units box
lattice sc 0.008
create_atoms 1 region blk
set group all density 2500 diameter 0.008
fix bondcr all bond/create/gran 1 1 1 0.00801 1 6
run 1
fix_modify bondcr every 0
",
        after: "",
        n1: 3000,
        n2: 3000,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split("bonded-block", &c);
    assert_eq!(atoms(&end), 294);
    // All 749 bonds hold until the split; the block lands after it, and some break.
    let bonds: Vec<f64> = rows.iter().map(|r| r[2]).collect();
    let last = *bonds.last().unwrap();
    assert!(bonds[0] == 749.0 && last < 749.0 && last > 0.0, "{bonds:?}");
}

/// `fix insert/fragments` (tests/data/fragments' rods): the split falls between the two
/// replacements; the continued run replaces the second rod at the same step, and its
/// fragments keep their bonds and bond IDs (the marks, the schedule and the counts come
/// back with the particles and the fix's state).
#[test]
fn fragments_continue_bit_for_bit() {
    let c = Case {
        head: "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
",
        make_box: "region box block -0.25 0.25 -0.1 0.1 -0.1 0.1 units box
create_box 2 box
group frags region box
group rods region box
",
        defs: "neighbor 0.01 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
fix m5 all property/global radiusMultiplierBond peratomtypepair 2 1 1 1 1
fix m6 all property/global normalBondStiffnessPerUnitArea peratomtypepair 2 1e7 1e7 1e7 1e7
fix m7 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 2 1e6 1e6 1e6 1e6
fix m8 all property/global maxDistanceBond peratomtypepair 2 0.05 0.05 0.05 0.05
fix m9 all property/global dampingNormalForceBond peratomtypepair 2 0. 0. 0. 0.
fix m10 all property/global dampingTangentialForceBond peratomtypepair 2 0. 0. 0. 0.
fix m11 all property/global dampingNormalTorqueBond peratomtypepair 2 0. 0. 0. 0.
fix m12 all property/global dampingTangentialTorqueBond peratomtypepair 2 0. 0. 0. 0.
fix m13 all property/global tsCreateBond scalar 0.
fix m14 all property/global createDistanceBond peratomtypepair 2 0.007 0.007 0.007 0.007
pair_style gran model hertz tangential history cohesion bond createBondAlways off
pair_coeff * *
timestep 0.00001
fix integrsp frags nve/sphere
fix ms rods multisphere
fix rod rods particletemplate/multisphere 999667 atom_type 1 density constant 2500 nspheres 3 ntry 100000 spheres -0.006 0 0 0.003 0 0 0 0.003 0.006 0 0 0.003 type 1
fix pdrod all particledistribution/discrete 999683 1 rod 1.0
region fac1 block -0.2001 -0.1999 0.019 0.021 -0.001 0.001 units box
region fac2 block -0.2007 -0.2005 -0.021 -0.019 -0.001 0.001 units box
fix ins1 all insert/rate/region seed 999999937 distributiontemplate pdrod vel constant 1. 0. 0. nparticles 1 particlerate 4000 insert_every 100 overlapcheck yes all_in no orientation constant 1. 0. 0. 0. region fac1
fix ins2 all insert/rate/region seed 999727 distributiontemplate pdrod vel constant 1. 0. 0. nparticles 1 particlerate 4000 insert_every 100 overlapcheck yes all_in no orientation constant 0.7071067811865476 0. 0.7071067811865476 0. region fac2
fix fragments frags particletemplate/multiplespheres 999671 atom_type 2 density constant 2500 relative yes nspheres 3 ntry 100000 spheres -0.66666666 0 0 0.33333333 0 0 0 0.33333333 0.66666666 0 0 0.33333333 bonded yes
fix pdfragments all particledistribution/discrete 999721 1 fragments 1.
region band block -0.04975 0.05 INF INF INF INF units box
fix replace all insert/fragments seed 999749 distributiontemplate pdfragments every 50 region band type_replace 1
compute bc all bond/counter
thermo_style custom step atoms ke f_replace[1] c_bc[3]
thermo 25
thermo_modify format float %.17g
",
        init: "",
        after: "",
        n1: 15075,
        n2: 200,
        files: Vec::new(),
        compare: &[],
    };
    let (end, rows) = check_split("fragments", &c);
    assert_eq!(atoms(&end), 6);
    // The second rod is replaced after the split: 2 replaced, 4 bonds.
    let last = rows.last().unwrap();
    assert_eq!((last[3], last[4]), (2.0, 4.0), "{rows:?}");
    assert!(rows.iter().any(|r| r[3] == 1.0), "{rows:?}");
}
