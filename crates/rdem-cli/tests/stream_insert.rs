//! `fix insert/stream` (a packet of particles through a planar face every time the
//! stream has crossed the extrusion), `fix massflow/mesh` (mass and count through a
//! face) and the portable restart files (`write_restart` / `read_restart`).

use crate::common;

use common::{run_with_files_raw, thermo_rows};

/// A 0.1 m square in the plane z = `z` (two triangles), ASCII STL.
fn square(z: f64) -> String {
    let v = |x: f64, y: f64| format!("vertex {x} {y} {z}\n");
    format!(
        "solid face\nfacet normal 0 0 1\nouter loop\n{}{}{}endloop\nendfacet\n\
         facet normal 0 0 1\nouter loop\n{}{}{}endloop\nendfacet\nendsolid face\n",
        v(-0.05, -0.05),
        v(0.05, -0.05),
        v(0.05, 0.05),
        v(-0.05, -0.05),
        v(0.05, 0.05),
        v(-0.05, 0.05)
    )
}

const HEAD: &str = "atom_style granular
boundary f f f
units si
region box block -0.1 0.1 -0.1 0.1 -0.5 0.3 units box
create_box 1 box
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.4
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-4
fix g all gravity 9.81 vector 0 0 -1
fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 10037 1 pts 1.0
fix face all mesh/surface file face.stl type 1
fix nve all nve/sphere
compute vz all property/atom vz
compute vmax all reduce max c_vz
compute vmin all reduce min c_vz
variable zlo equal bound(all,zmin)
variable zhi equal bound(all,zmax)
thermo_style custom step atoms c_vmax c_vmin v_zlo v_zhi
thermo_modify norm no format float %.15g
";

fn run(script: &str) -> Vec<Vec<f64>> {
    let stl = square(0.1);
    let out = run_with_files_raw(script, &[("face.stl", &stl)], None);
    thermo_rows(&common::success("the stream", &out))
}

/// Streaming down at 2 m/s through the face z = 0.1 from a 0.05 m extrusion with
/// dt = 1e-4: a packet every floor(0.05 / (2 · 1e-4)) = 250 steps of
/// 2000 /s · 250 · 1e-4 = 50 particles, until 120 are in (50, 50, 20 at steps 1, 251,
/// 501). Packets are placed whole inside the extrusion (`all_in yes`: 0.104 ≤ z ≤ 0.146)
/// and fly at exactly the insertion velocity, untouched by gravity, until they reach the
/// face; below it gravity acts.
#[test]
fn packets_stream_through_the_face() {
    let script = format!(
        "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 120 \
         particlerate 2000 vel constant 0 0 -2 overlapcheck yes all_in yes \
         insertion_face face extrude_length 0.05
thermo 50
run 1
run 699
"
    );
    let rows = run(&script);
    let at = |step: f64| {
        rows.iter()
            .rev()
            .find(|r| r[0] == step)
            .unwrap_or_else(|| panic!("no thermo row at step {step}: {rows:?}"))
            .clone()
    };
    let r1 = at(1.0);
    assert_eq!(r1[1], 50.0, "{r1:?}");
    assert_eq!(r1[2], -2.0, "inserted at the stream velocity: {r1:?}");
    assert_eq!(r1[3], -2.0, "{r1:?}");
    assert!(r1[4] >= 0.104 - 1e-12 && r1[5] <= 0.146 + 1e-12, "{r1:?}");
    // Step 201: the packet has moved 0.04 m; the particles not yet at the face still fly
    // at exactly -2 m/s, those below it have gained at most g · 200 dt.
    let r = at(200.0);
    assert_eq!(r[1], 50.0);
    assert_eq!(r[2], -2.0, "a held particle was accelerated: {r:?}");
    assert!(r[3] < -2.05 && r[3] >= -2.0 - 9.81 * 0.02 - 1e-9, "{r:?}");
    assert_eq!(at(250.0)[1], 50.0);
    assert_eq!(at(300.0)[1], 100.0);
    assert_eq!(at(500.0)[1], 100.0);
    assert_eq!(at(550.0)[1], 120.0);
    assert_eq!(at(700.0)[1], 120.0, "nparticles reached: no more packets");
}

