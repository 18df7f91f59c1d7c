//! Moving mesh walls: a sphere on a conveyor belt (`surface_vel`), on a floor that moves
//! (`fix move/mesh linear`) and in a turning drum (`surface_ang_vel`, `move/mesh
//! rotate`) ends up sticking: its contact point moves with the wall, and on a flat belt
//! its centre at 2/7 of the belt speed (a free sphere rolling on the belt: the friction
//! impulse J gives v = J/m and ω r = 5J/(2m), and sticking means v + ω r = belt speed).

use crate::common;

use common::{run_with_files_raw, thermo_rows};

/// A drum: a 48-sided cylinder of radius `r` about the y axis, 0.02 long.
fn drum(r: f64) -> String {
    let n = 48;
    let p = |k: usize, y: f64| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        format!("vertex {} {y} {}\n", r * a.cos(), r * a.sin())
    };
    let mut s = String::from("solid drum\n");
    for k in 0..n {
        let j = (k + 1) % n;
        for (a, b, c) in [
            (p(k, -0.01), p(j, -0.01), p(j, 0.01)),
            (p(k, -0.01), p(j, 0.01), p(k, 0.01)),
        ] {
            s += &format!("facet normal 0 0 0\nouter loop\n{a}{b}{c}endloop\nendfacet\n");
        }
    }
    s + "endsolid drum\n"
}

const HEAD: &str = "atom_style granular
boundary f f f
units si
region box block -0.12 0.12 -0.12 0.12 -0.12 0.12 units box
create_box 1 box
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.6
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
fix g all gravity 9.81 vector 0 0 -1
fix nve all nve/sphere
variable x equal x[1]
variable z equal z[1]
variable vx equal vx[1]
variable vz equal vz[1]
variable wy equal omegay[1]
thermo_style custom step v_x v_z v_vx v_vz v_wy
thermo_modify format float %.15g
thermo 1000
";

fn last_row(script: &str, files: &[(&str, &str)]) -> Vec<f64> {
    let out = run_with_files_raw(script, files, None);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    thermo_rows(&text).pop().expect("thermo rows")
}

/// A sphere of radius 2 mm dropped on a belt (`surface_vel`) or on a floor moving at the
/// same speed (`move/mesh linear`): after 0.1 s its contact point moves at the belt's
/// 0.3 m/s and its centre at 2/7 of it (both within 1e-3).
#[test]
fn belt_and_moving_floor_carry_a_sphere() {
    for (label, mesh) in [
        (
            "surface_vel",
            "fix belt all mesh/surface file floor.stl type 1 surface_vel 0.3 0 0\n",
        ),
        (
            "move/mesh linear",
            "fix belt all mesh/surface file floor.stl type 1\n\
             fix mv all move/mesh mesh belt linear 0.3 0 0\n",
        ),
    ] {
        let script = format!(
            "{HEAD}create_atoms 1 single 0 0 0.0021 units box
set atom 1 diameter 0.004 density 2500
{mesh}fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes belt
run 10000
"
        );
        let r = last_row(&script, &[("floor.stl", &common::floor_stl())]);
        let (vx, wy) = (r[3], r[5]);
        let contact = vx - 0.002 * wy;
        assert!(
            (contact - 0.3).abs() < 3e-4,
            "{label}: contact point at {contact} m/s: {r:?}"
        );
        assert!(
            (vx - 0.3 * 2.0 / 7.0).abs() < 3e-4,
            "{label}: centre at {vx} m/s, want {}: {r:?}",
            0.3 * 2.0 / 7.0
        );
    }
}

