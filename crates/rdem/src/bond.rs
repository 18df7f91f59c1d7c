//! `cohesion bond`: the parallel-bond model of Potyondy & Cundall (2004) as LIGGGHTS-INL
//! documents it, for particle–particle bonds (in `pair_style gran`) and particle–wall
//! bonds (in `fix wall/gran`).
//!
//! A bond is created with zero load between two particles closer than
//! `createDistanceBond` (centre distance; a wall counts as a mirror particle, so twice the
//! distance to the wall), at step `tsCreateBond` or, with `createBondAlways on`, at any
//! step. It is a cylinder of radius r_b = `radiusMultiplierBond` · min(r_i, r_j) (a wall
//! bond: r_i), with A = π r_b², J = π r_b⁴/2, I = π r_b⁴/4, and carries
//!
//! - a normal force F_n = k_n A (d₀ − d) along the pair, from the distance d₀ at creation
//!   (explicit);
//! - a shear force, a twisting torque and a bending torque that grow by
//!   −k_t A v_t dt, −k_t J ω_n dt and −k_n I ω_t dt (incremental; v_t is the relative
//!   tangential velocity at the bond's centre, ω = ω_i − ω_j split along and across the
//!   pair) and turn with the pair: every step the stored vectors are brought into the
//!   current frame (shear force and bending torque projected onto the plane normal to the
//!   pair and rescaled to their length, twisting torque onto the pair's axis).
//!
//! It breaks when the centre distance exceeds `maxDistanceBond`, or with `stressBreak on`
//! when σ = |F_n|/A + |T_t| r_b/I exceeds `maxSigmaBond` (times `ratioTensionCompression`
//! in tension when that switch is on) or τ = |F_t|/A + |T_n| r_b/J exceeds `maxTauBond`
//! (plus sign(d₀ − d) |F_n|/A tan φ with `druckerPrager on`). Damping
//! (`dampingBond`, default on) subtracts α |F_k| sign(v_k) from each component of each
//! force and torque, against the component of the matching relative velocity;
//! `dissipationBond` relaxes each of them by dt/τ per step.
//!
//! A second law, `cohesion bond/nonlinear`, lives in [`nonlinear`]; the table
//! ([`BondTable`]) knows its law ([`Law`]) and the law its history layout ([`Layout`]),
//! and what both laws share of a bonded pair's geometry is one `Section`.
//!
//! The history of a bond lives in the contact history of its pair (or, for a wall, in
//! the particle's wall history), so it survives re-neighboring, sorting, periodic wrap and
//! migration like any contact history. Layout: [`VEC`] values that change sign when the
//! pair's roles swap (shear force, twisting and bending torque on i), then the contact
//! model's own values, then the flag and d₀ (and, for walls, the anchor point).
//!
//! Where this differs from LIGGGHTS-INL's code (on purpose, each a bug there by our
//! reading): the wall bond's shear velocity uses the full lever arm (the anchor lies at
//! distance d from the centre; INL takes half of ω_i), the bending torque turns with the
//! pair (INL projects it onto the current bending rotation rate, and skips its update
//! when that is zero), and a bond stretched beyond the neighbor reach (possible only with
//! `tensionStress off`) breaks instead of silently disappearing from the list.

pub mod nonlinear;

use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;

use crate::contact::materials::pair_table;
use crate::error::{check, Error, Result};

/// History values that flip sign when i and j swap: F_t, T_n, T_t (3 each).
pub const VEC: usize = 9;
/// Trailing history values of a pair bond: flag (0 = none, 1 = bonded), d₀.
pub const PAIR_TAIL: usize = 2;
/// Trailing history values of a wall bond: flag, d₀, anchor point (3).
pub const WALL_TAIL: usize = 5;

/// The law of a bond: `cohesion bond` or `cohesion bond/nonlinear`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Law {
    /// `cohesion bond`: the parallel bond (this module).
    #[default]
    Parallel,
    /// `cohesion bond/nonlinear` ([`nonlinear`]).
    Nonlinear,
}

/// Where a bond's values sit in a pair's (or a wall contact's) history: `vec` values that
/// change sign when i and j swap come first, the contact law's values next, and a tail
/// last, starting with the flag and d₀ (a wall's tail then holds the anchor point).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Leading values that flip sign when i and j swap.
    pub vec: usize,
    /// Trailing values of a pair bond.
    pub pair_tail: usize,
    /// Trailing values of a wall bond.
    pub wall_tail: usize,
}

impl Law {
    /// The history layout of this law.
    pub const fn layout(self) -> Layout {
        match self {
            Law::Parallel => Layout {
                vec: VEC,
                pair_tail: PAIR_TAIL,
                wall_tail: WALL_TAIL,
            },
            Law::Nonlinear => Layout {
                vec: nonlinear::VEC,
                pair_tail: PAIR_TAIL + nonlinear::EXTRA,
                wall_tail: WALL_TAIL + nonlinear::EXTRA,
            },
        }
    }

