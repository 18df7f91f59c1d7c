//! `fix mesh/surface/stress` and the mesh dumps: a sphere resting on an STL floor presses
//! on it with its weight (total force, torque, the triangle's pressure), the mesh/vtk and
//! mesh/stl files read back with VTK's own reader and ours, and the per-triangle sums do
//! not depend on the thread count.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{rdem_in, scratch_dir, success, thermo_rows};

const HEAD: &str = "atom_style granular
boundary f f f
units si
region box block -0.1 0.1 -0.1 0.1 -0.01 0.2 units box
create_box 1 box
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global k_finnie peratomtypepair 1 1.0
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix g all gravity 9.81 vector 0 0 -1
fix cad all mesh/surface/stress file floor.stl type 1 wear finnie
fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad
fix nve all nve/sphere
";

/// Runs `script` in `dir` (with floor.stl) on `threads` threads; returns the screen output.
fn run_in(dir: &Path, script: &str, threads: usize) -> String {
    std::fs::write(dir.join("floor.stl"), common::floor_stl()).unwrap();
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = rdem_in(dir, "in.test", None)
        .env("RDEM_THREADS", threads.to_string())
        .output()
        .unwrap();
    success(&format!("{threads} threads"), &out)
}

/// Cell arrays of legacy VTK files as VTK's vtkPolyDataReader sees them.
const READER: &str = r#"
import sys, vtk
for f in sys.argv[1:]:
    r = vtk.vtkPolyDataReader()
    r.ReadAllFieldsOn(); r.ReadAllScalarsOn()
    r.SetFileName(f); r.Update()
    o = r.GetOutput()
    print('cells', o.GetNumberOfCells(), o.GetNumberOfPoints())
    cd = o.GetCellData()
    for k in range(cd.GetNumberOfArrays()):
        a = cd.GetArray(k)
        print('array', a.GetName(), *[repr(a.GetComponent(i, 0)) for i in range(a.GetNumberOfTuples())])
"#;

fn vtk_cells(file: &Path) -> (usize, usize, Vec<(String, Vec<f64>)>) {
    let out = Command::new("python3")
        .arg("-c")
        .arg(READER)
        .arg(file)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut counts = (0, 0);
    let mut arrays = Vec::new();
    for l in text.lines() {
        let mut w = l.split_whitespace();
        match w.next() {
            Some("cells") => {
                counts = (
                    w.next().unwrap().parse().unwrap(),
                    w.next().unwrap().parse().unwrap(),
                )
            }
            Some("array") => {
                let name = w.next().unwrap().to_string();
                arrays.push((name, w.map(|s| s.parse().unwrap()).collect()));
            }
            _ => panic!("{l}"),
        }
    }
    (counts.0, counts.1, arrays)
}

