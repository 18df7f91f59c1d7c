//! `compute pair/gran/local/bond` (LIGGGHTS-INL) with `dump local` and `dump
//! local/gran/vtk`: a chain of 4 spheres in a row (r = 1 mm, touching, so d₀ = 2 mm; 3
//! bonds with r_b = r, A = π r², k_n = 1e10 Pa/m), the first frozen and the last pulled
//! along the chain by F = 0.1 N and damped by `fix viscous` until it rests. Each bond
//! then carries F: the dumped force on i is k_n A (d − d₀) towards j (the bond model's
//! normal force, d read from the dumped centres) and equals F; it is all normal (no
//! tangential part, no torque); the history ends with the bond flag 1 and d₀.

use crate::common;

use std::f64::consts::PI;

const R: f64 = 0.001;
const KN: f64 = 1e10;
const AREA: f64 = PI * R * R;
const F: f64 = 0.1;

/// The chain script; `extra` goes before the runs (computes and dumps).
fn script(extra: &str) -> String {
    let mut s = String::from(
        "\
atom_style granular
atom_modify map array
boundary f f f
newton off
units si
region box block -0.01 0.02 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0002 bin
neigh_modify delay 0
",
    );
    for k in 0..4 {
        s += &format!(
            "create_atoms 1 single {} 0 0 units box\n",
            2.0 * R * k as f64
        );
    }
    s += &format!(
        "\
set atom * diameter {} density 2500
fix m1 all property/global youngsModulus peratomtype 5.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix b1 all property/global radiusMultiplierBond peratomtypepair 1 1.0
fix b2 all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 {KN}
fix b3 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 5e9
fix b4 all property/global maxDistanceBond peratomtypepair 1 0.0025
fix b5 all property/global createDistanceBond peratomtypepair 1 0.00201
fix b6 all property/global tsCreateBond scalar 1
fix d1 all property/global dampingNormalForceBond peratomtypepair 1 0.0
fix d2 all property/global dampingTangentialForceBond peratomtypepair 1 0.0
fix d3 all property/global dampingNormalTorqueBond peratomtypepair 1 0.0
fix d4 all property/global dampingTangentialTorqueBond peratomtypepair 1 0.0
pair_style gran model hertz tangential history cohesion bond
pair_coeff * *
timestep 1e-6
fix integr all nve/sphere
group end id 1
group tip id 4
group free id 2:4
fix hold end freeze
fix visc free viscous 0.5
",
        2.0 * R
    );
    s += extra;
    s += &format!("run 10\nfix pull tip addforce {F} 0 0\nrun 6000\n");
    s
}

/// The rows of numbers of the last snapshot of a `dump local` file.
fn last_rows(text: &str) -> Vec<Vec<f64>> {
    common::dump_frames(text).pop().expect("a snapshot").1
}

