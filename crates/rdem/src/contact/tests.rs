//! Unit checks of the contact kernel against hand computations of SPEC §3 and the
//! LIGGGHTS 3.8 sub-model definitions.

use super::cohesion::Cohesion;
use super::normal::Normal;
use super::*;
use glam::DVec3;

const PI: f64 = std::f64::consts::PI;

fn coeff(e: f64, mu: f64) -> PairCoeff {
    let m = Materials::uniform(1, 1e7, 0.3, e, mu);
    let mut c = *CoeffTable::new(&m, Needs::default()).unwrap().get(1, 1);
    c.mu_r = 0.1;
    c.eta_r = 0.3;
    c.cohesion = 1e4;
    c.vc = 1.0;
    c.kc_ratio = 0.5;
    c.phi_f = 0.05;
    c.k2max_ratio = 3.0;
    c
}

/// Two spheres of radius 1 cm touching with overlap `delta` along x (i on the right).
fn geom(delta: f64) -> Geom {
    let (ri, rj) = (0.01, 0.01);
    let m = 2500.0 * 4.0 / 3.0 * PI * ri * ri * ri;
    Geom {
        n: DVec3::X,
        delta,
        dist: ri + rj - delta,
        ri,
        rj,
        r_star: ri * rj / (ri + rj),
        m_star: 0.5 * m,
        ci: ri - 0.5 * delta,
        cj: rj - 0.5 * delta,
        vr: DVec3::ZERO,
        wi: DVec3::ZERO,
        wj: DVec3::ZERO,
        roll_scale: 1.0,
        inertia_i: 1.4 * m * ri * ri,
        inertia_j: 1.4 * m * rj * rj,
        dt: 1e-6,
        lq_i: 0.0,
        lq_j: 0.0,
        update: true,
    }
}

type HertzHist = Kernel<normal::Hertz, tangential::History, rolling::Off, cohesion::Off>;

#[test]
fn hertz_normal_force_and_damping() {
    let c = coeff(0.5, 0.5);
    let mut g = geom(1e-4);
    g.vr = DVec3::new(-0.3, 0.0, 0.0); // approaching
    let out = HertzHist::contact(&g, &c, Flags::default(), &mut [0.0; 3]);
    let sq = (g.r_star * g.delta).sqrt();
    let kn = 4.0 / 3.0 * c.e_star * sq;
    let beta = 0.5f64.ln() / (0.5f64.ln().powi(2) + PI * PI).sqrt();
    let gn = -2.0 * (5.0f64 / 6.0).sqrt() * beta * (2.0 * c.e_star * sq * g.m_star).sqrt();
    let expected = kn * g.delta + gn * 0.3;
    assert!((out.f_i.x - expected).abs() < 1e-12 * expected);
    assert_eq!(out.f_i.y, 0.0);
    // limitForce: a receding fast pair would pull; clamped to zero.
    g.vr = DVec3::new(30.0, 0.0, 0.0);
    let mut flags = Flags::default();
    let pulled = HertzHist::contact(&g, &c, flags, &mut [0.0; 3]);
    assert!(pulled.f_i.x < 0.0);
    flags.limit_force = true;
    let clamped = HertzHist::contact(&g, &c, flags, &mut [0.0; 3]);
    assert_eq!(clamped.f_i.x, 0.0);
}

#[test]
fn tangential_spring_sticks_then_slides_and_resets() {
    let c = coeff(1.0, 0.5); // e = 1: no damping, so the spring alone acts
    let mut g = geom(1e-4);
    g.vr = DVec3::new(0.0, 0.01, 0.0);
    let mut h = [0.0; 3];
    let out = HertzHist::contact(&g, &c, Flags::default(), &mut h);
    let kt = 8.0 * c.g_star * (g.r_star * g.delta).sqrt();
    // Stick: ξ = v dt, F_t = −k_t ξ.
    assert!((h[1] - 0.01 * g.dt).abs() < 1e-20);
    assert!((out.f_i.y + kt * 0.01 * g.dt).abs() < 1e-12 * kt * 0.01 * g.dt);
    // A large displacement slides: |F_t| = μ F_n and ξ = −F_t/k_t.
    let mut h = [0.0, 1.0, 0.0];
    let out = HertzHist::contact(&g, &c, Flags::default(), &mut h);
    let fn_ = out.f_i.x;
    assert!((out.f_i.y.abs() - 0.5 * fn_).abs() < 1e-12 * fn_);
    assert!((h[1] + out.f_i.y / kt).abs() < 1e-12 * h[1].abs());
    // Torques: τ_i = −c_i n × F_t, τ_j = −c_j n × F_t.
    let nxft = DVec3::X.cross(DVec3::new(0.0, out.f_i.y, 0.0));
    assert!((out.t_i - (-g.ci * nxft)).length() < 1e-15);
    assert!((out.t_j - (-g.cj * nxft)).length() < 1e-15);
}

