//! `fix buoyancy` (LIGGGHTS 3.8): the weight of the displaced fluid, with the submerged
//! cap of a partly submerged sphere, against LIGGGHTS 3.8 and against a floating sphere's
//! equilibrium.

use crate::common;

/// One sphere (diameter 0.02, density `rho`) at height `z`, gravity 9.81 along `gs`·z,
/// fluid of density 1000 below (or above) the level 0.06; `tail` follows.
fn script(z: f64, gs: f64, rho: f64, tail: &str) -> String {
    format!(
        "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.5 0.5 -0.5 0.5 -0.5 0.5 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
create_atoms 1 single 0 0 {z}
set type 1 diameter 0.02 density {rho}
fix g all gravity 9.81 vector 0 0 {gs}
fix bu all buoyancy level 0.06 dim z density 1000
fix integr all nve/sphere
variable fz equal fz[1]
variable z equal z[1]
{tail}"
    )
}

#[test]
fn the_displaced_weight_is_liggghts_weight() {
    // LIGGGHTS 3.8's f_bu[3] and the sphere's total force fz (buoyancy and its weight) at
    // `run 0`, density 500: wholly, partly and not submerged, gravity down and up.
    let liggghts = [
        (-1.0, 0.03, 0.0410920319089545, 0.0205460159544772),
        (-1.0, 0.055, 0.0346714019231803, 0.0141253859687031),
        (-1.0, 0.06, 0.0205460159544772, 0.0),
        (-1.0, 0.065, 0.00642062998577413, -0.0141253859687031),
        (-1.0, 0.08, 0.0, -0.0205460159544772),
        (1.0, 0.03, 0.0, 0.0205460159544772),
        (1.0, 0.055, -0.00642062998577415, 0.0141253859687031),
        (1.0, 0.06, -0.0205460159544772, 0.0),
        (1.0, 0.065, -0.0346714019231804, -0.0141253859687031),
        (1.0, 0.08, -0.0410920319089545, -0.0205460159544772),
    ];
    for (gs, z, fb, fz) in liggghts {
        let out = common::run_script(
            &script(
                z,
                gs,
                500.0,
                "thermo_style custom step f_bu[1] f_bu[2] f_bu[3] v_fz\nthermo_modify format float %20.15g\nrun 0\n",
            ),
            None,
        );
        let row = common::thermo_rows(&out).pop().unwrap();
        assert_eq!((row[1], row[2]), (0.0, 0.0));
        // LIGGGHTS printed 15 digits: within 2e-16 of 0.04 N.
        assert!(
            (row[3] - fb).abs() < 2e-16,
            "g {gs} z {z}: {} against {fb}",
            row[3]
        );
        assert!(
            (row[4] - fz).abs() < 2e-16,
            "g {gs} z {z}: {} against {fz}",
            row[4]
        );
    }
}

#[test]
fn a_light_sphere_floats_with_its_density_ratio_submerged() {
    // Density 300 in water: at rest the submerged cap holds 0.3 of the volume,
    // h²(3r − h) = 1.2 r³; a viscous drag settles it from 1 cm above the surface.
    let out = common::run_script(
        &script(
            0.07,
            -1.0,
            300.0,
            "fix damp all viscous 0.02\nthermo_style custom step v_z v_fz\nthermo_modify format float %20.15g\nthermo 100000\nrun 300000\n",
        ),
        None,
    );
    let last = common::thermo_rows(&out).pop().unwrap();
    let r = 0.01;
    let (mut lo, mut hi) = (0.0, 2.0);
    for _ in 0..100 {
        let x = 0.5 * (lo + hi);
        if x * x * (3.0 - x) < 1.2 {
            lo = x;
        } else {
            hi = x;
        }
    }
    let h = 0.5 * (lo + hi) * r;
    let z = 0.06 - h + r;
    assert!((last[1] - z).abs() < 1e-7, "z = {}, afloat at {z}", last[1]);
    assert!(last[2].abs() < 1e-8, "force {}", last[2]);
}

#[test]
fn buoyancy_refuses_what_liggghts_refuses() {
    let bad = [
        (
            "fix bx all buoyancy level 0.06 density 1000\n",
            "needs the keyword 'dim'",
        ),
        ("fix bx all buoyancy dim w\n", "'w'"),
        ("unfix g\nrun 1\n", "needs a fix gravity"),
        (
            "unfix g\nfix g2 all gravity 9.81 vector 1 0 -1\nrun 1\n",
            "fix buoyancy: gravity (",
        ),
    ];
    for (tail, want) in bad {
        let out = common::run_script_raw(&script(0.03, -1.0, 500.0, tail), None);
        assert!(!out.status.success(), "{tail}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(want) && err.contains("in.test:"),
            "{tail}: {err}"
        );
    }
}
