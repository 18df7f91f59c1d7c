//! The engine's share of a restart file: every owned particle with all its arrays and
//! named properties (which hold the wall and mesh contact histories, temperatures and
//! every fix's per-particle values), the particle–particle contact histories (bonds
//! included) by tag pair, and the bookkeeping that decides when particles are next
//! sorted.
//!
//! [`World::rank_state`] takes one rank's share; [`World::restore_particles`] adds the
//! particles a rank owns back, in the order they were written, and keeps the contact
//! histories until the next set-up, which hands them to the neighbor list once the pair
//! style has fixed their layout (the same way a run's set-up carries histories over by
//! tag pair). A continued run therefore starts from the state the writing run had at its
//! end: the same particles in the same order, with the same histories, so that (on the
//! same number of ranks) it goes on bit for bit.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::particles::{NewParticle, Tag};
use crate::world::World;

/// Why a saved mesh state does not fit the mesh read again
/// ([`crate::wall::MeshSurface::set_state`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MeshStateError {
    /// Another number of vertices.
    #[error("it has {saved} vertices, the mesh read now {now}")]
    Vertices {
        /// In the saved state.
        saved: usize,
        /// In the mesh read now.
        now: usize,
    },
    /// Stress tallies of another number of triangles.
    #[error("its stress tallies have another number of triangles")]
    StressTriangles,
}

/// One named per-particle property of the written particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PropertyState {
    /// Name.
    pub name: String,
    /// Values per particle.
    pub width: usize,
    /// Value given to new particles.
    pub default: Vec<f64>,
    /// Forward-communicated every step.
    pub forward: bool,
    /// `width` values per particle, in particle order.
    pub data: Vec<f64>,
}

/// Owned particles of one rank, in their storage order.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ParticleState {
    /// Tags.
    pub tag: Vec<Tag>,
    /// Types.
    pub ty: Vec<u32>,
    /// Group masks.
    pub mask: Vec<u32>,
    /// Positions.
    pub x: Vec<[f64; 3]>,
    /// Velocities.
    pub v: Vec<[f64; 3]>,
    /// Angular velocities.
    pub omega: Vec<[f64; 3]>,
    /// Radii.
    pub radius: Vec<f64>,
    /// Masses.
    pub rmass: Vec<f64>,
    /// Densities.
    pub density: Vec<f64>,
    /// Periodic image counts.
    pub image: Vec<[i32; 3]>,
    /// Named properties (retired ones left out).
    pub props: Vec<PropertyState>,
}

impl ParticleState {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.tag.len()
    }
    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.tag.is_empty()
    }
}

/// Particle–particle contact histories: `[tag i, tag j, width values]` per contact with
/// non-zero history, as the list of the writing rank held it (row of i).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct HistoryState {
    /// History values per contact.
    pub width: usize,
    /// Leading values that change sign when the pair is seen from the other side.
    pub odd: usize,
    /// The contacts, flattened.
    pub entries: Vec<f64>,
}

/// One rigid clump of a restart file ([`crate::multisphere::RigidBody`] and its tag):
/// what every rdem restart file keeps of it, then what files keep since bodies kept their
/// template's bounding sphere and frame. (Postcard writes a nested struct as its fields,
/// so older files are these bytes without the last two fields: [`BodyCore`] reads them.)
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BodyState {
    /// The body itself.
    pub core: BodyCore,
    /// Radius of its template's bounding sphere (0: unknown, from an older file).
    pub bound: f64,
    /// Its template's frame (input frame to body frame): x, y, z, w.
    pub frame: [f64; 4],
}

/// The part of a [`BodyState`] that every rdem restart file keeps.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BodyCore {
    /// The tag its spheres carry.
    pub tag: u64,
    /// Mass.
    pub mass: f64,
    /// Principal moments of inertia.
    pub moments: [f64; 3],
    /// Centre of mass.
    pub x: [f64; 3],
    /// Velocity of the centre of mass.
    pub v: [f64; 3],
    /// Orientation (body frame to space frame): x, y, z, w.
    pub q: [f64; 4],
    /// Angular momentum (space frame).
    pub angmom: [f64; 3],
    /// Translational switches.
    pub fflag: [bool; 3],
    /// Rotational switches.
    pub tflag: [bool; 3],
    /// Density of its template.
    pub density: f64,
    /// Atom type of its spheres.
    pub atom_type: u32,
    /// Multisphere type of its template.
    pub clump_type: u32,
}

