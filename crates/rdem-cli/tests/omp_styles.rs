//! LIGGGHTS-PFM's OpenMP styles (its hybrid parallelization: `package omp`,
//! `atom_style granular/omp`, `pair_style gran/omp`, `fix gravity/omp`, `nve/sphere/omp`,
//! `mesh/surface/omp`, `mesh/surface/planar/omp`, `wall/gran/omp`, `partitioner_style
//! zoltan`) run as the styles without `/omp` on rdem's threads: a script written with
//! them writes, byte for byte, the dump of the same script without them, and says what
//! it does not use.

use crate::common;

/// Spheres falling on a mesh floor beside a primitive wall; `omp` is "" or "/omp".
fn script(omp: &str, package: &str) -> String {
    format!(
        "{package}atom_style granular{omp}
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.1 0.1 -0.1 0.1 -0.01 0.2 units box
create_box 2 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran{omp} model hertz tangential history
pair_coeff * *
timestep 0.00001
fix floor all mesh/surface{omp} file floor.stl type 2
fix face all mesh/surface/planar{omp} file floor.stl type 2 move 0 0 0.15
fix walls all wall/gran{omp} model hertz tangential history mesh n_meshes 1 meshes floor
fix side all wall/gran{omp} model hertz tangential history primitive type 2 xplane -0.03
fix gravi all gravity{omp} 9.81 vector 0.0 0.0 -1.0
lattice sc 0.012
region pack block -0.03 0.03 -0.03 0.03 0.01 0.05 units box
create_atoms 1 region pack
set type 1 diameter 0.01 density 2500
velocity all set -0.3 0.1 0 
fix integr all nve/sphere{omp}
dump d all custom 2000 d.txt id x y z vx vy vz omegax omegay omegaz
dump_modify d sort id format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 10000
"
    )
}

#[test]
fn the_omp_styles_run_as_the_plain_ones() {
    let floor = common::floor_stl();
    let run = |text: &str| {
        let (dir, out) = common::run_kept("omp", text, &[("floor.stl", &floor)], None);
        let text = common::success("omp styles", &out);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let dump = std::fs::read_to_string(dir.join("d.txt")).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        (text + &err, dump)
    };
    let (_, plain) = run(&script("", ""));
    let (out, omp) = run(&script(
        "/omp",
        "package omp 4 force/neigh thread-binding verbose\npartitioner_style zoltan RCB_REUSE 1\n",
    ));
    assert_eq!(omp, plain);
    // The particles fell and hit the floor and the wall: the last snapshot differs from
    // the first.
    let frames = common::dump_frames(&plain);
    assert_eq!(frames.len(), 6);
    let mean_z =
        |k: usize| frames[k].1.iter().map(|r| r[3]).sum::<f64>() / frames[k].1.len() as f64;
    let lowest = frames[5]
        .1
        .iter()
        .map(|r| r[3])
        .fold(f64::INFINITY, f64::min);
    assert!(
        mean_z(0) - mean_z(5) > 0.01 && lowest < 0.0051,
        "{} {} {lowest}",
        mean_z(0),
        mean_z(5)
    );
    assert!(
        out.contains("package omp 4: rdem runs on its 1 thread(s)"),
        "{out}"
    );
    assert!(out.contains("the Zoltan options are not used"), "{out}");
    // `*` is OpenMP's default count: no warning.
    let (out, _) = run(&script("/omp", "package omp *\n"));
    assert!(!out.contains("package omp"), "{out}");
}

#[test]
fn omp_commands_refuse_what_they_do_not_take() {
    let bad = [
        ("package gpu force 0 0 1.0\n", "package"),
        ("package omp 4 mixed\n", "force/neigh"),
        ("partitioner_style zoltan RCB_REUSE\n", "without its value"),
        ("partitioner_style rcb\n", "zoltan"),
    ];
    for (head, want) in bad {
        let out = common::run_script_raw(&format!("{head}{}", script("/omp", "")), None);
        assert!(!out.status.success(), "{head}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(want) && err.contains("in.test:1"),
            "{head}: {err}"
        );
    }
}
