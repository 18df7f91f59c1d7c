//! Material properties (LIGGGHTS `fix property/global`) and their mixing into one table of
//! per-type-pair contact coefficients, computed once before a run.

use crate::error::{check, Error, Result};

/// Material properties as a LIGGGHTS script gives them: per type (`peratomtype`), per type
/// pair (`peratomtypepair`, row-major `ntypes × ntypes`, symmetric) and scalars. Types are
/// 1-based in scripts; index `t - 1` here.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Materials {
    /// Number of atom (material) types.
    pub ntypes: usize,
    /// `youngsModulus` per type.
    pub youngs_modulus: Vec<f64>,
    /// `poissonsRatio` per type.
    pub poissons_ratio: Vec<f64>,
    /// `coefficientRestitution` per type pair.
    pub restitution: Vec<f64>,
    /// `coefficientFriction` per type pair.
    pub friction: Vec<f64>,
    /// `coefficientRollingFriction` per type pair (rolling models only).
    pub rolling_friction: Vec<f64>,
    /// `coefficientRollingViscousDamping` per type pair (epsd only).
    pub rolling_viscous_damping: Vec<f64>,
    /// `cohesionEnergyDensity` per type pair (sjkr, sjkr2 only).
    pub cohesion_energy_density: Vec<f64>,
    /// `characteristicVelocity` scalar (hooke models only).
    pub characteristic_velocity: Option<f64>,
    /// `coefficientAdhesionStiffness` per type pair (hooke/hysteresis: kc = value · k1).
    pub adhesion_stiffness: Vec<f64>,
    /// `coefficientPlasticityDepth` per type pair (hooke/hysteresis).
    pub plasticity_depth: Vec<f64>,
    /// `coefficientMaxElasticStiffness` per type pair (hooke/hysteresis: k2max = value · k1).
    pub max_elastic_stiffness: Vec<f64>,
    /// `kn` per type pair (`hertz/stiffness`, `hooke/stiffness`).
    pub kn: Vec<f64>,
    /// `kt` per type pair (stiffness models).
    pub kt: Vec<f64>,
    /// `gamman` per type pair (stiffness models; multiplied by m*).
    pub gamman: Vec<f64>,
    /// `gammat` per type pair (stiffness models; multiplied by m*).
    pub gammat: Vec<f64>,
    /// `gamman_abs` per type pair (`hooke/stiffness` with `absolute_damping on`).
    pub gamman_abs: Vec<f64>,
    /// `gammat_abs` per type pair (`hooke/stiffness` with `absolute_damping on`).
    pub gammat_abs: Vec<f64>,
    /// `workOfAdhesion` per type pair (`model jkr`), in J/m².
    pub work_of_adhesion: Vec<f64>,
    /// `resolutionJKR` scalar (`model jkr`): the step of the fork's table of contact
    /// radii. rdem solves the contact radius exactly ([`super::jkr`]), so the value is
    /// checked (> 0) and not otherwise used.
    pub resolution_jkr: Option<f64>,
    /// `rollingStiffness` scalar: the prefactor of the epsd3 rolling stiffness (the
    /// LIGGGHTS 3.8 manual calls it `coeffRollingStiffness`, its code reads this name).
    pub rolling_stiffness: Option<f64>,
    /// The properties of `model hysteretic/nonlinear1|2` (LIGGGHTS-INL) that were given.
    pub hysteretic: HystereticProperties,
    /// The `cohesion bond` coefficients that were given.
    pub bond: crate::bond::BondCoefficients,
    /// The `cohesion bond/nonlinear` coefficients that were given (its own property
    /// names, [`crate::bond::Law::property`]).
    pub bond_nonlinear: crate::bond::BondCoefficients,
    /// The liquid-bridge properties that were given (`cohesion easo/capillary/viscous`).
    pub liquid: LiquidProperties,
}

/// The properties of `cohesion easo/capillary/viscous`, as a script gives them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LiquidProperties {
    /// `surfaceLiquidContentInitial` scalar: every particle's liquid content at the start.
    pub content_initial: Option<f64>,
    /// `surfaceTension` scalar (N/m).
    pub surface_tension: Option<f64>,
    /// `fluidViscosity` scalar (Pa s).
    pub fluid_viscosity: Option<f64>,
    /// `contactAngle` per type, in degrees.
    pub contact_angle: Vec<f64>,
    /// `minSeparationDistanceRatio` scalar.
    pub min_separation: Option<f64>,
    /// `maxSeparationDistanceRatio` scalar.
    pub max_separation: Option<f64>,
}

