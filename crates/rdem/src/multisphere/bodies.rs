//! The rigid clumps of a world (`fix multisphere`) and their place in the step.
//!
//! Each clump is a [`RigidBody`] and a set of member spheres, ordinary particles that
//! carry two named properties: the body's tag ([`BODY_PROP`], 0 for a free sphere) and
//! their centre in the body frame ([`OFFSET_PROP`]). Being properties, both travel with
//! their particles through sorting, removal and restarts. The step:
//!
//! - initial integrate: every body's half kick, drift and rotation, then its spheres put
//!   where the body says (x = X + R d, v = V + ω × R d, ω of the body);
//! - the forces as usual; pairs of spheres of one body are left out of the neighbor list
//!   ([`crate::neighbor::Exclusions::same_body`]);
//! - final integrate: each body's force and torque summed from its spheres, its half
//!   kick, and its spheres' velocities set again.
//!
//! Gravity: `fix gravity` acts on the spheres as on any particle (their masses are the
//! body's mass shared in proportion to their volumes, so they add up to it), but the
//! torque about the centre of mass leaves it out: gravity acts at the centre of mass, as
//! LIGGGHTS applies it to the body and not to its spheres.
//!
//! Contacts: a clump's sphere takes its body's mass into the effective mass m* of its
//! contacts, as LIGGGHTS does ([`crate::particles::Particles::mass_of_contact`]).
//!
//! Periodic boundaries: a body's centre of mass is never wrapped; each sphere is wrapped
//! by re-neighboring as any particle, and placed at the image its image counts say.
//!
//! Several ranks: every rank holds every body (the same list, in the same order), and
//! each rank's spheres are ordinary owned particles that migrate between ranks with
//! their two properties. Each rank adds up its spheres' forces and torques, the shares
//! are gathered and added in rank order, and every rank integrates every body alike. A
//! body goes on every rank when any rank loses one of its spheres.

use glam::{DQuat, DVec3};

use super::{ClumpTemplate, RigidBody};
use crate::error::Result;
use crate::fix::FixKind;
use crate::particles::{sphere_mass, NewParticle, PropId};
use crate::world::World;

/// Per-particle property: the tag of the body a sphere belongs to (0: none).
pub const BODY_PROP: &str = "multisphere_body";
/// Per-particle property: a member sphere's centre in its body's frame.
pub const OFFSET_PROP: &str = "multisphere_offset";

/// The rigid clumps of a world.
#[derive(Debug, Clone, Default)]
pub struct Multisphere {
    /// The bodies.
    pub bodies: Vec<RigidBody>,
    /// Each body's tag (from 1), as its spheres' [`BODY_PROP`] holds it.
    pub tags: Vec<u64>,
    /// What each body is made of (for output).
    pub info: Vec<BodyInfo>,
    /// Each tag's index in `bodies`, kept by [`Multisphere::reindex`].
    slots: Slots,
    /// Scratch of the step: each body's angular velocity.
    omegas: Vec<DVec3>,
    /// Scratch of the step: the gravity fixes (group bit, acceleration).
    gravity: Vec<(u32, DVec3)>,
    /// Scratch of the step: this rank's share of the bodies' forces and torques (and
    /// velocity gains, see [`World::sum_body_forces`]).
    reduce: Vec<f64>,
    /// Scratch of the step: the velocity each body gains as `insert/stream` releases it.
    gains: Vec<DVec3>,
}

/// What a body is made of, as `compute multisphere` reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyInfo {
    /// Density of its template (`density constant`).
    pub density: f64,
    /// Atom type of its spheres.
    pub atom_type: u32,
    /// Multisphere type of its template (`type MT` of `fix particletemplate/multisphere`;
    /// 0 if not from a template).
    pub clump_type: u32,
    /// Radius of its template's bounding sphere ([`super::ClumpTemplate::enclosing`]),
    /// which `fix insert/fragments` scales fragments by (0: unknown, a body from a
    /// restart file of an older rdem).
    pub bound: f64,
    /// Its template's frame: the rotation from the frame the template's spheres were
    /// given in to the body frame (the template's principal axes).
    pub frame: DQuat,
}