    /// The script's name of the model.
    pub const fn name(self) -> &'static str {
        match self {
            Law::Parallel => "cohesion bond",
            Law::Nonlinear => "cohesion bond/nonlinear",
        }
    }

    /// True if an intact bond takes the place of the normal contact force of its pair
    /// while the two touch (LIGGGHTS-INL's `bond/nonlinear` writes its force over the
    /// normal model's; its compression law is the contact). The tangential and rolling
    /// forces of the contact stay.
    pub const fn replaces_normal_contact(self) -> bool {
        matches!(self, Law::Nonlinear)
    }

    /// The per-atom property whose equal values bond spheres at their insertion step.
    pub const fn random_id_property(self) -> &'static str {
        match self {
            Law::Parallel => RANDOM_ID,
            Law::Nonlinear => "bondnonlinear_random_id",
        }
    }

    /// The name under which this law reads the `cohesion bond` property `base`
    /// (LIGGGHTS-INL appends `nonlinear` for `bond/nonlinear`, and its normal stiffness is
    /// the tension stiffness `stiffnessPerUnitAreaK_fn2`).
    pub fn property(self, base: &'static str) -> &'static str {
        if self == Law::Parallel {
            return base;
        }
        match base {
            "radiusMultiplierBond" => "radiusMultiplierBondnonlinear",
            "normalBondStiffnessPerUnitArea" => "stiffnessPerUnitAreaK_fn2",
            "tangentialBondStiffnessPerUnitArea" => "stiffnessPerUnitAreaK_ft",
            "dampingNormalForceBond" => "dampingNormalForceBondnonlinear",
            "dampingTangentialForceBond" => "dampingTangentialForceBondnonlinear",
            "dampingNormalTorqueBond" => "dampingNormalTorqueBondnonlinear",
            "dampingTangentialTorqueBond" => "dampingTangentialTorqueBondnonlinear",
            "maxDistanceBond" => "maxDistanceBondnonlinear",
            "maxSigmaBond" => "maxSigmaBondnonlinear",
            "maxTauBond" => "maxTauBondnonlinear",
            "createDistanceBond" => "createDistanceBondnonlinear",
            "ratioTensionCompression" => "ratioTensionCompressionBondnonlinear",
            "tsCreateBond" => "tsCreateBondnonlinear",
            other => other,
        }
    }
}

/// Per-particle property (LIGGGHTS-INL's `bond_random_id`): the spheres of one inserted
/// copy of a bonded template (`bonded yes` without bond atoms, or the fragments of
/// `fix insert/fragments`) share a value, the insertion step plus a number in (0, 1). Two
/// spheres that share it bond, as at `tsCreateBond`, while the step is below it: at the
/// step they were inserted.
pub const RANDOM_ID: &str = "bond_random_id";

/// A [`RANDOM_ID`] value for a copy inserted at `step`: the step plus a fraction in
/// (0, 1) drawn from `key` by a fixed mixing function (splitmix64), so that every rank
/// and thread count gives the same values; different keys give different values.
pub fn random_id(step: u64, key: u64) -> f64 {
    let mut z = key.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    // 52 bits, then in (0, 1): never the step itself.
    let frac = ((z >> 12) as f64 + 0.5) / (1u64 << 52) as f64;
    step as f64 + frac
}

/// Whether two spheres with [`RANDOM_ID`] values `a` and `b` are bonded by them at
/// `step`.
#[inline(always)]
pub fn same_random_id(a: f64, b: f64, step: u64) -> bool {
    a == b && (step as f64) < a
}

/// Below this radius multiplier a type pair does not bond (as LIGGGHTS-INL).
const MIN_MULTIPLIER: f64 = 1e-6;

/// Extra room on the longest possible bond for the neighbor reach (LIGGGHTS-INL's factor).
const REACH_FACTOR: f64 = 1.1;

/// The `cohesion bond` switches (LIGGGHTS-INL names and defaults).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BondFlags {
    /// `stressBreak` (off): break by stress instead of by distance.
    pub stress_break: bool,
    /// `tensionStress` (on): the normal force acts in tension.
    pub tension: bool,
    /// `compressionStress` (on): the normal force acts in compression.
    pub compression: bool,
    /// `shearStress` (on): the shear force acts.
    pub shear: bool,
    /// `normalTorqueStress` (on): the twisting torque acts.
    pub normal_torque: bool,
    /// `shearTorqueStress` (on): the bending torque acts.
    pub shear_torque: bool,
    /// `createBondAlways` (off): create at every step, not only at `tsCreateBond`.
    pub create_always: bool,
    /// `dampingBond` (on).
    pub damping: bool,
    /// `dampingBondSmooth` (off): damping switched linearly near zero velocity.
    pub damping_smooth: bool,
    /// `dissipationBond` (off).
    pub dissipation: bool,
    /// `druckerPrager` (off).
    pub drucker_prager: bool,
    /// `ratioTensionCompression` (off).
    pub ratio_tc: bool,
}

impl Default for BondFlags {
    fn default() -> Self {
        Self {
            stress_break: false,
            tension: true,
            compression: true,
            shear: true,
            normal_torque: true,
            shear_torque: true,
            create_always: false,
            damping: true,
            damping_smooth: false,
            dissipation: false,
            drucker_prager: false,
            ratio_tc: false,
        }
    }
}

/// The `cohesion bond` coefficients as the script gave them (`None`: not given). Each
/// table is per type pair, row-major `ntypes × ntypes`; [`BondTable::new`] checks which
/// are required by the switches, their length, ranges and symmetry. Error messages name
/// each coefficient by its LIGGGHTS-INL property (given in each field's doc), as the
/// other material errors do.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BondCoefficients {
    /// `radiusMultiplierBond`: bond radius over the smaller particle radius.
    pub radius_multiplier: Option<Vec<f64>>,
    /// `normalBondStiffnessPerUnitArea` k_n.
    pub normal_stiffness: Option<Vec<f64>>,
    /// `tangentialBondStiffnessPerUnitArea` k_t.
    pub tangential_stiffness: Option<Vec<f64>>,
    /// `dampingNormalForceBond`.
    pub damping_normal_force: Option<Vec<f64>>,
    /// `dampingTangentialForceBond`.
    pub damping_tangential_force: Option<Vec<f64>>,
    /// `dampingNormalTorqueBond`.
    pub damping_normal_torque: Option<Vec<f64>>,
    /// `dampingTangentialTorqueBond`.
    pub damping_tangential_torque: Option<Vec<f64>>,
    /// `dissipationNormalForceBond` (a relaxation time).
    pub dissipation_normal_force: Option<Vec<f64>>,
    /// `dissipationTangentialForceBond` (a relaxation time).
    pub dissipation_tangential_force: Option<Vec<f64>>,
    /// `dissipationNormalTorqueBond` (a relaxation time).
    pub dissipation_normal_torque: Option<Vec<f64>>,
    /// `dissipationTangentialTorqueBond` (a relaxation time).
    pub dissipation_tangential_torque: Option<Vec<f64>>,
    /// `maxDistanceBond`: breakage distance (without `stressBreak`).
    pub max_distance: Option<Vec<f64>>,
    /// `maxSigmaBond`: breakage normal stress (`stressBreak on`).
    pub max_sigma: Option<Vec<f64>>,
    /// `maxTauBond`: breakage shear stress (`stressBreak on`).
    pub max_tau: Option<Vec<f64>>,
    /// `createDistanceBond`: centre distance below which a bond is created.
    pub create_distance: Option<Vec<f64>>,
    /// `frictionAngle` in degrees (`druckerPrager on`).
    pub friction_angle: Option<Vec<f64>>,
    /// `ratioTensionCompression` (`ratioTensionCompression on`).
    pub ratio_tension_compression: Option<Vec<f64>>,
    /// `tsCreateBond`: the step at which bonds are created, as given (checked to be a
    /// step number when `createBondAlways` is off).
    pub ts_create: Option<f64>,
    /// `cohesion bond/nonlinear`: the stiffness tables, in
    /// [`nonlinear::STIFFNESS_PROPERTIES`] order.
    pub stiffness: [Option<Vec<f64>>; 13],
}