/// The per-type-pair properties of `model hysteretic/nonlinear1|2` (LIGGGHTS-INL), as a
/// script gives them ([`super::hysteretic`]); with these laws `coefficientAdhesionStiffness`
/// and `coefficientPlasticityDepth` are read too.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HystereticProperties {
    /// `LoadingStiffness`.
    pub loading_stiffness: Vec<f64>,
    /// `UnloadingStiffness`.
    pub unloading_stiffness: Vec<f64>,
    /// `pullOffForce`.
    pub pull_off_force: Vec<f64>,
    /// `alphaCustom` (α).
    pub alpha: Vec<f64>,
    /// `cinCustom` (C).
    pub cin: Vec<f64>,
    /// `aoneCustom` (A₁).
    pub a1: Vec<f64>,
    /// `atwoCustom` (A₂).
    pub a2: Vec<f64>,
    /// `athreeCustom` (A₃).
    pub a3: Vec<f64>,
    /// `kcinCustom`.
    pub kcin: Vec<f64>,
}

impl HystereticProperties {
    /// The mixed coefficients of every type pair for `n` types, checked; `variant` is 1 or
    /// 2 (nonlinear2 divides by C, which must then be > 0). `rest` is the restitution
    /// table, `kc_ratio` `coefficientAdhesionStiffness`.
    fn coeffs(
        &self,
        n: usize,
        variant: u8,
        rest: &[f64],
        kc_ratio: &[f64],
    ) -> Result<Vec<super::hysteretic::HystereticCoeff>> {
        let t = |name, v: &Vec<f64>, ok: fn(f64) -> bool, range| {
            pair_table(name, v, n, true, ok, range)
        };
        let ge0: fn(f64) -> bool = |v| v >= 0.0;
        let gt0: fn(f64) -> bool = |v| v > 0.0;
        let any: fn(f64) -> bool = |v| v.is_finite();
        let loading = t(
            "LoadingStiffness",
            &self.loading_stiffness,
            ge0,
            "must be >= 0",
        )?;
        t(
            "UnloadingStiffness",
            &self.unloading_stiffness,
            ge0,
            "must be >= 0",
        )?;
        let pull = t("pullOffForce", &self.pull_off_force, any, "must be finite")?;
        let alpha = t("alphaCustom", &self.alpha, gt0, "must be > 0")?;
        let cin = if variant == 2 {
            t(
                "cinCustom",
                &self.cin,
                gt0,
                "must be > 0 (hysteretic/nonlinear2 divides by it)",
            )?
        } else {
            t("cinCustom", &self.cin, ge0, "must be >= 0")?
        };
        let a1 = t("aoneCustom", &self.a1, ge0, "must be >= 0")?;
        let a2 = t("atwoCustom", &self.a2, gt0, "must be > 0")?;
        let a3 = t("athreeCustom", &self.a3, gt0, "must be > 0")?;
        let kcin = t("kcinCustom", &self.kcin, ge0, "must be >= 0")?;
        let pi2 = std::f64::consts::PI * std::f64::consts::PI;
        Ok((0..n * n)
            .map(|k| {
                let ln_e = rest[k].ln();
                super::hysteretic::HystereticCoeff {
                    alpha: alpha[k],
                    cin: cin[k],
                    a1: a1[k],
                    a2: a2[k],
                    a3: a3[k],
                    kc_adh: kcin[k] * a2[k],
                    pull_off: pull[k],
                    limitable: kc_ratio[k] * loading[k] == 0.0 && pull[k] == 0.0,
                    // e = 1 (ln e = 0) gives no damping, as the fork's formula does.
                    damp: 4.0 / (1.0 + pi2 / (ln_e * ln_e)),
                }
            })
            .collect())
    }
}

impl LiquidProperties {
    /// A scalar property that must be given.
    fn need(v: Option<f64>, name: &'static str) -> Result<f64> {
        v.ok_or_else(|| Error::Invalid {
            what: name,
            reason: format!(
                "cohesion easo/capillary/viscous needs fix property/global {name} scalar"
            ),
        })
    }

