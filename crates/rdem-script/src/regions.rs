//! Regions as the script defines them: the engine's [`Region`] where it was defined, and
//! for a moving region (`move v_x v_y v_z`, `rotate v_theta Px Py Pz Rx Ry Rz`) the
//! equal-style variables that place it. A use of a region takes it where it is at the
//! current step (LAMMPS evaluates the variables each time a dynamic region is used).

use crate::error::Error;
use glam::DVec3;
use rdem::region::{Pose, Region, Shape};

use crate::context::equal_variable;
use crate::sim::Sim;

/// How a region moves: each a variable name (without `v_`), `None` for no motion.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Motion {
    /// `move`: x, y, z displacement variables (`NULL`: none).
    pub shift: [Option<String>; 3],
    /// `rotate`: angle variable (radians), point on the axis, axis direction.
    pub rotate: Option<(String, DVec3, DVec3)>,
}

/// A region definition.
#[derive(Debug, Clone)]
pub struct RegionDef {
    /// The region where it was defined.
    pub region: Region,
    /// Its motion, if it moves.
    pub motion: Option<Motion>,
    /// For `union` and `intersect`: the IDs of the parts (which may move).
    pub parts: Vec<String>,
}

impl RegionDef {
    /// A region that does not move by itself.
    pub fn fixed(region: Region, parts: Vec<String>) -> Self {
        Self {
            region,
            motion: None,
            parts,
        }
    }
}

/// A fix's `region ID` argument (the next word): the region where it is now, and its ID
/// when it moves (the fix places it again before each step).
pub fn fix_region(
    sim: &Sim,
    a: &mut crate::args::Args,
) -> crate::args::CmdResult<(Region, Option<String>)> {
    let id = sim.region_id(a)?;
    let moving = is_dynamic(sim, &id).then(|| id.clone());
    let region = region_now(sim, &id).map_err(|e| a.error_prev(e, None))?;
    Ok((region, moving))
}

/// True if region `id` or any of its parts moves (LIGGGHTS: "dynamic").
pub fn is_dynamic(sim: &Sim, id: &str) -> bool {
    sim.defs
        .regions
        .get(id)
        .is_some_and(|d| d.motion.is_some() || d.parts.iter().any(|p| is_dynamic(sim, p)))
}

/// Region `id` where it is at the world's current step. Errors: a motion variable that
/// is missing, not equal-style or fails.
pub fn region_now(sim: &Sim, id: &str) -> Result<Region, Error> {
    posed(sim, id, 0)
}

pub(crate) fn posed(sim: &Sim, id: &str, depth: usize) -> Result<Region, Error> {
    let def = sim
        .defs
        .regions
        .get(id)
        .ok_or_else(|| Error::undefined("region", id))?;
    if !is_dynamic(sim, id) {
        return Ok(def.region.clone());
    }
    let mut r = def.region.clone();
    if !def.parts.is_empty() {
        let parts = def
            .parts
            .iter()
            .map(|p| posed(sim, p, depth + 1))
            .collect::<Result<Vec<_>, _>>()?;
        r.shape = match r.shape {
            Shape::Union(_) => Shape::Union(parts),
            _ => Shape::Intersect(parts),
        };
    }
    if let Some(m) = &def.motion {
        let var = |name: &str| {
            equal_variable(sim, name, depth + 1)
                .map_err(|e| format!("region {id} moves with v_{name}: {e}"))
        };
        let mut shift = DVec3::ZERO;
        for (k, v) in m.shift.iter().enumerate() {
            if let Some(v) = v {
                shift[k] = var(v)?;
            }
        }
        let pose = match &m.rotate {
            Some((theta, point, axis)) => Pose::new(shift, *point, *axis, var(theta)?),
            None => Pose::new(shift, DVec3::ZERO, DVec3::Z, 0.0),
        };
        r = r.posed(pose);
    }
    Ok(r)
}