/// The bond parameters of one type pair (or particle type × wall type).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BondCoeff {
    /// `radiusMultiplierBond` (0: this pair does not bond).
    pub multiplier: f64,
    /// `normalBondStiffnessPerUnitArea` k_n.
    pub kn: f64,
    /// `tangentialBondStiffnessPerUnitArea` k_t.
    pub kt: f64,
    /// Damping coefficients α: normal force, shear force, twisting, bending torque.
    pub damping: [f64; 4],
    /// Dissipation rates 1/τ, same order.
    pub dissipation: [f64; 4],
    /// `maxDistanceBond`.
    pub max_distance: f64,
    /// `maxSigmaBond`.
    pub max_sigma: f64,
    /// `maxTauBond`.
    pub max_tau: f64,
    /// `ratioTensionCompression` (1 when off).
    pub ratio_tc: f64,
    /// tan of `frictionAngle` (degrees in the script; 0 when off).
    pub tan_phi: f64,
    /// `createDistanceBond`.
    pub create_distance: f64,
}

/// The bond parameters of every type pair, the creation step and the reach.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BondTable {
    ntypes: usize,
    coeffs: Vec<BondCoeff>,
    /// The nonlinear law's stiffnesses per type pair (empty for the parallel bond).
    stiffness: Vec<nonlinear::Stiffness>,
    law: Law,
    /// `tsCreateBond` (`None` with `createBondAlways on`).
    pub ts_create: Option<u64>,
    /// Longest centre distance at which a pair of particles may be bonded (or bond).
    pub pair_reach: f64,
    /// Longest distance from a wall at which a particle may be bonded to it.
    pub wall_reach: f64,
}

