//! Placement shared by the insertion fixes: draw positions from a sampler until a sphere
//! fits without overlapping what is there (`overlapcheck yes`), with `maxattempt` tries
//! per particle pooled over one insertion as LIGGGHTS does, largest templates first.

use std::collections::HashMap;

use glam::{DQuat, DVec3};
use rand::Rng;
use rand_distr::{Distribution as _, Normal};

use super::{ClumpShape, Distribution, InsertRng, Orientation, ParticleTemplate, VelocityLaw};
use crate::error::Result;
use crate::multisphere::NewClump;
use crate::particles::{NewParticle, Tag};
use crate::world::World;

/// A rotation drawn uniformly over all rotations (Shoemake's method: a uniform point on
/// the unit 3-sphere from three uniform numbers).
pub(crate) fn random_rotation(rng: &mut InsertRng) -> DQuat {
    let (u1, u2, u3): (f64, f64, f64) = (rng.gen(), rng.gen(), rng.gen());
    let tau = std::f64::consts::TAU;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    DQuat::from_xyzw(
        a * (tau * u2).sin(),
        a * (tau * u2).cos(),
        b * (tau * u3).sin(),
        b * (tau * u3).cos(),
    )
    .normalize()
}

/// The orientation of a new clump of `shape` (body frame to space frame).
fn draw_orientation(law: Orientation, shape: &ClumpShape, rng: &mut InsertRng) -> DQuat {
    match law {
        Orientation::Random => random_rotation(rng),
        Orientation::Template => shape.q_template(),
        Orientation::Constant(q) => (q * shape.q_template()).normalize(),
    }
}

/// Draws a velocity from `law`.
pub(crate) fn draw_velocity(law: VelocityLaw, rng: &mut InsertRng) -> DVec3 {
    match law {
        VelocityLaw::Constant(v) => v,
        VelocityLaw::Uniform(m, d) => DVec3::new(
            m.x + d.x * (rng.gen::<f64>() - 0.5) * 2.0,
            m.y + d.y * (rng.gen::<f64>() - 0.5) * 2.0,
            m.z + d.z * (rng.gen::<f64>() - 0.5) * 2.0,
        ),
        VelocityLaw::Gaussian(m, s) => {
            let mut c = |mu: f64, sigma: f64| {
                if sigma > 0.0 {
                    Normal::new(mu, sigma)
                        .map(|n| n.sample(&mut *rng))
                        .unwrap_or(mu)
                } else {
                    mu
                }
            };
            DVec3::new(c(m.x, s.x), c(m.y, s.y), c(m.z, s.z))
        }
    }
}

/// One sphere, or one clump, to be inserted.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Placed {
    /// Template index in the distribution.
    pub template: usize,
    /// Centre (a clump: its centre of mass).
    pub x: DVec3,
    /// Radius (a clump: its bounding radius).
    pub radius: f64,
    /// Velocity.
    pub v: DVec3,
    /// A clump's orientation (spheres: the identity).
    pub q: DQuat,
    /// The spheres of a `multiplespheres` template go at `x + q * offset` with the
    /// template's [`ClumpShape::bound_offsets`] (`x` the bounding sphere's centre, `q`
    /// the turn from the frame they were given in), not about the centre of mass.
    pub about_bound: bool,
}

/// Existing particles (of every rank) near an insertion volume, on a grid of cells two
/// largest radii wide, for the overlap check. Across a periodic boundary a sphere near one
/// face is also held at its image beyond the other face, so a new sphere cannot overlap
/// an existing one through the boundary.
pub(crate) struct OverlapGrid {
    cell: f64,
    cells: HashMap<[i64; 3], Vec<(DVec3, f64)>>,
    /// The box's extent along each periodic axis (`None`: not periodic).
    periodic: [Option<(f64, f64)>; 3],
}

