//! `poissonsRatio` at the ends of LIGGGHTS 3.8's range, 0 ≤ ν ≤ 0.5 (measured: 0 and 0.5
//! run; −1e-9 and 0.50000001 stop with "0 <= poissonsRatio <= 0.5 required").
//!
//! The LIGGGHTS run ([`SCRIPT`] with `dump_modify d format '%d %.17g %.17g %.17g %.17g'`
//! of `id x fx fy fz` every step, `liggghts -in in.x -log none`, Debian 3.8.0): two spheres
//! of diameter 0.01 overlapping by 5e-4, no integration (they keep their place and
//! velocities), particle 2 approaching at 0.01 and sliding at 0.02.

// LIGGGHTS' figures are kept with the 17 digits it printed.
#![allow(clippy::excessive_precision)]

use rdem_script::Interpreter;

use crate::common;

const SCRIPT: &str = "\
units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region domain block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 1 domain
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype NU
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0.0095 0 0 units box
set atom 1 diameter 0.01 density 1000
set atom 2 diameter 0.01 density 1000
velocity all set 0 0 0
set atom 2 vx -0.01 vy 0.02
timestep 1e-6
";

fn run(nu: &str, steps: u32) -> Result<Interpreter, String> {
    let src = format!("{}run {steps}\n", SCRIPT.replace("NU", nu));
    common::try_run("in.nu", &src)
}

/// Force on particle 1 (tag 1).
fn force1(i: &Interpreter) -> [f64; 2] {
    let p = &i.sim.world.as_ref().unwrap().particles;
    let k = (0..p.nlocal()).find(|&k| p.tag[k] == 1).unwrap();
    [p.f[k].x, p.f[k].y]
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

/// ν = 0.5 against the Hertz closed form and LIGGGHTS 3.8.
///
/// E* = E / (2 (1 − ν²)) = 2E/3, G* = E / (4 (2 − ν)(1 + ν)) = E/9, R* = r/2, δ = 5e-4.
/// Normal: F = 4/3 E* √R* δ^{3/2} + γ_n v_n, γ_n = 2 √(5/6) |β| √(2 E* √(R* δ) m*),
/// β = ln e / √(ln² e + π²), m* = m/2. Tangential: the spring grows by
/// k_t v_t dt = 8 G* √(R* δ) v_t dt per step (no integration: δ and v stay).
/// LIGGGHTS 3.8, particle 1: fx = −4.9768109093838184 at every step; fy =
/// 0.012689923535584942, 0.012888685133584923, 0.013087446731584905 at steps 0, 1, 2.
#[test]
fn half_is_incompressible_hertz() {
    let e_mod = 1e7;
    let (r_star, delta): (f64, f64) = (0.0025, 5e-4);
    let e_star = 2.0 * e_mod / 3.0;
    let g_star = e_mod / 9.0;
    let m_star = 1000.0 * std::f64::consts::PI / 6.0 * 1e-6 / 2.0;
    let ln_e = 0.5f64.ln();
    let beta = ln_e / (ln_e * ln_e + std::f64::consts::PI.powi(2)).sqrt();
    let sqrt_rd = (r_star * delta).sqrt();
    let gamma_n =
        2.0 * (5.0f64 / 6.0).sqrt() * beta.abs() * (2.0 * e_star * sqrt_rd * m_star).sqrt();
    let fn_closed = 4.0 / 3.0 * e_star * r_star.sqrt() * delta.powf(1.5) + gamma_n * 0.01;
    let dft_closed = 8.0 * g_star * sqrt_rd * 0.02 * 1e-6;

    let fy_liggghts = [
        0.012689923535584942,
        0.012888685133584923,
        0.013087446731584905,
    ];
    let mut fy = Vec::new();
    for steps in 0..3 {
        let i = run("0.5", steps).unwrap_or_else(|e| panic!("ν = 0.5 must run: {e}"));
        let [fx, f_y] = force1(&i);
        // Particle 1 is pushed away from particle 2 (−x).
        assert!(
            close(-fx, fn_closed, 1e-12),
            "fx {fx} vs closed form {fn_closed}"
        );
        assert!(close(fx, -4.9768109093838184, 1e-13), "fx {fx} vs LIGGGHTS");
        assert!(
            close(f_y, fy_liggghts[steps as usize], 1e-12),
            "step {steps}: fy {f_y} vs LIGGGHTS {}",
            fy_liggghts[steps as usize]
        );
        fy.push(f_y);
    }
    for k in 1..3 {
        let d = fy[k] - fy[k - 1];
        assert!(
            close(d, dft_closed, 1e-9),
            "spring step {d} vs {dft_closed}"
        );
    }
}

/// ν = 0 runs (LIGGGHTS 3.8, `run 0`, no velocities: fx = −3.7267799624996543 = −4/3 E/2
/// √R* δ^{3/2}); just outside the range stops with a located error naming the range.
#[test]
fn range_as_liggghts() {
    let still = SCRIPT.replace("set atom 2 vx -0.01 vy 0.02\n", "");
    let mut i = common::interpreter();
    i.run_source("in.nu", &format!("{}run 0\n", still.replace("NU", "0")))
        .unwrap_or_else(|e| panic!("{:?}", miette::Report::new(*e)));
    let [fx, _] = force1(&i);
    let closed = 4.0 / 3.0 * (1e7 / 2.0) * 0.0025f64.sqrt() * 5e-4f64.powf(1.5);
    assert!(close(-fx, closed, 1e-14), "{fx} vs {closed}");
    assert!(close(fx, -3.7267799624996543, 1e-14), "{fx}");
    for nu in ["0.50000001", "0.51", "-1e-9", "-0.3"] {
        let e = run(nu, 0)
            .err()
            .unwrap_or_else(|| panic!("ν = {nu} must stop"));
        assert!(e.contains("poissonsRatio"), "{nu}: {e}");
        assert!(e.contains("must be in [0, 0.5]"), "{nu}: {e}");
    }
}