impl BondTable {
    /// Checks the `given` coefficients of the bond law `law` for `ntypes` types and
    /// switches `fl` (what is required, the lengths, ranges and symmetry) and builds the
    /// table.
    pub fn new(given: &BondCoefficients, ntypes: usize, fl: BondFlags, law: Law) -> Result<Self> {
        let n = ntypes;
        let model = law.name();
        fn need<'a>(
            values: Option<&'a Vec<f64>>,
            name: &'static str,
            why: &str,
            model: &str,
            n: usize,
        ) -> Result<&'a Vec<f64>> {
            values.ok_or_else(|| Error::Invalid {
                what: name,
                reason: format!(
                    "{model}{why} needs 'fix ID all property/global {name} peratomtypepair {n} ...'"
                ),
            })
        }
        let table = |values: &Option<Vec<f64>>,
                     base: &'static str,
                     why: &str,
                     needed: bool,
                     ok: fn(f64) -> bool,
                     range: &'static str|
         -> Result<Vec<f64>> {
            if !needed {
                return Ok(vec![0.0; n * n]);
            }
            let name = law.property(base);
            pair_table(
                name,
                need(values.as_ref(), name, why, model, n)?,
                n,
                true,
                ok,
                range,
            )
        };
        if law == Law::Parallel && !fl.damping && !fl.damping_smooth && !fl.dissipation {
            return Err(Error::Invalid {
                what: "cohesion bond",
                reason:
                    "damping or dissipation has to be on (dampingBond on, or dissipationBond on)"
                        .into(),
            });
        }
        let damping = fl.damping || fl.damping_smooth;
        let pos = |v: f64| v > 0.0;
        let nonneg = |v: f64| v >= 0.0;
        let mut stiffness = Vec::new();
        if law == Law::Nonlinear {
            let mut cols = Vec::new();
            for (values, name) in given.stiffness.iter().zip(nonlinear::STIFFNESS_PROPERTIES) {
                cols.push(pair_table(
                    name,
                    need(values.as_ref(), name, "", model, n)?,
                    n,
                    true,
                    nonneg,
                    "must be >= 0",
                )?);
            }
            stiffness = (0..n * n)
                .map(|k| nonlinear::Stiffness::from_values(std::array::from_fn(|c| cols[c][k])))
                .collect();
        }
        let mult = table(
            &given.radius_multiplier,
            "radiusMultiplierBond",
            "",
            true,
            nonneg,
            "must be >= 0",
        )?;
        let parallel = law == Law::Parallel;
        let mut kn = table(
            &given.normal_stiffness,
            "normalBondStiffnessPerUnitArea",
            "",
            parallel,
            nonneg,
            "must be >= 0",
        )?;
        let mut kt = table(
            &given.tangential_stiffness,
            "tangentialBondStiffnessPerUnitArea",
            "",
            parallel,
            nonneg,
            "must be >= 0",
        )?;
        if !parallel {
            // The nonlinear law's tension and shear stiffness play their parts.
            kn = stiffness.iter().map(|s| s.tension.k).collect();
            kt = stiffness.iter().map(|s| s.shear).collect();
        }
        let create = table(
            &given.create_distance,
            "createDistanceBond",
            "",
            true,
            nonneg,
            "must be >= 0",
        )?;
        let mut damp = Vec::new();
        for (values, name) in [
            (&given.damping_normal_force, "dampingNormalForceBond"),
            (
                &given.damping_tangential_force,
                "dampingTangentialForceBond",
            ),
            (&given.damping_normal_torque, "dampingNormalTorqueBond"),
            (
                &given.damping_tangential_torque,
                "dampingTangentialTorqueBond",
            ),
        ] {
            damp.push(table(
                values,
                name,
                " with dampingBond on",
                damping,
                |v| (0.0..=1.0).contains(&v),
                "must be in [0, 1]",
            )?);
        }
        let mut diss = Vec::new();
        for (values, name) in [
            (
                &given.dissipation_normal_force,
                "dissipationNormalForceBond",
            ),
            (
                &given.dissipation_tangential_force,
                "dissipationTangentialForceBond",
            ),
            (
                &given.dissipation_normal_torque,
                "dissipationNormalTorqueBond",
            ),
            (
                &given.dissipation_tangential_torque,
                "dissipationTangentialTorqueBond",
            ),
        ] {
            diss.push(table(
                values,
                name,
                " with dissipationBond on",
                fl.dissipation,
                pos,
                "must be > 0 (a relaxation time)",
            )?);
        }
        let simple = !fl.stress_break;
        let max_d = table(
            &given.max_distance,
            "maxDistanceBond",
            "",
            simple,
            pos,
            "must be > 0",
        )?;
        let sigma = table(
            &given.max_sigma,
            "maxSigmaBond",
            " with stressBreak on",
            fl.stress_break,
            pos,
            "must be > 0",
        )?;
        let tau = table(
            &given.max_tau,
            "maxTauBond",
            " with stressBreak on",
            fl.stress_break,
            pos,
            "must be > 0",
        )?;
        let rtc = table(
            &given.ratio_tension_compression,
            "ratioTensionCompression",
            " with ratioTensionCompression on",
            fl.stress_break && fl.ratio_tc,
            pos,
            "must be > 0",
        )?;
        let phi = table(
            &given.friction_angle,
            "frictionAngle",
            " with druckerPrager on",
            fl.stress_break && fl.drucker_prager,
            |v| (0.0..90.0).contains(&v),
            "must be in [0, 90) degrees",
        )?;
        let ts_create = if fl.create_always {
            None
        } else {
            let name = law.property("tsCreateBond");
            let t = given.ts_create.ok_or_else(|| Error::Invalid {
                what: name,
                reason: format!(
                    "{model} with createBondAlways off needs 'fix ID all property/global {name} scalar ...'"
                ),
            })?;
            check(
                name,
                t,
                t >= 0.0 && t.fract() == 0.0,
                "must be a step number >= 0",
            )?;
            Some(t as u64)
        };
        let mut coeffs = Vec::with_capacity(n * n);
        let (mut pair_reach, mut wall_reach) = (0.0f64, 0.0f64);
        for k in 0..n * n {
            let c = BondCoeff {
                multiplier: mult[k],
                kn: kn[k],
                kt: kt[k],
                damping: [damp[0][k], damp[1][k], damp[2][k], damp[3][k]],
                dissipation: [diss[0][k], diss[1][k], diss[2][k], diss[3][k]].map(|t| {
                    if t > 0.0 {
                        1.0 / t
                    } else {
                        0.0
                    }
                }),
                max_distance: max_d[k],
                max_sigma: sigma[k],
                max_tau: tau[k],
                ratio_tc: if fl.ratio_tc { rtc[k] } else { 1.0 },
                tan_phi: (phi[k] * std::f64::consts::PI / 180.0).tan(),
                create_distance: create[k],
            };
            if c.multiplier >= MIN_MULTIPLIER {
                if fl.stress_break && c.kn <= 0.0 {
                    return Err(Error::Invalid {
                        what: law.property("normalBondStiffnessPerUnitArea"),
                        reason: "must be > 0 with stressBreak on (it sets the longest bond)".into(),
                    });
                }
                let (p, w) = if fl.stress_break {
                    let stretch = c.max_sigma * c.ratio_tc.max(1.0) / c.kn;
                    (
                        c.create_distance + stretch,
                        0.5 * c.create_distance + stretch,
                    )
                } else {
                    (
                        c.max_distance.max(c.create_distance),
                        c.max_distance.max(0.5 * c.create_distance),
                    )
                };
                pair_reach = pair_reach.max(REACH_FACTOR * p);
                wall_reach = wall_reach.max(REACH_FACTOR * w);
            }
            coeffs.push(c);
        }
        Ok(Self {
            ntypes: n,
            coeffs,
            stiffness,
            law,
            ts_create,
            pair_reach,
            wall_reach,
        })
    }

    /// The table for `model` with `cohesion bond` (else `None`), from `materials`.
    pub fn for_model(
        model: &crate::contact::ContactModel,
        materials: &crate::contact::Materials,
    ) -> Result<Option<Self>> {
        let Some(law) = model.bond_law() else {
            return Ok(None);
        };
        let given = match law {
            Law::Parallel => &materials.bond,
            Law::Nonlinear => &materials.bond_nonlinear,
        };
        Self::new(given, materials.ntypes, model.bond, law).map(Some)
    }

    /// The bond law.
    pub fn law(&self) -> Law {
        self.law
    }

    /// The history layout of the bond law.
    pub fn layout(&self) -> Layout {
        self.law.layout()
    }

    /// One bonded pair of the 1-based types `(ti, tj)` (a wall: its type as `tj`) under
    /// the table's law: [`bond`] or [`nonlinear::bond`].
    #[inline(always)]
    pub fn force(
        &self,
        g: &BondGeom,
        ti: u32,
        tj: u32,
        fl: BondFlags,
        vecs: &mut [f64],
        tail: &mut [f64],
    ) -> (BondForce, Event) {
        let k = (ti as usize - 1) * self.ntypes + (tj as usize - 1);
        match self.law {
            Law::Parallel => bond(g, &self.coeffs[k], fl, vecs, tail),
            Law::Nonlinear => {
                nonlinear::bond(g, &self.coeffs[k], &self.stiffness[k], fl, vecs, tail)
            }
        }
    }

    /// Parameters of the 1-based type pair `(ti, tj)`.
    #[inline(always)]
    pub fn get(&self, ti: u32, tj: u32) -> &BondCoeff {
        &self.coeffs[(ti as usize - 1) * self.ntypes + (tj as usize - 1)]
    }

    /// Whether bonds may be created at step `step` (of a history-advancing evaluation).
    pub fn creates_at(&self, step: u64) -> bool {
        self.ts_create.is_none_or(|t| t == step)
    }
}

