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

mod common;

use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::Output;

use common::rdem_command;

/// Sphere radius.
const R: f64 = 0.001;
/// `normalBondStiffnessPerUnitArea`.
const KN: f64 = 1e10;
/// Bond cross-section π r_b² (r_b = 1 · r).
const AREA: f64 = PI * R * R;
/// Bending moment of inertia π r_b⁴/4.
const I_BEND: f64 = PI * R * R * R * R / 4.0;

/// A fresh, empty directory for one run.
fn temp_dir() -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!(
        "rdem-bonds-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `script` (as `in.test`) in a fresh directory with `-log none`.
fn run_raw(script: &str) -> Output {
    let dir = temp_dir();
    std::fs::write(dir.join("in.test"), script).unwrap();
    let out = rdem_command(None)
        .args(["-in", "in.test", "-log", "none"])
        .env("RDEM_THREADS", "1")
        .current_dir(&dir)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    out
}

/// Runs `script`, which must succeed; returns the screen output.
fn run(script: &str) -> String {
    let out = run_raw(script);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// Every thermo row (the lines of numbers after a `Step ...` header), in order, without
/// the first row of a run that repeats the step of the previous run's last row (the
/// counters, evaluated once per step, repeat there).
fn rows(out: &str) -> Vec<Vec<f64>> {
    let mut all = Vec::new();
    let mut in_table = false;
    for l in out.lines() {
        if l.trim_start().starts_with("Step") {
            in_table = true;
            continue;
        }
        if in_table {
            let v: Result<Vec<f64>, _> = l.split_whitespace().map(str::parse).collect();
            match v {
                Ok(v) if !v.is_empty() => {
                    if all.last().is_none_or(|l: &Vec<f64>| l[0] != v[0]) {
                        all.push(v)
                    }
                }
                _ => in_table = false,
            }
        }
    }
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
fix b3 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 5.e9
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

/// The load (column `load_col`) of the first thermo row whose intact pair bond count
/// (c_bc[3]) is 0 after the bond was created, checking that this row counts the one
/// breakage (c_bc[2] = 1), that no other bond broke, and that the bond held at every
/// earlier row.
fn breaking_load(out: &str, load_col: usize) -> f64 {
    let rows = rows(out);
    let created = rows
        .iter()
        .position(|r| r[4] == 1.0)
        .expect("the bond was created");
    let k = created
        + rows[created..]
            .iter()
            .position(|r| r[4] == 0.0)
            .unwrap_or_else(|| panic!("the bond never broke:\n{out}"));
    assert_eq!(rows[k][3], 1.0, "the breaking row counts one breakage");
    let broken: f64 = rows.iter().map(|r| r[3]).sum();
    assert_eq!(broken, 1.0, "one breakage in all");
    rows[k][load_col]
}

/// A bonded pair, sphere 1 frozen and sphere 2 pulled along the bond by F = 0.1 N
/// (`fix addforce`, after the bond was created at rest), settles at the elongation
/// d − d₀ = F/(k_n A) = 3.1831e-6 m (A = π r_b², r_b = `radiusMultiplierBond` · r): within
/// 1 % (in practice 1e-9); the one bond is created once and stays intact.
#[test]
fn a_pulled_pair_stretches_by_force_over_kn_area() {
    let f = 0.1;
    let mut s = head(
        &[[0.0, 0.0, 0.0], [2.0 * R, 0.0, 0.0]],
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
    let out = run(&s);
    let rows = rows(&out);
    let last = rows.last().unwrap();
    let want = f / (KN * AREA);
    let got = last[8] - R;
    eprintln!("wall tension: elongation {got:e}, expected {want:e}");
    assert!(
        rel(got, want) < 0.01,
        "elongation {got:e}, expected {want:e}"
    );
    assert_eq!(last[4], 0.0, "no pair bond");
    assert_eq!(last[7], 1.0, "one wall bond");
    let created: f64 = rows.iter().map(|r| r[5]).sum();
    assert_eq!(created, 1.0, "one wall bond created");
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
    let mut s = head(
        &[[0.0, 0.0, 0.0], [2.0 * R, 0.0, 0.0]],
        &by_distance(max_d),
        false,
    );
    s += "group end id 1\ngroup tip id 2\nfix hold end freeze\nfix visc tip viscous 1.0\n\
          variable dx equal x[2]-x[1]\nvariable load equal 0\n";
    s += &thermo("v_dx v_load", 200);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [1.0, 0.0, 0.0], 200);
    let out = run(&s);
    let got = breaking_load(&out, 9);
    eprintln!("distance break: load {got}, expected {fb}");
    assert!(rel(got, fb) < 0.01, "broke at {got} N, expected {fb} N");
}

/// Breakage by normal stress (`stressBreak on`, `maxSigmaBond` 1e6 Pa, `maxTauBond` far
/// above): in pure tension σ = |F_n|/A, so the bond breaks at the load
/// `maxSigmaBond` · A = 3.1416 N, within 1 % (loads raised in 0.5 % steps).
#[test]
fn a_bond_breaks_in_tension_at_max_sigma() {
    let sigma = 1e6;
    let fb = sigma * AREA;
    let mut s = head(
        &[[0.0, 0.0, 0.0], [2.0 * R, 0.0, 0.0]],
        &by_stress(sigma, 1e12),
        false,
    );
    s += "group end id 1\ngroup tip id 2\nfix hold end freeze\nfix visc tip viscous 1.0\n\
          variable dx equal x[2]-x[1]\nvariable load equal 0\n";
    s += &thermo("v_dx v_load", 200);
    s += "run 10\n";
    s += &staircase(&loads_around(fb), [1.0, 0.0, 0.0], 200);
    let out = run(&s);
    let got = breaking_load(&out, 9);
    eprintln!("tension stress break: load {got}, expected {fb}");
    assert!(rel(got, fb) < 0.01, "broke at {got} N, expected {fb} N");
}