impl From<BodyCore> for BodyState {
    /// A body of an older restart file: its bounding sphere unknown.
    fn from(core: BodyCore) -> Self {
        Self {
            core,
            bound: 0.0,
            frame: [0.0, 0.0, 0.0, 1.0],
        }
    }
}

/// One rank's share of a restart file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RankState {
    /// Its owned particles.
    pub particles: ParticleState,
    /// Its contact histories.
    pub history: HistoryState,
    /// Its rigid clumps (`fix multisphere`: every clump in the first rank's state, none in
    /// the others', as every rank holds every clump), `None` without that fix.
    pub bodies: Option<Vec<BodyState>>,
}

/// World-wide engine values of a restart file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct WorldValues {
    /// The step.
    pub step: u64,
    /// The timestep size.
    pub dt: f64,
    /// The step of the next spatial sort.
    pub next_sort: u64,
    /// Particles lost so far.
    pub lost: u64,
}

/// `v` as an array.
fn arr(v: DVec3) -> [f64; 3] {
    v.to_array()
}

impl World {
    /// This rank's owned particles and their contact histories, in storage order.
    pub fn rank_state(&self) -> RankState {
        let p = &self.particles;
        let n = p.nlocal();
        let props = p
            .props
            .iter()
            .filter(|q| !q.name.is_empty())
            .map(|q| PropertyState {
                name: q.name.clone(),
                width: q.width,
                default: q.default.clone(),
                forward: q.forward,
                data: q.data[..n * q.width].to_vec(),
            })
            .chain(p.sparse.iter().filter(|q| !q.name.is_empty()).map(|q| {
                // Written as a dense property: the file does not depend on the layout.
                PropertyState {
                    name: q.name.clone(),
                    width: q.width,
                    default: vec![0.0; q.width],
                    forward: false,
                    data: q.dense(n),
                }
            }))
            .collect();
        let particles = ParticleState {
            tag: p.tag[..n].to_vec(),
            ty: p.ty[..n].to_vec(),
            mask: p.mask[..n].to_vec(),
            x: p.x[..n].iter().copied().map(arr).collect(),
            v: p.v[..n].iter().copied().map(arr).collect(),
            omega: p.omega[..n].iter().copied().map(arr).collect(),
            radius: p.radius[..n].to_vec(),
            rmass: p.rmass[..n].to_vec(),
            density: p.density[..n].to_vec(),
            image: p.image[..n].iter().map(|m| m.get()).collect(),
            props,
        };
        RankState {
            particles,
            history: self.neighbor.history_state(p),
            // Every rank holds every body: the first rank's state carries them.
            bodies: self.multisphere.as_ref().map(|ms| {
                let n = if self.comm.rank() == 0 {
                    ms.bodies.len()
                } else {
                    0
                };
                ms.bodies[..n]
                    .iter()
                    .zip(&ms.tags)
                    .zip(&ms.info)
                    .map(|((b, &tag), info)| BodyState {
                        core: BodyCore {
                            tag,
                            mass: b.mass,
                            moments: arr(b.moments),
                            x: arr(b.x),
                            v: arr(b.v),
                            q: b.q.to_array(),
                            angmom: arr(b.angmom),
                            fflag: b.fflag,
                            tflag: b.tflag,
                            density: info.density,
                            atom_type: info.atom_type,
                            clump_type: info.clump_type,
                        },
                        bound: info.bound,
                        frame: info.frame.to_array(),
                    })
                    .collect()
            }),
        }
    }

    /// Adds the rigid clumps of a restart file (their spheres come with the particles).
    pub fn restore_bodies(&mut self, bodies: &[BodyState]) {
        let ms = self.multisphere.get_or_insert_with(Default::default);
        for state in bodies {
            let b = &state.core;
            let mut body = crate::multisphere::RigidBody::at_rest(
                b.mass,
                DVec3::from(b.moments),
                DVec3::from(b.x),
                glam::DQuat::from_array(b.q),
            );
            body.v = DVec3::from(b.v);
            body.angmom = DVec3::from(b.angmom);
            body.fflag = b.fflag;
            body.tflag = b.tflag;
            let info = crate::multisphere::BodyInfo {
                density: b.density,
                atom_type: b.atom_type,
                clump_type: b.clump_type,
                bound: state.bound,
                frame: glam::DQuat::from_array(state.frame),
            };
            ms.push(body, b.tag, info);
        }
        if let Some(id) = self
            .particles
            .property(crate::multisphere::bodies::BODY_PROP)
        {
            self.neighbor.exclude.same_body = Some(id);
        }
    }