/// Bond creation and breakage events, counted from any thread (integer sums: the totals
/// do not depend on the order).
#[derive(Debug, Default)]
pub struct BondEvents {
    created: AtomicU64,
    broken: AtomicU64,
}

impl Clone for BondEvents {
    fn clone(&self) -> Self {
        let (c, b) = self.totals();
        Self {
            created: AtomicU64::new(c),
            broken: AtomicU64::new(b),
        }
    }
}

impl BondEvents {
    /// Counts one event.
    #[inline]
    pub fn count(&self, e: Event) {
        match e {
            Event::None => {}
            Event::Created => {
                self.created.fetch_add(1, Ordering::Relaxed);
            }
            Event::Broken => {
                self.broken.fetch_add(1, Ordering::Relaxed);
            }
        }
    }

    /// Bonds created and broken on this rank since the start.
    pub fn totals(&self) -> (u64, u64) {
        (
            self.created.load(Ordering::Relaxed),
            self.broken.load(Ordering::Relaxed),
        )
    }
}

/// What happened to a bond in one evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event {
    /// Nothing.
    None,
    /// It was created.
    Created,
    /// It broke.
    Broken,
}

/// The kinematics of one bonded (or bondable) pair, as seen from particle i. For a wall,
/// j is the anchor on the wall: `rj = ∞`, `wj = 0`.
#[derive(Debug, Clone, Copy)]
pub struct BondGeom {
    /// x_i − x_j (a wall: x_i − anchor).
    pub d: DVec3,
    /// Radius of i.
    pub ri: f64,
    /// Radius of j (∞ for a wall).
    pub rj: f64,
    /// v_i − v_j (a wall: v_i − v_wall).
    pub vr: DVec3,
    /// Angular velocity of i.
    pub wi: DVec3,
    /// Angular velocity of j (0 for a wall).
    pub wj: DVec3,
    /// Timestep.
    pub dt: f64,
    /// Whether this evaluation advances the history (false at a run's set-up).
    pub update: bool,
    /// Longest distance at which the bond may exist (the neighbor reach).
    pub reach: f64,
}

impl BondGeom {
    /// A particle of radius `ri` at `d` from its anchor on a wall, moving at `vr`
    /// relative to the wall and spinning at `wi`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn wall(
        d: DVec3,
        ri: f64,
        vr: DVec3,
        wi: DVec3,
        dt: f64,
        update: bool,
        reach: f64,
    ) -> Self {
        Self {
            d,
            ri,
            rj: f64::INFINITY,
            vr,
            wi,
            wj: DVec3::ZERO,
            dt,
            update,
            reach,
        }
    }
}

/// Force and torques of one bond.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BondForce {
    /// Force on i (j gets the opposite).
    pub f_i: DVec3,
    /// Torque on i.
    pub t_i: DVec3,
    /// Torque on j.
    pub t_j: DVec3,
}

/// Whether a pair `r_create` apart (a wall: twice the distance) gets a bond now.
#[inline(always)]
pub fn creates(c: &BondCoeff, create_now: bool, r_create: f64) -> bool {
    create_now && c.multiplier >= MIN_MULTIPLIER && r_create < c.create_distance
}

/// Starts a bond at distance `d0`: flag set, every other value zero (the wall anchor is
/// the caller's to set).
#[inline(always)]
pub fn create(vecs: &mut [f64], tail: &mut [f64], d0: f64) {
    vecs.fill(0.0);
    tail.fill(0.0);
    tail[0] = 1.0;
    tail[1] = d0;
}

/// True if the history tail holds a bond.
#[inline(always)]
pub fn is_bonded(tail: &[f64]) -> bool {
    tail[0] != 0.0
}