#[test]
fn spring_is_projected_onto_the_current_tangent_plane() {
    let c = coeff(1.0, 10.0);
    let g = geom(1e-4);
    // A spring with a normal component (the contact turned): only the tangential part stays.
    let mut h = [1e-7, 2e-7, 0.0];
    HertzHist::contact(&g, &c, Flags::default(), &mut h);
    assert_eq!(h[0], 0.0);
    assert_eq!(h[1], 2e-7);
}

#[test]
fn relative_velocity_includes_spin_on_contact_radii() {
    let c = coeff(1.0, 10.0);
    let mut g = geom(1e-4);
    // Equal spins about z on both spheres: contact points move oppositely along y, so the
    // relative tangential velocity is −(c_i + c_j) ω (along −y for n = +x).
    g.wi = DVec3::new(0.0, 0.0, 2.0);
    g.wj = DVec3::new(0.0, 0.0, 2.0);
    let mut h = [0.0; 3];
    HertzHist::contact(&g, &c, Flags::default(), &mut h);
    let expected = -(g.ci + g.cj) * 2.0 * g.dt;
    assert!((h[1] - expected).abs() < 1e-15 * expected.abs() + 1e-25);
}

#[test]
fn no_history_is_damping_capped_by_coulomb() {
    type K = Kernel<normal::Hertz, tangential::NoHistory, rolling::Off, cohesion::Off>;
    assert_eq!(K::HIST, 0);
    let c = coeff(0.5, 0.5);
    let mut g = geom(1e-4);
    g.vr = DVec3::new(0.0, 1e-4, 0.0);
    let out = K::contact(&g, &c, Flags::default(), &mut []);
    let sq = (g.r_star * g.delta).sqrt();
    let beta = 0.5f64.ln() / (0.5f64.ln().powi(2) + PI * PI).sqrt();
    let gt = -2.0 * (5.0f64 / 6.0).sqrt() * beta * (8.0 * c.g_star * sq * g.m_star).sqrt();
    assert!((out.f_i.y + gt * 1e-4).abs() < 1e-12 * gt * 1e-4);
    g.vr = DVec3::new(0.0, 100.0, 0.0);
    let out = K::contact(&g, &c, Flags::default(), &mut []);
    assert!((out.f_i.y.abs() - 0.5 * out.f_i.x).abs() < 1e-12 * out.f_i.x);
    let flags = Flags {
        tangential_damping: false,
        ..Flags::default()
    };
    assert_eq!(K::contact(&g, &c, flags, &mut []).f_i.y, 0.0);
}

#[test]
fn cdt_torque_opposes_rolling_and_drops_torsion() {
    type K = Kernel<normal::Hertz, tangential::History, rolling::Cdt, cohesion::Off>;
    let c = coeff(1.0, 0.5);
    let mut g = geom(1e-4);
    g.wi = DVec3::new(3.0, 0.0, 4.0); // torsion 3 (along n = x), rolling 4 about z
    let out = K::contact(&g, &c, Flags::default(), &mut [0.0; 3]);
    let kn_delta = 4.0 / 3.0 * c.e_star * (g.r_star * g.delta).sqrt() * g.delta;
    let m = c.mu_r * kn_delta * g.r_star;
    // Direction of the full w_r is (0.6, 0, 0.8); the torsion part is removed from the torque.
    let tq_roll = out.t_i - (-g.ci * DVec3::X.cross(out.f_i - out.fn_total * DVec3::X));
    assert!((tq_roll - DVec3::new(0.0, 0.0, -0.8 * m)).length() < 1e-12 * m);
    let tq_roll_j = out.t_j - (-g.cj * DVec3::X.cross(out.f_i - out.fn_total * DVec3::X));
    assert!((tq_roll_j + tq_roll).length() < 1e-12 * m);
}