/// `x` and its periodic images within `reach` of the box (along the axes of `periodic`,
/// each the box's lo and hi along it), calling `f` on each.
fn for_images(x: DVec3, periodic: &[Option<(f64, f64)>; 3], reach: f64, mut f: impl FnMut(DVec3)) {
    let shifts = |a: usize| -> [Option<f64>; 2] {
        match periodic[a] {
            Some((lo, hi)) => {
                let len = hi - lo;
                [
                    (x[a] < lo + reach).then_some(len),
                    (x[a] > hi - reach).then_some(-len),
                ]
            }
            None => [None, None],
        }
    };
    let [sx, sy, sz] = [shifts(0), shifts(1), shifts(2)];
    for dz in std::iter::once(0.0).chain(sz.into_iter().flatten()) {
        for dy in std::iter::once(0.0).chain(sy.into_iter().flatten()) {
            for dx in std::iter::once(0.0).chain(sx.into_iter().flatten()) {
                f(x + DVec3::new(dx, dy, dz));
            }
        }
    }
}

impl OverlapGrid {
    /// The particles of `world` within reach of the box `bb` (`None`: everywhere),
    /// gathered from every rank so that each rank places the same particles with the
    /// same random numbers (the result does not depend on the number of ranks).
    pub fn gather(world: &World, bb: Option<(DVec3, DVec3)>, max_new_radius: f64) -> Self {
        let p = &world.particles;
        let n = p.nlocal();
        let rmax = world
            .comm
            .max(p.radius[..n].iter().copied().fold(max_new_radius, f64::max));
        let d = &world.domain;
        let periodic = [0, 1, 2].map(|a| d.periodic(a).then_some((d.boxlo[a], d.boxhi[a])));
        let reach = DVec3::splat(2.0 * rmax);
        let near = |x: DVec3| {
            bb.is_none_or(|(lo, hi)| x.cmpge(lo - reach).all() && x.cmple(hi + reach).all())
        };
        let mut mine = Vec::new();
        for i in 0..n {
            let x = p.x[i];
            let mut inside = false;
            for_images(x, &periodic, 2.0 * rmax, |y| inside |= near(y));
            if inside {
                mine.extend_from_slice(&[x.x, x.y, x.z, p.radius[i]]);
            }
        }
        let near = world.comm.all_gather(&mine);
        let mut g = Self {
            cell: 2.0 * rmax,
            cells: HashMap::new(),
            periodic,
        };
        for c in near.chunks_exact(4) {
            g.push(DVec3::new(c[0], c[1], c[2]), c[3]);
        }
        g
    }

    fn key(&self, x: DVec3) -> [i64; 3] {
        [
            (x.x / self.cell).floor() as i64,
            (x.y / self.cell).floor() as i64,
            (x.z / self.cell).floor() as i64,
        ]
    }

    /// Adds a sphere (and its periodic images near the box).
    pub fn push(&mut self, x: DVec3, r: f64) {
        let (periodic, reach) = (self.periodic, self.cell);
        for_images(x, &periodic, reach, |y| {
            let k = self.key(y);
            self.cells.entry(k).or_default().push((y, r));
        });
    }

    /// True if a sphere at `x` of radius `r` overlaps none of the grid's.
    pub fn is_free(&self, x: DVec3, r: f64) -> bool {
        let c = self.key(x);
        !(-1..=1).any(|dz| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    self.cells
                        .get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        .is_some_and(|v| {
                            v.iter()
                                .any(|&(y, ry)| (x - y).length_squared() < (r + ry) * (r + ry))
                        })
                })
            })
        })
    }
}