    /// The initial liquid content (checked: ≥ 0).
    pub fn initial_content(&self) -> Result<f64> {
        let v = Self::need(self.content_initial, "surfaceLiquidContentInitial")?;
        check("surfaceLiquidContentInitial", v, v >= 0.0, "must be >= 0")
    }

    /// The bridge's neighbor-distance factor, as LIGGGHTS 3.8 registers it:
    /// 1.1 · maxSeparationDistanceRatio (checked: the ratio ≥ 1).
    pub fn contact_distance_factor(&self) -> Result<f64> {
        let v = Self::need(self.max_separation, "maxSeparationDistanceRatio")?;
        check(
            "maxSeparationDistanceRatio",
            v,
            v >= 1.0,
            "must be >= 1 (LIGGGHTS 3.8 requires it)",
        )?;
        Ok(1.1 * v)
    }

    /// The mixed coefficients of types `a`, `b` (0-based) for `ntypes` types.
    fn coeff(&self, a: usize, b: usize, ntypes: usize) -> Result<super::liquid::LiquidCoeff> {
        let gamma = Self::need(self.surface_tension, "surfaceTension")?;
        let visc = Self::need(self.fluid_viscosity, "fluidViscosity")?;
        let min = Self::need(self.min_separation, "minSeparationDistanceRatio")?;
        check("surfaceTension", gamma, gamma >= 0.0, "must be >= 0")?;
        check("fluidViscosity", visc, visc >= 0.0, "must be >= 0")?;
        check("minSeparationDistanceRatio", min, min > 0.0, "must be > 0")?;
        let max = self.contact_distance_factor()? / 1.1;
        let angles = &self.contact_angle;
        if angles.len() != ntypes {
            return Err(Error::Invalid {
                what: "contactAngle",
                reason: format!(
                    "cohesion easo/capillary/viscous needs fix property/global contactAngle peratomtype with one value per type ({ntypes}), got {}",
                    angles.len()
                ),
            });
        }
        for &t in angles {
            check(
                "contactAngle",
                t,
                (0.0..=180.0).contains(&t),
                "must be in [0, 180] degrees",
            )?;
        }
        let rad = |t: f64| t * std::f64::consts::PI / 180.0;
        Ok(super::liquid::LiquidCoeff {
            surface_tension: gamma,
            viscosity: visc,
            angle: 0.5 * rad(angles[a]) * rad(angles[b]),
            min_sep: min,
            max_sep: max,
            ln_inv_min: (1.0 / min).ln(),
        })
    }
}

impl Materials {
    /// Materials for `ntypes` types with every type pair given the same e and μ: the common
    /// one-material case.
    pub fn uniform(
        ntypes: usize,
        youngs: f64,
        poisson: f64,
        restitution: f64,
        friction: f64,
    ) -> Self {
        let nn = ntypes * ntypes;
        Self {
            ntypes,
            youngs_modulus: vec![youngs; ntypes],
            poissons_ratio: vec![poisson; ntypes],
            restitution: vec![restitution; nn],
            friction: vec![friction; nn],
            ..Default::default()
        }
    }

    /// Sets a per-pair table to one value for every pair.
    pub fn fill_pairs(table: &mut Vec<f64>, ntypes: usize, value: f64) {
        *table = vec![value; ntypes * ntypes];
    }
}