/// An oblique stream (`vel constant 0 -0.5 -2` through the horizontal face): a held
/// sphere or clump moves along the face normal only, at the normal part of its velocity
/// (vy = 0, vz = -2), and gains the rest (vy = -0.5) at the step its centre reaches the
/// face, so it leaves the face where it was placed above it. Measured with LIGGGHTS 3.8
/// (a 0.2 m square face, `extrude_length 0.1`, `vel constant 0 -0.5 -2` on spheres and
/// `0 0.5 -1` on two-sphere clumps, dumps of every 10 steps): every held particle had
/// vy = 0 exactly, and the full velocity from the step its centre crossed the face.
/// rdem held them at the full velocity, so a stream leaving at an angle crossed the face
/// plane off the face and never met the particles still held.
#[test]
fn an_oblique_stream_moves_along_the_normal_until_the_face() {
    let sphere = (
        "fix pdd all particledistribution/discrete 10037 1 pts 1.0\n",
        "fix nve all nve/sphere\n",
        5.0,
    );
    let clump = (
        "fix pdd all particledistribution/discrete 10037 1 dumbbell 1.0\n",
        "fix ms all multisphere\n",
        10.0,
    );
    for (dist, integrator, spheres) in [sphere, clump] {
        let head = HEAD
            .replace(
                "fix pdd all particledistribution/discrete 10037 1 pts 1.0\n",
                dist,
            )
            .replace("fix nve all nve/sphere\n", integrator);
        let script = format!(
            "fix dumbbell all particletemplate/multisphere 10039 atom_type 1 density constant \
             2500 nspheres 2 ntry 100000 spheres 0 0 0 0.004 0.006 0 0 0.004 type 1
{head}fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 5 \
         particlerate 200 vel constant 0 -0.5 -2 overlapcheck yes all_in yes \
         insertion_face face extrude_length 0.05
compute vy all property/atom vy
compute vymax all reduce max c_vy
compute vymin all reduce min c_vy
thermo_style custom step atoms c_vymax c_vymin c_vmax c_vmin
thermo 10
run 1
run 299
"
        );
        let rows = run(&script);
        let at = |step: f64| rows.iter().rev().find(|r| r[0] == step).unwrap().clone();
        let r1 = at(1.0);
        assert_eq!(r1[1], spheres, "{r1:?}");
        assert_eq!(
            &r1[2..],
            [0.0, 0.0, -2.0, -2.0],
            "held: the normal part only {r1:?}"
        );
        // Halfway, some have crossed (vy = -0.5) and some are still held (vy = 0).
        let r = at(120.0);
        assert_eq!((r[2], r[3]), (0.0, -0.5), "{rows:?}");
        // All have crossed by step 230 (0.046 m at 2 m/s), nothing is added after.
        let r = at(300.0);
        assert_eq!(r[1], spheres, "{r:?}");
        assert!(
            (r[2] + 0.5).abs() < 1e-12 && (r[3] + 0.5).abs() < 1e-12,
            "released: the full velocity {r:?}"
        );
        assert!(r[4] < -2.05, "gravity acts below the face {r:?}");
    }
}