/// Chooses positions for up to `wanted` particles of `dist` (the per-template counts of
/// [`Distribution::counts_for`], largest first). `sample(rng, r)` draws a centre where a
/// sphere of radius `r` may go (`None`: the volume has no room at all; a clump is drawn
/// with its bounding radius, as LIGGGHTS does); with `grid` given the spheres (each
/// sphere of a clump, turned as `orientation` says, drawn with each try) may not overlap
/// its spheres or each other. The insertion may make `budget` tries in all (the caller's
/// `maxattempt` per particle, pooled). Each placed particle's velocity is drawn right
/// after its position.
#[allow(clippy::too_many_arguments)]
pub(crate) fn choose(
    dist: &mut Distribution,
    rng: &mut InsertRng,
    wanted: u64,
    mut budget: u64,
    mut grid: Option<&mut OverlapGrid>,
    orientation: Orientation,
    mut sample: impl FnMut(&mut InsertRng, f64) -> Option<DVec3>,
    velocity: VelocityLaw,
) -> Vec<Placed> {
    let counts = dist.counts_for(wanted as usize);
    let mut out = Vec::with_capacity(wanted as usize);
    for (k, &count) in counts.iter().enumerate() {
        let clump = dist.templates[k].clump.clone();
        for _ in 0..count {
            let r = dist.templates[k].draw_radius();
            let mut placed = None;
            while budget > 0 {
                budget -= 1;
                let Some(x) = sample(rng, r) else { break };
                let q = clump
                    .as_ref()
                    .map_or(DQuat::IDENTITY, |c| draw_orientation(orientation, c, rng));
                let free = grid.as_ref().is_none_or(|g| match &clump {
                    None => g.is_free(x, r),
                    Some(c) => (c.template.spheres.iter()).all(|s| g.is_free(x + q * s.x, s.r)),
                });
                if free {
                    placed = Some((x, q));
                    break;
                }
            }
            let Some((x, q)) = placed else { continue };
            if let Some(g) = grid.as_mut() {
                match &clump {
                    None => g.push(x, r),
                    Some(c) => c
                        .template
                        .spheres
                        .iter()
                        .for_each(|s| g.push(x + q * s.x, s.r)),
                }
            }
            out.push(Placed {
                template: k,
                x,
                radius: r,
                v: draw_velocity(velocity, rng),
                q,
                about_bound: false,
            });
        }
    }
    out
}

/// The tags of an insertion's particles: each copy placed takes the next block of tags,
/// its spheres in the template's order, in the order the copies are placed. Every rank
/// places every copy, so every rank knows every new tag (a bond of a template across two
/// ranks' subdomains is made by both, each knowing the other sphere's tag), and the tags
/// are the same on any number of ranks (serially, the order of
/// [`World::extend_tags`]).
pub(crate) struct TagCursor(Tag);

impl TagCursor {
    /// The first tag after the largest on any rank (collective).
    pub(crate) fn new(world: &World) -> Self {
        let (_, max) = world.particles.tag_extent();
        Self(world.comm.max_count(max) + 1)
    }

    /// The first of the next `n` tags.
    fn take(&mut self, n: usize) -> Tag {
        let first = self.0;
        self.0 += n as Tag;
        first
    }
}

/// The bonds of an inserted bonded template whose spheres were added at the local
/// indices `at` (`None`: on another rank) with the tags `first..`: each rank makes the
/// sides of the spheres it holds.
fn bond_template(
    world: &mut World,
    id: &str,
    bonds: &[(u32, u32, u32)],
    at: &[Option<usize>],
    first: Tag,
) -> Result<()> {
    let Some(store) = world.bonds.as_mut() else {
        return Err(crate::error::Error::Invalid {
            what: "particletemplate/multiplespheres",
            reason: format!("template '{id}' has bonds: it needs atom_style ... bond/gran"),
        });
    };
    for &(a, b, t) in bonds {
        for (me, other) in [(a, b), (b, a)] {
            if let Some(i) = at[me as usize] {
                store.add_pending(i, first + other as Tag, t);
            }
        }
    }
    Ok(())
}

/// Adds the placed sphere or clump `pl` (of a template of `dist`, spinning at `omega`,
/// in the groups `groupbit` and `all`) to `world` if this rank owns its position (a
/// clump's centre of mass; every rank adds a clump's body); returns its mass and, when
/// added here, the indices of its particles (one sphere, or a clump's spheres).
pub(crate) fn add_placed(
    world: &mut World,
    dist: &Distribution,
    pl: &Placed,
    omega: DVec3,
    groupbit: u32,
    tags: &mut TagCursor,
) -> Result<(f64, Option<std::ops::Range<usize>>)> {
    // The particles join the distribution's groups too (LIGGGHTS 3.8).
    let t = &dist.templates[pl.template];
    add_placed_of(world, t, pl, omega, groupbit | dist.groupbit, tags)
}