    /// The world-wide values a restart file keeps.
    pub fn world_values(&self) -> WorldValues {
        WorldValues {
            step: self.step,
            dt: self.dt,
            next_sort: self.next_sort,
            lost: self.lost,
        }
    }

    /// Sets the world-wide values read from a restart file.
    pub fn set_world_values(&mut self, v: &WorldValues) -> Result<()> {
        self.set_timestep(v.dt)?;
        self.step = v.step;
        self.next_sort = v.next_sort;
        self.lost = v.lost;
        Ok(())
    }

    /// Adds the particles of `s` that this rank owns (by position; all of them on one
    /// rank), in their written order, with every array and named property, and keeps the
    /// contact histories of `histories` whose first particle is now owned here for the
    /// next set-up. Returns the number of particles added.
    pub fn restore_particles(&mut self, s: &ParticleState) -> Result<usize> {
        let n = s.len();
        let lens = [
            s.ty.len(),
            s.mask.len(),
            s.x.len(),
            s.v.len(),
            s.omega.len(),
            s.radius.len(),
            s.rmass.len(),
            s.density.len(),
            s.image.len(),
        ];
        if lens.iter().any(|&l| l != n) || s.props.iter().any(|q| q.data.len() != n * q.width) {
            return Err(Error::Invalid {
                what: "restart file",
                reason: "its particle arrays have different lengths".into(),
            });
        }
        // A dense property, or the sparse one of that name (a wall's history, when the
        // wall is defined already).
        enum Target {
            Dense(crate::particles::PropId),
            Sparse(crate::particles::SparseId),
        }
        let mut ids = Vec::with_capacity(s.props.len());
        for q in &s.props {
            let id = match self.particles.sparse_property(&q.name) {
                Some(_) => Target::Sparse(self.particles.add_sparse_property(&q.name, q.width)?),
                None => Target::Dense(self.particles.add_property(&q.name, q.width, &q.default)?),
            };
            if let (Target::Dense(id), true) = (&id, q.forward) {
                self.particles.set_forward(*id);
            }
            ids.push(id);
        }
        let mut added = 0;
        for k in 0..n {
            let x = DVec3::from_array(s.x[k]);
            if !self.owns_point(x) {
                continue;
            }
            let np = NewParticle {
                tag: s.tag[k],
                ty: s.ty[k],
                mask: s.mask[k],
                x,
                v: DVec3::from_array(s.v[k]),
                omega: DVec3::from_array(s.omega[k]),
                radius: s.radius[k],
                density: s.density[k],
            };
            let i = self.add_particle(&np)?;
            let p = &mut self.particles;
            p.rmass[i] = s.rmass[k];
            p.image[i] = s.image[k].into();
            for (q, id) in s.props.iter().zip(&ids) {
                let w = q.width;
                let values = &q.data[k * w..(k + 1) * w];
                match id {
                    Target::Dense(id) => p.props[id.0].get_mut(i).copy_from_slice(values),
                    Target::Sparse(id) if values.iter().any(|v| v.to_bits() != 0) => {
                        p.sparse[id.0].get_mut(i).copy_from_slice(values)
                    }
                    Target::Sparse(_) => {}
                }
            }
            added += 1;
        }
        Ok(added)
    }

    /// Keeps the contact histories of a restart file (every rank's, concatenated) for the
    /// next set-up, which gives them to the pairs of the particles owned here.
    pub fn restore_history(&mut self, h: HistoryState) {
        self.restored_history = Some(h);
    }

    /// At a set-up, once the pair style fixed the history layout: hands the restored
    /// contact histories to the neighbor list (entries of pairs whose first particle is
    /// owned here, and their mirror images for pairs listed from the other side). A
    /// layout that differs from the pair style's (another contact model than the
    /// writing run's) drops them with a warning.
    pub(crate) fn apply_restored_history(&mut self) {
        let Some(h) = self.restored_history.take() else {
            return;
        };
        if h.entries.is_empty() {
            return;
        }
        let (w, odd) = (self.neighbor.list.width, self.neighbor.list.odd);
        if h.width != w || h.odd != odd {
            self.warnings.push(format!(
                "the restart file's contact histories have {} values per contact, the pair \
                 style now in use {w}: every contact starts afresh",
                h.width
            ));
            return;
        }
        let n = self.particles.nlocal();
        let mut owned: Vec<Tag> = self.particles.tag[..n].to_vec();
        owned.sort_unstable();
        let mine = |t: Tag| owned.binary_search(&t).is_ok();
        let stride = 2 + w;
        let mut entries = Vec::new();
        // The written entries first: where a pair was written from both sides (two
        // ranks), each side keeps its own values rather than the other's mirror image.
        for c in h.entries.chunks_exact(stride) {
            if mine(c[0] as Tag) {
                entries.extend_from_slice(c);
            }
        }
        for c in h.entries.chunks_exact(stride) {
            if mine(c[1] as Tag) {
                entries.push(c[1]);
                entries.push(c[0]);
                entries.extend(
                    c[2..]
                        .iter()
                        .enumerate()
                        .map(|(k, &v)| if k < odd { -v } else { v }),
                );
            }
        }
        self.neighbor.append_history(&entries);
    }
}

