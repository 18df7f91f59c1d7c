//! `fix gravity` styles `chute` and `spherical`, and values given as equal-style
//! variables, against closed forms and LIGGGHTS 3.8 runs of the same scripts (made with
//! `liggghts -in in.x -log none` in a scratch folder; the numbers are copied from its
//! thermo rows, printed with `thermo_modify format float %.17g`).

// The LIGGGHTS figures are kept with the 17 digits it printed.
#![allow(clippy::excessive_precision)]

use crate::common;
use common::render;

/// One sphere (d = 0.1 m, 1000 kg/m³) at the origin of a 2 m box, dt = 1 ms.
const FREE: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -1 1 -1 1 -1 1 units box
create_box 1 reg
neighbor 0.01 bin
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.001
create_atoms 1 single 0 0 0
set atom 1 diameter 0.1 density 1000
";

/// Runs `script` and returns its thermo rows (each row's numbers) and the interpreter.
fn rows(script: &str) -> Vec<Vec<f64>> {
    let mut i = common::interpreter();
    if let Err(e) = i.run_source("in.g", script) {
        panic!("{}", render(&e));
    }
    let out = common::screen(&i);
    out.lines()
        .map(|l| {
            l.split_whitespace()
                .map(str::parse::<f64>)
                .collect::<Result<Vec<_>, _>>()
        })
        .filter_map(Result::ok)
        .filter(|r| r.len() > 1)
        .collect()
}

fn close(ours: f64, theirs: f64, tol: f64, what: &str) {
    let scale = theirs.abs().max(1e-300);
    assert!(
        (ours - theirs).abs() <= tol * scale.max(1e-12),
        "{what}: rdem {ours:e}, expected {theirs:e}"
    );
}

const PROBE: &str = "\
fix i all nve/sphere
variable vx equal vx[1]
variable vy equal vy[1]
variable vz equal vz[1]
thermo_style custom step v_vx v_vy v_vz
thermo_modify format float %.17g
thermo 10
run 10
";

#[test]
fn spherical_direction_matches_liggghts() {
    // LIGGGHTS 3.8, `fix g all gravity 9.81 spherical 30 120`, step 10:
    // 0.073575000000000002 0.042478546055626731 -0.049049999999999969
    // Closed form: v = g t (sin θ cos φ, sin θ sin φ, cos θ), t = 0.01 s.
    let r = rows(&format!(
        "{FREE}fix g all gravity 9.81 spherical 30 120\n{PROBE}"
    ));
    let last = r.last().unwrap();
    assert_eq!(last[0], 10.0);
    let (phi, theta) = (30f64.to_radians(), 120f64.to_radians());
    let t = 0.01;
    let want = [
        9.81 * t * theta.sin() * phi.cos(),
        9.81 * t * theta.sin() * phi.sin(),
        9.81 * t * theta.cos(),
    ];
    let liggghts = [
        0.073575000000000002,
        0.042478546055626731,
        -0.049049999999999969,
    ];
    for k in 0..3 {
        close(last[1 + k], want[k], 1e-12, "spherical v vs closed form");
        close(
            last[1 + k],
            liggghts[k],
            1e-14,
            "spherical v vs LIGGGHTS 3.8",
        );
    }
}

#[test]
fn variable_magnitude_and_chute_angle_match_liggghts() {
    // LIGGGHTS 3.8, `fix g all gravity v_gm chute v_ang` with gm = 9.81 (1 + step/100),
    // ang = 30 + step degrees (evaluated every step):
    //   step 5:  vx 0.027020394812975874  vz -0.042377682563435583
    //   step 10: vx 0.059123903088602284  vz -0.084184155031979901
    let script = format!(
        "{FREE}variable gm equal 9.81*(1+step*0.01)\nvariable ang equal 30+step\nfix g all gravity v_gm chute v_ang\n{}",
        PROBE.replace("thermo 10", "thermo 5")
    );
    let r = rows(&script);
    let at = |s: f64| r.iter().find(|row| row[0] == s).unwrap().clone();
    // Closed form of velocity Verlet with the acceleration a_n of step n (evaluated
    // before step n's forces): v_N = Σ_{n=1..N} dt (a_{n-1} + a_n)/2, a_0 from step 0.
    let acc = |n: f64| {
        let g = 9.81 * (1.0 + n * 0.01);
        let t = (30.0 + n).to_radians();
        (g * t.sin(), -g * t.cos())
    };
    for (n, lx, lz) in [
        (5.0, 0.027020394812975874, -0.042377682563435583),
        (10.0, 0.059123903088602284, -0.084184155031979901),
    ] {
        let row = at(n);
        let (mut vx, mut vz) = (0.0, 0.0);
        for k in 1..=(n as u32) {
            let (a0, a1) = (acc(k as f64 - 1.0), acc(k as f64));
            vx += 0.001 * (a0.0 + a1.0) / 2.0;
            vz += 0.001 * (a0.1 + a1.1) / 2.0;
        }
        close(row[1], vx, 1e-12, "vx vs closed form");
        close(row[3], vz, 1e-12, "vz vs closed form");
        close(row[1], lx, 1e-14, "vx vs LIGGGHTS 3.8");
        close(row[3], lz, 1e-14, "vz vs LIGGGHTS 3.8");
        assert_eq!(row[2], 0.0, "chute gravity has no y component");
    }
}