impl Multisphere {
    /// Rebuilds the index of each body tag in [`Multisphere::bodies`]; to call whenever
    /// bodies are added or dropped.
    pub(crate) fn reindex(&mut self) {
        let top = self.tags.iter().copied().max().unwrap_or(0) as usize;
        let of = &mut self.slots.of;
        of.clear();
        of.resize(top + 1, usize::MAX);
        for (k, &t) in self.tags.iter().enumerate() {
            of[t as usize] = k;
        }
        self.slots.n = self.tags.len();
    }

    /// The index in [`Multisphere::bodies`] of the body whose tag a sphere's
    /// [`BODY_PROP`] value `tag` holds (`None`: a free sphere, or a body that is gone).
    #[inline]
    pub fn body_of(&self, tag: f64) -> Option<usize> {
        self.slots.get(tag)
    }

    /// Appends a body (and keeps the index).
    pub(crate) fn push(&mut self, body: RigidBody, tag: u64, info: BodyInfo) {
        self.bodies.push(body);
        self.tags.push(tag);
        self.info.push(info);
        let t = tag as usize;
        if self.slots.of.len() <= t {
            self.slots.of.resize(t + 1, usize::MAX);
        }
        self.slots.of[t] = self.bodies.len() - 1;
        self.slots.n = self.bodies.len();
    }
}

/// Each body tag's index in [`Multisphere::bodies`], by a table indexed by tag (tags are
/// given in order, so the table is dense; a lookup per sphere and step must be cheap).
#[derive(Debug, Clone, Default)]
struct Slots {
    of: Vec<usize>,
    n: usize,
}

impl Slots {
    /// The body of a sphere whose [`BODY_PROP`] value is `tag` (`None`: a free sphere,
    /// or a body that is gone).
    #[inline]
    fn get(&self, tag: f64) -> Option<usize> {
        let t = tag as usize;
        if t == 0 {
            return None;
        }
        self.of.get(t).copied().filter(|&k| k != usize::MAX)
    }

    /// The number of bodies.
    fn len(&self) -> usize {
        self.n
    }
}

/// Drops the entries of `v` whose `gone` flag is set (one flag per entry).
fn drop_gone<T>(v: &mut Vec<T>, gone: &[bool]) {
    let mut k = 0;
    v.retain(|_| {
        k += 1;
        !gone[k - 1]
    });
}

/// A clump to add: where, how it is turned and how it moves.
#[derive(Debug, Clone, Copy)]
pub struct NewClump {
    /// Centre of mass.
    pub x: DVec3,
    /// Orientation (body frame to space frame).
    pub q: DQuat,
    /// Velocity of the centre of mass.
    pub v: DVec3,
    /// Angular velocity (space frame).
    pub omega: DVec3,
    /// Atom type of the spheres.
    pub ty: u32,
    /// Group bit mask of the spheres.
    pub mask: u32,
}

impl World {
    /// Adds a clump of `template` as `c` says: its spheres as particles, its body to
    /// [`World::multisphere`] (made if there is none). Returns the body's tag. On several
    /// ranks, every rank must add it (see [`World::add_clump_on`]).
    pub fn add_clump(&mut self, template: &ClumpTemplate, c: &NewClump) -> Result<u64> {
        self.add_clump_on(template, c, true)
    }

    /// [`World::add_clump`], with its spheres only where `spheres` (the rank that owns
    /// the centre of mass; exchange moves them to their owners at the next
    /// re-neighboring). Every rank holds every body, so every rank adds each clump, in
    /// the same order: the tags agree.
    pub fn add_clump_on(
        &mut self,
        template: &ClumpTemplate,
        c: &NewClump,
        spheres: bool,
    ) -> Result<u64> {
        let (body_id, offset_id) = self.multisphere_props()?;
        // Clumps added during a run: their spheres are kept apart from the first.
        self.neighbor.exclude.same_body = Some(body_id);
        let last = self.multisphere.as_ref().and_then(|ms| ms.tags.last());
        let tag = last.map_or(1, |t| t + 1);
        let mut body = RigidBody::at_rest(template.props.mass, template.moments, c.x, c.q);
        body.v = c.v;
        body.set_omega(c.omega);
        let vol: f64 = template.spheres.iter().map(|s| s.r.powi(3)).sum();
        let omega = body.omega();
        for s in template.spheres.iter().filter(|_| spheres) {
            let (x, v) = body.point(s.x);
            // The sphere's share of the body's mass, by volume.
            let share = template.props.mass * s.r.powi(3) / vol;
            let density = share / sphere_mass(1.0, s.r);
            let i = self.add_particle(&NewParticle {
                tag: 0,
                ty: c.ty,
                mask: c.mask,
                x,
                v,
                omega,
                radius: s.r,
                density,
            })?;
            let p = &mut self.particles;
            p.props[body_id.0].data[i] = tag as f64;
            p.props[offset_id.0].data[3 * i..3 * i + 3].copy_from_slice(&s.x.to_array());
        }
        let ms = self.multisphere.get_or_insert_with(Multisphere::default);
        let info = BodyInfo {
            density: template.props.mass / template.props.volume,
            atom_type: c.ty,
            clump_type: 0,
            bound: template.enclosing.1,
            frame: DQuat::from_mat3(&template.axes.transpose()).normalize(),
        };
        ms.push(body, tag, info);
        Ok(tag)
    }

