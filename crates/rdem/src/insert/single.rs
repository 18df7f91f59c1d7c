//! One particle of a template put where a script says (LIGGGHTS-INL's
//! `create_particles ... single`): a sphere at the point, or the spheres of a
//! `particletemplate/multiplespheres` template with the centre of their bounding sphere
//! at the point, turned about it.

use glam::{DQuat, DVec3};

use super::place::{add_placed_of, Placed, TagCursor};
use super::ParticleTemplate;
use crate::error::{Error, Result};
use crate::world::World;

/// What [`create_single`] puts in the box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Single {
    /// Where the sphere's centre, or the template's bounding-sphere centre, goes.
    pub x: DVec3,
    /// The turn of the template about that point, from the frame its spheres are given
    /// in (the identity: as given).
    pub turn: DQuat,
    /// Velocity of every sphere.
    pub v: DVec3,
    /// Angular velocity of every sphere (each spins about its own centre; their
    /// velocities are not changed by it).
    pub omega: DVec3,
}

/// Adds one particle of `t` (a sphere of a radius drawn from its law, or every sphere of
/// a `multiplespheres` template) at `s` to the ranks that own the spheres' centres, gives
/// them the tags after the largest in the template's order, and returns how many spheres
/// it made. A rigid clump template is refused.
pub fn create_single(world: &mut World, t: &mut ParticleTemplate, s: &Single) -> Result<u64> {
    let (x, radius, q) = match &t.clump {
        Some(c) if c.rigid => {
            return Err(Error::Invalid {
                what: "create_particles",
                reason: format!(
                    "template '{}' is a rigid clump (particletemplate/multisphere); \
                     create_particles places spheres and particletemplate/multiplespheres",
                    t.id
                ),
            })
        }
        // The spheres about the bounding sphere's centre, turned from the frame they
        // were given in.
        Some(c) => (s.x, c.template.bound_radius, s.turn),
        None => (s.x, t.draw_radius(), DQuat::IDENTITY),
    };
    let pl = Placed {
        template: 0,
        x,
        radius,
        v: s.v,
        q,
        about_bound: true,
    };
    // The spheres take the tags after the largest in the template's order, whichever
    // rank holds them, so a script's `group ... id` finds the same ones on any number
    // of ranks.
    let mut tags = TagCursor::new(world);
    add_placed_of(world, t, &pl, s.omega, 0, &mut tags)?;
    let n = match t.clump.as_ref() {
        Some(c) => c.bound_offsets.len() as u64,
        None => 1,
    };
    Ok(n)
}
