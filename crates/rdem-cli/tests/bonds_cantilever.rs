//! A cantilever of bonded spheres (`cohesion bond`) against Euler–Bernoulli beam theory.
//!
//! The beam: N + 1 equal spheres of radius r in a straight line, touching (centre distance
//! L_b = 2r), bonded at step 1 (`tsCreateBond`); the first sphere is clamped with
//! `fix freeze` (force and torque zeroed: it neither moves nor turns), the last one
//! carries a load P perpendicular to the line (`fix addforce`), no gravity. Theory:
//! δ = P L³/(3 E I) at the tip and w(x) = P x² (3L − x)/(6 E I) along it, with L = N L_b.
//!
//! **Mapping of the bond onto a beam segment.** A bond (radius r_b, A = π r_b²,
//! I = π r_b⁴/4) joins two centres L_b apart. Take the transverse displacements w_i, w_j
//! and slopes φ_i, φ_j of its two centres (φ = −θ_y for a beam along x bending in z). The
//! bond has exactly two transverse springs:
//!
//! - bending: the torque grows by −k_n I (ω_i − ω_j) dt, so M = k_n I (φ_i − φ_j);
//! - shear: the force grows by −k_t A v_t dt with v_t the relative velocity of the two
//!   sides of the bond's middle (lever arms L_b/2 from each centre), so F = k_t A s with
//!   s = w_i − w_j + (L_b/2)(φ_i + φ_j) (zero for a rigid turn of the pair).
//!
//! Its energy is ½ k_t A s² + ½ k_n I (φ_i − φ_j)². The strain energy of an Euler–Bernoulli
//! segment of length L_b with the same end values is (with a = (φ_i + φ_j)/2 and the chord
//! slope ψ = (w_j − w_i)/L_b)
//! (2EI/L_b)(φ_i² + φ_i φ_j + φ_j² − 3ψ(φ_i + φ_j) + 3ψ²)
//! = ½ (12 EI/L_b³) s² + ½ (EI/L_b)(φ_i − φ_j)²:
//! the same two uncoupled modes. So the bond *is* an exact EB segment (clamped–clamped
//! stiffness, in the nodal unknowns) when k_n I = E I/L_b, i.e. E = k_n L_b, and
//! k_t A = 12 E I/L_b³, i.e. k_t = 12 E I/(A L_b³) = 12 k_n I/(A L_b²) (= ¾ k_n for
//! r_b = r).
//!
//! **What the discrete chain should give.** Assembled exact segments give exact nodal
//! values for a cantilever under nodal loads (the EB solution is a cubic on each segment,
//! which the segment reproduces), so every node, the tip included, deflects exactly as the
//! continuous beam, for any N (even N = 1), provided the clamp is at the first sphere's
//! centre, which it is: `freeze` fixes that centre's position and rotation and the first
//! bond starts there. No convergence in N is needed. With any other k_t the tip moves by
//! δ = P L³/(3EI) + N P (1/(k_t A) − L_b³/(12 EI)) (the bending springs alone give the
//! midpoint rule, P L_b³ (N³/3 − N/12)/(EI), a relative error −1/(4N²)); so the shear
//! spring matters most for short chains, which is where the tests check it sharply (N = 1
//! and 2, and k_t halved for N = 1: 5/4 of the EB deflection).
//!
//! **Dynamics.** Bond damping (`dampingBond`, on) is Coulomb-like and leaves a dead band,
//! so its coefficients are 0 here and `fix viscous` (all particles) takes the chain to
//! rest, set to about critical damping of the first mode (γ = 2 m ω₁ with the cantilever's
//! ω₁ = 1.875² √(E I/(μ L⁴)), μ = m/L_b; the discrete chain's ω₁ is some 10 % lower, so a
//! factor 0.9). The stiffest mode is a shear–rotation one, ω² = k_t A L_b²/(⅖ m r²) = 10
//! k_t A/m (the axial one 4 k_n A/m, the bending–rotation one 4 k_n I/(⅖ m r²) are lower),
//! ω_max = 1.5e5 s⁻¹ here: Verlet is stable below dt = 2/ω_max = 1.3e-5 s (1.2e-5 runs,
//! 1.4e-5 blows up), and the tests use 2e-6 (ω_max dt = 0.3). The load is small
//! (δ/L = 1e-3) so the geometry stays linear, and the run is long enough (∝ N², the ratio
//! of the fastest to the slowest mode) for the transient to die out well below 1e-3.

use crate::common;

/// Sphere radius r (bond radius r_b = r), density, k_n.
const R: f64 = 1e-3;
const RHO: f64 = 2500.0;
const KN: f64 = 1e10;
/// Timestep (see the module comment).
const DT: f64 = 2e-6;

