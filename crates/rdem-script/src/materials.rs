//! The engine's material table from the `fix property/global` values: the one place where
//! LIGGGHTS' property names (`youngsModulus`, `radiusMultiplierBond`, ...) map onto the
//! engine's typed fields, with the errors about a property's style and value count.

use crate::error::Error;
use rdem::bond::nonlinear::STIFFNESS_PROPERTIES;
use rdem::bond::BondCoefficients;
use rdem::Materials;

use crate::sim::Sim;

/// The `cohesion bond` coefficient that the property `name` gives, if it is one (the
/// per-type-pair tables; `tsCreateBond` is the scalar [`BondCoefficients::ts_create`]).
fn bond_table<'a>(b: &'a mut BondCoefficients, name: &str) -> Option<&'a mut Option<Vec<f64>>> {
    Some(match name {
        "radiusMultiplierBond" => &mut b.radius_multiplier,
        "normalBondStiffnessPerUnitArea" => &mut b.normal_stiffness,
        "tangentialBondStiffnessPerUnitArea" => &mut b.tangential_stiffness,
        "dampingNormalForceBond" => &mut b.damping_normal_force,
        "dampingTangentialForceBond" => &mut b.damping_tangential_force,
        "dampingNormalTorqueBond" => &mut b.damping_normal_torque,
        "dampingTangentialTorqueBond" => &mut b.damping_tangential_torque,
        "dissipationNormalForceBond" => &mut b.dissipation_normal_force,
        "dissipationTangentialForceBond" => &mut b.dissipation_tangential_force,
        "dissipationNormalTorqueBond" => &mut b.dissipation_normal_torque,
        "dissipationTangentialTorqueBond" => &mut b.dissipation_tangential_torque,
        "maxDistanceBond" => &mut b.max_distance,
        "maxSigmaBond" => &mut b.max_sigma,
        "maxTauBond" => &mut b.max_tau,
        "createDistanceBond" => &mut b.create_distance,
        "frictionAngle" => &mut b.friction_angle,
        "ratioTensionCompression" => &mut b.ratio_tension_compression,
        _ => return None,
    })
}

/// The `cohesion bond/nonlinear` coefficient that the property `name` gives, if it is one
/// (its names are those of `cohesion bond` with `nonlinear` appended, and the stiffness
/// tables of [`rdem::bond::nonlinear::STIFFNESS_PROPERTIES`]).
fn nonlinear_table<'a>(
    b: &'a mut BondCoefficients,
    name: &str,
) -> Option<&'a mut Option<Vec<f64>>> {
    if let Some(k) = STIFFNESS_PROPERTIES.iter().position(|p| *p == name) {
        return Some(&mut b.stiffness[k]);
    }
    let base = name.strip_suffix("nonlinear")?;
    if matches!(
        base,
        "normalBondStiffnessPerUnitArea"
            | "tangentialBondStiffnessPerUnitArea"
            | "frictionAngle"
            | "ratioTensionCompression"
    ) || base.starts_with("dissipation")
    {
        return None;
    }
    match base {
        "ratioTensionCompressionBond" => Some(&mut b.ratio_tension_compression),
        _ => bond_table(b, base),
    }
}