    /// Extends `remove` (a flag for each owned particle) to every sphere of each body one
    /// of whose spheres it holds, and drops those bodies (LIGGGHTS removes a body when
    /// any of its spheres goes). Returns how many bodies were dropped. With clumps on
    /// several ranks, a collective call: every rank makes it, `remove` empty or not.
    pub fn remove_whole_bodies(&mut self, remove: &mut [bool]) -> usize {
        let Some(ms) = &self.multisphere else {
            return 0;
        };
        let body_id = self.particles.property(BODY_PROP);
        let n = remove.len().min(self.particles.nlocal());
        let mut gone = vec![false; ms.slots.len()];
        if let Some(id) = body_id {
            let tags = &self.particles.props[id.0].data;
            for i in (0..n).filter(|&i| remove[i]) {
                if let Some(k) = ms.slots.get(tags[i]) {
                    gone[k] = true;
                }
            }
        }
        if self.comm.size() > 1 {
            // Every rank holds every body: each drops those any rank lost a sphere of.
            let mine: Vec<f64> = (0..gone.len())
                .filter(|&k| gone[k])
                .map(|k| ms.tags[k] as f64)
                .collect();
            for t in self.comm.all_gather(&mine) {
                if let Some(k) = ms.slots.get(t) {
                    gone[k] = true;
                }
            }
        }
        if !gone.iter().any(|&g| g) {
            return 0;
        }
        if let Some(id) = body_id {
            let tags = &self.particles.props[id.0].data;
            for i in 0..n {
                if let Some(k) = ms.slots.get(tags[i]) {
                    remove[i] |= gone[k];
                }
            }
        }
        let ms = self.multisphere.as_mut().expect("checked above");
        drop_gone(&mut ms.bodies, &gone);
        drop_gone(&mut ms.tags, &gone);
        drop_gone(&mut ms.info, &gone);
        ms.reindex();
        gone.iter().filter(|&&g| g).count()
    }

    /// Before a force computation: the contact mass of every particle, its body's for a
    /// clump's sphere, else its own ([`crate::particles::Particles::mass_of_contact`]).
    pub(crate) fn refresh_contact_mass(&mut self) {
        let Some((body_id, _)) = self.members() else {
            return;
        };
        let Some(ms) = &self.multisphere else {
            return;
        };
        let p = &mut self.particles;
        let n = p.len();
        let tags = &p.props[body_id.0].data;
        p.mass_of_contact.clear();
        p.mass_of_contact.extend((0..n).map(|i| {
            match ms.slots.get(tags.get(i).copied().unwrap_or(0.0)) {
                Some(k) => ms.bodies[k].mass,
                None => p.rmass[i],
            }
        }));
    }

