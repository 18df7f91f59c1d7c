//! `cohesion bond` (the parallel bond of Potyondy & Cundall, as LIGGGHTS-INL has it) run
//! through the binary on small scripts with an analytical answer: a bonded pair, a chain
//! and a wall bond loaded by `fix addforce` settle at the elongation F/(k_n A); bonds
//! break at the load the distance, normal stress, shear stress or bending stress
//! criterion predicts; bad bond input stops with a located error.
//!
//! Common set-up: spheres of radius r = 1 mm (density 2500), `radiusMultiplierBond` 1
//! (so r_b = r, A = π r², I = π r⁴/4), k_n = 1e10 Pa/m, k_t = 5e9 Pa/m, bonds created at
//! step 1 (`tsCreateBond`) between touching spheres (`createDistanceBond` 2.01 mm, above
//! the 2 mm centre distance) before any load acts, so d₀ is exactly 2 mm. Bond damping is
//! Coulomb-like (α |F| sign(v)) and leaves a dead band around the equilibrium, so the four
//! `damping*Bond` coefficients are 0 and `fix viscous` on the moving spheres damps the
//! motion instead (it does not change the equilibrium). No gravity.

use crate::common;

use std::f64::consts::PI;
use std::process::Output;

/// Sphere radius.
const R: f64 = 0.001;
/// `normalBondStiffnessPerUnitArea`.
const KN: f64 = 1e10;
/// Bond cross-section π r_b² (r_b = 1 · r).
const AREA: f64 = PI * R * R;
/// Bending moment of inertia π r_b⁴/4.
const I_BEND: f64 = PI * R * R * R * R / 4.0;
/// `tangentialBondStiffnessPerUnitArea`.
const KT: f64 = 5e9;
/// Rest length of a pair bond (touching spheres).
const L: f64 = 2.0 * R;

/// Runs `script` (as `in.test`) in a fresh directory with `-log none`.
fn run_raw(script: &str) -> Output {
    common::run_script_raw(script, None)
}

/// Runs `script`, which must succeed; returns the screen output.
fn run(script: &str) -> String {
    common::run_script(script, None)
}

/// Every thermo row (the lines of numbers after a `Step ...` header), in order, without
/// the first row of a run that repeats the step of the previous run's last row (the
/// counters, evaluated once per step, repeat there).
fn rows(out: &str) -> Vec<Vec<f64>> {
    let mut all: Vec<Vec<f64>> = common::thermo_rows(out);
    all.dedup_by(|b, a| a[0] == b[0]);
    assert!(!all.is_empty(), "no thermo row in\n{out}");
    all
}

/// Relative difference of `got` from `want`.
fn rel(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs()
}

/// The bond's break criterion (`fix property/global` lines and `cohesion bond` switches).
struct Break {
    props: String,
    switches: &'static str,
}

/// Break when the centre distance exceeds `max_distance`.
fn by_distance(max_distance: f64) -> Break {
    Break {
        props: format!(
            "fix b4 all property/global maxDistanceBond peratomtypepair 1 {max_distance}\n"
        ),
        switches: "",
    }
}

/// Break by stress (`stressBreak on`) at σ > `sigma` or τ > `tau`.
fn by_stress(sigma: f64, tau: f64) -> Break {
    Break {
        props: format!(
            "fix b4 all property/global maxSigmaBond peratomtypepair 1 {sigma}\n\
             fix b7 all property/global maxTauBond peratomtypepair 1 {tau}\n"
        ),
        switches: " stressBreak on",
    }
}