/// A particle rate through `insert_every` (the extrusion follows: 100 steps · 1e-4 s ·
/// 2 m/s = 0.02 m), and `mass` instead of a count: 30 particles' mass gives 30.
#[test]
fn insert_every_and_mass_limits() {
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.004f64.powi(3);
    let script = format!(
        "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd mass {} \
         particlerate 1000 insert_every 100 vel constant 0 0 -2 overlapcheck yes \
         insertion_face face
thermo 100
run 400
",
        30.0 * m
    );
    let rows = run(&script);
    let atoms: Vec<f64> = rows.iter().map(|r| r[1]).collect();
    // 10 per packet at steps 1, 101, 201.
    assert_eq!(atoms, [0.0, 10.0, 20.0, 30.0, 30.0], "{rows:?}");
    let last = rows.last().unwrap();
    assert!(last[4] >= -0.5, "{last:?}");
    // A mass of 30.8 particles stands for 30 (rounded down, as LIGGGHTS 3.8 does: the
    // tutorial conveyor's 382.99 particles' mass gave 382).
    let rows = run(&script.replace(&format!("mass {}", 30.0 * m), &format!("mass {}", 30.8 * m)));
    assert_eq!(rows.last().unwrap()[1], 30.0, "{rows:?}");
}

/// The packets follow the time step of the run, not the one in force when the fix was
/// defined, as in LIGGGHTS 3.8. Recorded with LIGGGHTS 3.8 on this script (with `newton
/// off`, `communicate single vel yes` and without `all_in`, which LIGGGHTS needs for a
/// `mesh/surface` face), timestep 2e-4 before the fix and 1e-4 after it:
/// `extrude_length 0.05` at 2 m/s gave "50.000000 particles every 250 steps", packets at
/// steps 1 and 251 (at the definition's 2e-4 it would be every 125 steps);
/// `particlerate 1000 insert_every 100` gave "10.000000 particles every 100 steps",
/// 10 at steps 1, 101, 201 (not 20).
#[test]
fn packets_follow_the_timestep_of_the_run() {
    let head = HEAD.replace("timestep 1e-4\n", "timestep 2e-4\n");
    let stl = square(0.1);
    let cases = [
        (
            "nparticles 120 particlerate 2000 vel constant 0 0 -2 overlapcheck yes \
             verbose yes insertion_face face extrude_length 0.05",
            "50.000000 particles every 250 steps",
            [(250.0, 50.0), (300.0, 100.0)],
        ),
        (
            "nparticles 120 particlerate 1000 insert_every 100 vel constant 0 0 -2 \
             overlapcheck yes verbose yes insertion_face face",
            "10.000000 particles every 100 steps",
            [(150.0, 20.0), (250.0, 30.0)],
        ),
    ];
    for (words, info, counts) in cases {
        let script = format!(
            "{head}fix ins all insert/stream seed 10039 distributiontemplate pdd {words}
timestep 1e-4
thermo 50
run 300
"
        );
        let out = run_with_files_raw(&script, &[("face.stl", &stl)], None);
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{text}");
        assert!(
            text.contains(&format!(
                "INFO: Particle insertion ins: {info} - particle rate"
            )),
            "{text}"
        );
        let rows = thermo_rows(&text);
        for (step, atoms) in counts {
            let r = rows.iter().find(|r| r[0] == step).unwrap();
            assert_eq!(r[1], atoms, "step {step}: {text}");
        }
    }
}

/// Bad combinations are refused with the line and the keyword to fix.
#[test]
fn stream_errors_are_located() {
    let cases = [
        (
            "insertion_face nowhere extrude_length 0.05",
            "no mesh 'nowhere'",
        ),
        (
            "insertion_face face",
            "needs 'extrude_length L' or 'insert_every N'",
        ),
        (
            "insertion_face face extrude_length 0.05 insert_every 10",
            "not both",
        ),
    ];
    for (tail, want) in cases {
        let script = format!(
            "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 10 \
             particlerate 1000 vel constant 0 0 -2 {tail}\nrun 1\n"
        );
        let out = run_with_files_raw(&script, &[("face.stl", &square(0.1))], None);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success());
        assert!(err.contains(want), "{tail}: {err}");
        assert!(err.contains("in.test:"), "{err}");
    }
    // A velocity along the face.
    let script = format!(
        "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 10 \
         particlerate 1000 vel constant 1 0 0 insertion_face face extrude_length 0.05\n"
    );
    let out = run_with_files_raw(&script, &[("face.stl", &square(0.1))], None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no component normal"), "{err}");
}