    /// Which clump each particle belongs to: for particle `i`, the index of its body in
    /// [`Multisphere::bodies`] (`None`: a free sphere, or no clumps at all).
    pub fn clump_of(&self) -> impl Fn(usize) -> Option<usize> + '_ {
        let p = &self.particles;
        let ms = self.multisphere.as_ref().zip(p.property(BODY_PROP));
        move |i| ms.and_then(|(ms, b)| ms.body_of(p.props[b.0].data[i]))
    }

    /// The two member properties, added if missing.
    fn multisphere_props(&mut self) -> Result<(PropId, PropId)> {
        let p = &mut self.particles;
        let body = match p.property(BODY_PROP) {
            Some(id) => id,
            None => p.add_property(BODY_PROP, 1, &[0.0])?,
        };
        let offset = match p.property(OFFSET_PROP) {
            Some(id) => id,
            None => p.add_property(OFFSET_PROP, 3, &[0.0; 3])?,
        };
        Ok((body, offset))
    }

    /// The two member properties (`None` without clumps).
    fn members(&self) -> Option<(PropId, PropId)> {
        self.multisphere.as_ref()?;
        let p = &self.particles;
        Some((p.property(BODY_PROP)?, p.property(OFFSET_PROP)?))
    }

    /// Set-up: the checks, and the spheres of one body excluded from each other.
    pub(crate) fn setup_multisphere(&mut self) -> Result<()> {
        if self.multisphere.is_none() {
            return Ok(());
        }
        let (body, _) = self.multisphere_props()?;
        self.neighbor.exclude.same_body = Some(body);
        Ok(())
    }

    /// Step 2 (after the integrating fixes): every body's first half step, then its
    /// spheres placed and moving with it.
    pub(crate) fn initial_integrate_bodies(&mut self) {
        let Some(ms) = &mut self.multisphere else {
            return;
        };
        for b in &mut ms.bodies {
            b.initial_integrate(self.dt);
        }
        self.place_members(true);
    }

    /// Body `k`'s centre of mass and velocity as the box holds it: wrapped into the
    /// periodic box, and under Lees–Edwards shear moved by the offset along x and by
    /// γ̇ L_y in v_x for each box length it was wrapped along y ([`crate::shear`]). The
    /// body itself keeps both unwrapped.
    pub fn body_in_box(&self, k: usize) -> Option<(DVec3, DVec3)> {
        let b = self.multisphere.as_ref()?.bodies.get(k)?;
        let (mut x, mut v) = (b.x, b.v);
        if let Some(s) = &self.domain.shear {
            crate::shear::wrap_y(s, self.domain.boxlo, self.domain.prd(), &mut x, &mut v);
        }
        let mut image = [0; 3];
        self.domain.remap(&mut x, &mut image);
        Some((x, v))
    }

    /// Every clump's spheres moving with their body again (after a body's velocity was
    /// set from outside the step).
    pub fn refresh_clump_velocities(&mut self) {
        self.place_members(false);
    }

    /// Step 13 (after the integrating fixes): every body's force and torque from its
    /// spheres, its second half kick, and its spheres' velocities.
    pub(crate) fn final_integrate_bodies(&mut self) {
        if self.multisphere.is_none() {
            return;
        }
        self.sum_body_forces();
        if let Some(ms) = &mut self.multisphere {
            for b in &mut ms.bodies {
                b.final_integrate(self.dt);
            }
        }
        self.place_members(false);
    }

    /// Each body's total force and torque about its centre of mass from its owned
    /// spheres, in particle order; the torque leaves out the gravity of the `fix gravity`
    /// fixes (gravity acts at the centre of mass), and spheres `insert/stream` holds add
    /// nothing (the body drifts until released). A body that `insert/stream` has just
    /// released gains the rest of its insertion velocity, which its spheres carry
    /// ([`crate::insert::stream::TANGENT_PROPERTY`]; every copy is the same, and every
    /// rank takes it from the first rank that has one).
    pub(crate) fn sum_body_forces(&mut self) {
        let Some((body_id, offset_id)) = self.members() else {
            return;
        };
        let Some(ms) = &mut self.multisphere else {
            return;
        };
        let p = &mut self.particles;
        ms.gravity.clear();
        ms.gravity
            .extend(self.fixes.iter().filter_map(|f| match f.kind {
                FixKind::Gravity { accel } => Some((f.groupbit, accel)),
                _ => None,
            }));
        for b in &mut ms.bodies {
            b.force = DVec3::ZERO;
            b.torque = DVec3::ZERO;
        }
        ms.gains.clear();
        ms.gains.resize(ms.bodies.len(), DVec3::ZERO);
        // Spheres `insert/stream` still holds (their forces are zero) carry their body.
        let held = p.property(crate::insert::stream::HOLD_PROPERTY);
        let tangent = p.property(crate::insert::stream::TANGENT_PROPERTY);
        let step = self.step as f64;
        for i in 0..p.nlocal() {
            let Some(k) = ms.slots.get(p.props[body_id.0].data[i]) else {
                continue;
            };
            if held.is_some_and(|h| p.props[h.0].data[i] > step) {
                continue;
            }
            if let Some(t) = tangent {
                let d = &mut p.props[t.0].data[3 * i..3 * i + 3];
                if d.iter().any(|&c| c != 0.0) {
                    ms.gains[k] = DVec3::from_slice(d);
                    d.fill(0.0);
                }
            }
            let offsets = &p.props[offset_id.0].data;
            let b = &mut ms.bodies[k];
            let d = b.q * DVec3::from_slice(&offsets[3 * i..3 * i + 3]);
            let g: DVec3 = ms
                .gravity
                .iter()
                .filter(|(bit, _)| p.mask[i] & bit != 0)
                .map(|(_, a)| p.rmass[i] * *a)
                .sum();
            b.force += p.f[i];
            b.torque += d.cross(p.f[i] - g) + p.torque[i];
        }
        if self.comm.size() > 1 {
            // Every rank's share, gathered and added in rank order: the same sums, bit for
            // bit, on every rank, which then integrate every body alike.
            let buf = &mut ms.reduce;
            buf.clear();
            for (b, g) in ms.bodies.iter().zip(&ms.gains) {
                buf.extend_from_slice(&b.force.to_array());
                buf.extend_from_slice(&b.torque.to_array());
                buf.extend_from_slice(&g.to_array());
            }
            let all = self.comm.all_gather(buf);
            let per_rank = buf.len();
            for (k, b) in ms.bodies.iter_mut().enumerate() {
                let (mut f, mut t, mut g) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
                for share in all.chunks_exact(per_rank.max(1)) {
                    f += DVec3::from_slice(&share[9 * k..9 * k + 3]);
                    t += DVec3::from_slice(&share[9 * k + 3..9 * k + 6]);
                    let gain = DVec3::from_slice(&share[9 * k + 6..9 * k + 9]);
                    if g == DVec3::ZERO {
                        g = gain;
                    }
                }
                b.force = f;
                b.torque = t;
                ms.gains[k] = g;
            }
        }
        for (b, g) in ms.bodies.iter_mut().zip(&ms.gains) {
            b.v += *g;
        }
    }

    /// The spheres of every body where it says (with `positions`) and moving with it. The
    /// centre of mass is unwrapped; a sphere is put at the periodic image its own image
    /// counts say, x = X + R d − n ⊙ L, so that it stays where re-neighboring wrapped it.
    /// Under Lees–Edwards shear the image n_y boxes up is also shifted by n_y times the
    /// offset along x and moves n_y γ̇ L_y faster ([`crate::shear`]): x_x less n_y d,
    /// v_x less n_y γ̇ L_y.
    fn place_members(&mut self, positions: bool) {
        let Some((body_id, offset_id)) = self.members() else {
            return;
        };
        let Some(ms) = &mut self.multisphere else {
            return;
        };
        let periodic = self.domain.periodicity().iter().any(|&p| p);
        let prd = self.domain.prd();
        let shear = self.domain.shear.map(|s| (s.offset, s.jump(prd.y)));
        let p = &mut self.particles;
        ms.omegas.clear();
        ms.omegas.extend(ms.bodies.iter().map(RigidBody::omega));
        for i in 0..p.nlocal() {
            let Some(k) = ms.slots.get(p.props[body_id.0].data[i]) else {
                continue;
            };
            let b = &ms.bodies[k];
            let off = &p.props[offset_id.0].data[3 * i..3 * i + 3];
            let r = b.q * DVec3::from_slice(off);
            if positions {
                p.x[i] = b.x + r;
                if periodic {
                    let n = p.image[i].get();
                    p.x[i] -= DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) * prd;
                }
            }
            p.v[i] = b.v + ms.omegas[k].cross(r);
            p.omega[i] = ms.omegas[k];
            if let Some((offset, jump)) = shear {
                let ny = p.image[i].get()[1] as f64;
                if positions {
                    p.x[i].x -= ny * offset;
                }
                p.v[i].x -= ny * jump;
            }
        }
    }
}