/// Mixed coefficients of one type pair (or particle type × wall type).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairCoeff {
    /// Effective Young's modulus E*.
    pub e_star: f64,
    /// Effective shear modulus G*.
    pub g_star: f64,
    /// β = ln e / √(ln²e + π²) (≤ 0).
    pub beta: f64,
    /// ln²e / (ln²e + π²), used by the Hooke damping.
    pub ln_e_ratio: f64,
    /// Coulomb friction coefficient μ.
    pub mu: f64,
    /// Rolling friction coefficient μ_r.
    pub mu_r: f64,
    /// Rolling viscous damping η_r (epsd).
    pub eta_r: f64,
    /// Cohesion energy density (J/m³).
    pub cohesion: f64,
    /// Characteristic impact velocity (hooke).
    pub vc: f64,
    /// Adhesion stiffness ratio kc/k1 (hooke/hysteresis).
    pub kc_ratio: f64,
    /// Plasticity depth φ_f (hooke/hysteresis).
    pub phi_f: f64,
    /// Maximum unloading stiffness ratio k2max/k1 (hooke/hysteresis).
    pub k2max_ratio: f64,
    /// Stiffness models: the given normal stiffness `kn`.
    pub kn: f64,
    /// Stiffness models: the given tangential stiffness `kt`.
    pub kt: f64,
    /// Stiffness models: the given normal damping (`gamman`, or `gamman_abs` with
    /// `absolute_damping on`).
    pub gamman: f64,
    /// Stiffness models: the given tangential damping (`gammat` or `gammat_abs`).
    pub gammat: f64,
    /// Rolling stiffness prefactor: 2.25 for epsd, `rollingStiffness` for epsd3.
    pub roll_stiffness: f64,
    /// −2√(5/6) β √(2E*): Hertz γ_n = this × √(√(R*δ) m*).
    pub hertz_damp_n: f64,
    /// −2√(5/6) β √(8G*): Hertz γ_t = this × √(√(R*δ) m*).
    pub hertz_damp_t: f64,
    /// Liquid-bridge coefficients (`cohesion easo/capillary/viscous`).
    pub liquid: super::liquid::LiquidCoeff,
    /// `model jkr`: the work of adhesion W.
    pub jkr_w: f64,
    /// `model jkr`: 9πW/(2E*), so that a₀³ = this × R*² ([`super::jkr::Scales`]).
    pub jkr_k: f64,
    /// `model hysteretic/nonlinear1|2`: their coefficients.
    pub hysteretic: super::hysteretic::HystereticCoeff,
}

/// Which optional properties a contact model needs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Needs {
    /// The tangential model is `off`: no `coefficientFriction` is needed.
    pub no_tangential: bool,
    /// Rolling friction coefficient.
    pub rolling_friction: bool,
    /// Rolling viscous damping.
    pub rolling_damping: bool,
    /// Cohesion energy density.
    pub cohesion: bool,
    /// The liquid-bridge properties (`cohesion easo/capillary/viscous`).
    pub liquid: bool,
    /// Characteristic velocity.
    pub characteristic_velocity: bool,
    /// Hysteresis coefficients.
    pub hysteresis: bool,
    /// The properties of `model hysteretic/nonlinear1|2`: `Some(1)` or `Some(2)`.
    pub hysteretic_nonlinear: Option<u8>,
    /// The epsd3 rolling stiffness prefactor.
    pub rolling_stiffness: bool,
    /// `workOfAdhesion` and `resolutionJKR` (`model jkr`).
    pub work_of_adhesion: bool,
    /// LIGGGHTS-PFM's `model jkr`: the work of adhesion is twice `cohesionEnergyDensity`.
    pub jkr_pfm: bool,
    /// A stiffness model (`hertz/stiffness`, `hooke/stiffness`): `Some(absolute_damping)`.
    /// It needs `kn`, `kt` and the damping tables (`gamman_abs`, `gammat_abs` with
    /// absolute damping, else `gamman`, `gammat`), and not Young's modulus, Poisson's
    /// ratio or the coefficient of restitution.
    pub stiffness: Option<bool>,
}

/// Mixed coefficients for every ordered type pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CoeffTable {
    ntypes: usize,
    coeffs: Vec<PairCoeff>,
    /// `model jkr`: the largest δ_c/R*^⅓ of the type pairs (0 without it).
    neck: f64,
}

/// A per-type-pair table `table` for `n` types, checked (length, `ok`, symmetry); zeros
/// when not `needed`.
pub(crate) fn pair_table(
    name: &'static str,
    table: &[f64],
    n: usize,
    needed: bool,
    ok: impl Fn(f64) -> bool,
    range: &'static str,
) -> Result<Vec<f64>> {
    if !needed {
        return Ok(vec![0.0; n * n]);
    }
    if table.is_empty() {
        return Err(Error::Invalid {
            what: name,
            reason: format!(
                "the contact model needs it: define fix ID all property/global {name} peratomtypepair {n} followed by {} values",
                n * n
            ),
        });
    }
    if table.len() != n * n {
        return Err(Error::Invalid {
            what: name,
            reason: format!(
                "needs {} values (one per type pair for {n} types), got {}",
                n * n,
                table.len()
            ),
        });
    }
    for a in 0..n {
        for b in 0..n {
            let v = table[a * n + b];
            check(name, v, ok(v), range)?;
            if v != table[b * n + a] {
                return Err(Error::Invalid {
                    what: name,
                    reason: format!(
                        "must be symmetric: value for types {} {} is {v}, for {} {} it is {}",
                        a + 1,
                        b + 1,
                        b + 1,
                        a + 1,
                        table[b * n + a]
                    ),
                });
            }
        }
    }
    Ok(table.to_vec())
}