#[test]
fn a_sphere_slides_down_a_frictionless_chute() {
    // A sphere resting on a frictionless floor (coefficientFriction 0) under
    // `gravity 9.81 chute 20`: it slides with a = g sin 20° and never spins, while the
    // normal part g cos 20° settles it onto the floor. LIGGGHTS 3.8 (the script below,
    // dt = 0.1 ms, thermo every 1000 steps) printed
    //   step x                     vx                  z                    wy
    //   1000 0.016776088030123822 0.33552176060247585 0.049701350247569019 0
    //   3000 0.15098479227111403  1.0065652818074262  0.049701223161768365 0
    //   5000 0.41940220075309437  1.6776088030123766  0.049701223161866641 0
    let script = FREE
        .replace("-1 1 -1 1 -1 1", "-1 1 -1 1 -0.5 1")
        .replace(
            "coefficientFriction peratomtypepair 1 0.5",
            "coefficientFriction peratomtypepair 1 0.0",
        )
        .replace("timestep 0.001", "timestep 0.0001\nneigh_modify delay 0")
        .replace("single 0 0 0", "single 0 0 0.05")
        + "\
fix g all gravity 9.81 chute 20
fix w all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix i all nve/sphere
variable x equal x[1]
variable z equal z[1]
variable vx equal vx[1]
variable vz equal vz[1]
variable wy equal omegay[1]
thermo_style custom step v_x v_vx v_z v_vz v_wy
thermo_modify format float %.17g
thermo 1000
run 5000
";
    let r = rows(&script);
    let a = 9.81 * 20f64.to_radians().sin();
    for (n, lx, lvx, lz) in [
        (
            1000.0,
            0.016776088030123822,
            0.33552176060247585,
            0.049701350247569019,
        ),
        (
            3000.0,
            0.15098479227111403,
            1.0065652818074262,
            0.049701223161768365,
        ),
        (
            5000.0,
            0.41940220075309437,
            1.6776088030123766,
            0.049701223161866641,
        ),
    ] {
        let row = r.iter().find(|row| row[0] == n).unwrap();
        let t = n * 1e-4;
        // Velocity Verlet is exact for a constant acceleration.
        close(row[1], 0.5 * a * t * t, 1e-12, "x vs ½ g sin θ t²");
        close(row[2], a * t, 1e-12, "vx vs g sin θ t");
        assert_eq!(row[5], 0.0, "no friction, no spin");
        close(row[1], lx, 1e-13, "x vs LIGGGHTS 3.8");
        close(row[2], lvx, 1e-13, "vx vs LIGGGHTS 3.8");
        close(row[3], lz, 1e-12, "z vs LIGGGHTS 3.8");
    }
    // At rest on the floor: the Hertz overlap carries m g cos θ. z = R − δ with
    // m g cos θ = 4/3 E* √R δ^{3/2}, E* = E / (1 − ν²) (the wall of the same material:
    // LIGGGHTS' wall E* is 1/((1−ν²)/E + (1−ν²)/E) = E / (2 (1 − ν²))).
    let m = 1000.0 * std::f64::consts::PI / 6.0 * 0.1f64.powi(3);
    let estar = 5e6 / (2.0 * (1.0 - 0.45f64 * 0.45));
    let delta = (m * 9.81 * 20f64.to_radians().cos() / (4.0 / 3.0 * estar * 0.05f64.sqrt()))
        .powf(2.0 / 3.0);
    let row = r.iter().find(|row| row[0] == 5000.0).unwrap();
    close(row[3], 0.05 - delta, 1e-9, "resting height vs Hertz");
}

#[test]
fn gradient_and_bad_gravity_are_located_errors() {
    for (line, msg, word) in [
        (
            "fix g all gravity 9.81 gradient 0 180 1 1",
            "gravity style 'gradient' is not supported: LIGGGHTS 3.8 refuses it too",
            "gradient",
        ),
        (
            "fix g all gravity 9.81 sideways 3",
            "unknown gravity style 'sideways'",
            "sideways",
        ),
        (
            "fix g all gravity 9.81 vector 0 0 0",
            "the gravity vector has no direction",
            "0",
        ),
        ("fix g all gravity 9.81 chute", "missing chute angle", ""),
    ] {
        let mut i = common::interpreter();
        let e = i
            .run_source("in.g", &format!("{FREE}{line}\n"))
            .expect_err(line);
        let r = render(&e);
        assert!(r.contains(msg), "{line}: '{msg}' missing in\n{r}");
        let col = 1 + line.find(word).expect("word in line");
        assert!(
            word.is_empty() || r.contains(&format!("in.g:19:{col}]")),
            "{line}: not located at '{word}':\n{r}"
        );
    }
    // A variable that is not equal-style stops the run with its name.
    let mut i = common::interpreter();
    let e = i
        .run_source(
            "in.g",
            &format!("{FREE}variable a atom x\nfix g all gravity 9.81 chute v_a\nfix i all nve/sphere\nrun 1\n"),
        )
        .expect_err("atom-style angle");
    let r = render(&e);
    assert!(r.contains("variable 'a' is not equal-style"), "{r}");
}