#[test]
fn a_pulled_chain_dumps_each_bond_force_as_kn_area_elongation() {
    let dir = common::scratch_dir("bonds_local");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let cols: String = (1..=41).map(|k| format!(" c_b[{k}]")).collect();
    let extra = format!(
        "compute b all pair/gran/local/bond\n\
         dump d1 all local 6010 post/bonds*.txt{cols}\n\
         dump d2 all local/gran/vtk 6010 post/bonds*.vtk b\n"
    );
    std::fs::write(dir.join("in.chain"), script(&extra)).unwrap();
    let out = common::rdem_command(None)
        .current_dir(&dir)
        .args(["-in", "in.chain", "-log", "none"])
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("post/bonds6010.txt")).unwrap();
    let mut rows = last_rows(&text);
    assert_eq!(rows.len(), 3, "three bonds:\n{text}");
    // 27 fixed columns, then the history: 9 bond vectors, 3 shear-spring values, flag, d0.
    assert!(rows.iter().all(|r| r.len() == 41));
    rows.sort_by(|a, b| a[6].total_cmp(&b[6]));
    for (k, r) in rows.iter().enumerate() {
        let (ti, tj) = (r[6], r[7]);
        assert_eq!(
            (ti.min(tj), ti.max(tj), r[8]),
            ((k + 1) as f64, (k + 2) as f64, 0.0),
            "bond {k}: ids"
        );
        let (xi, xj) = (r[0], r[3]);
        let d = (xj - xi).abs();
        // The force on i points to j: +x when j is to the right.
        let dir = (xj - xi).signum();
        let fx = r[9];
        let want = KN * AREA * (d - 2.0 * R) * dir;
        eprintln!(
            "bond {}-{}: F_x on i {fx:e}, k_n A (d - d0) {want:e}",
            ti, tj
        );
        // d is read from 6-digit positions (each ±5e-9 m, so d ±1e-8 m of the 3.2e-6 m
        // elongation: 3.1e-3).
        assert!((fx - want).abs() < 5e-3 * want.abs(), "{fx} vs {want}");
        assert!((fx.abs() - F).abs() < 0.01 * F, "carries F: {fx}");
        // force_normal = force, force_tangential and the torques zero.
        for c in 0..3 {
            assert_eq!(r[12 + c], r[9 + c], "force_normal = force");
            assert!(r[15 + c].abs() < 1e-9, "force_tangential {}", r[15 + c]);
            assert!(r[18 + c].abs() < 1e-12, "torque {}", r[18 + c]);
        }
        assert_eq!((r[39], r[40]), (1.0, 2.0 * R), "flag and d0");
    }
    let vtk = std::fs::read_to_string(dir.join("post/bonds6010.vtk")).unwrap();
    assert!(vtk.contains("POINTS 6 float"), "{vtk}");
    for name in [
        "force 3 3 double",
        "torque_normal 3 3 double",
        "torque_tangential 3 3 double",
    ] {
        assert!(vtk.contains(name), "{name} in\n{vtk}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bond_local_takes_no_keywords_and_needs_bonds() {
    let s = script("compute b all pair/gran/local/bond force\n");
    let out = common::run_script_raw(&s, None);
    let text =
        String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    assert!(
        text.contains("pair/gran/local/bond takes no keywords"),
        "{text}"
    );
    let s = script("compute b all pair/gran/local/bond\n").replace(" cohesion bond", "");
    let out = common::run_script_raw(&s, None);
    let text =
        String::from_utf8_lossy(&out.stderr).to_string() + &String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    assert!(
        text.contains("needs a pair style with a cohesion bond model"),
        "{text}"
    );
}

/// A cantilever of 4 bonded spheres along z (r = 0.5 mm, touching; the bond properties
/// of wild case 18, LIGGGHTS-INL's chain bending example), the first frozen and the last
/// pushed sideways by P = 1 N (`fix addforce`) and damped by `fix viscous` until it rests,
/// bent far. At rest the part of the chain beyond each bond balances the tip load, so,
/// whatever the deflection, each dumped bond gives i the force ±P x̂ and the moment
/// ±P (z_tip − z_i) ŷ (+ when i is the sphere nearer the clamp), all of it bending
/// (torque_normal 0): the moment within 1e-4 of P times the chain's length (3 mm; rdem
/// is off by 8e-8 N m at most, the chain still swaying slightly), the force within 1e-4.
#[test]
fn a_bent_cantilever_dumps_the_statics_of_a_tip_load() {
    let dir = common::scratch_dir("bonds_local");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let mut s = String::from(
        "\
atom_style granular
atom_modify map array
boundary f f f
newton off
units si
region box block -0.005 0.005 -0.005 0.005 0 0.008 units box
create_box 1 box
neighbor 5e-4 bin
neigh_modify delay 0
",
    );
    for k in 0..4 {
        s += &format!("create_atoms 1 single 0 0 {} units box\n", 0.001 * k as f64);
    }
    s += "\
set group all density 430 diameter 0.001
fix m1 all property/global youngsModulus peratomtype 10e6
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.1
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global radiusMultiplierBond peratomtypepair 1 1.0
fix m6 all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 1e10
fix m7 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 6e8
fix m8 all property/global maxDistanceBond peratomtypepair 1 0.0015
fix m9 all property/global dampingNormalForceBond peratomtypepair 1 0
fix m10 all property/global dampingTangentialForceBond peratomtypepair 1 0
fix m11 all property/global dampingNormalTorqueBond peratomtypepair 1 0
fix m12 all property/global dampingTangentialTorqueBond peratomtypepair 1 0
fix m13 all property/global tsCreateBond scalar 1
fix m14 all property/global createDistanceBond peratomtypepair 1 0.0011
pair_style gran model hertz tangential history cohesion bond
pair_coeff * *
group head id 1
group tip id 4
fix hold head freeze
fix push tip addforce 1 0 0
fix visc all viscous 0.2
fix integr all nve/sphere
compute b all pair/gran/local/bond
dump d1 all local 100000 post/b*.txt c_b[1] c_b[2] c_b[3] c_b[4] c_b[5] c_b[6] c_b[7] c_b[8] c_b[9] c_b[10] c_b[11] c_b[12] c_b[13] c_b[14] c_b[15] c_b[16] c_b[17] c_b[18] c_b[19] c_b[20] c_b[21] c_b[22] c_b[23] c_b[24] c_b[25] c_b[26] c_b[27]
dump d2 all custom 100000 post/a*.txt id x y z
timestep 2e-7
run 100000
";
    std::fs::write(dir.join("in.bend"), s).unwrap();
    let out = common::rdem_command(None)
        .current_dir(&dir)
        .args(["-in", "in.bend", "-log", "none"])
        .env("RDEM_THREADS", "1")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let text = std::fs::read_to_string(dir.join("post/b100000.txt")).unwrap();
    let rows = last_rows(&text);
    assert_eq!(rows.len(), 3, "three bonds:\n{text}");
    let atoms = std::fs::read_to_string(dir.join("post/a100000.txt")).unwrap();
    let z_tip: f64 = atoms
        .lines()
        .find_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w.len() == 4 && w[0] == "4").then(|| w[3].parse().unwrap())
        })
        .expect("the tip's row");
    assert!(z_tip < 0.0025, "bent far: the tip is at z = {z_tip}");
    for r in &rows {
        let (ti, tj, zi) = (r[6], r[7], r[2]);
        let sign = (tj - ti).signum();
        let (fx, ty) = (r[9], r[19]);
        let moment = sign * (z_tip - zi);
        eprintln!("bond {ti}-{tj}: F_x {fx}, T_y {ty:e}, P (z_tip - z_i) {moment:e}");
        assert!((fx - sign).abs() < 1e-4, "force {fx}");
        assert!(
            (ty - moment).abs() < 1e-3 * moment.abs(),
            "{ty} vs {moment}"
        );
        assert!(
            r[21..24].iter().all(|&t| t == 0.0),
            "no twist: {:?}",
            &r[21..24]
        );
        assert_eq!(r[24..27], r[18..21], "the torque is all bending");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