impl CoeffTable {
    /// Validates `m` and mixes it: E* and G* from the per-type E and ν, the rest per pair.
    pub fn new(m: &Materials, needs: Needs) -> Result<Self> {
        let n = m.ntypes;
        if n == 0 {
            return Err(Error::Invalid {
                what: "materials",
                reason: "at least one atom type is needed".into(),
            });
        }
        let elastic = needs.stiffness.is_none();
        if elastic {
            Self::check_elastic(m)?;
        }
        let rest = pair_table(
            "coefficientRestitution",
            &m.restitution,
            n,
            elastic,
            |e| e > 0.0 && e <= 1.0,
            "must be in (0, 1]",
        )?;
        let fric = pair_table(
            "coefficientFriction",
            &m.friction,
            n,
            !needs.no_tangential,
            |v| v >= 0.0,
            "must be >= 0",
        )?;
        let rf = pair_table(
            "coefficientRollingFriction",
            &m.rolling_friction,
            n,
            needs.rolling_friction,
            |v| v >= 0.0,
            "must be >= 0",
        )?;
        let rd = pair_table(
            "coefficientRollingViscousDamping",
            &m.rolling_viscous_damping,
            n,
            needs.rolling_damping,
            |v| v >= 0.0,
            "must be >= 0",
        )?;
        let coh = pair_table(
            "cohesionEnergyDensity",
            &m.cohesion_energy_density,
            n,
            needs.cohesion,
            |v| v >= 0.0,
            "must be >= 0",
        )?;
        let hyst_nl = needs.hysteretic_nonlinear;
        let kc = pair_table(
            "coefficientAdhesionStiffness",
            &m.adhesion_stiffness,
            n,
            needs.hysteresis || hyst_nl.is_some(),
            |v| v >= 0.0,
            "must be >= 0",
        )?;
        let phi = pair_table(
            "coefficientPlasticityDepth",
            &m.plasticity_depth,
            n,
            needs.hysteresis || hyst_nl.is_some(),
            |v| v > 0.0,
            "must be > 0",
        )?;
        let k2 = pair_table(
            "coefficientMaxElasticStiffness",
            &m.max_elastic_stiffness,
            n,
            needs.hysteresis,
            |v| v > 1.0,
            "must be > 1",
        )?;
        let wa = pair_table(
            "workOfAdhesion",
            &m.work_of_adhesion,
            n,
            needs.work_of_adhesion,
            |v| v >= 0.0,
            "must be >= 0 (0: Hertz's contact for the type pair, as the forks do)",
        )?;
        if needs.work_of_adhesion {
            let v = m.resolution_jkr.ok_or_else(|| Error::Invalid {
                what: "resolutionJKR",
                reason: "model jkr needs fix property/global resolutionJKR scalar (the fork's \
                         table step; rdem solves the contact radius exactly and only checks it)"
                    .into(),
            })?;
            check("resolutionJKR", v, v > 0.0, "must be > 0")?;
        }
        // The work of adhesion W of the JKR laws: PFM's is twice its surface energy.
        let w_jkr: Vec<f64> = if needs.jkr_pfm {
            coh.iter().map(|g| 2.0 * g).collect()
        } else {
            wa
        };
        let stiff = needs.stiffness.is_some();
        let abs = needs.stiffness == Some(true);
        // A zero kn is LIGGGHTS 3.8's "no normal spring" for type pairs that never touch
        // (walls of types 2 and 3 in a script's table); it runs them, and so does rdem.
        // LIGGGHTS 3.8 also runs a negative kn (an attractive spring): rdem refuses it.
        let kn = pair_table("kn", &m.kn, n, stiff, |v| v >= 0.0, "must be >= 0")?;
        let kt = pair_table("kt", &m.kt, n, stiff, |v| v >= 0.0, "must be >= 0")?;
        let (gn_name, gn_table, gt_name, gt_table) = if abs {
            ("gamman_abs", &m.gamman_abs, "gammat_abs", &m.gammat_abs)
        } else {
            ("gamman", &m.gamman, "gammat", &m.gammat)
        };
        let gn = pair_table(gn_name, gn_table, n, stiff, |v| v >= 0.0, "must be >= 0")?;
        let gt = pair_table(gt_name, gt_table, n, stiff, |v| v >= 0.0, "must be >= 0")?;
        let roll_stiffness = if needs.rolling_stiffness {
            let v = m.rolling_stiffness.ok_or_else(|| Error::Invalid {
                what: "rollingStiffness",
                reason: "rolling_friction epsd3 needs fix property/global rollingStiffness scalar \
                         (the name LIGGGHTS 3.8 reads; its manual says coeffRollingStiffness)"
                    .into(),
            })?;
            check("rollingStiffness", v, v >= 0.0, "must be >= 0")?
        } else {
            2.25
        };
        let vc = if needs.characteristic_velocity {
            let v = m.characteristic_velocity.ok_or_else(|| Error::Invalid {
                what: "characteristicVelocity",
                reason: "the hooke models need fix property/global characteristicVelocity scalar"
                    .into(),
            })?;
            check("characteristicVelocity", v, v > 0.0, "must be > 0")?
        } else {
            0.0
        };
        let hyst = match hyst_nl {
            Some(variant) => m.hysteretic.coeffs(n, variant, &rest, &kc)?,
            None => vec![Default::default(); n * n],
        };
        let mut coeffs = Vec::with_capacity(n * n);
        for a in 0..n {
            for b in 0..n {
                let (e_star, g_star) = if elastic {
                    let (ea, eb) = (m.youngs_modulus[a], m.youngs_modulus[b]);
                    let (na, nb) = (m.poissons_ratio[a], m.poissons_ratio[b]);
                    (
                        1.0 / ((1.0 - na * na) / ea + (1.0 - nb * nb) / eb),
                        1.0 / (2.0 * (2.0 - na) * (1.0 + na) / ea
                            + 2.0 * (2.0 - nb) * (1.0 + nb) / eb),
                    )
                } else {
                    (0.0, 0.0)
                };
                let k = a * n + b;
                // Without a restitution table (stiffness models) ln e = 0: β = 0.
                let ln_e = if elastic { rest[k].ln() } else { 0.0 };
                let beta =
                    ln_e / (ln_e * ln_e + std::f64::consts::PI * std::f64::consts::PI).sqrt();
                let pi2 = std::f64::consts::PI * std::f64::consts::PI;
                let liquid = if needs.liquid {
                    m.liquid.coeff(a, b, n)?
                } else {
                    Default::default()
                };
                coeffs.push(PairCoeff {
                    e_star,
                    g_star,
                    beta,
                    ln_e_ratio: ln_e * ln_e / (ln_e * ln_e + pi2),
                    mu: fric[k],
                    mu_r: rf[k],
                    eta_r: rd[k],
                    cohesion: coh[k],
                    vc,
                    kc_ratio: kc[k],
                    phi_f: phi[k],
                    k2max_ratio: k2[k],
                    kn: kn[k],
                    kt: kt[k],
                    gamman: gn[k],
                    gammat: gt[k],
                    roll_stiffness,
                    hertz_damp_n: -2.0 * (5.0f64 / 6.0).sqrt() * beta * (2.0 * e_star).sqrt(),
                    hertz_damp_t: -2.0 * (5.0f64 / 6.0).sqrt() * beta * (8.0 * g_star).sqrt(),
                    liquid,
                    jkr_w: w_jkr[k],
                    jkr_k: 4.5 * std::f64::consts::PI * w_jkr[k] / e_star,
                    hysteretic: hyst[k],
                });
            }
        }
        // δ_c = a₀²/(2·6^⅓R*) with a₀³ = kR*², so δ_c/R*^⅓ = k^⅔/(2·6^⅓), largest for
        // the largest k (a slight overestimate, rounding aside, is harmless: a reach).
        let neck = coeffs
            .iter()
            .filter(|c| needs.work_of_adhesion && c.jkr_w > 0.0)
            .map(|c| super::jkr::Scales::of(c, 1.0).delta_c * (1.0 + 1e-12))
            .fold(0.0, f64::max);
        Ok(Self {
            ntypes: n,
            coeffs,
            neck,
        })
    }