/// The head of every script: a box, the spheres at `atoms`, the materials and bond
/// properties (criterion `brk`), with the bond in the pair style (`wall == false`) or in
/// a `fix wall/gran` plane z = 0 (`wall == true`); Velocity-Verlet at dt = 1 µs and
/// `compute bc all bond/counter`.
fn head(atoms: &[[f64; 3]], brk: &Break, wall: bool) -> String {
    let mut s = String::from(
        "\
atom_style granular
atom_modify map array
boundary f f f
units si
region box block -0.02 0.05 -0.02 0.02 -0.02 0.02 units box
create_box 1 box
neighbor 0.0002 bin
neigh_modify delay 0
",
    );
    for a in atoms {
        s += &format!(
            "create_atoms 1 single {} {} {} units box\n",
            a[0], a[1], a[2]
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
fix b3 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 {KT}
fix b5 all property/global createDistanceBond peratomtypepair 1 0.00201
fix b6 all property/global tsCreateBond scalar 1
fix d1 all property/global dampingNormalForceBond peratomtypepair 1 0.0
fix d2 all property/global dampingTangentialForceBond peratomtypepair 1 0.0
fix d3 all property/global dampingNormalTorqueBond peratomtypepair 1 0.0
fix d4 all property/global dampingTangentialTorqueBond peratomtypepair 1 0.0
{}",
        2.0 * R,
        brk.props
    );
    let model = "model hertz tangential history";
    if wall {
        s += &format!(
            "pair_style gran {model}\npair_coeff * *\n\
             fix wall all wall/gran {model} cohesion bond{} primitive type 1 zplane 0.0\n",
            brk.switches
        );
    } else {
        s += &format!(
            "pair_style gran {model} cohesion bond{}\npair_coeff * *\n",
            brk.switches
        );
    }
    s += "\
timestep 1e-6
fix integr all nve/sphere
compute bc all bond/counter
";
    s
}

/// Thermo with full precision: step, atoms, the six bond counters, then `extra`.
fn thermo(extra: &str, every: usize) -> String {
    format!(
        "thermo_style custom step atoms c_bc[1] c_bc[2] c_bc[3] c_bc[4] c_bc[5] c_bc[6] {extra}\n\
         thermo_modify format float %24.17g\n\
         thermo {every}\n"
    )
}

/// Runs of `steps` steps under the constant forces `load · dir` on group `tip`, one per
/// load (the fix replaced between runs), with the load printed as `v_load`.
fn staircase(loads: &[f64], dir: [f64; 3], steps: usize) -> String {
    let mut s = String::new();
    for &l in loads {
        s += &format!(
            "variable load equal {l:e}\nfix pull tip addforce {:e} {:e} {:e}\nrun {steps}\n",
            l * dir[0],
            l * dir[1],
            l * dir[2]
        );
    }
    s
}

/// The loads of a breaking test for a predicted breaking load `fb`: 30 %, 60 % and 90 %
/// of it, then steps of 0.5 % from 90.25 % to 104.75 % (so that no load equals the
/// prediction): the first load at which the bond breaks is within 0.5 % above `fb`.
fn loads_around(fb: f64) -> Vec<f64> {
    let mut v = vec![0.3 * fb, 0.6 * fb, 0.9 * fb];
    v.extend((0..30).map(|k| fb * (0.9025 + 0.005 * k as f64)));
    v
}

/// The load (column `load_col`) of the first thermo row whose intact bond count (c_bc[3]
/// for pair bonds, c_bc[6] with `wall`) is 0 after the bond was created, checking that
/// this row counts the one breakage (c_bc[2], c_bc[5]), that no other bond broke, and that
/// the bond held at every earlier row.
fn breaking_load(out: &str, load_col: usize, wall: bool) -> f64 {
    let rows = rows(out);
    let (broken_col, intact_col) = if wall { (6, 7) } else { (3, 4) };
    let created = rows
        .iter()
        .position(|r| r[intact_col] == 1.0)
        .expect("the bond was created");
    let k = created
        + rows[created..]
            .iter()
            .position(|r| r[intact_col] == 0.0)
            .unwrap_or_else(|| panic!("the bond never broke:\n{out}"));
    assert_eq!(
        rows[k][broken_col], 1.0,
        "the breaking row counts one breakage"
    );
    let broken: f64 = rows.iter().map(|r| r[3] + r[6]).sum();
    assert_eq!(broken, 1.0, "one breakage in all");
    rows[k][load_col]
}

/// Checks that the bond broke at the first load of [`loads_around`] above the predicted
/// `fb` (0.25 % above it): the load before (0.25 % below) held. A bond breaking 0.25 %
/// early or late fails.
fn assert_first_above(got: f64, fb: f64) {
    assert!(
        got > fb && got < 1.005 * fb,
        "broke at {got} N ({:+.3} %), expected the first load above {fb} N",
        100.0 * (got / fb - 1.0)
    );
}

/// Lateral displacement of the free sphere of a pair (the other one held) under a load
/// `f` across the bond, small-angle: the shear spring k_t A carries f, and with the
/// sphere's rotation φ (its torque balance: the bending torque k_n I φ equals the moment
/// of the shear force about its centre, (L/2) f) the bond's middle lags the centre by
/// (L/2) φ, so y = f/(k_t A) + (L/2)² f/(k_n I).
fn lateral_displacement(f: f64) -> f64 {
    f / (KT * AREA) + (0.5 * L) * (0.5 * L) * f / (KN * I_BEND)
}

/// A bonded pair, sphere 1 frozen and sphere 2 pulled along the bond by F = 0.1 N
/// (`fix addforce`, after the bond was created at rest), settles at the elongation
/// d − d₀ = F/(k_n A) = 3.1831e-6 m (A = π r_b², r_b = `radiusMultiplierBond` · r): within
/// 1 % (in practice 1e-9); the one bond is created once and stays intact.
#[test]
fn a_pulled_pair_stretches_by_force_over_kn_area() {
    let f = 0.1;
    let mut s = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_distance(0.0025),
        false,
    );
    s += "\
group end id 1
group tip id 2
fix hold end freeze
fix visc tip viscous 1.0
variable dx equal x[2]-x[1]
";
    s += &thermo("v_dx", 1000);
    s += &format!("run 10\nfix pull tip addforce {f} 0 0\nrun 5000\n");
    let out = run(&s);
    let rows = rows(&out);
    let last = rows.last().unwrap();
    let want = f / (KN * AREA);
    let got = last[8] - 2.0 * R;
    eprintln!("pair tension: elongation {got:e}, expected {want:e}");
    assert!(
        rel(got, want) < 0.01,
        "elongation {got:e}, expected {want:e}"
    );
    let created: f64 = rows.iter().map(|r| r[2]).sum();
    assert_eq!(created, 1.0, "one bond created");
    assert_eq!((last[3], last[4]), (0.0, 1.0), "the bond is intact");
}