/// A 4 mm glass sphere settled on the triangle x > |y| at (0.03, 0.01): the mesh carries
/// its weight m g (f_cad[3] = −m g within 1e-6), the torque about the origin is
/// q × F = (−0.01 m g, 0.03 m g, 0), that triangle's normal stress is m g / 0.01 m² and
/// the others' zero (read by VTK from dump mesh/vtk), and dump mesh/stl gives back the
/// floor's triangles (and its old name `dump stl` the same file).
#[test]
fn resting_sphere_presses_with_its_weight() {
    let dir = scratch_dir("mesh-stress");
    let script = format!(
        "{HEAD}create_atoms 1 single 0.03 0.01 0.00199 units box
set atom 1 diameter 0.004 density 2500
variable fx equal f_cad[1]
variable fy equal f_cad[2]
variable fz equal f_cad[3]
variable tx equal f_cad[4]
variable ty equal f_cad[5]
thermo_style custom step v_fx v_fy v_fz v_tx v_ty
thermo_modify format float %.15g
thermo 10000
run 30000
dump d all mesh/vtk 1 post/floor_*.vtk stress wear area cad
dump s all mesh/stl 1 post/floor_*.stl
dump o all stl 1 post/old_*.stl
run 0
"
    );
    let text = run_in(&dir, &script, 1);
    let r = thermo_rows(&text).pop().unwrap();
    let mg = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.002f64.powi(3) * 9.81;
    assert!(r[1].abs() < 1e-9 * mg && r[2].abs() < 1e-9 * mg, "{r:?}");
    assert!((r[3] + mg).abs() < 1e-6 * mg, "fz {} vs -{mg}", r[3]);
    assert!((r[4] + 0.01 * mg).abs() < 1e-6 * mg, "{r:?}");
    assert!((r[5] - 0.03 * mg).abs() < 1e-6 * mg, "{r:?}");
    let (ncells, npoints, arrays) = vtk_cells(&dir.join("post/floor_30000.vtk"));
    assert_eq!((ncells, npoints), (4, 12));
    let names: Vec<&str> = arrays.iter().map(|a| a.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "normal_stress_average",
            "shear_stress_average",
            "wear",
            "area"
        ]
    );
    let normal = &arrays[0].1;
    // Triangle 1 has the corners (0.1, −0.1), (0.1, 0.1), (0, 0): x > |y|.
    assert!(
        (normal[1] - mg / 0.01).abs() < 1e-6 * mg / 0.01,
        "{normal:?}"
    );
    for t in [0, 2, 3] {
        assert_eq!(normal[t], 0.0);
    }
    assert!(arrays[1].1.iter().all(|&s| s.abs() < 1e-9 * mg / 0.01));
    assert!(arrays[3].1.iter().all(|&a| (a - 0.01).abs() < 1e-12));
    // Wear only where the sphere landed, and it did land (approaching impact).
    assert!(
        arrays[2].1[1] > 0.0
            && arrays[2]
                .1
                .iter()
                .enumerate()
                .all(|(t, &w)| t == 1 || w == 0.0)
    );
    assert!(dir.join("post/floor.pvd").exists());
    let stl = rdem_io_read(&dir.join("post/floor_30000.stl"));
    assert_eq!(stl, 4);
    // `dump stl`, the old name that LIGGGHTS 3.8 still takes, writes the same bytes.
    assert_eq!(
        std::fs::read(dir.join("post/old_30000.stl")).unwrap(),
        std::fs::read(dir.join("post/floor_30000.stl")).unwrap()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The reference point (`f_ID[7..9]`, the torque's pivot) moves with the mesh, as in
/// LIGGGHTS 3.8: from (1, 2, 3) mm, 30 steps of `linear 0.1 0 -0.4` then 20 steps of a
/// rotation about the z axis of period 1 s. LIGGGHTS 3.8 printed (1.3, 2, 1.8) mm, then
/// (1.2747653, 2.0161779, 1.8) mm; here the closed forms within 1e-12.
#[test]
fn the_reference_point_moves_with_the_mesh() {
    let dir = scratch_dir("mesh-refpoint");
    let script = HEAD.replace(
        "wear finnie\n",
        "wear finnie reference_point 0.001 0.002 0.003\n",
    ) + "timestep 1e-4
create_atoms 1 single 0.05 0.05 0.1 units box
set atom 1 diameter 0.004 density 2500
fix lin all move/mesh mesh cad linear 0.1 0.0 -0.4
variable a equal f_cad[7]
variable b equal f_cad[8]
variable c equal f_cad[9]
thermo_style custom step v_a v_b v_c
thermo_modify format float %.15g
thermo 10
run 30
unfix lin
fix rot all move/mesh mesh cad rotate origin 0 0 0 axis 0 0 1 period 1.0
run 20
";
    let rows = thermo_rows(&run_in(&dir, &script, 1));
    let at = |step: f64| rows.iter().rev().find(|r| r[0] == step).unwrap().clone();
    let close = |got: &[f64], want: [f64; 3]| {
        for k in 0..3 {
            assert!((got[k + 1] - want[k]).abs() < 1e-12, "{got:?} {want:?}");
        }
    };
    close(&at(30.0), [0.0013, 0.002, 0.0018]);
    let phi = std::f64::consts::TAU * 20.0 * 1e-4;
    let (s, c) = phi.sin_cos();
    close(
        &at(50.0),
        [0.0013 * c - 0.002 * s, 0.0013 * s + 0.002 * c, 0.0018],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Triangles of an STL file (our reader, as fix mesh/surface reads it).
fn rdem_io_read(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.starts_with("solid LIGGGHTS_STL_EXPORT\n"));
    text.matches("facet normal").count()
}

/// A pile of 1500 spheres dropped on the floor (0.15 s): the mesh/vtk file of stress and wear is the same
/// byte for byte on 1 and 2 threads.
#[test]
fn stress_sums_do_not_depend_on_threads() {
    let script = format!(
        "{HEAD}fix pts all particletemplate/sphere 10007 atom_type 1 density constant 2500 radius constant 0.003
fix pdd all particledistribution/discrete 10037 1 pts 1.0
region fill block -0.09 0.09 -0.09 0.09 0.01 0.1 units box
fix ins all insert/pack seed 10039 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 1500 region fill
thermo_modify lost ignore
run 15000
dump d all mesh/vtk 1 post/floor_*.vtk stress wear cad
run 0
"
    );
    let mut files = Vec::new();
    for threads in [1, 2] {
        let dir = scratch_dir("mesh-stress-threads");
        run_in(&dir, &script, threads);
        files.push(std::fs::read(dir.join("post/floor_15000.vtk")).unwrap());
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(files[0] == files[1], "1 and 2 threads differ");
    let text = String::from_utf8(files.remove(0)).unwrap();
    let at = text.find("normal_stress_average 1 4 double\n").unwrap();
    let values: Vec<f64> = text[at..]
        .lines()
        .nth(1)
        .unwrap()
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert!(
        values.iter().all(|&v| v > 0.0),
        "the pile presses on every triangle: {values:?}"
    );
}