/// The damping multiplier of one component: sign(v), or with `dampingBondSmooth` a
/// linear ramp below a velocity set by the force (as LIGGGHTS-INL computes it).
#[inline(always)]
fn ramp(smooth: bool, v: f64, f: f64, minvel: f64, dt: f64) -> f64 {
    if smooth {
        (v / minvel.max(0.01 * f * dt)).clamp(-1.0, 1.0)
    } else if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// `f − α |f_k| m(v_k)` per component.
#[inline(always)]
fn damped(f: DVec3, v: DVec3, alpha: f64, smooth: bool, minvel: f64, dt: f64) -> DVec3 {
    let m = DVec3::new(
        ramp(smooth, v.x, f.x, minvel, dt),
        ramp(smooth, v.y, f.y, minvel, dt),
        ramp(smooth, v.z, f.z, minvel, dt),
    );
    f - alpha * f.abs() * m
}

/// `h` brought onto the plane normal to `n` with its length kept (a rotation for the
/// small turn of one step).
#[inline(always)]
pub(crate) fn turn_tangent(h: DVec3, n: DVec3) -> DVec3 {
    let len2 = h.length_squared();
    if len2 == 0.0 {
        return h;
    }
    let t = h - h.dot(n) * n;
    let t2 = t.length_squared();
    if t2 == 0.0 {
        DVec3::ZERO
    } else {
        t * (len2 / t2).sqrt()
    }
}

#[inline(always)]
fn load(h: &[f64], k: usize) -> DVec3 {
    DVec3::new(h[3 * k], h[3 * k + 1], h[3 * k + 2])
}

#[inline(always)]
fn store(h: &mut [f64], k: usize, v: DVec3) {
    h[3 * k] = v.x;
    h[3 * k + 1] = v.y;
    h[3 * k + 2] = v.z;
}

/// Breaks the bond: every bond value zeroed.
#[inline(always)]
fn break_bond(vecs: &mut [f64], tail: &mut [f64]) {
    vecs.fill(0.0);
    tail.fill(0.0);
}

/// What every bond law needs of one bonded pair: its axis, its section and the relative
/// motions of its two ends.
#[derive(Debug, Clone, Copy)]
struct Section {
    /// Centre distance (a wall: the distance to the anchor).
    r: f64,
    /// Unit vector from j (the anchor) to i.
    n: DVec3,
    /// Bond radius r_b, its area A, polar moment J and moment of inertia I.
    rb: f64,
    area: f64,
    j_polar: f64,
    i_bend: f64,
    /// Lever arms from the centres to the bond's middle (a wall: to the anchor).
    ci: f64,
    cj: f64,
    /// Normal relative velocity (a vector along n).
    vn: DVec3,
    /// Relative velocity of i's side of the bond's middle against j's, across the pair.
    v_shear: DVec3,
    /// Relative spin ω_i − ω_j along the pair (twisting) and across it (bending).
    wn: DVec3,
    wt: DVec3,
    /// Velocity scale of `dampingBondSmooth`.
    minvel: f64,
}

impl Section {
    /// The section of a bonded pair, or what the law returns at once: no force at a
    /// run's set-up for a degenerate distance, or the bond broken by `maxDistanceBond`
    /// (without `stressBreak`), by the reach, or by a distance that is not a number.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn of(
        g: &BondGeom,
        c: &BondCoeff,
        fl: BondFlags,
        vecs: &mut [f64],
        tail: &mut [f64],
    ) -> std::result::Result<Self, (BondForce, Event)> {
        let r = g.d.length();
        // Written as "not within" so that a NaN distance breaks the bond (or, at set-up,
        // gives no force).
        if !g.update && !(r > 0.0) {
            return Err((BondForce::default(), Event::None));
        }
        if g.update && ((!fl.stress_break && r > c.max_distance) || !(r <= g.reach) || !(r > 0.0)) {
            break_bond(vecs, tail);
            return Err((BondForce::default(), Event::Broken));
        }
        let wall = !g.rj.is_finite();
        let n = g.d / r;
        let rmin = if wall { g.ri } else { g.ri.min(g.rj) };
        let rb = c.multiplier * rmin;
        let area = std::f64::consts::PI * rb * rb;
        let j_polar = 0.5 * area * rb * rb;
        let (ci, cj) = if wall {
            (r, 0.0)
        } else {
            let s = r / (g.ri + g.rj);
            (g.ri * s, g.rj * s)
        };
        let vn = g.vr.dot(n) * n;
        let w = g.wi - g.wj;
        let wn = w.dot(n) * n;
        Ok(Self {
            r,
            n,
            rb,
            area,
            j_polar,
            i_bend: 0.5 * j_polar,
            ci,
            cj,
            vn,
            v_shear: g.vr - vn + n.cross(ci * g.wi + cj * g.wj),
            wn,
            wt: w - wn,
            minvel: 1e-5 * rmin / g.dt,
        })
    }

    /// The force on i and the torques on i and j from the damped normal and shear forces
    /// and the damped torques `tb` (twisting plus bending) of the bond.
    #[inline(always)]
    fn forces(&self, fnorm: DVec3, ft: DVec3, tb: DVec3) -> BondForce {
        let lever = ft.cross(self.n);
        BondForce {
            f_i: fnorm + ft,
            t_i: self.ci * lever + tb,
            t_j: self.cj * lever - tb,
        }
    }
}