/// A chain of 6 spheres in a row (5 bonds), the first frozen and the last pulled along
/// the chain by F = 0.1 N: every bond carries F, so each stretches by F/(k_n A) =
/// 3.1831e-6 m and the chain by 5 F/(k_n A) = 1.5915e-5 m, within 1 %; the 5 bonds differ
/// from each other by less than 0.1 % (non-neighbours, 4 mm apart, are not bonded).
#[test]
fn a_pulled_chain_stretches_every_bond_alike() {
    let f = 0.1;
    let n = 5;
    let atoms: Vec<[f64; 3]> = (0..=n).map(|k| [2.0 * R * k as f64, 0.0, 0.0]).collect();
    let mut s = head(&atoms, &by_distance(0.0025), false);
    s += &format!(
        "group end id 1\ngroup tip id {}\ngroup free id 2:{}\nfix hold end freeze\n\
         fix visc free viscous 0.5\n",
        n + 1,
        n + 1
    );
    let mut cols = String::new();
    for k in 1..=n {
        s += &format!("variable d{k} equal x[{}]-x[{k}]\n", k + 1);
        cols += &format!("v_d{k} ");
    }
    s += &format!("variable dx equal x[{}]-x[1]\n", n + 1);
    s += &thermo(&format!("{cols}v_dx"), 1000);
    s += &format!("run 10\nfix pull tip addforce {f} 0 0\nrun 6000\n");
    let out = run(&s);
    let rows = rows(&out);
    let last = rows.last().unwrap();
    let one = f / (KN * AREA);
    assert_eq!(last[4], n as f64, "{n} intact bonds");
    let total = last[8 + n] - 2.0 * R * n as f64;
    eprintln!(
        "chain: total elongation {total:e}, expected {:e}",
        n as f64 * one
    );
    assert!(
        rel(total, n as f64 * one) < 0.01,
        "chain elongation {total:e}, expected {:e}",
        n as f64 * one
    );
    for k in 0..n {
        let e = last[8 + k] - 2.0 * R;
        eprintln!("chain: bond {} elongation {e:e}", k + 1);
        assert!(
            rel(e, one) < 0.01,
            "bond {}: elongation {e:e}, expected {one:e}",
            k + 1
        );
        let e0 = last[8] - 2.0 * R;
        assert!(rel(e, e0) < 1e-3, "bond {} {e:e} vs bond 1 {e0:e}", k + 1);
    }
}

/// A sphere resting on the wall z = 0 (`fix wall/gran ... cohesion bond`; created since
/// 2 · distance = 2 r < `createDistanceBond`, rest length d₀ = r, r_b = r), pulled off
/// along +z by F = 0.1 N, settles at z − r = F/(k_n A) = 3.1831e-6 m within 1 %; the
/// counters show one intact wall bond (c_bc[6] = 1) and no pair bond (c_bc[3] = 0).
#[test]
fn a_wall_bond_stretches_by_force_over_kn_area() {
    let f = 0.1;
    let mut s = head(&[[0.0, 0.0, R]], &by_distance(0.0025), true);
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable dz equal z[1]\n";
    s += &thermo("v_dz", 1000);
    s += &format!("run 10\nfix pull tip addforce 0 0 {f}\nrun 5000\n");
    let rows = rows(&run(&s));
    assert_wall_tension("wall tension", &rows, f);
    assert_eq!(rows.last().unwrap()[4], 0.0, "no pair bond");
}