    /// Checks the per-type Young's modulus and Poisson's ratio.
    fn check_elastic(m: &Materials) -> Result<()> {
        let n = m.ntypes;
        for (name, v) in [
            ("youngsModulus", &m.youngs_modulus),
            ("poissonsRatio", &m.poissons_ratio),
        ] {
            if v.len() != n {
                return Err(Error::Invalid {
                    what: name,
                    reason: format!("needs one value per type ({n}), got {}", v.len()),
                });
            }
        }
        for &e in &m.youngs_modulus {
            check("youngsModulus", e, e > 0.0, "must be > 0")?;
        }
        // LIGGGHTS 3.8's range, measured: 0 and 0.5 run (0.5, the incompressible limit,
        // gives E* = 2E/3 and a finite G*), -1e-9 and 0.50000001 stop with
        // "0 <= poissonsRatio <= 0.5 required".
        for &nu in &m.poissons_ratio {
            check(
                "poissonsRatio",
                nu,
                (0.0..=0.5).contains(&nu),
                "must be in [0, 0.5], as LIGGGHTS 3.8 requires",
            )?;
        }
        Ok(())
    }

    /// Number of types.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    /// Coefficients of type `ti` (1-based) with every type: entry `tj − 1` is `(ti, tj)`.
    #[inline(always)]
    pub fn row(&self, ti: u32) -> &[PairCoeff] {
        let n = self.ntypes;
        &self.coeffs[(ti as usize - 1) * n..ti as usize * n]
    }