/// Builds the engine's material table from the `fix property/global` values.
pub fn materials(sim: &Sim) -> Result<Materials, Error> {
    let n = sim.ntypes();
    let mut m = Materials {
        ntypes: n,
        ..Default::default()
    };
    for (name, p) in &sim.defs.properties {
        let scalar = name == "tsCreateBond" || name == "tsCreateBondnonlinear";
        let known = bond_table(&mut m.bond, name).is_some()
            || nonlinear_table(&mut m.bond_nonlinear, name).is_some();
        if scalar || known {
            let ok = if scalar {
                p.style == "scalar"
            } else {
                p.style == "peratomtypepair"
            };
            if !ok {
                return Err(format!(
                    "property {name} (fix {}) must be {}, not {}",
                    p.fix_id,
                    if scalar { "scalar" } else { "peratomtypepair" },
                    p.style
                )
                .into());
            }
            if !scalar && p.values.len() != n * n {
                return Err(format!(
                    "property {name} (fix {}) has {} value(s); the box has {n} atom type(s), so {} are needed",
                    p.fix_id,
                    p.values.len(),
                    n * n
                ).into());
            }
            if name == "tsCreateBond" {
                // A scalar property has exactly one value.
                m.bond.ts_create = p.values.first().copied();
            } else if name == "tsCreateBondnonlinear" {
                m.bond_nonlinear.ts_create = p.values.first().copied();
            } else if let Some(table) = bond_table(&mut m.bond, name) {
                *table = Some(p.values.clone());
            } else if let Some(table) = nonlinear_table(&mut m.bond_nonlinear, name) {
                *table = Some(p.values.clone());
            }
            continue;
        }
        if liquid_property(&mut m, name, p, n).is_some() {
            continue;
        }
        let slot = match name.as_str() {
            "youngsModulus" => &mut m.youngs_modulus,
            "poissonsRatio" => &mut m.poissons_ratio,
            "coefficientRestitution" => &mut m.restitution,
            "coefficientFriction" => &mut m.friction,
            "coefficientRollingFriction" => &mut m.rolling_friction,
            "coefficientRollingViscousDamping" => &mut m.rolling_viscous_damping,
            "cohesionEnergyDensity" => &mut m.cohesion_energy_density,
            "coefficientAdhesionStiffness" => &mut m.adhesion_stiffness,
            "coefficientPlasticityDepth" => &mut m.plasticity_depth,
            "coefficientMaxElasticStiffness" => &mut m.max_elastic_stiffness,
            "kn" => &mut m.kn,
            "kt" => &mut m.kt,
            "gamman" => &mut m.gamman,
            "gammat" => &mut m.gammat,
            "gamman_abs" => &mut m.gamman_abs,
            "gammat_abs" => &mut m.gammat_abs,
            "characteristicVelocity" => {
                m.characteristic_velocity = p.values.first().copied();
                continue;
            }
            "rollingStiffness" => {
                m.rolling_stiffness = p.values.first().copied();
                continue;
            }
            "workOfAdhesion" => &mut m.work_of_adhesion,
            "LoadingStiffness" => &mut m.hysteretic.loading_stiffness,
            "UnloadingStiffness" => &mut m.hysteretic.unloading_stiffness,
            "pullOffForce" => &mut m.hysteretic.pull_off_force,
            "alphaCustom" => &mut m.hysteretic.alpha,
            "cinCustom" => &mut m.hysteretic.cin,
            "aoneCustom" => &mut m.hysteretic.a1,
            "atwoCustom" => &mut m.hysteretic.a2,
            "athreeCustom" => &mut m.hysteretic.a3,
            "kcinCustom" => &mut m.hysteretic.kcin,
            "resolutionJKR" => {
                m.resolution_jkr = p.values.first().copied();
                continue;
            }
            _ => continue,
        };
        let want = match p.style.as_str() {
            "peratomtype" => n,
            "peratomtypepair" => n * n,
            _ => {
                return Err(format!(
                    "property {name} (fix {}) must be peratomtype or peratomtypepair, not {}",
                    p.fix_id, p.style
                )
                .into())
            }
        };
        if p.values.len() != want {
            return Err(format!(
                "property {name} (fix {}) has {} value(s); the box has {n} atom type(s), so {want} are needed",
                p.fix_id,
                p.values.len()
            ).into());
        }
        *slot = p.values.clone();
    }
    let cg = sim.setup.coarse_graining;
    if cg.active() {
        crate::coarse_graining::scale_stiffness(&mut m, cg.factor);
    }
    Ok(m)
}

/// Reads the liquid-bridge property `name` (`cohesion easo/capillary/viscous`) into `m`, if
/// it is one: `contactAngle` per type, the others scalars. One of another style or count
/// (another model's property of the same name) is left out: the bridge model, if used,
/// then stops the run saying which property it needs and how.
fn liquid_property(
    m: &mut Materials,
    name: &str,
    p: &crate::sim::Property,
    n: usize,
) -> Option<()> {
    let l = &mut m.liquid;
    let slot = match name {
        "surfaceLiquidContentInitial" => &mut l.content_initial,
        "surfaceTension" => &mut l.surface_tension,
        "fluidViscosity" => &mut l.fluid_viscosity,
        "minSeparationDistanceRatio" => &mut l.min_separation,
        "maxSeparationDistanceRatio" => &mut l.max_separation,
        "contactAngle" => {
            if p.style == "peratomtype" && p.values.len() == n {
                l.contact_angle = p.values.clone();
            }
            return Some(());
        }
        _ => return None,
    };
    if p.style == "scalar" {
        *slot = p.values.first().copied();
    }
    Some(())
}