/// The rows of a wall tension run (load `f`, z − r in column 8) end at the elongation
/// F/(k_n A) within 1 %, with one wall bond created and intact.
fn assert_wall_tension(name: &str, rows: &[Vec<f64>], f: f64) {
    let last = rows.last().unwrap();
    let want = f / (KN * AREA);
    let got = last[8] - R;
    eprintln!("{name}: elongation {got:e}, expected {want:e}");
    assert!(
        rel(got, want) < 0.01,
        "{name}: elongation {got:e}, expected {want:e}"
    );
    assert_eq!(last[7], 1.0, "{name}: one wall bond");
    let created: f64 = rows.iter().map(|r| r[5]).sum();
    assert_eq!(created, 1.0, "{name}: one wall bond created");
}

/// A wall bond's anchor moves with the wall surface (`shear x 0.1`): a sphere bonded to
/// the plane z = 0 (motion damped by `fix viscous`) is dragged along at the wall speed,
/// v_x = 0.1 m/s within 0.5 % after 20 ms, having moved v t behind the anchor by no more
/// than the shear spring's lag γ v/(k_t A) plus the bending's (1 % of v t allowed); the
/// bond stays intact.
#[test]
fn a_wall_bond_follows_a_moving_wall_surface() {
    let v = 0.1;
    let mut s = head(&[[0.0, 0.0, R]], &by_distance(0.0025), true)
        .replace("zplane 0.0\n", &format!("zplane 0.0 shear x {v}\n"));
    assert!(s.contains("shear x"));
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable px equal x[1]\n\
          variable pv equal vx[1]\n";
    s += &thermo("v_px v_pv", 1000);
    s += "run 20000\n";
    let out = run(&s);
    let last = rows(&out).last().unwrap().clone();
    let t = 20000.0 * 1e-6;
    assert!(rel(last[9], v) < 5e-3, "velocity {} (want {v})", last[9]);
    assert!(rel(last[8], v * t) < 1e-2, "x {} (want {})", last[8], v * t);
    assert_eq!(last[7], 1.0, "the wall bond holds");
}