    /// Every type pair's coefficients (row-major).
    pub fn all(&self) -> &[PairCoeff] {
        &self.coeffs
    }

    /// The longest JKR neck for contacts of effective radius up to `r_star`: the largest
    /// δ_c over the type pairs (δ_c grows as R*^⅓; 0 without `model jkr`).
    #[inline]
    pub fn neck_reach(&self, r_star: f64) -> f64 {
        if self.neck == 0.0 {
            0.0
        } else {
            self.neck * r_star.cbrt()
        }
    }

    /// Coefficients of the 1-based type pair `(ti, tj)`.
    #[inline(always)]
    pub fn get(&self, ti: u32, tj: u32) -> &PairCoeff {
        &self.coeffs[(ti as usize - 1) * self.ntypes + (tj as usize - 1)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mixing_same_material() {
        let m = Materials::uniform(1, 5e6, 0.45, 0.3, 0.5);
        let t = CoeffTable::new(&m, Needs::default()).unwrap();
        let c = t.get(1, 1);
        assert!((c.e_star - 5e6 / (2.0 * (1.0 - 0.45 * 0.45))).abs() < 1e-6);
        assert!((c.g_star - 5e6 / (4.0 * 1.55 * 1.45)).abs() < 1e-6);
        let b = 0.3f64.ln() / (0.3f64.ln().powi(2) + std::f64::consts::PI.powi(2)).sqrt();
        assert!((c.beta - b).abs() < 1e-15);
    }

    #[test]
    fn bad_materials_are_refused() {
        let ok = Materials::uniform(1, 5e6, 0.3, 0.5, 0.5);
        assert!(CoeffTable::new(&ok, Needs::default()).is_ok());
        let mut m = ok.clone();
        m.poissons_ratio = vec![0.5];
        assert!(CoeffTable::new(&m, Needs::default()).is_ok());
        m.poissons_ratio = vec![0.0];
        assert!(CoeffTable::new(&m, Needs::default()).is_ok());
        m.poissons_ratio = vec![0.500_000_01];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        m.poissons_ratio = vec![-1e-9];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let mut m = ok.clone();
        m.poissons_ratio = vec![-1.0];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let mut m = ok.clone();
        m.youngs_modulus = vec![0.0];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let mut m = ok.clone();
        m.restitution = vec![0.0];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let mut m = ok.clone();
        m.restitution = vec![1.1];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let mut m = ok.clone();
        m.friction = vec![0.5, 0.5];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
        let needs = Needs {
            rolling_friction: true,
            ..Default::default()
        };
        assert!(CoeffTable::new(&ok, needs).is_err());
        let needs = Needs {
            characteristic_velocity: true,
            ..Default::default()
        };
        assert!(CoeffTable::new(&ok, needs).is_err());
        let mut m = Materials::uniform(2, 5e6, 0.3, 0.5, 0.5);
        m.friction = vec![0.1, 0.2, 0.3, 0.4];
        assert!(CoeffTable::new(&m, Needs::default()).is_err());
    }
}