/// Runs `script` in a fresh directory; returns the screen output.
fn run(script: &str) -> String {
    common::run_script(script, None)
}

/// The numbers of the last thermo row.
fn last_row(out: &str) -> Vec<f64> {
    common::thermo_rows(out).pop().expect("a thermo row")
}

/// One cantilever: `n` bonds along the unit vector `e`, tip load along the unit vector
/// `q` (perpendicular to `e`), k_t scaled by `kt_factor` from the EB value.
struct Cantilever {
    n: usize,
    e: [f64; 3],
    q: [f64; 3],
    kt_factor: f64,
}

/// What a run measured and what theory predicts.
#[derive(Debug)]
struct Outcome {
    /// Intact bonds at the end.
    bonds: f64,
    /// Tip deflection along q: measured, EB.
    tip: (f64, f64),
    /// Deflection along q of the middle node (node n/2): measured, EB.
    mid: (f64, f64),
    /// Tip displacement across both q and the beam (should be 0).
    cross: f64,
    /// Tip displacement along the beam (second order): measured, predicted.
    axial: (f64, f64),
}

impl Cantilever {
    fn along_x(n: usize) -> Self {
        Self {
            n,
            e: [1.0, 0.0, 0.0],
            q: [0.0, 0.0, 1.0],
            kt_factor: 1.0,
        }
    }

    fn run(&self) -> Outcome {
        let n = self.n;
        let lb = 2.0 * R;
        let area = std::f64::consts::PI * R * R;
        let i_bend = std::f64::consts::PI * R.powi(4) / 4.0;
        let e_mod = KN * lb;
        let ei = e_mod * i_bend;
        let kt = self.kt_factor * 12.0 * KN * i_bend / (area * lb * lb);
        let len = n as f64 * lb;
        // δ/L = 1e-3.
        let p = 3.0 * ei * 1e-3 / (len * len);
        let mass = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3) * RHO;
        let omega1 = 1.875f64.powi(2) * (ei / (mass / lb * len.powi(4))).sqrt();
        let gamma = 2.0 * mass * 0.9 * omega1;
        let steps = (16_000 * n * n / 100).max(4000);
        let [ex, ey, ez] = self.e;
        let [qx, qy, qz] = self.q;
        let pos = |k: usize| [ex, ey, ez].map(|c| c * k as f64 * lb);
        let (lo, hi) = (0..3).fold(([0.0f64; 3], [0.0f64; 3]), |(mut lo, mut hi), c| {
            let end = pos(n)[c];
            lo[c] = end.min(0.0) - 4.0 * R;
            hi[c] = end.max(0.0) + 4.0 * R;
            (lo, hi)
        });
        let mut atoms = String::new();
        for k in 0..=n {
            let [x, y, z] = pos(k);
            atoms += &format!("create_atoms 1 single {x:?} {y:?} {z:?} units box\n");
        }
        let tip = n + 1;
        let mid = n / 2 + 1;
        // Displacement of node `id` relative to the clamped one, projected on `v` (the
        // initial offset is along e, so its projection on q, or on q × e, is zero).
        let proj = |id: usize, v: [f64; 3]| {
            format!(
                "(x[{id}]-x[1])*({:?})+(y[{id}]-y[1])*({:?})+(z[{id}]-z[1])*({:?})",
                v[0], v[1], v[2]
            )
        };
        let cross = [qy * ez - qz * ey, qz * ex - qx * ez, qx * ey - qy * ex];
        // Motion of the tip along the beam: projection on e minus the initial length.
        let along = format!("{}-{len:?}", proj(tip, self.e));
        let script = format!(
            "\
atom_style granular
atom_modify map array
boundary f f f
units si
region box block {:?} {:?} {:?} {:?} {:?} {:?} units box
create_box 1 box
neighbor 0.0002 bin
neigh_modify delay 0
{atoms}set atom * diameter {d:?} density {RHO:?}
fix m1 all property/global youngsModulus peratomtype 5.e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix b1 all property/global radiusMultiplierBond peratomtypepair 1 1.0
fix b2 all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 {KN:?}
fix b3 all property/global tangentialBondStiffnessPerUnitArea peratomtypepair 1 {kt:?}
fix b4 all property/global maxDistanceBond peratomtypepair 1 {maxd:?}
fix b5 all property/global createDistanceBond peratomtypepair 1 {created:?}
fix b6 all property/global tsCreateBond scalar 1
fix d1 all property/global dampingNormalForceBond peratomtypepair 1 0
fix d2 all property/global dampingTangentialForceBond peratomtypepair 1 0
fix d3 all property/global dampingNormalTorqueBond peratomtypepair 1 0
fix d4 all property/global dampingTangentialTorqueBond peratomtypepair 1 0
pair_style gran model hertz tangential history cohesion bond
pair_coeff * *
timestep {DT:?}
group root id 1
group tip id {tip}
fix integr all nve/sphere
fix hold root freeze
fix load tip addforce {:?} {:?} {:?}
fix damp all viscous {gamma:?}
compute bc all bond/counter
variable tip equal {}
variable mid equal {}
variable cross equal {}
variable axial equal {}
thermo_style custom step atoms c_bc[3] v_tip v_mid v_cross v_axial
thermo_modify format float %24.17g
thermo {steps}
run {steps}
",
            lo[0],
            hi[0],
            lo[1],
            hi[1],
            lo[2],
            hi[2],
            p * qx,
            p * qy,
            p * qz,
            proj(tip, self.q),
            proj(mid, self.q),
            proj(tip, cross),
            along,
            d = 2.0 * R,
            maxd = 1.1 * lb,
            created = 1.01 * lb,
        );
        let row = last_row(&run(&script));
        assert_eq!(row[0], steps as f64, "{row:?}");
        // EB deflection at distance x from the clamp.
        let w = |x: f64| p * x * x * (3.0 * len - x) / (6.0 * ei);
        // Each bond keeps its length but for the stretch by the load's component along
        // it, P ψ/(k_n A), and turns by its chord slope ψ: the tip comes back by
        // Σ (½ L_b ψ² − P ψ/(k_n A)).
        let axial = (0..n)
            .map(|k| {
                let psi = (w((k + 1) as f64 * lb) - w(k as f64 * lb)) / lb;
                p * psi / (KN * area) - 0.5 * lb * psi * psi
            })
            .sum::<f64>();
        Outcome {
            bonds: row[2],
            tip: (row[3], w(len)),
            mid: (row[4], w((n / 2) as f64 * lb)),
            cross: row[5],
            axial: (row[6], axial),
        }
    }
}