/// Breakage by distance (`maxDistanceBond` 2.1 mm): a pair pulled apart by a load raised
/// in small steps (runs of 200 steps at 0.5 % increments around the prediction) breaks
/// once the centre distance exceeds 2.1 mm, i.e. at the load k_n A (2.1 mm − d₀) =
/// 3.1416 N: the first load that breaks it is within 1 % of that (the steps allow
/// +0.25 %), and the counters show the breakage (c_bc[2] = 1, c_bc[3] = 0).
#[test]
fn a_bond_breaks_beyond_max_distance() {
    let max_d = 0.0021;
    let fb = KN * AREA * (max_d - 2.0 * R);
    let got = pull_pair_to_break(&by_distance(max_d), fb);
    eprintln!("distance break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}

/// The load at which a bonded pair (sphere 1 frozen) pulled along the bond by loads
/// raised step by step around `fb` breaks (criterion `brk`).
fn pull_pair_to_break(brk: &Break, fb: f64) -> f64 {
    let mut s = head(&[[0.0, 0.0, 0.0], [L, 0.0, 0.0]], brk, false);
    s += "group end id 1\ngroup tip id 2\nfix hold end freeze\nfix visc tip viscous 1.0\n\
          variable dx equal x[2]-x[1]\nvariable load equal 0\n";
    s += &thermo("v_dx v_load", 200);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [1.0, 0.0, 0.0], 200);
    breaking_load(&run(&s), 9, false)
}

/// Breakage of a wall bond by distance (`maxDistanceBond` 1.1 mm, the distance from the
/// centre to the bond's anchor on the wall, d₀ = r = 1 mm): a sphere bonded to the wall
/// z = 0 and pulled off by loads raised in 0.5 % steps breaks at k_n A (1.1 mm − r) =
/// 3.1416 N (the first load above it), and the counters show it (c_bc[5] = 1, c_bc[6] = 0).
#[test]
fn a_wall_bond_breaks_beyond_max_distance() {
    let max_d = 0.0011;
    let fb = KN * AREA * (max_d - R);
    let mut s = head(&[[0.0, 0.0, R]], &by_distance(max_d), true);
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable dz equal z[1]\n\
          variable load equal 0\n";
    s += &thermo("v_dz v_load", 200);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [0.0, 0.0, 1.0], 200);
    let out = run(&s);
    let got = breaking_load(&out, 9, true);
    eprintln!("wall distance break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}

/// Breakage by normal stress (`stressBreak on`, `maxSigmaBond` 1e6 Pa, `maxTauBond` far
/// above): in pure tension σ = |F_n|/A, so the bond breaks at the load
/// `maxSigmaBond` · A = 3.1416 N, within 1 % (loads raised in 0.5 % steps).
#[test]
fn a_bond_breaks_in_tension_at_max_sigma() {
    let sigma = 1e6;
    let fb = sigma * AREA;
    let got = pull_pair_to_break(&by_stress(sigma, 1e12), fb);
    eprintln!("tension stress break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}

/// The pair of the tension test loaded across the bond (F = 0.1 N along y on sphere 2):
/// the shear force and the bending torque balance the load, and sphere 2 settles at the
/// lateral displacement F/(k_t A) + (L/2)² F/(k_n I) = 6.3662e-6 + 1.2732e-5 =
/// 1.9099e-5 m (see [`lateral_displacement`]), within 1 %.
#[test]
fn a_pair_loaded_across_shears_and_bends() {
    let f = 0.1;
    let mut s = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_distance(0.0025),
        false,
    );
    s += "group end id 1\ngroup tip id 2\nfix hold end freeze\nfix visc tip viscous 1.0\n\
          variable dy equal y[2]-y[1]\n";
    s += &thermo("v_dy", 1000);
    s += &format!("run 10\nfix pull tip addforce 0 {f} 0\nrun 6000\n");
    let out = run(&s);
    let rows = rows(&out);
    let last = rows.last().unwrap();
    let want = lateral_displacement(f);
    eprintln!("lateral: displacement {:e}, expected {want:e}", last[8]);
    assert!(
        rel(last[8], want) < 0.01,
        "lateral displacement {:e}, expected {want:e}",
        last[8]
    );
    assert_eq!(last[4], 1.0, "the bond is intact");
}

/// The script of a pair, sphere 1 frozen, whose stress-breaking bond (σ_max `sigma`,
/// τ_max `tau`) is loaded across (along y) by the loads of [`loads_around`] `fb`, 500
/// steps each; returns the load at which it broke.
fn shear_break(sigma: f64, tau: f64, fb: f64) -> f64 {
    let mut s = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_stress(sigma, tau),
        false,
    );
    s += "group end id 1\ngroup tip id 2\nfix hold end freeze\nfix visc tip viscous 1.0\n\
          variable dy equal y[2]-y[1]\nvariable load equal 0\n";
    s += &thermo("v_dy v_load", 500);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [0.0, 1.0, 0.0], 500);
    let out = run(&s);
    breaking_load(&out, 9, false)
}

/// Breakage by shear stress (`stressBreak on`, `maxTauBond` 1e5 Pa, `maxSigmaBond` 1e7
/// Pa): a pair loaded across the bond by F. At rest the bond force balances F, so the
/// shear force is F cos θ (θ = atan(y/L), the turn of the bond, y from
/// [`lateral_displacement`]) and τ = F cos θ/A (no twist), which reaches `maxTauBond` at
/// F = τ_max A / cos θ = 0.31430 N (θ = 0.030: +0.045 % on τ_max A). The bending stress
/// there, (L/2) F r_b/I ≈ 4e5 Pa (plus F sin θ/A), stays far below `maxSigmaBond`. The
/// first load that breaks the bond (0.5 % steps) is the first above the prediction.
#[test]
fn a_bond_loaded_across_breaks_at_max_tau() {
    let (sigma, tau) = (1e7, 1e5);
    let mut fb = tau * AREA;
    for _ in 0..20 {
        let theta = (lateral_displacement(fb) / L).atan();
        fb = tau * AREA / theta.cos();
    }
    let theta = (lateral_displacement(fb) / L).atan();
    let sigma_at_break = fb * theta.sin() / AREA + 0.5 * L * fb * theta.cos() * R / I_BEND;
    assert!(
        sigma_at_break < 0.1 * sigma,
        "σ {sigma_at_break} would govern"
    );
    let got = shear_break(sigma, tau, fb);
    eprintln!("shear (tau) break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}

/// Breakage by bending (`stressBreak on`, `maxSigmaBond` 2e5 Pa, `maxTauBond` 1e12 Pa):
/// a pair loaded across the bond by F. At rest the bond force balances F (normal part
/// F sin θ, shear part F cos θ, θ = atan(y/L) with y from [`lateral_displacement`]) and
/// the bending torque balances the shear force's moment about the free sphere's centre,
/// |T_t| = (L/2) F cos θ (the bond's middle is L/2 from the centre), so
/// σ = F sin θ/A + (L/2) F cos θ r_b/I reaches `maxSigmaBond` at F = 0.15650 N (without
/// the turn, σ_max I/((L/2) r_b) = 0.15708 N: the normal part is a 0.37 % correction).
/// The first load that breaks the bond (0.5 % steps) is the first above the prediction.
#[test]
fn a_bond_loaded_across_breaks_by_bending_at_max_sigma() {
    let (sigma, tau) = (2e5, 1e12);
    let mut fb = sigma * I_BEND / (0.5 * L * R);
    for _ in 0..20 {
        let theta = (lateral_displacement(fb) / L).atan();
        fb = sigma / (theta.sin() / AREA + 0.5 * L * theta.cos() * R / I_BEND);
    }
    let got = shear_break(sigma, tau, fb);
    eprintln!("bending (sigma) break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}

/// Text with white space and the report's gutter bars removed, so that a message that
/// miette wrapped at the terminal width still compares equal.
fn squeeze(s: &str) -> String {
    s.chars()
        .filter(|c| !c.is_whitespace() && *c != '│')
        .collect()
}

/// Runs `script`, which must stop with exit code 1 and a report on standard error that
/// points at `in.test:LINE:COL`, where LINE is the first line containing `line_text` and
/// COL the column of the last `at` within that text (any column with `at` = `None`), and
/// that contains `message`.
fn assert_error(script: &str, line_text: &str, at: Option<&str>, message: &str) {
    let out = run_raw(script);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "exit code\n{stderr}");
    let (n, line) = script
        .lines()
        .enumerate()
        .find(|(_, l)| l.contains(line_text))
        .expect("the line is in the script");
    let loc = match at {
        Some(at) => {
            let col =
                line.find(line_text).unwrap() + line_text.rfind(at).expect("`at` in the text");
            format!("in.test:{}:{}", n + 1, col + 1)
        }
        None => format!("in.test:{}:", n + 1),
    };
    assert!(stderr.contains(&loc), "no {loc} in\n{stderr}");
    assert!(
        squeeze(&stderr).contains(&squeeze(message)),
        "no '{message}' in\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "panic\n{stderr}");
}

/// Bad bond input stops with a located error (exit code 1, `in.test:line:col` on standard
/// error): `temperatureBreak on` is not supported (at the switch's value); a missing
/// required property (`normalBondStiffnessPerUnitArea`) is named, at the first `run`; a
/// second `compute bond/counter` is refused, on its line.
#[test]
fn bad_bond_input_is_a_located_error() {
    let tail = "run 10\n";
    let ok = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_distance(0.0025),
        false,
    );
    // The good script runs.
    run(&format!("{ok}{tail}"));

    let s = ok.replace("cohesion bond\n", "cohesion bond temperatureBreak on\n");
    assert_error(
        &format!("{s}{tail}"),
        "temperatureBreak on",
        Some("on"),
        "temperatureBreak on: bond breakage by temperature is not supported",
    );

    let s: String = ok
        .lines()
        .filter(|l| !l.contains("normalBondStiffnessPerUnitArea"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_error(
        &format!("{s}{tail}"),
        "run 10",
        Some("run"),
        "cohesion bond needs 'fix ID all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 ...'",
    );

    // A bond reach beyond 10 diameters (1.1 × 25 mm against 2 mm spheres).
    let far = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_distance(0.025),
        false,
    );
    assert_error(
        &format!("{far}{tail}"),
        "run 10",
        Some("run"),
        "exceeds 10 diameters of the smallest particle",
    );

    assert_error(
        &format!("{ok}compute bc2 all bond/counter\n{tail}"),
        "compute bc2 all bond/counter",
        Some("bond/counter"),
        "only one compute bond/counter is allowed (compute bc is one)",
    );
}

/// `tsCreateBond 0` makes no bond (bonds are made in the force evaluation of that step, and
/// step 0 is only evaluated at a run's set-up, which never advances history): the run
/// warns once and the counter stays at zero.
#[test]
fn ts_create_bond_at_the_set_up_step_warns() {
    let ok = head(
        &[[0.0, 0.0, 0.0], [L, 0.0, 0.0]],
        &by_distance(0.0025),
        false,
    );
    let s = ok.replace("tsCreateBond scalar 1", "tsCreateBond scalar 0");
    let out = run(&format!("{s}{}run 10\nrun 10\n", thermo("", 5)));
    assert_eq!(
        out.matches("tsCreateBond 0 is not after the current step")
            .count(),
        1,
        "{out}"
    );
    for r in rows(&out) {
        assert!(r[2..8].iter().all(|&v| v == 0.0), "{r:?}");
    }
    let out = run(&format!("{ok}{}run 10\n", thermo("", 5)));
    assert!(!out.contains("tsCreateBond"), "{out}");
}

/// Twisting: the free sphere of a bonded pair (the other frozen) spun about the bond's
/// axis at ω₀ oscillates on the twisting spring T_n = −k_t J θ alone (the spin has no
/// shear or bending part): ω_x(t) = ω₀ cos(Ω t), Ω = √(k_t J / I_p), I_p = 2/5 m r², so
/// ω_x first vanishes at t = π/(2Ω) (within 0.5 %). With `stressBreak on` (σ_max = 1e7
/// Pa, never reached: the spin loads neither the normal force nor the bending) the twist
/// stress peaks at τ = k_t J θ_max r_b / J = k_t r_b ω₀/Ω: the bond holds at 0.97 and
/// breaks at 1.03 times the ω₀ that makes that peak equal `maxTauBond`.
#[test]
fn a_twisted_pair_oscillates_and_breaks_at_max_tau() {
    let mass = 2500.0 * 4.0 / 3.0 * PI * R * R * R;
    let ip = 0.4 * mass * R * R;
    let j = PI * R.powi(4) / 2.0;
    let omega_t = (KT * j / ip).sqrt();
    let dt = 1e-7;
    let tau_max = 1e6;
    let spin = |w0: f64, brk: &Break, steps: usize, every: usize| {
        let mut s = head(&[[0.0, 0.0, 0.0], [L, 0.0, 0.0]], brk, false);
        s += &format!(
            "timestep {dt}\ngroup end id 1\nfix hold end freeze\nrun 10\n\
             set atom 2 omega {w0} 0.0 0.0\nvariable w equal omegax[2]\n"
        );
        s += &thermo("v_w", every);
        s += &format!("run {steps}\n");
        // Only the rows of the spinning run (the first run prints default columns).
        let rows: Vec<Vec<f64>> = rows(&run(&s))
            .into_iter()
            .filter(|r| r.len() == 9)
            .collect();
        rows
    };
    // Period: the first zero of ω_x, interpolated between thermo rows (every step).
    let w0 = 10.0;
    let r = spin(w0, &by_distance(0.0025), 600, 1);
    let k = r
        .iter()
        .position(|r| r[8] <= 0.0)
        .expect("ω_x changes sign");
    let (a, b) = (&r[k - 1], &r[k]);
    // The spin is set at step 10.
    let t = (a[0] + a[8] / (a[8] - b[8]) * (b[0] - a[0]) - 10.0) * dt;
    let want = PI / (2.0 * omega_t);
    assert!(rel(t, want) < 5e-3, "quarter period {t} s, want {want} s");
    assert!(r.iter().all(|r| r[4] == 1.0), "bond intact");
    // Breakage by twist.
    let w_break = tau_max * omega_t / (KT * R);
    let hold = spin(0.97 * w_break, &by_stress(1e7, tau_max), 800, 100);
    assert!(hold.iter().all(|r| r[4] == 1.0 && r[3] == 0.0), "{hold:?}");
    let broke = spin(1.03 * w_break, &by_stress(1e7, tau_max), 800, 100);
    let last = broke.last().unwrap();
    assert_eq!(last[4], 0.0, "{broke:?}");
    assert_eq!(broke.iter().map(|r| r[3]).sum::<f64>(), 1.0, "{broke:?}");
}

/// Runs `script` beside `floor.stl` ([`common::floor_stl`], the square z = 0 of four
/// triangles meeting at the origin); returns the screen output.
fn run_on_floor(script: &str) -> String {
    common::run_with_files(script, &[("floor.stl", &common::floor_stl())], None)
}

/// A wall-bond script of [`head`] with the primitive plane z = 0 replaced by the STL
/// floor (`fix mesh/surface ... {mesh_keys}` and `wall/gran ... mesh`).
fn on_floor(script: &str, mesh_keys: &str) -> String {
    let s = script
        .replace(
            "primitive type 1 zplane 0.0\n",
            "mesh n_meshes 1 meshes floor\n",
        )
        .replace(
            "fix wall all wall/gran",
            &format!("fix floor all mesh/surface file floor.stl type 1{mesh_keys}\nfix wall all wall/gran"),
        );
    assert!(s.contains("meshes floor"));
    s
}

/// Wall bonds work on mesh walls: the tension test of
/// [`a_wall_bond_stretches_by_force_over_kn_area`] on the STL floor (the sphere off the
/// triangles' shared edges) gives the plane's run: every thermo row (bond counters,
/// position) equal within 1e-9 relative, and the elongation F/(k_n A) within 1 %.
#[test]
fn a_wall_bond_on_a_mesh_floor_holds_as_on_the_plane() {
    let f = 0.1;
    let mut s = head(&[[0.013, 0.007, R]], &by_distance(0.0025), true);
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable dz equal z[1]\n\
          variable dx equal x[1]\nvariable dy equal y[1]\n";
    s += &thermo("v_dz v_dx v_dy", 500);
    s += &format!("run 10\nfix pull tip addforce 0 0 {f}\nrun 5000\n");
    let plane = rows(&run(&s));
    let mesh = rows(&run_on_floor(&on_floor(&s, "")));
    assert_eq!(plane.len(), mesh.len());
    for (a, b) in plane.iter().zip(&mesh) {
        for (x, y) in a.iter().zip(b) {
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
                "plane {a:?}\nmesh  {b:?}"
            );
        }
    }
    assert_wall_tension("mesh wall tension", &mesh, f);
}

/// A mesh wall bond's anchor goes with the wall: on a conveyor floor (`surface_vel`
/// 0.1 0 0) and on a floor moved by `fix move/mesh linear 0.1 0 0`, a sphere bonded to
/// it (motion damped by `fix viscous`) is dragged along at v_x = 0.1 m/s within 0.5 %
/// after 20 ms, at x = x₀ + v t within 1 % of v t, the bond intact.
#[test]
fn a_mesh_wall_bond_follows_a_belt_and_a_moving_mesh() {
    let v = 0.1;
    let x0 = 0.013;
    let mut s = head(&[[x0, 0.007, R]], &by_distance(0.0025), true);
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable px equal x[1]\n\
          variable pv equal vx[1]\n";
    s += &thermo("v_px v_pv", 1000);
    s += "run 20000\n";
    let belt = on_floor(&s, &format!(" surface_vel {v} 0 0"));
    let moving = on_floor(&s, "").replace(
        "timestep 1e-6\n",
        &format!("timestep 1e-6\nfix mv all move/mesh mesh floor linear {v} 0 0\n"),
    );
    assert!(moving.contains("move/mesh"));
    let t = 20000.0 * 1e-6;
    for (name, script) in [("belt", belt), ("moving mesh", moving)] {
        let last = rows(&run_on_floor(&script)).last().unwrap().clone();
        eprintln!("{name}: x - x0 = {:e}, vx = {}", last[8] - x0, last[9]);
        assert!(
            rel(last[9], v) < 5e-3,
            "{name}: velocity {} (want {v})",
            last[9]
        );
        assert!(
            rel(last[8] - x0, v * t) < 1e-2,
            "{name}: x - x0 = {} (want {})",
            last[8] - x0,
            v * t
        );
        assert_eq!(last[7], 1.0, "{name}: the wall bond holds");
    }
}

/// Breakage of a mesh wall bond by distance, as
/// [`a_wall_bond_breaks_beyond_max_distance`] on the plane: the first load above
/// k_n A (1.1 mm − r) breaks it, and the counters show it.
#[test]
fn a_mesh_wall_bond_breaks_beyond_max_distance() {
    let max_d = 0.0011;
    let fb = KN * AREA * (max_d - R);
    let mut s = head(&[[0.013, 0.007, R]], &by_distance(max_d), true);
    s += "group tip id 1\nfix visc tip viscous 1.0\nvariable dz equal z[1]\n\
          variable load equal 0\n";
    s += &thermo("v_dz v_load", 200);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [0.0, 0.0, 1.0], 200);
    let out = run_on_floor(&on_floor(&s, ""));
    let got = breaking_load(&out, 9, true);
    eprintln!("mesh wall distance break: load {got}, expected {fb}");
    assert_first_above(got, fb);
}