/// A sphere in a drum of radius 5 cm turning at 2 rad/s about y (the surface turning with
/// `surface_ang_vel`, or the mesh itself with `move/mesh rotate`): after 0.3 s its
/// contact point moves along the wall with the drum, ω × (q − o), within 1 % of
/// ωR = 0.1 m/s (the
/// sphere rolls to and fro about the bottom without slipping: a lone sphere has nothing
/// to hold it up the wall).
#[test]
fn turning_drum_carries_a_sphere() {
    let w = 2.0;
    let big_r = 0.05;
    for (label, mesh) in [
        (
            "surface_ang_vel",
            format!(
                "fix drum all mesh/surface file drum.stl type 1 surface_ang_vel origin 0 0 0 axis 0 1 0 omega {w}\n"
            ),
        ),
        (
            "move/mesh rotate",
            format!(
                "fix drum all mesh/surface file drum.stl type 1\n\
                 fix turn all move/mesh mesh drum rotate origin 0 0 0 axis 0 1 0 period {}\n",
                std::f64::consts::TAU / w
            ),
        ),
    ] {
        let script = format!(
            "{HEAD}create_atoms 1 single 0 0 -0.047 units box
set atom 1 diameter 0.005 density 2500
{mesh}fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes drum
run 30000
"
        );
        let r = last_row(&script, &[("drum.stl", &drum(big_r))]);
        let (x, z, vx, vz, wy) = (r[1], r[2], r[3], r[4], r[5]);
        // Contact point on the wall, radially outwards from the axis (the facets make
        // it off by up to 3.75° in angle, which moves the point along the normal: only
        // the tangential components are compared).
        let c = (x * x + z * z).sqrt();
        let (nx, nz) = (x / c, z / c);
        let rp = 0.0025;
        let (qx, qz) = (x + rp * nx, z + rp * nz);
        // Particle surface velocity at q: v + ω_p × (q − x), ω_p = wy ŷ: ŷ × (dx, 0, dz) = (dz, 0, −dx).
        let (ux, uz) = (vx + wy * (qz - z), vz - wy * (qx - x));
        // Wall velocity ω ŷ × (q − o).
        let (wx, wz) = (w * qz, -w * qx);
        // Tangent (−n_z, n_x) in the x-z plane.
        let err = ((ux - wx) * -nz + (uz - wz) * nx).abs();
        assert!(
            err < 0.01 * w * big_r,
            "{label}: contact velocity ({ux}, {uz}) vs wall ({wx}, {wz}): {r:?}"
        );
    }
}

/// A sphere pressed 0.5 mm into a plate that a new `fix move/mesh` drives down at
/// 0.1 m/s (E = 23.3 kPa, e = 0.5): LIGGGHTS 3.8 gives the first run's set-up the force
/// without the plate's velocity (no step has moved the plate yet), and every later step
/// and set-up the damped one, also after `unfix` and a new motion. Figures: LIGGGHTS 3.8
/// runs of this script (fz of the sphere, dumped at steps 0–4). Before, rdem's set-up
/// force was −0.0762913 N.
#[test]
fn a_new_mesh_motion_has_no_velocity_at_its_first_set_up() {
    let piston = std::fs::read_to_string(
        "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/hydrogel_multicontact/meshes/piston_hydrogel.stl",
    )
    .expect("liggghts-doc's hydrogel tutorial (scripts/test.sh installs it)");
    let script = "atom_style sphere
atom_modify map array
boundary f f f
newton off
soft_particles yes
communicate single vel yes
units si
region box block -0.05 0.25 -0.05 0.25 -0.05 0.3 units box
create_box 2 box
neighbor 0.004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 23.3e3 5e7
fix m2 all property/global poissonsRatio peratomtype 0.5 0.5
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.3 0.3 0.3 0.3
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix piston_m all mesh/surface/stress file piston.stl type 2 move 0. 0. 0.1
fix piston all wall/gran model hertz tangential history mesh n_meshes 1 meshes piston_m
create_atoms 1 single 0.08 0.08 0.0905 units box
set atom * diameter 0.02 density 1000
dump d all custom 1 d.txt id fx fy fz
dump_modify d format \"%d %.16g %.16g %.16g\"
fix mv all move/mesh mesh piston_m linear 0. 0. -0.1
run 1
run 1
unfix mv
fix mv2 all move/mesh mesh piston_m linear 0.05 0. 0.1
run 1
unfix mv2
run 1
";
    let (dir, out) = common::run_kept(
        "mesh-setup-velocity",
        script,
        &[("piston.stl", &piston)],
        None,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dump = std::fs::read_to_string(dir.join("d.txt")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    // The sphere's row after each TIMESTEP block.
    let fz: Vec<f64> = dump
        .lines()
        .filter(|l| l.starts_with("1 "))
        .map(|l| l.split_whitespace().nth(3).unwrap().parse().unwrap())
        .collect();
    let liggghts = [
        -0.0462898812493323,
        -0.07644520273276043,
        -0.07659924755574622,
        -0.016412437876789,
        -0.04642882030477471,
    ];
    assert_eq!(fz.len(), liggghts.len(), "{dump}");
    for (k, (a, b)) in fz.iter().zip(liggghts).enumerate() {
        assert!(
            (a / b - 1.0).abs() < 1e-12,
            "step {k}: fz {a} vs LIGGGHTS {b}"
        );
    }
}