/// Checks a cantilever against EB: 2 % (the claim), and, since a chain of exact segments
/// is exact at its nodes, 2e-3 (what is left of the transient); the middle node too; no
/// motion across both the load and the beam, and the second-order motion along the beam
/// as predicted within 5e-3 (its third-order terms are ~ψ ~ 1e-3 of it).
fn check(c: &Cantilever) -> Outcome {
    let o = c.run();
    eprintln!("N = {}: {o:?}", c.n);
    assert_eq!(o.bonds, c.n as f64, "all bonds intact: {o:?}");
    let rel = |(m, t): (f64, f64)| (m - t).abs() / t;
    assert!(rel(o.tip) < 0.02, "tip deflection off EB by > 2 %: {o:?}");
    assert!(rel(o.tip) < 2e-3, "tip deflection not exact: {o:?}");
    if c.n >= 2 {
        assert!(rel(o.mid) < 2e-3, "middle deflection not exact: {o:?}");
    }
    assert!(
        o.cross.abs() < 1e-6 * o.tip.1,
        "motion across the load: {o:?}"
    );
    assert!(rel(o.axial) < 5e-3, "motion along the beam: {o:?}");
    o
}

/// A single bond (N = 1) and two (N = 2): the shear spring carries a quarter of the
/// deflection (N = 1), so these pin k_t = 12 k_n I/(A L_b²) down.
#[test]
fn short_cantilevers_deflect_as_euler_bernoulli() {
    for n in [1, 2] {
        check(&Cantilever::along_x(n));
    }
}

/// With k_t halved, one bond's tip moves by P L_b³/(4EI) + 2 P L_b³/(12EI) = 5/4 of the EB
/// value: the test does see the shear spring.
#[test]
fn halved_shear_stiffness_softens_a_single_bond_by_a_quarter() {
    let o = Cantilever {
        kt_factor: 0.5,
        ..Cantilever::along_x(1)
    }
    .run();
    let ratio = o.tip.0 / o.tip.1;
    assert!((ratio - 1.25).abs() < 2e-3, "{o:?}");
}

#[test]
fn cantilever_of_10_deflects_as_euler_bernoulli() {
    check(&Cantilever::along_x(10));
}

#[test]
fn cantilever_of_20_deflects_as_euler_bernoulli() {
    check(&Cantilever::along_x(20));
}

#[test]
fn cantilever_of_40_deflects_as_euler_bernoulli() {
    check(&Cantilever::along_x(40));
}

/// The same beam along an oblique line, (3, 4, 0)/5, loaded in the plane across it and
/// out of it: every component of the bond's vectors takes part.
#[test]
fn oblique_cantilever_deflects_as_euler_bernoulli() {
    let s = 0.5f64.sqrt();
    check(&Cantilever {
        n: 10,
        e: [0.6, 0.8, 0.0],
        q: [-0.8 * s, 0.6 * s, s],
        kt_factor: 1.0,
    });
}