/// [`add_placed`] for the template `t` itself (`pl.template` only keys a bonded copy's
/// random bond ID).
pub(crate) fn add_placed_of(
    world: &mut World,
    t: &ParticleTemplate,
    pl: &Placed,
    omega: DVec3,
    groupbit: u32,
    tags: &mut TagCursor,
) -> Result<(f64, Option<std::ops::Range<usize>>)> {
    // The particles join the template's groups too (LIGGGHTS 3.8).
    let groupbit = groupbit | t.groupbit;
    if let Some(c) = t.clump.as_ref().filter(|c| !c.rigid) {
        // Separate spheres: each goes to the rank that owns its centre; the spheres of a
        // bonded template share a new molecule ID.
        let first = world.particles.nlocal();
        let molecule = match world.bonds.as_mut() {
            Some(b) if !c.bonds.is_empty() => b.molecule_id().map(|id| (id, b.next_molecule())),
            _ => None,
        };
        // LIGGGHTS-INL's bonded copy: one random bond ID for its spheres, the same on
        // every rank (keyed by where the copy goes).
        let random_id = if c.random_bond_id {
            let key =
                pl.x.to_array()
                    .iter()
                    .fold(pl.template as u64, |k, v| k.rotate_left(21) ^ v.to_bits());
            let id = world
                .particles
                .property(crate::bond::RANDOM_ID)
                .ok_or_else(|| crate::error::Error::Invalid {
                    what: "particletemplate/multiplespheres",
                    reason: format!(
                        "template '{}' is bonded, but its spheres have no {}",
                        t.id,
                        crate::bond::RANDOM_ID
                    ),
                })?;
            Some((id, crate::bond::random_id(world.step, key)))
        } else {
            None
        };
        let first_tag = tags.take(c.template.spheres.len());
        let mut at = Vec::with_capacity(c.template.spheres.len());
        for (k, s) in c.template.spheres.iter().enumerate() {
            let x = match c.bound_offsets.get(k).filter(|_| pl.about_bound) {
                Some(&o) => pl.x + pl.q * o,
                None => pl.x + pl.q * s.x,
            };
            if !world.owns_inserted(x) {
                at.push(None);
                continue;
            }
            let mut np = NewParticle::at(x, s.r, t.density)
                .with_type(c.sphere_type(k).unwrap_or(t.ty))
                .with_omega(omega)
                .with_tag(first_tag + k as Tag);
            np.v = pl.v;
            np.mask = 1 | groupbit;
            let i = world.add_particle(&np)?;
            if let Some((id, m)) = molecule {
                world.particles.props[id.0].data[i] = m;
            }
            if let Some((id, r)) = random_id {
                world.particles.props[id.0].data[i] = r;
            }
            at.push(Some(i));
        }
        if !c.bonds.is_empty() {
            bond_template(world, &t.id, &c.bonds, &at, first_tag)?;
        }
        let last = world.particles.nlocal();
        return Ok((c.template.props.mass, (last > first).then_some(first..last)));
    }
    if let Some(c) = &t.clump {
        if world.multisphere.is_none() {
            return Err(crate::error::Error::Invalid {
                what: "particletemplate/multisphere",
                reason: format!(
                    "inserting clumps of template '{}' needs a fix multisphere",
                    t.id
                ),
            });
        }
        // Every rank holds every body; the owner of its centre adds its spheres.
        let owned = world.owns_inserted(pl.x);
        let first = world.particles.nlocal();
        let first_tag = tags.take(c.template.spheres.len());
        let tag = world.add_clump_on(
            &c.template,
            &NewClump {
                x: pl.x,
                q: pl.q,
                v: pl.v,
                omega,
                ty: t.ty,
                mask: 1 | groupbit,
            },
            owned,
        )?;
        let ms = world.multisphere.as_mut().expect("a clump was added");
        debug_assert_eq!(ms.tags.last(), Some(&tag));
        let body = ms.bodies.last_mut().expect("a clump was added");
        body.fflag = c.fflag;
        body.tflag = c.tflag;
        let info = ms.info.last_mut().expect("a clump was added");
        info.density = t.density;
        info.clump_type = c.clump_type;
        let last = world.particles.nlocal();
        for (k, i) in (first..last).enumerate() {
            world.particles.tag[i] = first_tag + k as Tag;
        }
        return Ok((c.template.props.mass, owned.then_some(first..last)));
    }
    let mut np = NewParticle::at(pl.x, pl.radius, t.density)
        .with_type(t.ty)
        .with_omega(omega)
        .with_tag(tags.take(1));
    np.v = pl.v;
    np.mask = 1 | groupbit;
    let mass = crate::particles::sphere_mass(np.density, pl.radius);
    let index = if world.owns_inserted(pl.x) {
        let i = world.add_particle(&np)?;
        Some(i..i + 1)
    } else {
        None
    };
    Ok((mass, index))
}