/// One bonded pair (the tail's flag must be set): forces and torques, and whether it
/// broke. `vecs` are the [`VEC`] odd history values, `tail` the flag and d₀ (and anchor).
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn bond(
    g: &BondGeom,
    c: &BondCoeff,
    fl: BondFlags,
    vecs: &mut [f64],
    tail: &mut [f64],
) -> (BondForce, Event) {
    let sec = match Section::of(g, c, fl, vecs, tail) {
        Ok(s) => s,
        Err(out) => return out,
    };
    let Section {
        r,
        n,
        rb,
        area,
        j_polar,
        i_bend,
        vn,
        v_shear,
        wn,
        wt,
        minvel,
        ..
    } = sec;
    let (update, dt) = (g.update, g.dt);
    let smooth = fl.damping_smooth;
    let damping = fl.damping || smooth;
    let relax = |k: usize| 1.0 - (dt * c.dissipation[k]).min(1.0);

    let u = tail[1] - r;
    if fl.dissipation && update {
        tail[1] += (r - tail[1]) * (dt * c.dissipation[0]).min(1.0);
    }
    let mut fnorm = DVec3::ZERO;
    let mut fnorm_d = DVec3::ZERO;
    if (fl.tension && u < -1e-15) || (fl.compression && u > 1e-15) {
        fnorm = c.kn * area * u * n;
        fnorm_d = if damping {
            damped(fnorm, vn, c.damping[0], smooth, minvel, dt)
        } else {
            fnorm
        };
    }
    // The incremental loads: the stored value (already in the current frame), relaxed
    // with `dissipationBond`, plus this step's increment; and its damped value.
    let advance = |h: DVec3, k: usize, inc: DVec3, v: DVec3, smooth: bool| {
        let h = if fl.dissipation { h * relax(k) } else { h } + inc;
        let d = if damping {
            damped(h, v, c.damping[k], smooth, minvel, dt)
        } else {
            h
        };
        (h, d)
    };
    let (mut ft, mut ft_d) = (load(vecs, 0), DVec3::ZERO);
    if fl.shear {
        let inc = -c.kt * area * dt * v_shear;
        (ft, ft_d) = advance(turn_tangent(ft, n), 1, inc, v_shear, smooth);
    }
    let (mut tn, mut tn_d) = (load(vecs, 1), DVec3::ZERO);
    if fl.normal_torque {
        let inc = -c.kt * j_polar * dt * wn;
        (tn, tn_d) = advance(tn.dot(n) * n, 2, inc, wn, false);
    }
    let (mut tt, mut tt_d) = (load(vecs, 2), DVec3::ZERO);
    if fl.shear_torque {
        let inc = -c.kn * i_bend * dt * wt;
        (tt, tt_d) = advance(turn_tangent(tt, n), 3, inc, wt, false);
    }
    if fl.stress_break && update {
        // |F_n| = k_n A |u| and T_n lies along n: no square roots for those two.
        let fn_mag = if fnorm == DVec3::ZERO {
            0.0
        } else {
            c.kn * area * u.abs()
        };
        let sigma = fn_mag / area + tt.length() * rb / i_bend;
        let tau = ft.length() / area + tn.dot(n).abs() * rb / j_polar;
        let sigma_max = if fl.ratio_tc && u < 1e-16 {
            c.max_sigma * c.ratio_tc
        } else {
            c.max_sigma
        };
        let tau_max = if fl.drucker_prager {
            c.max_tau + u.signum() * fn_mag / area * c.tan_phi
        } else {
            c.max_tau
        };
        if sigma > sigma_max || tau > tau_max {
            break_bond(vecs, tail);
            return (BondForce::default(), Event::Broken);
        }
    }
    if update {
        store(vecs, 0, ft);
        store(vecs, 1, tn);
        store(vecs, 2, tt);
    }
    (sec.forces(fnorm_d, ft_d, tn_d + tt_d), Event::None)
}

#[cfg(test)]
mod tests {

    /// Random bond IDs: the step plus a fraction in (0, 1), different for different keys;
    /// they bond only at the step of the insertion.
    #[test]
    fn random_ids_bond_at_their_step_only() {
        let ids: Vec<f64> = (0..1000).map(|k| random_id(15051, k)).collect();
        assert!(ids.iter().all(|&v| v > 15051.0 && v < 15052.0));
        let mut sorted = ids.clone();
        sorted.sort_by(f64::total_cmp);
        sorted.dedup();
        assert_eq!(sorted.len(), ids.len());
        assert_eq!(random_id(7, 3), random_id(7, 3));
        let a = random_id(100, 1);
        assert!(same_random_id(a, a, 100));
        assert!(!same_random_id(a, a, 101));
        assert!(!same_random_id(a, random_id(100, 2), 100));
        // Spheres without an ID (the default, -1) never bond by it.
        assert!(!same_random_id(-1.0, -1.0, 0));
    }

    use super::*;

    fn flags_plain() -> BondFlags {
        BondFlags {
            damping: false,
            dissipation: true,
            ..Default::default()
        }
    }

    fn coeff() -> BondCoeff {
        BondCoeff {
            multiplier: 1.0,
            kn: 1e9,
            kt: 5e8,
            damping: [0.0; 4],
            dissipation: [0.0; 4],
            max_distance: 1.0,
            max_sigma: 0.0,
            max_tau: 0.0,
            ratio_tc: 1.0,
            tan_phi: 0.0,
            create_distance: 0.0021,
        }
    }

    fn geom(d: DVec3) -> BondGeom {
        BondGeom {
            d,
            ri: 0.001,
            rj: 0.001,
            vr: DVec3::ZERO,
            wi: DVec3::ZERO,
            wj: DVec3::ZERO,
            dt: 1e-7,
            update: true,
            reach: 1.0,
        }
    }

    /// A stretched bond pulls with k_n A (d − d₀); the twist and bend increments follow
    /// the formulas, and a pair moved rigidly across gets no shear force.
    #[test]
    fn forces_follow_the_formulas() {
        let c = coeff();
        let fl = flags_plain();
        let (mut v, mut t) = ([0.0; VEC], [0.0; PAIR_TAIL]);
        create(&mut v, &mut t, 0.002);
        let area = std::f64::consts::PI * 1e-6;
        let (out, e) = bond(&geom(DVec3::new(0.0021, 0.0, 0.0)), &c, fl, &mut v, &mut t);
        assert_eq!(e, Event::None);
        let want = -c.kn * area * 1e-4;
        assert!((out.f_i.x - want).abs() < 1e-9 * want.abs(), "{out:?}");
        // Twist: ω_i − ω_j along the pair.
        let mut g = geom(DVec3::new(0.002, 0.0, 0.0));
        g.wi = DVec3::new(3.0, 0.0, 0.0);
        let (out, _) = bond(&g, &c, fl, &mut v, &mut t);
        let j = 0.5 * area * 1e-6;
        assert!((out.t_i.x + c.kt * j * g.dt * 3.0).abs() < 1e-18, "{out:?}");
        assert_eq!(out.t_j.x, -out.t_i.x);
        // Rigid rotation of the pair about its middle: v_i − v_j = ω × d, ω_i = ω_j = ω.
        let (mut v, mut t) = ([0.0; VEC], [0.0; PAIR_TAIL]);
        create(&mut v, &mut t, 0.002);
        let mut g = geom(DVec3::new(0.002, 0.0, 0.0));
        let w = DVec3::new(0.0, 0.0, 7.0);
        g.wi = w;
        g.wj = w;
        g.vr = w.cross(g.d);
        let (out, _) = bond(&g, &c, fl, &mut v, &mut t);
        assert!(out.f_i.length() < 1e-12, "{out:?}");
    }