/// What a mesh keeps in a restart file: where its vertices are (a servo or a motion
/// moved them), their velocities, the stress and wear tallies and the servo
/// controller's state.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshState {
    /// Vertex positions.
    pub verts: Vec<[f64; 3]>,
    /// Vertex velocities (empty at rest).
    pub vel: Vec<[f64; 3]>,
    /// With `/stress`: per-triangle force, pressing force and wear; total force and
    /// torque.
    pub stress: Option<StressState>,
    /// With `/servo`: active, centre, velocity, error integral, last process value,
    /// contact flag.
    pub servo: Option<ServoState>,
}

/// The tallies of a `/stress` mesh.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct StressState {
    /// Force per triangle.
    pub force: Vec<[f64; 3]>,
    /// Pressing force per triangle.
    pub pressing: Vec<f64>,
    /// Wear per triangle.
    pub wear: Vec<f64>,
    /// Total force.
    pub total_force: [f64; 3],
    /// Total torque.
    pub total_torque: [f64; 3],
}

/// A servo controller's state.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ServoState {
    /// Moving.
    pub active: bool,
    /// Centre.
    pub com: [f64; 3],
    /// Velocity for the next step.
    pub vel: [f64; 3],
    /// Error integral.
    pub sum: f64,
    /// Last process value.
    pub old_pv: f64,
    /// Particles near at the last build.
    pub contacts: bool,
}

impl crate::wall::MeshSurface {
    /// The mesh's state for a restart file.
    pub fn state(&self) -> MeshState {
        let a = |v: &[DVec3]| v.iter().copied().map(arr).collect();
        MeshState {
            verts: a(&self.mesh.verts),
            vel: a(&self.motion.vel),
            stress: self.stress.as_ref().map(|s| StressState {
                force: a(&s.force),
                pressing: s.pressing.clone(),
                wear: s.wear.clone(),
                total_force: arr(s.total_force),
                total_torque: arr(s.total_torque),
            }),
            servo: self.servo.as_ref().map(|s| ServoState {
                active: s.active,
                com: arr(s.com),
                vel: arr(s.vel),
                sum: s.sum,
                old_pv: s.old_pv,
                contacts: s.contacts,
            }),
        }
    }

    /// Takes back the state [`crate::wall::MeshSurface::state`] gave (the mesh read
    /// again from its file, with the same triangles).
    pub fn set_state(&mut self, s: &MeshState) -> std::result::Result<(), MeshStateError> {
        let ntri = self.mesh.tris.len();
        if s.verts.len() != self.mesh.verts.len() {
            return Err(MeshStateError::Vertices {
                saved: s.verts.len(),
                now: self.mesh.verts.len(),
            });
        }
        if let (Some(st), Some(mine)) = (&s.stress, &mut self.stress) {
            if st.force.len() != ntri || st.wear.len() != ntri || st.pressing.len() != ntri {
                return Err(MeshStateError::StressTriangles);
            }
            mine.force = st.force.iter().map(|&v| DVec3::from_array(v)).collect();
            mine.pressing = st.pressing.clone();
            mine.wear = st.wear.clone();
            mine.total_force = DVec3::from_array(st.total_force);
            mine.total_torque = DVec3::from_array(st.total_torque);
        }
        if let (Some(st), Some(mine)) = (&s.servo, &mut self.servo) {
            mine.active = st.active;
            mine.com = DVec3::from_array(st.com);
            mine.vel = DVec3::from_array(st.vel);
            mine.sum = st.sum;
            mine.old_pv = st.old_pv;
            mine.contacts = st.contacts;
        }
        self.mesh.verts = s.verts.iter().map(|&v| DVec3::from_array(v)).collect();
        // The normals from the vertices, as after every motion.
        self.mesh.transform(|p| p);
        self.motion.vel = s.vel.iter().map(|&v| DVec3::from_array(v)).collect();
        Ok(())
    }
}