#[test]
fn epsd_spring_damper_and_cap() {
    type K = Kernel<normal::Hertz, tangential::NoHistory, rolling::Epsd, cohesion::Off>;
    let c = coeff(1.0, 0.5);
    let mut g = geom(1e-4);
    g.wi = DVec3::new(0.0, 0.0, 1.0);
    let mut h = [0.0; 3];
    let out = K::contact(&g, &c, Flags::default(), &mut h);
    let kn = 4.0 / 3.0 * c.e_star * (g.r_star * g.delta).sqrt();
    let kr = 2.25 * kn * c.mu_r * c.mu_r * g.r_star * g.r_star;
    assert!((h[2] + kr * g.dt).abs() < 1e-12 * kr * g.dt);
    let ir = 1.0 / (1.0 / g.inertia_i + 1.0 / g.inertia_j);
    let cr = c.eta_r * 2.0 * (ir * kr).sqrt();
    assert!((out.t_i.z - (-kr * g.dt - cr)).abs() < 1e-12 * cr);
    // Past the cap μ_r R* F_n: the torque sits on the cap and the dashpot is off.
    let mut h = [0.0, 0.0, -1.0];
    let out = K::contact(&g, &c, Flags::default(), &mut h);
    let cap = c.mu_r * g.r_star * kn * g.delta;
    assert!((out.t_i.z + cap).abs() < 1e-12 * cap);
}

#[test]
fn epsd3_is_epsd_with_the_given_stiffness_prefactor() {
    type K3 = Kernel<normal::HookeStiffness, tangential::NoHistory, rolling::Epsd, cohesion::Off>;
    let mut c = coeff(1.0, 0.5);
    c.kn = 5000.0;
    c.kt = 4000.0;
    c.roll_stiffness = 1.7;
    let mut g = geom(1e-4);
    g.wi = DVec3::new(0.0, 0.0, 1.0);
    let mut h = [0.0; 3];
    let out = K3::contact(&g, &c, Flags::default(), &mut h);
    // k_r = rollingStiffness · k_n μ_r² R*², the spring gains −k_r w_r dt, plus the dashpot.
    let kr = 1.7 * c.kn * c.mu_r * c.mu_r * g.r_star * g.r_star;
    assert!((h[2] + kr * g.dt).abs() < 1e-12 * kr * g.dt);
    let ir = 1.0 / (1.0 / g.inertia_i + 1.0 / g.inertia_j);
    let cr = c.eta_r * 2.0 * (ir * kr).sqrt();
    assert!((out.t_i.z - (-kr * g.dt - cr)).abs() < 1e-12 * cr);
    // On the cap μ_r R* F_n (F_n = k_n δ here, no normal damping at rest): no dashpot.
    let mut h = [0.0, 0.0, -1.0];
    let out = K3::contact(&g, &c, Flags::default(), &mut h);
    let cap = c.mu_r * g.r_star * c.kn * g.delta;
    assert!((out.t_i.z + cap).abs() < 1e-12 * cap);
    // The three names run one kernel, and the table gives epsd the prefactor 2.25.
    struct Name;
    impl Visitor for Name {
        type Output = &'static str;
        fn visit<K: ContactKernel>(self) -> &'static str {
            std::any::type_name::<K>()
        }
    }
    let mut m = ContactModel::hertz_history();
    m.rolling = RollingKind::Epsd;
    let epsd = m.dispatch(Name);
    m.rolling = RollingKind::Epsd3;
    assert_eq!(m.dispatch(Name), epsd);
    assert!(epsd.contains("rolling::Spring,"), "{epsd}");
    m.rolling = RollingKind::Epsd2;
    assert_eq!(m.dispatch(Name), epsd);
    assert_eq!(coeff(1.0, 0.5).roll_stiffness, 2.25);
}

