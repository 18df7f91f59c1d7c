//! `fix slowinit` (LIGGGHTS_CFDRC): the relaxation of an overlapped packing before a
//! sheared run. Checked against the fork's own log and against the rules of its code:
//!
//! - a dilute bed of rigid dumbbells (no overlaps, at rest) prints at step 1000 the line
//!   the fork printed for its `scripts/rod2/in.shear.rod2_0` with the same timesteps
//!   (`start_dt 2.347e-09 end_dt 1.174e-08`): `ke/mass=0.000e+00 … overlap=1.000e+00,
//!   cor=9.736e-01, dt=3.467e-09 nbody: …`, and ends its run there, as the fork's did
//!   (999 neighbor builds in its log; the next run starts at step 1000);
//! - two spheres overlapping by 40 % of their radii are pushed apart by the capped
//!   integrator: each moves exactly xmax in the first step, both are capped in both half
//!   kicks (`f_ID` 4), and the run ends once they have come apart, with the timestep at
//!   end_dt.

use crate::common;

/// Box and material settings of both scripts (frictionless Hertz, E 8.7e9, ν 0.3).
const HEAD: &str = "atom_style granular
atom_modify map array
boundary p p p
newton off
communicate single vel yes
units si
region domain block 0 0.004 0 0.004 0 0.002 units box
create_box 1 domain
neighbor 0.0001 bin
neigh_modify every 1 delay 0 check no
hard_particles yes
fix m1 all property/global youngsModulus peratomtype 8.7e9
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.95
fix m4 all property/global coefficientFriction peratomtypepair 1 0.0
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-9
";

#[test]
fn a_relaxed_bed_prints_the_forks_line_and_ends_the_run() {
    let script = HEAD.to_string()
        + "fix pts all particletemplate/multisphere 123457 atom_type 1 density constant 2500 nspheres 2 ntry 1000000 spheres 0 0 0 0.0001 0.00015 0 0 0.0001 type 1
fix pdd all particledistribution/discrete 15485867 1 pts 1.0
fix ins all insert/pack seed 32452867 distributiontemplate pdd maxattempt 48 vel constant 0 0 0 omega constant 0 0 0 insert_every once overlapcheck yes all_in yes region domain volumefraction_region 0.025
fix ms all multisphere
run 1
unfix ins
fix limcheck all slowinit xmax 1.00e-06 reset 1000 threshold 1.00e-06 start_dt 2.347e-09 end_dt 1.174e-08
thermo_style custom step atoms dt
thermo_modify format float %20.15g
thermo 500
run 100000
unfix limcheck
run 0
";
    let out = common::run_script(&script, None);
    let lines: Vec<&str> = out.lines().filter(|l| l.starts_with("pre-run")).collect();
    assert_eq!(lines.len(), 1, "{out}");
    let natoms = common::thermo_rows(&out).last().unwrap()[1];
    let nbody = natoms / 2.0;
    assert!(nbody > 10.0, "{out}");
    assert_eq!(
        lines[0],
        format!(
            "pre-run, step: 1000, ke/mass=0.000e+00, natoms={natoms}, overlap=1.000e+00, cor=9.736e-01, dt=3.467e-09 nbody: {nbody} "
        )
    );
    // The run ended at step 1000 with the timestep at end_dt; `run 0` starts there.
    let rows = common::thermo_rows(&out);
    let last = rows.last().unwrap();
    assert_eq!(last[0], 1000.0, "{out}");
    assert_eq!(last[2], 1.174e-8);
    assert!(out.contains("for 999 steps"), "{out}");
}

#[test]
fn overlapped_spheres_are_pushed_apart_at_the_capped_speed() {
    // Centres 0.12 mm apart, radii 0.1 mm: d / (r_i + r_j) = 0.6.
    let script = HEAD.to_string()
        + "create_atoms 1 single 0.00194 0.002 0.001 units box
create_atoms 1 single 0.00206 0.002 0.001 units box
set atom * diameter 0.0002 density 2500
fix limcheck all slowinit xmax 1e-7 reset 100 threshold 1e-3 start_dt 1e-8 end_dt 1e-7
dump d all custom 1 d.txt id x y z
dump_modify d format \"%d %.17g %.17g %.17g\"
thermo_style custom step f_limcheck dt
thermo_modify format float %20.15g
thermo 1
run 100000
unfix limcheck
thermo_style custom step dt dt
thermo_modify format float %20.15g
run 0
";
    let (dir, out) = common::run_kept("slowinit", &script, &[], None);
    let text = common::success("slowinit pair", &out);
    let frames = common::dump_frames(&std::fs::read_to_string(dir.join("d.txt")).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
    // Step 1: each sphere moved xmax apart along x (the cap at xmax/dt, dt = start_dt).
    let (x0, x1) = (&frames[0].1, &frames[1].1);
    assert!((x0[0][1] - x1[0][1] - 1e-7).abs() < 1e-15, "{x0:?} {x1:?}");
    assert!((x1[1][1] - x0[1][1] - 1e-7).abs() < 1e-15, "{x0:?} {x1:?}");
    let rows = common::thermo_rows(&text);
    // Both spheres capped in both half kicks of step 1 (the first kick alone would move
    // them 0.5 dt² F/m = 0.154 µm).
    assert_eq!(rows[1][1], 4.0, "resets in step 1: {rows:?}");
    // They came apart; the run ended at the first check (step 1000, the first multiple
    // of `reset` with a check), with the timestep at end_dt for what follows.
    assert!(text.contains("for 1000 steps with 2 atoms"), "{text}");
    let last = rows.last().unwrap();
    assert_eq!((last[0], last[2]), (1000.0, 1e-7), "{text}");
    let (a, b) = (&frames.last().unwrap().1[0], &frames.last().unwrap().1[1]);
    assert!(b[1] - a[1] >= 0.0002, "still overlapped: {a:?} {b:?}");
}