/// Four particles fall through the face, one beside it: massflow/mesh counts four and
/// their mass, and with `delete_atoms yes` removes them.
#[test]
fn massflow_counts_what_crosses_the_face() {
    let m = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.004f64.powi(3);
    for delete in ["no", "yes"] {
        let script = format!(
            "{HEAD}create_atoms 1 single 0 0 0.12 units box
create_atoms 1 single 0.02 0.03 0.13 units box
create_atoms 1 single -0.04 0.04 0.14 units box
create_atoms 1 single 0.03 -0.045 0.15 units box
create_atoms 1 single 0.08 0 0.12 units box
set group all diameter 0.008 density 2500
fix mf all massflow/mesh mesh face vec_side 0 0 -1 count once delete_atoms {delete}
variable m equal f_mf[1]
variable n equal f_mf[2]
thermo_style custom step atoms v_m v_n
thermo_modify format float %.15g
thermo 500
run 2000
"
        );
        let rows = run(&script);
        let last = rows.last().unwrap();
        assert_eq!(last[3], 4.0, "{rows:?}");
        assert!((last[2] - 4.0 * m).abs() < 1e-12 * m, "{rows:?}");
        assert_eq!(last[1], if delete == "yes" { 1.0 } else { 5.0 });
    }
}

/// write_restart writes the particles, box and step; read_restart in a new script
/// continues from them.
#[test]
fn restart_round_trip() {
    let dir = common::scratch_dir("restart");
    std::fs::write(dir.join("face.stl"), square(0.1)).unwrap();
    let first = format!(
        "{HEAD}create_atoms 1 single 0 0 0.12 units box
create_atoms 1 single 0.02 0.03 0.13 units box
set group all diameter 0.008 density 2500
run 300
write_restart post/state.restart
"
    );
    std::fs::write(dir.join("in.first"), first).unwrap();
    let out = common::rdem_command(None)
        .args(["-in", "in.first", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let second = "atom_style granular
boundary f f f
units si
read_restart post/state.restart
variable z equal bound(all,zmin)
thermo_style custom step atoms v_z
thermo_modify format float %.15g
run 0
";
    std::fs::write(dir.join("in.second"), second).unwrap();
    let out = common::rdem_command(None)
        .args(["-in", "in.second", "-log", "none"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = thermo_rows(&text);
    assert_eq!(rows[0][0], 300.0, "{text}");
    assert_eq!(rows[0][1], 2.0);
    // Free fall from 0.12 for 300 steps of 1e-4 s (velocity Verlet is exact for it).
    let t: f64 = 0.03;
    assert!(
        (rows[0][2] - (0.12 - 0.5 * 9.81 * t * t)).abs() < 1e-12,
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `duration`: a pulsed stream pours each packet (insert_every's worth of particles) in
/// that many steps, so the packet starts in a volume 50 steps · 1e-4 s · 2 m/s = 0.01 m
/// deep (plus a radius: the spheres start wholly behind the face), and is through the
/// face within 100 steps.
#[test]
fn pulsed_stream_pours_in_its_duration() {
    let script = format!(
        "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 40 \
         particlerate 1000 insert_every 200 duration 50 vel constant 0 0 -2 \
         overlapcheck yes insertion_face face
thermo 50
run 1
run 399
"
    );
    let rows = run(&script);
    let r1 = rows.iter().find(|r| r[0] == 1.0).unwrap();
    assert_eq!(r1[1], 20.0, "{rows:?}");
    // Whole spheres behind the face: centres from one radius (4 mm) to 0.01 m beyond.
    assert!(r1[4] >= 0.104 - 1e-12 && r1[5] <= 0.114 + 1e-12, "{r1:?}");
    // All below the face and accelerating after 50 steps.
    let r = rows.iter().find(|r| r[0] == 100.0).unwrap();
    assert!(r[5] < 0.1 && r[2] < -2.0, "{r:?}");
    assert_eq!(rows.last().unwrap()[1], 40.0);
}

/// A closed box of mesh walls (x, y in ±0.05, z from −0.2 to 0.16), filled through a
/// planar face that spans its whole cross-section at z = 0.1, with an oblique stream
/// (`vel 0.6 0 -1`, a 0.05 m extrusion, `all_in yes`) and soft spheres (E = 1e7, r =
/// 4 mm; the walls E = 1e8).
///
/// LIGGGHTS 3.8 (the same script, `-log none`) keeps all 150 particles, with the
/// largest x at 0.04600 to 0.04612 (the wall less a radius, plus the overlap) at every
/// thermo row to step 3000. rdem before commit e0e8abc moved the held particles at the
/// whole oblique velocity, so they drifted 0.6 · 0.05 = 0.03 m sideways through the
/// wall (held particles feel no force) and were released outside the box, whose wall
/// then fired them out: "1 particle(s) lost at step 155", one of the lost
/// particles from a mesh box (an old build lost one at step 306 in a 0.2 m box of four
/// STL meshes). The run must keep all of them inside the walls.
#[test]
fn an_oblique_stream_into_a_mesh_box_loses_none() {
    let quad = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| {
        [[a, b, c], [a, c, d]]
            .iter()
            .map(|t| {
                let v: String = t
                    .iter()
                    .map(|p| format!("vertex {} {} {}\n", p[0], p[1], p[2]))
                    .collect();
                format!("facet normal 0 0 0\nouter loop\n{v}endloop\nendfacet\n")
            })
            .collect::<String>()
    };
    let (h, lo, hi) = (0.05, -0.2, 0.16);
    let walls = [
        quad([-h, -h, lo], [h, -h, lo], [h, h, lo], [-h, h, lo]),
        quad([-h, -h, lo], [-h, h, lo], [-h, h, hi], [-h, -h, hi]),
        quad([h, -h, lo], [h, h, lo], [h, h, hi], [h, -h, hi]),
        quad([-h, -h, lo], [h, -h, lo], [h, -h, hi], [-h, -h, hi]),
        quad([-h, h, lo], [h, h, lo], [h, h, hi], [-h, h, hi]),
    ];
    let boxstl = format!("solid box\n{}endsolid box\n", walls.concat());
    // The face spans the box: the 0.1 m square at z = 0.1.
    let face = square(0.1);
    let script = "atom_style granular
units si
newton off
communicate single vel yes
boundary f f f
region box block -0.1 0.1 -0.1 0.1 -0.25 0.3 units box
create_box 2 box
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7 1e8
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.4 0.4 0.4 0.4
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-4
fix g all gravity 9.81 vector 0 0 -1
fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 10037 1 pts 1.0
fix box all mesh/surface file box.stl type 2
fix walls all wall/gran model hertz tangential history mesh n_meshes 1 meshes box
fix face all mesh/surface/planar file face.stl type 1
fix ins all insert/stream seed 10039 distributiontemplate pdd nparticles 150 particlerate 2000 vel constant 0.6 0 -1 overlapcheck yes all_in yes insertion_face face extrude_length 0.05
fix nve all nve/sphere
variable xlo equal bound(all,xmin)
variable xhi equal bound(all,xmax)
variable ylo equal bound(all,ymin)
variable yhi equal bound(all,ymax)
variable zlo equal bound(all,zmin)
thermo_style custom step atoms v_xlo v_xhi v_ylo v_yhi v_zlo
thermo_modify norm no format float %.15g
thermo 100
run 3000
";
    let out = run_with_files_raw(script, &[("box.stl", &boxstl), ("face.stl", &face)], None);
    let text = common::success("the mesh box", &out);
    assert!(!text.contains("WARNING"), "{text}");
    let rows = thermo_rows(&text);
    assert_eq!(rows.len(), 31, "{text}");
    assert_eq!(rows.last().unwrap()[1], 150.0, "{text}");
    // No particle at step 0: bound() of an empty group is ±1e20, as LIGGGHTS prints it.
    assert_eq!(&rows[0][1..4], &[0.0, 1e20, -1e20], "{text}");
    // Every particle inside the walls, less its radius, at every row (an overlap of
    // 0.5 mm at most: LIGGGHTS' largest x is 0.04612).
    for r in rows.iter().filter(|r| r[1] > 0.0) {
        for v in [-r[2], r[3], -r[4], r[5]] {
            assert!(
                v < 0.0465,
                "step {}: a particle at {v} against walls at 0.05: {text}",
                r[0]
            );
        }
        assert!(r[6] > -0.2, "{text}");
    }
}

/// The rate lines at the first set-up, as LIGGGHTS 3.8 prints them (with `verbose no`
/// too, which silences only the per-insertion lines): `insert/rate/region` with a mass
/// limit of 0.05 kg of 4 mm spheres at 0.2 kg/s every 300 steps (dt 1e-4) printed
/// "8.952466 particles every 300 steps - particle rate 298.415518  (mass rate
/// 2.000000e-01)" and "74 particles (mass 4.959528e-02) within 2400 steps" (74 / 8.95
/// gives 8 whole packets of 300 steps); the tutorial insert_stream (5000 particles in
/// packets of 300 every 30000 steps) "within 480000 steps", and nothing after the rate
/// line with `nparticles INF` or `mass INF`.
#[test]
fn rate_lines_give_the_limit_as_liggghts() {
    let script = "atom_style granular
boundary f f f
units si
region box block -0.1 0.1 -0.1 0.1 0 0.3 units box
create_box 1 box
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.4
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-4
fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.004
fix pdd all particledistribution/discrete 10037 1 pts 1.0
region ins block -0.05 0.05 -0.05 0.05 0.1 0.2 units box
fix ins all insert/rate/region seed 10039 distributiontemplate pdd mass 0.05 massrate 0.2 insert_every 300 overlapcheck yes verbose no region ins
fix nve all nve/sphere
run 1
";
    let out = common::run_script(script, None);
    assert!(
        out.contains(
            "INFO: Particle insertion ins: 8.952466 particles every 300 steps - particle rate 298.415518  (mass rate 2.000000e-01)\n      74 particles (mass 4.959528e-02) within 2400 steps\n"
        ),
        "{out}"
    );
    assert!(!out.contains("inserted"), "verbose no: {out}");
    let stl = square(0.1);
    for (limit, line) in [
        ("nparticles 5000", Some("      5000 particles (mass ")),
        ("nparticles INF", None),
        // The manual's `mass INF`: LIGGGHTS 3.8 prints the same rate line, no limit.
        ("mass INF", None),
    ] {
        let script = format!(
            "{HEAD}fix ins all insert/stream seed 10039 distributiontemplate pdd {limit} \
             particlerate 2000 insert_every 100 vel constant 0 0 -2 insertion_face face
run 1
"
        );
        let out = run_with_files_raw(&script, &[("face.stl", &stl)], None);
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        let info = text
            .lines()
            .position(|l| l.contains("20.000000 particles every 100 steps"))
            .unwrap_or_else(|| panic!("{text}"));
        let next = text.lines().nth(info + 1).unwrap();
        match line {
            // 5000 / 20 = 250 packets of 100 steps.
            Some(start) => {
                assert!(next.starts_with(start), "{text}");
                assert!(next.ends_with("within 25000 steps"), "{text}");
            }
            None => assert!(!next.contains("within"), "{text}"),
        }
    }
}