#[test]
fn stiffness_models_use_the_given_coefficients() {
    let mut c = coeff(1.0, 0.5);
    (c.kn, c.kt, c.gamman, c.gammat) = (1.2e7, 9e6, 1.5e6, 1e6);
    let mut g = geom(1e-4);
    g.vr = DVec3::new(-0.3, 0.2, 0.0); // approaching, sliding along y
    let sq = (g.r_star * g.delta).sqrt();
    let no = normal::HertzStiffness::normal(&g, &c, -0.3, Flags::default(), &mut []);
    assert_eq!(no.kn, c.kn * sq);
    assert_eq!(no.kt, c.kt * sq);
    assert!((no.gamma_t - c.gammat * g.m_star * sq).abs() < 1e-12 * no.gamma_t);
    let f = c.kn * sq * g.delta + c.gamman * g.m_star * sq * 0.3;
    assert!((no.fn_contact - f).abs() < 1e-12 * f);
    (c.kn, c.kt, c.gamman, c.gammat) = (5000.0, 4000.0, 0.7, 0.4);
    let mut flags = Flags::default();
    let rel = normal::HookeStiffness::normal(&g, &c, -0.3, flags, &mut []);
    flags.absolute_damping = true;
    let abs = normal::HookeStiffness::normal(&g, &c, -0.3, flags, &mut []);
    assert_eq!(
        (rel.kn, rel.kt, abs.kn, abs.kt),
        (5000.0, 4000.0, 5000.0, 4000.0)
    );
    assert!((rel.fn_contact - (5000.0 * g.delta + 0.7 * g.m_star * 0.3)).abs() < 1e-12);
    assert!((abs.fn_contact - (5000.0 * g.delta + 0.7 * 0.3)).abs() < 1e-12);
    assert!((rel.gamma_t - 0.4 * g.m_star).abs() < 1e-15);
    assert_eq!(abs.gamma_t, 0.4);
    // limitForce: separating fast, the damping would pull; the force is clamped at 0.
    flags.limit_force = true;
    let lf = normal::HookeStiffness::normal(&g, &c, 10.0, flags, &mut []);
    assert_eq!(lf.fn_contact, 0.0);
}

#[test]
fn sjkr_area_is_the_intersection_circle() {
    let c = coeff(1.0, 0.5);
    let (ri, rj, delta) = (0.01, 0.006, 2e-4);
    let mut g = geom(delta);
    g.ri = ri;
    g.rj = rj;
    g.dist = ri + rj - delta;
    g.r_star = ri * rj / (ri + rj);
    // Radius of the intersection circle from the two sphere equations.
    let d = g.dist;
    let xa = (d * d + ri * ri - rj * rj) / (2.0 * d);
    let a2 = ri * ri - xa * xa;
    let f = cohesion::Sjkr::force(&g, &c, Flags::default());
    assert!((f - c.cohesion * PI * a2).abs() < 1e-9 * f);
    let f2 = cohesion::Sjkr2::force(&g, &c, Flags::default());
    assert!((f2 - c.cohesion * 2.0 * PI * delta * 2.0 * g.r_star).abs() < 1e-12 * f2);
    // Wall: circle of the sphere cut by the plane, and 2π δ r_i for sjkr2.
    g.rj = f64::INFINITY;
    g.r_star = ri;
    g.dist = ri - delta;
    let fw = cohesion::Sjkr::force(&g, &c, Flags::default());
    assert!((fw - c.cohesion * PI * (2.0 * ri * delta - delta * delta)).abs() < 1e-9 * fw);
    let fw2 = cohesion::Sjkr2::force(&g, &c, Flags::default());
    assert!((fw2 - c.cohesion * 2.0 * PI * delta * ri).abs() < 1e-12 * fw2);
}

#[test]
fn cohesion_pulls_and_tangential_reduce_changes_the_cap() {
    type K = Kernel<normal::Hertz, tangential::History, rolling::Off, cohesion::Sjkr2>;
    let c = coeff(1.0, 0.5);
    let g = geom(1e-4);
    let fe = 4.0 / 3.0 * c.e_star * (g.r_star * g.delta).sqrt() * g.delta;
    let fc = cohesion::Sjkr2::force(&g, &c, Flags::default());
    let mut h = [0.0, 1.0, 0.0];
    let out = K::contact(&g, &c, Flags::default(), &mut h);
    assert!((out.f_i.x - (fe - fc)).abs() < 1e-12 * fe);
    // Cap from the normal model's force alone (tangential_reduce off, LIGGGHTS default).
    assert!((out.f_i.y.abs() - 0.5 * fe).abs() < 1e-12 * fe);
    let flags = Flags {
        tangential_reduce: true,
        ..Flags::default()
    };
    let mut h = [0.0, 1.0, 0.0];
    let out = K::contact(&g, &c, flags, &mut h);
    assert!((out.f_i.y.abs() - 0.5 * (fe - fc).abs()).abs() < 1e-12 * fe);
}