    /// Distance breakage, and stress breakage at σ = |F_n|/A.
    #[test]
    fn breaks() {
        let mut c = coeff();
        c.max_distance = 0.0022;
        let fl = flags_plain();
        let (mut v, mut t) = ([0.0; VEC], [0.0; PAIR_TAIL]);
        create(&mut v, &mut t, 0.002);
        let (_, e) = bond(&geom(DVec3::new(0.00219, 0.0, 0.0)), &c, fl, &mut v, &mut t);
        assert_eq!(e, Event::None);
        let (_, e) = bond(&geom(DVec3::new(0.00221, 0.0, 0.0)), &c, fl, &mut v, &mut t);
        assert_eq!(e, Event::Broken);
        assert!(!is_bonded(&t));
        let fl = BondFlags {
            stress_break: true,
            ..flags_plain()
        };
        c.max_sigma = c.kn * 1e-4; // breaks beyond a stretch of 0.1 mm
        c.max_tau = 1e30;
        create(&mut v, &mut t, 0.002);
        let (_, e) = bond(
            &geom(DVec3::new(0.0020999, 0.0, 0.0)),
            &c,
            fl,
            &mut v,
            &mut t,
        );
        assert_eq!(e, Event::None);
        let (_, e) = bond(
            &geom(DVec3::new(0.0021001, 0.0, 0.0)),
            &c,
            fl,
            &mut v,
            &mut t,
        );
        assert_eq!(e, Event::Broken);
    }

    /// Damping: each component of the stretched bond's force loses α |F_k| against the
    /// sign of the relative normal velocity; with `dampingBondSmooth` a velocity far
    /// below the ramp's threshold (1e-5 r/dt here) takes only its share v/threshold.
    /// Dissipation relaxes d₀ towards d by dt/τ per step, and the shear force by the
    /// factor 1 − dt/τ.
    #[test]
    fn damping_and_dissipation() {
        let mut c = coeff();
        c.damping = [0.3; 4];
        let fl = BondFlags::default();
        let (mut v, mut t) = ([0.0; VEC], [0.0; PAIR_TAIL]);
        create(&mut v, &mut t, 0.002);
        let mut g = geom(DVec3::new(0.0021, 0.0, 0.0));
        g.vr = DVec3::new(1e-3, 0.0, 0.0); // separating
        let (out, _) = bond(&g, &c, fl, &mut v, &mut t);
        let f = -c.kn * std::f64::consts::PI * 1e-6 * 1e-4;
        assert!((out.f_i.x - 1.3 * f).abs() < 1e-12 * f.abs(), "{out:?}");
        let smooth = BondFlags {
            damping_smooth: true,
            ..fl
        };
        let threshold = 1e-5 * 0.001 / g.dt;
        g.vr = DVec3::new(0.25 * threshold, 0.0, 0.0);
        let (out, _) = bond(&g, &c, smooth, &mut v, &mut t);
        assert!(
            (out.f_i.x - (1.0 + 0.3 * 0.25) * f).abs() < 1e-9 * f.abs(),
            "{out:?}"
        );
        // Dissipation of the rest length and of the shear force.
        let diss = BondFlags {
            damping: false,
            dissipation: true,
            ..fl
        };
        c.dissipation = [1.0 / 1e-5; 4]; // τ = 10 µs, dt/τ = 0.01
        let (mut v, mut t) = ([0.0; VEC], [0.0; PAIR_TAIL]);
        create(&mut v, &mut t, 0.002);
        v[1] = 2.0; // a stored shear force along y
        let g = geom(DVec3::new(0.0021, 0.0, 0.0));
        bond(&g, &c, diss, &mut v, &mut t);
        assert!((t[1] - (0.002 + 0.01 * 1e-4)).abs() < 1e-15, "d0 {}", t[1]);
        assert!((v[1] - 2.0 * 0.99).abs() < 1e-12, "shear {}", v[1]);
    }

    /// Shear history turns with the pair and keeps its length.
    #[test]
    fn shear_turns_with_the_pair() {
        let h = DVec3::new(0.0, 2.0, 0.0);
        // The pair turned by 0.1 rad about z: n was (1, 0, 0).
        let n = DVec3::new(0.1f64.cos(), 0.1f64.sin(), 0.0);
        let t = turn_tangent(h, n);
        assert!(t.dot(n).abs() < 1e-14, "{t}");
        assert!((t.length() - 2.0).abs() < 1e-15);
    }

    /// The table reads the typed coefficients (1 type): the reach follows the longest
    /// bond (1.1 × max(maxDistanceBond, createDistanceBond)), the dissipation times
    /// become rates, and a coefficient the switches require but that was not given is
    /// named by its LIGGGHTS-INL property in the error.
    #[test]
    fn table_from_typed_coefficients() {
        let one = |v: f64| Some(vec![v]);
        let mut given = BondCoefficients {
            radius_multiplier: one(1.0),
            normal_stiffness: one(1e9),
            tangential_stiffness: one(5e8),
            create_distance: one(0.0021),
            max_distance: one(0.003),
            dissipation_normal_force: one(0.5),
            dissipation_tangential_force: one(0.5),
            dissipation_normal_torque: one(0.5),
            dissipation_tangential_torque: one(0.25),
            ts_create: Some(3.0),
            ..Default::default()
        };
        let t = BondTable::new(&given, 1, flags_plain(), Law::Parallel).unwrap();
        assert_eq!(t.ts_create, Some(3));
        assert!(
            (t.pair_reach - 1.1 * 0.003).abs() < 1e-18,
            "{}",
            t.pair_reach
        );
        assert_eq!(t.get(1, 1).dissipation, [2.0, 2.0, 2.0, 4.0]);
        given.normal_stiffness = None;
        let e = BondTable::new(&given, 1, flags_plain(), Law::Parallel).unwrap_err();
        assert!(
            e.to_string().contains(
                "cohesion bond needs 'fix ID all property/global normalBondStiffnessPerUnitArea peratomtypepair 1 ...'"
            ),
            "{e}"
        );
    }
}