#[test]
fn hooke_stiffness_and_hysteresis_branches() {
    let c = coeff(1.0, 0.5);
    let g = geom(1e-4);
    let k1 = normal::hooke_kn(&c, g.r_star, g.m_star);
    let sr = g.r_star.sqrt();
    let expected =
        16.0 / 15.0 * sr * c.e_star * (15.0 * g.m_star * 1.0 / (16.0 * sr * c.e_star)).powf(0.2);
    assert!((k1 - expected).abs() < 1e-12 * k1);
    type K = Kernel<normal::HookeHysteresis, tangential::NoHistory, rolling::Off, cohesion::Off>;
    assert_eq!(K::HIST, 1);
    let dlim = 3.0 / 2.0 * c.phi_f * 2.0 * g.r_star;
    let mut h = [0.0];
    // Loading: F = k1 δ, δ_max follows.
    let mut g1 = geom(1e-4);
    let f = K::contact(&g1, &c, Flags::default(), &mut h).f_i.x;
    assert!((f - k1 * 1e-4).abs() < 1e-12 * f);
    assert_eq!(h[0], 1e-4);
    // Unloading to half the overlap: F = k2 (δ − δ_max) + k1 δ_max.
    g1.delta = 0.5e-4;
    let k2 = k1 + 2.0 * k1 * 1e-4 / dlim;
    let f = K::contact(&g1, &c, Flags::default(), &mut h).f_i.x;
    let expected = k2 * (0.5e-4 - 1e-4) + k1 * 1e-4;
    assert!((f - expected).abs() < 1e-9 * k1 * 1e-4, "{f} vs {expected}");
    // Far below: the adhesive branch −kc δ.
    g1.delta = 1e-7;
    let f = K::contact(&g1, &c, Flags::default(), &mut h).f_i.x;
    // (The unloading line would give k2 (δ − δ_max) + k1 δ_max ≈ −0.27e-4 k1, far below −kc δ.)
    assert!(k2 * (1e-7 - 1e-4) + k1 * 1e-4 < -0.5 * k1 * 1e-7);
    assert!((f + 0.5 * k1 * 1e-7).abs() < 1e-9 * k1 * 1e-7, "{f}");
}

#[test]
fn swapping_the_pair_mirrors_the_contact() {
    type K = Kernel<normal::Hertz, tangential::History, rolling::Epsd2, cohesion::Sjkr>;
    let c = coeff(0.6, 0.4);
    let mut g = geom(2e-4);
    g.vr = DVec3::new(-0.1, 0.02, -0.03);
    g.wi = DVec3::new(1.0, -2.0, 0.5);
    g.wj = DVec3::new(-0.3, 0.7, 2.0);
    let mut hi = [1e-7, 2e-7, -1e-7, 1e-9, -2e-9, 3e-9];
    let mut hj: Vec<f64> = hi.iter().map(|v| -v).collect();
    let a = K::contact(&g, &c, Flags::default(), &mut hi);
    let mut s = g;
    s.n = -g.n;
    s.vr = -g.vr;
    s.wi = g.wj;
    s.wj = g.wi;
    let b = K::contact(&s, &c, Flags::default(), &mut hj);
    assert!((a.f_i + b.f_i).length() < 1e-12 * a.f_i.length());
    assert!((a.t_i - b.t_j).length() < 1e-12 * a.t_i.length());
    assert!((a.t_j - b.t_i).length() < 1e-12 * a.t_j.length());
    for k in 0..6 {
        assert!((hi[k] + hj[k]).abs() < 1e-20);
    }
}

/// `incremental_history`'s history is the force (3 values that change sign when i and j
/// swap) and two scalars (k_t and the normal force of the step before) that do not: the
/// scalars sit after the rolling vector, outside the odd part that a mirrored entry
/// negates.
#[test]
fn incremental_history_keeps_its_scalars_out_of_the_odd_part() {
    let mut m = ContactModel::hertz_history();
    m.tangential = TangentialKind::IncrementalHistory;
    assert_eq!((m.history_width(), m.history_odd()), (5, 3));
    m.rolling = RollingKind::Epsd2;
    assert_eq!((m.history_width(), m.history_odd()), (8, 6));
    // With the rolling spring between them, the scalars are read where they were
    // written: the tangential force of a loading-then-unloading sequence is the same with
    // and without rolling friction.
    type Inc = Kernel<normal::Hertz, tangential::IncrementalHistory, rolling::Off, cohesion::Off>;
    type IncRoll =
        Kernel<normal::Hertz, tangential::IncrementalHistory, rolling::Epsd2, cohesion::Off>;
    let c = coeff(0.5, 0.5);
    let (mut h, mut hr) = ([0.0; 5], [0.0; 8]);
    for (k, d) in [1e-5, 2e-5, 3e-5, 2.5e-5, 1.5e-5].into_iter().enumerate() {
        let mut g = geom(d);
        g.vr = DVec3::new(if k < 3 { -0.01 } else { 0.01 }, 0.02, 0.0);
        g.wi = DVec3::new(0.0, 0.0, 1.0);
        let a = Inc::contact(&g, &c, Flags::default(), &mut h);
        let b = IncRoll::contact(&g, &c, Flags::default(), &mut hr);
        assert_eq!(a.f_i, b.f_i, "step {k}");
    }
    // The unloading steps scaled the stored force by k_t/k_t,old (k_t ∝ √δ).
    assert!(h[3] > 0.0 && h[4] > 0.0, "{h:?}");
    assert_eq!((hr[6], hr[7]), (h[3], h[4]));
}

/// The kernels that serve several laws ([`rolling::Spring`], [`cohesion::Pull`]) give
/// each law's own force and torques, to the bit, when the model's flags name it; and the
/// model dispatches those names to them.
#[test]
fn shared_kernels_run_the_law_the_model_names() {
    struct Run<'a>(&'a Geom, &'a PairCoeff, Flags);
    impl Visitor for Run<'_> {
        type Output = (ContactForce, Vec<f64>);
        fn visit<K: ContactKernel>(self) -> (ContactForce, Vec<f64>) {
            let mut h = vec![1e-9; K::HIST];
            (K::contact(self.0, self.1, self.2, &mut h), h)
        }
    }
    fn own<K: ContactKernel>(g: &Geom, c: &PairCoeff) -> (ContactForce, Vec<f64>) {
        let mut h = vec![1e-9; K::HIST];
        (K::contact(g, c, Flags::default(), &mut h), h)
    }
    type H = normal::Hertz;
    type T = tangential::History;
    let c = coeff(0.6, 0.4);
    let mut g = geom(2e-4);
    g.vr = DVec3::new(-0.1, 0.02, -0.03);
    g.wi = DVec3::new(1.0, -2.0, 0.5);
    g.wj = DVec3::new(-0.3, 0.7, 2.0);
    let mut m = ContactModel::hertz_history();
    let cases: [(RollingKind, CohesionKind, (ContactForce, Vec<f64>)); 4] = [
        (
            RollingKind::Epsd,
            CohesionKind::Sjkr,
            own::<Kernel<H, T, rolling::Epsd, cohesion::Sjkr>>(&g, &c),
        ),
        (
            RollingKind::Epsd2,
            CohesionKind::Sjkr2,
            own::<Kernel<H, T, rolling::Epsd2, cohesion::Sjkr2>>(&g, &c),
        ),
        (
            RollingKind::Cdt,
            CohesionKind::Sjkr2,
            own::<Kernel<H, T, rolling::Cdt, cohesion::Sjkr2>>(&g, &c),
        ),
        (
            RollingKind::Off,
            CohesionKind::Sjkr,
            own::<Kernel<H, T, rolling::Off, cohesion::Sjkr>>(&g, &c),
        ),
    ];
    for (rolling, cohesion, want) in cases {
        (m.rolling, m.cohesion) = (rolling, cohesion);
        let got = m.dispatch(Run(&g, &c, m.kernel_flags()));
        assert_eq!(got, want, "{rolling:?} {cohesion:?}");
    }
    // The laws differ on this contact, so the comparison can tell them apart.
    let sjkr = own::<Kernel<H, T, rolling::Epsd, cohesion::Sjkr>>(&g, &c).0;
    let sjkr2 = own::<Kernel<H, T, rolling::Epsd, cohesion::Sjkr2>>(&g, &c).0;
    let epsd2 = own::<Kernel<H, T, rolling::Epsd2, cohesion::Sjkr>>(&g, &c).0;
    assert_ne!(sjkr.fn_total, sjkr2.fn_total);
    assert_ne!(sjkr.t_i, epsd2.t_i);
}
