//! `fix wall/gran ... mesh n_meshes k meshes ID...`: granular walls made of triangle
//! meshes ([`crate::mesh::TriMesh`]), with the particle–particle contact law.
//!
//! Each step a particle's contacts are the closest points of the triangles it overlaps,
//! each with its feature (face, edge or corner), as LIGGGHTS 3.8 counts them: a face
//! always; an edge or a corner only through the one triangle that holds it, the last of
//! its triangles, and only when it is active (an edge between triangles that are not
//! flat within the `curvature` angle, a corner where such an edge ends and does not run
//! on straight: [`TriMesh::edge_owners`], [`TriMesh::corner_owners`]). So a shared edge
//! or corner counts once, a flat seam never, and a sphere pressed on a face near a convex
//! edge also touches that edge when the edge's holder is the neighbouring triangle, as
//! in LIGGGHTS (measured: a sphere sliding down a 19-facet half cylinder picks up the
//! second contact at LIGGGHTS' step).
//!
//! History: each particle with candidate triangles has [`SLOTS`] contact slots (a sparse
//! per-particle property, [`crate::particles::SparseProperty`], so it travels with the
//! particle through sorting and migration), each a feature key and the
//! contact model's history. A contact keeps the slot of its feature; a new contact takes
//! over the slot of an ended contact whose feature shares a vertex with its own (the
//! sphere rolled from a face to its edge, or from one triangle to its neighbour), else
//! starts from zero. (LIGGGHTS copies history only between coplanar neighbours; doing so
//! here slowed the hopper discharge by 4 % at D = 35 mm, away from LIGGGHTS' rate.)
//!
//! Flat surfaces: triangles sharing a corner whose normals are within the `curvature`
//! angle ([`MeshSurface::coplanar_cos`]) make one surface, which touches a sphere once:
//! of two contacts on it (a sphere over the corner of a polygonal hole touches both rim
//! edges) the deeper counts, as in LIGGGHTS.
//!
//! Candidates: at each re-neighboring, the triangles within r + skin of each particle
//! (with bonds, within the bond reach + skin), found through a grid of bins over the
//! triangles' bounding boxes.
//!
//! Wall bonds (`cohesion bond`, [`crate::bond`]): a particle bonds to the nearest point
//! of the wall's meshes when twice its distance is below `createDistanceBond`, one bond
//! per particle and wall as on a primitive wall. The anchor is held as a triangle and
//! barycentric coordinates, so it moves with the mesh (`fix move/mesh`), plus an offset
//! that the surface velocity (`surface_vel`, `surface_ang_vel`) carries along.

use glam::DVec3;

use crate::bond::{self, BondEvents, BondGeom, BondTable, Event};
use crate::contact::{CoeffTable, ContactKernel, ContactModel, Geom, Materials, Visitor};
use crate::error::{Error, Result};
use crate::mesh::{Feature, TriMesh};
use crate::multicontact::MultiContact;
use crate::par::View;
use crate::particles::{Particles, PropId, SparseId};

/// Contact slots per particle and mesh wall.
pub const SLOTS: usize = 6;

/// Values of a wall bond after the slots: the bond's vectors and tail (flag, d₀, anchor
/// offset), then the anchor's mesh (index in the wall), triangle and barycentric
/// coordinates (2).
/// Values of a particle's wall bond: the law's vectors and tail, and the link to its
/// triangle (mesh, triangle, two barycentric coordinates).
fn bond_block(l: bond::Layout) -> usize {
    l.vec + l.wall_tail + 4
}

/// Largest history of one particle (all slots).
const MAX_WIDTH: usize = 256;

/// Most triangle features one particle is checked against in a step (more are ignored).
const MAX_TOUCH: usize = 64;

/// A mesh of a wall: the triangles, their material type and the velocity of the surface
/// (`surface_vel`: a conveyor belt moves its surface, not its triangles).
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSurface {
    /// Name (the `fix mesh/surface` ID).
    pub id: String,
    /// The triangles.
    pub mesh: TriMesh,
    /// Material type (1-based).
    pub wall_type: u32,
    /// Velocity of the surface material.
    pub surface_vel: DVec3,
    /// `surface_ang_vel`: (a point of the axis, angular velocity vector) of a surface
    /// turning about a fixed axis (a drum) without moving its triangles.
    pub surface_ang_vel: Option<(DVec3, DVec3)>,
    /// `fix move/mesh` motions and the vertex velocities they give.
    pub motion: crate::mesh_motion::MeshMotion,
    /// `fix mesh/surface/stress`: per-triangle forces and wear.
    pub stress: Option<crate::wall::mesh_stress::MeshStress>,
    /// `fix mesh/surface/stress/servo`: the controller that moves the mesh.
    pub servo: Option<crate::mesh_servo::Servo>,
    /// Cosine of the `curvature` angle: two triangles sharing a corner whose normals
    /// are closer than this belong to one flat surface, which touches a sphere once.
    pub coplanar_cos: f64,
    /// Fixed temperature of the mesh for heat conduction (`temperature T`), if any.
    pub temperature: Option<f64>,
}

/// Default [`MeshSurface::coplanar_cos`]: normals within about 0.26° (LIGGGHTS' default).
pub const COPLANAR_COS: f64 = 1.0 - 1e-5;

impl MeshSurface {
    /// Velocity of the wall at the point `q` of triangle `t`: the surface velocity
    /// (`surface_vel`, `surface_ang_vel`) plus the mesh's own motion, interpolated
    /// from its corners' velocities (exact for rigid motions).
    #[inline]
    pub fn wall_velocity(&self, t: u32, q: DVec3) -> DVec3 {
        let mut v = self.surface_velocity(q);
        if !self.motion.vel.is_empty() {
            let tri = self.mesh.tris[t as usize];
            let [a, b, c] = tri.map(|k| self.mesh.verts[k as usize]);
            let [l0, l1, l2] = barycentric(a, b, c, q);
            let vel = &self.motion.vel;
            v += vel[tri[0] as usize] * l0 + vel[tri[1] as usize] * l1 + vel[tri[2] as usize] * l2;
        }
        v
    }

    /// Velocity of the surface material at `q` over the triangles (`surface_vel`,
    /// `surface_ang_vel`), without the mesh's own motion.
    #[inline]
    pub fn surface_velocity(&self, q: DVec3) -> DVec3 {
        let mut v = self.surface_vel;
        if let Some((o, w)) = self.surface_ang_vel {
            v += w.cross(q - o);
        }
        v
    }

    /// The point of triangle `t` at barycentric coordinates (1 − u − v, u, v).
    #[inline]
    pub fn point_at(&self, t: u32, u: f64, v: f64) -> DVec3 {
        let [a, b, c] = self.mesh.corners(t);
        a + (b - a) * u + (c - a) * v
    }

    /// Moves the mesh to time `t` of its motions (nothing for a mesh at rest).
    pub fn move_to(&mut self, t: f64) {
        if self.motion.is_moving() {
            let mut verts = std::mem::take(&mut self.mesh.verts);
            self.motion.update(t, &mut verts);
            self.mesh.verts = verts;
            self.mesh.transform(|p| p);
            // The stress's reference point moves with the mesh (LIGGGHTS 3.8: its
            // `f_ID[7..9]` follow a move/mesh, and the torque is about it).
            if let (Some(st), Some(r)) = (&mut self.stress, self.motion.carry(t, 0)) {
                st.reference_point = r;
            }
        }
    }

    /// True if the mesh moves (`move/mesh` motions or a servo).
    pub fn is_moving(&self) -> bool {
        self.motion.is_moving() || self.servo.is_some()
    }

    /// Mesh `id` of material type `wall_type`, at rest.
    pub fn new(id: &str, mesh: TriMesh, wall_type: u32) -> Self {
        Self {
            id: id.to_string(),
            mesh,
            wall_type,
            surface_vel: DVec3::ZERO,
            surface_ang_vel: None,
            motion: Default::default(),
            stress: None,
            servo: None,
            coplanar_cos: COPLANAR_COS,
            temperature: None,
        }
    }
}

/// A granular wall made of meshes.
#[derive(Debug, Clone)]
pub struct MeshWall {
    /// Contact model.
    pub model: ContactModel,
    /// The meshes: indices into the world's meshes ([`crate::world::World::meshes`]).
    pub meshes: Vec<usize>,
    /// Name of the per-particle history property.
    pub history_name: String,
    /// With `store_force yes`: the name of the per-particle property (3 values) that
    /// receives the wall's total force on each particle at every force pass.
    pub store_force: Option<String>,
    store: Option<PropId>,
    table: CoeffTable,
    hist: Option<SparseId>,
    /// Per-slot values after the contact history when a mesh records stress
    /// ([`crate::wall::mesh_stress::EXTRA`]), else 0.
    pub(crate) extra: usize,
    /// Values per contact slot: key, contact history, `extra`.
    pub(crate) stride: usize,
    /// With `cohesion bond`: the bond parameters (particle type × wall type).
    bond: Option<BondTable>,
    /// Wall bonds created and broken on this rank so far.
    pub bond_events: BondEvents,
    /// The current step (bonds are created at `tsCreateBond`).
    pub step: u64,
    /// Candidate triangles of each owned particle: `cand[cand_first[i]..cand_first[i+1]]`
    /// as (mesh, triangle).
    cand_first: Vec<u32>,
    cand: Vec<(u32, u32)>,
    /// Per mesh of [`MeshWall::meshes`]: the holders of its edges and corners
    /// ([`TriMesh::edge_owners`], [`TriMesh::corner_owners`]), set by
    /// [`MeshWall::setup`].
    owners: Vec<Holders>,
    /// The owned particles with candidate triangles, ascending: they alone hold history
    /// rows, row `c` for particle `rows[c]`.
    rows: Vec<u32>,
    /// With `surface multicontact`: the contacts' store and this wall's number in it
    /// ([`crate::multicontact::MultiContact::wall_key`]).
    pub multicontact: Option<(std::sync::Arc<crate::multicontact::MultiContact>, u64)>,
}

/// The holders of a mesh's edges and of its corners (`None`: inactive).
type Holders = (Vec<Option<u32>>, Vec<Option<u32>>);

/// The key of a feature in a history slot: 0 is "empty".
fn key(mesh: u32, f: Feature) -> f64 {
    let (kind, id) = match f {
        Feature::Face(t) => (1u64, t),
        Feature::Edge(e) => (2, e),
        Feature::Vertex(v) => (3, v),
    };
    (((mesh as u64) << 34) | (kind << 32) | id as u64) as f64
}

pub(crate) fn unkey(k: f64) -> Option<(u32, Feature)> {
    if k == 0.0 {
        return None;
    }
    let k = k as u64;
    let (mesh, kind, id) = ((k >> 34) as u32, (k >> 32) & 3, k as u32);
    Some((
        mesh,
        match kind {
            1 => Feature::Face(id),
            2 => Feature::Edge(id),
            _ => Feature::Vertex(id),
        },
    ))
}

/// The vertices of a feature (up to 3).
fn feature_verts(m: &TriMesh, f: Feature) -> ([u32; 3], usize) {
    match f {
        Feature::Face(t) => (m.tris[t as usize], 3),
        Feature::Edge(e) => {
            let [a, b] = m.edges[e as usize];
            ([a, b, u32::MAX], 2)
        }
        Feature::Vertex(v) => ([v, u32::MAX, u32::MAX], 1),
    }
}

/// True when two features of one mesh share a vertex.
fn adjacent(m: &TriMesh, a: Feature, b: Feature) -> bool {
    let (va, na) = feature_verts(m, a);
    let (vb, nb) = feature_verts(m, b);
    va[..na].iter().any(|v| vb[..nb].contains(v))
}

/// True when triangles `a` and `b` share a corner and lie in one plane (normals closer
/// than `cos`): the same flat surface.
fn same_surface(m: &TriMesh, a: u32, b: u32, cos: f64) -> bool {
    a == b
        || (m.normals[a as usize].dot(m.normals[b as usize]).abs() >= cos
            && m.tris[a as usize]
                .iter()
                .any(|v| m.tris[b as usize].contains(v)))
}

/// One contact of a particle with a mesh.
#[derive(Debug, Clone, Copy)]
struct Touch {
    mesh: u32,
    feature: Feature,
    /// A triangle the feature belongs to, and the closest point on it.
    tri: u32,
    q: DVec3,
    /// Unit normal from the wall to the centre.
    n: DVec3,
    /// Distance from the closest point to the centre.
    dist: f64,
}

impl MeshWall {
    /// A wall called `id` (the fix ID) of `meshes` (indices into the world's meshes).
    pub fn new(id: &str, model: ContactModel, meshes: Vec<usize>) -> Result<Self> {
        if meshes.is_empty() {
            return Err(Error::Invalid {
                what: "mesh wall",
                reason: "needs at least one mesh".into(),
            });
        }
        Ok(Self {
            model,
            meshes,
            history_name: format!("wallhist_{id}"),
            store_force: None,
            store: None,
            table: CoeffTable::default(),
            hist: None,
            extra: 0,
            stride: 0,
            bond: None,
            bond_events: BondEvents::default(),
            multicontact: None,
            step: 0,
            cand_first: Vec::new(),
            cand: Vec::new(),
            rows: Vec::new(),
            owners: Vec::new(),
        })
    }

    /// Mixes the material table and registers the history property; called before a run.
    pub fn setup(
        &mut self,
        materials: &Materials,
        all: &[MeshSurface],
        p: &mut Particles,
    ) -> Result<()> {
        self.model.resolve_jkr(materials)?;
        self.table = CoeffTable::new(materials, self.model.needs())?;
        for &k in &self.meshes {
            let m = all.get(k).ok_or(Error::Invalid {
                what: "mesh wall",
                reason: format!("no mesh {k}"),
            })?;
            if m.wall_type == 0 || m.wall_type as usize > materials.ntypes {
                return Err(Error::TypeOutOfRange {
                    ty: m.wall_type,
                    ntypes: materials.ntypes as u32,
                });
            }
        }
        self.owners = self
            .meshes
            .iter()
            .map(|&k| {
                let m = &all[k];
                (
                    m.mesh.edge_owners(m.coplanar_cos),
                    m.mesh.corner_owners(m.coplanar_cos),
                )
            })
            .collect();
        self.extra = if self.meshes.iter().any(|&k| all[k].stress.is_some()) {
            crate::wall::mesh_stress::EXTRA
        } else {
            0
        };
        self.bond = BondTable::for_model(&self.model, materials)?;
        self.stride = 1 + self.model.contact_history_width() + self.extra;
        let w = SLOTS * self.stride + self.bond.as_ref().map_or(0, |b| bond_block(b.layout()));
        assert!(
            SLOTS * self.stride <= MAX_WIDTH,
            "mesh wall history too wide"
        );
        self.hist = Some(p.add_sparse_property(&self.history_name, w)?);
        self.store = super::store_prop(self.store_force.as_deref(), p)?;
        Ok(())
    }

    /// The history property's ID.
    pub(crate) fn history_prop(&self) -> Option<SparseId> {
        self.hist
    }

    /// The owned particles holding history rows, in row order (since the last
    /// [`MeshWall::build_candidates`]).
    pub(crate) fn rows(&self) -> &[u32] {
        &self.rows
    }

    /// The `store_force` property's ID (after [`MeshWall::setup`]).
    pub(crate) fn store_prop(&self) -> Option<PropId> {
        self.store
    }

    /// Where a particle's wall bond flag sits in its history (with `cohesion bond`).
    pub(crate) fn bond_flag_at(&self) -> Option<usize> {
        self.bond
            .as_ref()
            .map(|b| SLOTS * self.stride + b.layout().vec)
    }

    /// Intact bonds of owned particles with this wall.
    pub fn count_bonds(&self, p: &Particles) -> u64 {
        super::count_bonded(p, self.hist, self.bond_flag_at())
    }

    /// Lists, for each owned particle of group `groupbit`, the triangles within r + `skin`
    /// (call at every re-neighboring); particles with none lose their history.
    pub fn build_candidates(
        &mut self,
        all: &[MeshSurface],
        p: &mut Particles,
        groupbit: u32,
        skin: f64,
    ) {
        let n = p.nlocal();
        let bond_reach = self.bond.as_ref().map_or(0.0, |b| b.wall_reach);
        let rmax = p.radius[..n].iter().copied().fold(0.0, f64::max);
        // A JKR neck holds beyond contact: the longest, for the largest sphere.
        let skin = skin + self.table.neck_reach(rmax);
        let reach = rmax.max(bond_reach) + skin;
        // One grid per mesh over its bounds grown by the reach; cells of about the reach
        // (at least the mean triangle size, so a triangle spans few cells).
        self.cand_first.clear();
        self.cand.clear();
        self.cand_first.push(0);
        self.rows.clear();
        let grids: Vec<Grid> = self
            .meshes
            .iter()
            .map(|&m| Grid::new(&all[m].mesh, reach))
            .collect();
        let mut found: Vec<(u32, u32)> = Vec::new();
        for i in 0..n {
            found.clear();
            if p.mask[i] & groupbit != 0 {
                let x = p.x[i];
                let lim = p.radius[i].max(bond_reach) + skin;
                for (mi, (&m, g)) in self.meshes.iter().zip(&grids).enumerate() {
                    for &t in g.near(x) {
                        let (q, _) = all[m].mesh.closest_point(t, x);
                        if (x - q).length_squared() < lim * lim {
                            found.push((mi as u32, t));
                        }
                    }
                }
                found.sort_unstable();
                found.dedup();
            }
            if found.is_empty() {
                // Beyond the reach of every triangle: a bond there is broken.
                let bonded =
                    |id: SparseId, at: usize| bond::is_bonded(&p.sparse[id.0].get(i)[at..]);
                if let (Some(id), Some(at)) = (self.hist, self.bond_flag_at()) {
                    if bonded(id, at) {
                        self.bond_events.count(Event::Broken);
                    }
                }
            } else {
                self.rows.push(i as u32);
            }
            self.cand.extend_from_slice(&found);
            self.cand_first.push(self.cand.len() as u32);
        }
        if let Some(id) = self.hist {
            let rows = &self.rows;
            p.sparse[id.0].keep_rows(rows.iter().map(|&i| i as usize), rows.len());
        }
    }

    /// Calls `f(surface, distance)` for each contact of owned particle `i` that the last
    /// force pass with history update recorded in its slots (the feature touched and the
    /// distance from its centre to that feature now) and that touches (distance below
    /// the radius: a JKR neck held apart is a contact but conducts no heat).
    pub(crate) fn for_each_contact(
        &self,
        all: &[MeshSurface],
        p: &Particles,
        i: usize,
        mut f: impl FnMut(&MeshSurface, f64),
    ) {
        let Some(id) = self.hist else { return };
        let h = &p.sparse[id.0].get(i)[..SLOTS * self.stride];
        let x = p.x[i];
        for s in 0..SLOTS {
            let Some((mi, feature)) = unkey(h[s * self.stride]) else {
                break;
            };
            let surface = &all[self.meshes[mi as usize]];
            let m = &surface.mesh;
            let dist = match feature {
                Feature::Face(t) => {
                    let v0 = m.verts[m.tris[t as usize][0] as usize];
                    (x - v0).dot(m.normals[t as usize]).abs()
                }
                Feature::Edge(e) => {
                    let [a, b] = m.edges[e as usize].map(|v| m.verts[v as usize]);
                    let ab = b - a;
                    let u = ((x - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                    (x - (a + u * ab)).length()
                }
                Feature::Vertex(v) => (x - m.verts[v as usize]).length(),
            };
            if dist < p.radius[i] {
                f(surface, dist);
            }
        }
    }

    /// True when some owned particle has a candidate triangle of mesh `mesh` (an index
    /// into the world's meshes) since the last build.
    pub fn has_candidates_on(&self, mesh: usize) -> bool {
        self.cand
            .iter()
            .any(|&(mi, _)| self.meshes[mi as usize] == mesh)
    }

    /// The candidate triangles of owned particle `i` (mesh, triangle).
    pub fn candidates_of(&self, i: usize) -> &[(u32, u32)] {
        &self.cand[self.cand_first[i] as usize..self.cand_first[i + 1] as usize]
    }

    /// True when the candidates cover the first `n` particles (after a re-neighboring).
    pub(super) fn has_candidates_for(&self, n: usize) -> bool {
        self.cand_first.len() > n
    }

    /// Adds the wall forces on particles `lo..lo + f.len()`; `hist` (the history rows)
    /// starts at the row of the first particle from `lo` on that has one (see
    /// [`super::chunk_rows`]).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply_range(
        &self,
        all: &[MeshSurface],
        view: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        hist: &mut [f64],
        touches: super::Touches,
        dt: f64,
        update: bool,
    ) {
        if self.cand_first.len() < lo + f.len() + 1 {
            return;
        }
        let model = self.model;
        model.dispatch(MeshPass {
            wall: self,
            all,
            view,
            lo,
            f,
            torque,
            hist,
            touches,
            dt,
            update,
            rec: None,
        });
    }
}

/// A uniform grid of bins over a mesh's triangles (by bounding box grown by the reach).
/// Barycentric coordinates of `q` (in the plane of the triangle `a b c`).
#[inline]
fn barycentric(a: DVec3, b: DVec3, c: DVec3, q: DVec3) -> [f64; 3] {
    let (e0, e1, e2) = (b - a, c - a, q - a);
    let (d00, d01, d11) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (d20, d21) = (e2.dot(e0), e2.dot(e1));
    let den = d00 * d11 - d01 * d01;
    if den <= 0.0 {
        return [1.0 / 3.0; 3];
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    [1.0 - v - w, v, w]
}

struct Grid {
    lo: DVec3,
    inv: f64,
    n: [usize; 3],
    first: Vec<u32>,
    tris: Vec<u32>,
}

impl Grid {
    fn new(m: &TriMesh, reach: f64) -> Self {
        let (lo, hi) = m.bounds();
        let lo = lo - DVec3::splat(reach);
        let hi = hi + DVec3::splat(reach);
        let ext = hi - lo;
        let mean_edge = {
            let s: f64 = m
                .edges
                .iter()
                .map(|[a, b]| (m.verts[*a as usize] - m.verts[*b as usize]).length())
                .sum();
            s / m.edges.len().max(1) as f64
        };
        let mut size = (2.0 * reach).max(mean_edge).max(1e-300);
        // At most about 64 bins per triangle, 2^21 in all.
        let limit = (64 * m.tris.len()).clamp(64, 1 << 21) as f64;
        while (ext.x / size).ceil() * (ext.y / size).ceil() * (ext.z / size).ceil() > limit {
            size *= 1.5;
        }
        let n = [0, 1, 2].map(|a| ((ext[a] / size).ceil() as usize).max(1));
        let inv = 1.0 / size;
        let cell =
            |p: DVec3, a: usize| (((p[a] - lo[a]) * inv).floor().max(0.0) as usize).min(n[a] - 1);
        let nb = n[0] * n[1] * n[2];
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); nb];
        for (t, tri) in m.tris.iter().enumerate() {
            let c = tri.map(|v| m.verts[v as usize]);
            let tlo = c[0].min(c[1]).min(c[2]) - DVec3::splat(reach);
            let thi = c[0].max(c[1]).max(c[2]) + DVec3::splat(reach);
            for z in cell(tlo, 2)..=cell(thi, 2) {
                for y in cell(tlo, 1)..=cell(thi, 1) {
                    for x in cell(tlo, 0)..=cell(thi, 0) {
                        lists[(z * n[1] + y) * n[0] + x].push(t as u32);
                    }
                }
            }
        }
        let mut first = Vec::with_capacity(nb + 1);
        let mut tris = Vec::new();
        first.push(0);
        for l in lists {
            tris.extend_from_slice(&l);
            first.push(tris.len() as u32);
        }
        Self {
            lo,
            inv,
            n,
            first,
            tris,
        }
    }

    /// Triangles whose grown bounding box may contain `x` (none outside the grid).
    fn near(&self, x: DVec3) -> &[u32] {
        let mut idx = [0usize; 3];
        for a in 0..3 {
            let c = (x[a] - self.lo[a]) * self.inv;
            if c.is_nan() || c < 0.0 || c >= self.n[a] as f64 {
                return &[];
            }
            idx[a] = c as usize;
        }
        let b = (idx[2] * self.n[1] + idx[1]) * self.n[0] + idx[0];
        &self.tris[self.first[b] as usize..self.first[b + 1] as usize]
    }
}

/// The force pass of a mesh wall over a range of owned particles.
pub(super) struct MeshPass<'a> {
    pub(super) wall: &'a MeshWall,
    pub(super) all: &'a [MeshSurface],
    pub(super) view: &'a View<'a>,
    pub(super) lo: usize,
    pub(super) f: &'a mut [DVec3],
    pub(super) torque: &'a mut [DVec3],
    pub(super) hist: &'a mut [f64],
    /// Where each particle last touched a wall, for the lost-particle report.
    pub(super) touches: super::Touches<'a>,
    pub(super) dt: f64,
    pub(super) update: bool,
    /// Where each contact is recorded, for per-contact output (`None` in a force pass).
    pub(super) rec: Option<&'a mut super::mesh_local::WallContacts>,
}

impl Visitor for MeshPass<'_> {
    type Output = ();
    fn visit<K: ContactKernel>(self) {
        debug_assert_eq!(self.wall.bond.is_some(), K::BONDS);
        // `K::BONDS` is a constant: each kernel is compiled with or without bonds, not both.
        self.run(K::HIST, K::NECK, K::BONDS, &|c, pt, t, s, o, h, sk| {
            lay_out::<K>(c, pt, t, s, o, h, sk)
        })
    }
}

/// The wall bond of owned particle `i` (history `bh`, [`bond_block`] values): created
/// to the nearest point of its candidate triangles `cands` when `create_now` and close
/// enough, then loaded; returns its force and torque on the particle, and whether it
/// holds after this step.
#[allow(clippy::too_many_arguments)]
fn wall_bond(
    wall: &MeshWall,
    surfaces: &[MeshSurface],
    p: &View,
    i: usize,
    cands: &[(u32, u32)],
    bh: &mut [f64],
    dt: f64,
    update: bool,
    create_now: bool,
) -> (DVec3, DVec3, bool) {
    let table = wall.bond.as_ref().expect("bond table");
    let layout = table.layout();
    let (vecs, rest) = bh.split_at_mut(layout.vec);
    let (tail, link) = rest.split_at_mut(layout.wall_tail);
    let x = p.x[i];
    if !bond::is_bonded(tail) && create_now {
        // The nearest point of the wall (first of equals, in candidate order).
        let mut best: Option<(f64, u32, u32, DVec3)> = None;
        for &(mi, t) in cands {
            let mesh = &surfaces[wall.meshes[mi as usize]].mesh;
            let (q, _) = mesh.closest_point(t, x);
            let d = (x - q).length();
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, mi, t, q));
            }
        }
        if let Some((d, mi, t, q)) = best {
            let surface = &surfaces[wall.meshes[mi as usize]];
            let c = table.get(p.ty[i], surface.wall_type);
            if bond::creates(c, true, 2.0 * d) {
                bond::create(vecs, tail, d);
                tail[2..5].fill(0.0);
                let [a, b, cc] = surface.mesh.corners(t);
                let [_, u, v] = barycentric(a, b, cc, q);
                link.copy_from_slice(&[mi as f64, t as f64, u, v]);
                wall.bond_events.count(Event::Created);
            }
        }
    }
    if !bond::is_bonded(tail) {
        return (DVec3::ZERO, DVec3::ZERO, false);
    }
    let (mi, t) = (link[0] as usize, link[1] as u32);
    let surface = &surfaces[wall.meshes[mi]];
    let mut offset = DVec3::from_slice(&tail[2..5]);
    let mut anchor = surface.point_at(t, link[2], link[3]) + offset;
    if update {
        // The surface material carries the anchor over the triangles.
        offset += surface.surface_velocity(anchor) * dt;
        tail[2..5].copy_from_slice(&offset.to_array());
        anchor = surface.point_at(t, link[2], link[3]) + offset;
    }
    let g = BondGeom::wall(
        x - anchor,
        p.radius[i],
        p.v[i] - surface.wall_velocity(t, anchor),
        p.omega[i],
        dt,
        update,
        table.wall_reach,
    );
    let (b, e) = table.force(&g, p.ty[i], surface.wall_type, wall.model.bond, vecs, tail);
    wall.bond_events.count(e);
    (b.f_i, b.t_i, e != Event::Broken)
}

/// The contacts of a sphere at `x` of radius `r` with its candidate triangles `cands`,
/// written to the front of `found` (their number is returned): one per feature (edges
/// and corners of touched faces, and corners of touched edges, do not count again), one
/// per flat surface (the deeper one), at most [`SLOTS`]. A feature within r + `neck` (a
/// JKR neck's reach; 0 for other laws) counts: the caller keeps those beyond r only
/// where a neck holds. Not generic over the contact law, so that it is compiled once,
/// not once per kernel.
fn touches_of(
    wall: &MeshWall,
    surfaces: &[MeshSurface],
    x: DVec3,
    r: f64,
    neck: f64,
    cands: &[(u32, u32)],
    found: &mut [Touch; MAX_TOUCH],
) -> usize {
    let mut nt = 0;
    for &(mi, t) in cands {
        let mesh = &surfaces[wall.meshes[mi as usize]].mesh;
        let (mut q, mut feature) = mesh.closest_point(t, x);
        // Over the face within LIGGGHTS' tolerance: a face contact, the projection its
        // point (a sphere exactly over a seam touches the faces beside it).
        if !matches!(feature, Feature::Face(_)) && over_face(mesh, t, x) {
            let nt = mesh.normals[t as usize];
            q = x - (x - mesh.verts[mesh.tris[t as usize][0] as usize]).dot(nt) * nt;
            feature = Feature::Face(t);
        }
        // An edge or corner counts only through its holder (LIGGGHTS 3.8).
        let (edges, corners) = &wall.owners[mi as usize];
        let held = match feature {
            Feature::Face(_) => true,
            Feature::Edge(e) => edges[e as usize] == Some(t),
            Feature::Vertex(v) => corners[v as usize] == Some(t),
        };
        if !held {
            continue;
        }
        let (n, dist) = if let Feature::Face(t) = feature {
            // On the face: the plane distance (exact for axis-aligned planes).
            let nt = mesh.normals[t as usize];
            let s = (x - mesh.verts[mesh.tris[t as usize][0] as usize]).dot(nt);
            (if s >= 0.0 { nt } else { -nt }, s.abs())
        } else {
            let d = x - q;
            let dist = d.length();
            (d / dist, dist)
        };
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(dist < r + neck) || dist == 0.0 {
            continue;
        }
        if nt < MAX_TOUCH {
            found[nt] = Touch {
                mesh: mi,
                feature,
                tri: t,
                q,
                n,
                dist,
            };
            nt += 1;
        }
    }
    // One contact per feature (a face touched from one triangle only, an edge or corner
    // from its holder only: this keeps the first of equal keys should a face be listed
    // twice).
    let all = &mut found[..nt];
    all.sort_unstable_by_key(|t| (t.mesh, t.feature));
    let mut nd = 0;
    for q in 0..all.len() {
        if nd == 0 || (all[nd - 1].mesh, all[nd - 1].feature) != (all[q].mesh, all[q].feature) {
            all[nd] = all[q];
            nd += 1;
        }
    }
    let all = &found[..nd];
    // One contact per flat surface: of two contacts on neighbouring triangles of
    // one plane (a sphere over the corner of a hole touches its two rim edges),
    // the deeper counts.
    let mut shadowed = [false; MAX_TOUCH];
    for q in 0..nd {
        let c = &all[q];
        let surface = &surfaces[wall.meshes[c.mesh as usize]];
        let deeper = |o: &Touch, oq: usize| o.dist < c.dist || (o.dist == c.dist && oq < q);
        if all.iter().enumerate().any(|(oq, o)| {
            oq != q
                && o.mesh == c.mesh
                && deeper(o, oq)
                && same_surface(&surface.mesh, o.tri, c.tri, surface.coplanar_cos)
        }) {
            shadowed[q] = true;
        }
    }
    let mut nk = 0;
    for q in 0..nd {
        if !shadowed[q] && nk < SLOTS {
            found[nk] = found[q];
            nk += 1;
        }
    }
    nk
}

/// True when the projection of `x` on the plane of triangle `t` lies on the triangle
/// within LIGGGHTS 3.8's tolerance: each barycentric coordinate above −p / (2 r_b), p the
/// mesh's `precision` (10⁻⁸ by default) and r_b the radius of the triangle's bounding
/// sphere about its centroid, so that LIGGGHTS counts it a face contact (measured: a
/// sphere sliding over a faceted half cylinder follows LIGGGHTS 3.8 for precision 10⁻⁸,
/// 10⁻⁵ and 10⁻⁴, which give three different paths).
fn over_face(mesh: &TriMesh, t: u32, x: DVec3) -> bool {
    let [a, b, c] = mesh.corners(t);
    let centre = (a + b + c) / 3.0;
    let rb = [a, b, c]
        .iter()
        .map(|v| (*v - centre).length())
        .fold(0.0, f64::max);
    let tol = -mesh.precision / (2.0 * rb);
    barycentric(a, b, c, x).iter().all(|&l| l > tol)
}

/// For each contact of `touches`, the slot of the previous step's history `old` (slots of
/// `stride` values, each led by its feature key) that it goes on from, or `usize::MAX`:
/// the slot of the same feature, else a slot whose feature has ended and is adjacent to
/// the contact's. Not generic over the contact law, so that it is compiled once, not
/// once per kernel.
fn match_slots(
    wall: &MeshWall,
    surfaces: &[MeshSurface],
    touches: &[Touch],
    old: &[f64],
    stride: usize,
) -> [usize; SLOTS] {
    let mut taken = [false; SLOTS];
    let mut slot_of = [usize::MAX; SLOTS];
    for (c, t) in touches.iter().enumerate() {
        let kk = key(t.mesh, t.feature);
        if let Some(s) = (0..SLOTS).find(|&s| !taken[s] && old[s * stride] == kk) {
            taken[s] = true;
            slot_of[c] = s;
        }
    }
    for (c, t) in touches.iter().enumerate() {
        if slot_of[c] != usize::MAX {
            continue;
        }
        let mesh = &surfaces[wall.meshes[t.mesh as usize]].mesh;
        let near = (0..SLOTS).find(|&s| {
            !taken[s]
                && unkey(old[s * stride]).is_some_and(|(m, f)| {
                    m == t.mesh
                        && !touches
                            .iter()
                            .any(|o| key(o.mesh, o.feature) == old[s * stride])
                        && adjacent(mesh, f, t.feature)
                })
        });
        if let Some(s) = near {
            taken[s] = true;
            slot_of[c] = s;
        }
    }
    slot_of
}

impl MeshPass<'_> {
    /// The pass with a kernel whose history has `hw` values, whose contacts hold apart
    /// with `neck_law` (a JKR neck) and which has wall bonds with `bonds`; `lay` (the
    /// kernel's [`lay_out`]) evaluates each particle's contacts. Not generic over the
    /// contact law, so that the search for contacts and their slots is compiled once,
    /// not once per kernel; the indirect call is one per particle near the wall.
    fn run(self, hw: usize, neck_law: bool, bonds: bool, lay: &LayFn) {
        let MeshPass {
            wall,
            all: surfaces,
            view: p,
            lo,
            f,
            torque,
            hist,
            touches: last_touch,
            dt,
            update,
            rec,
        } = self;
        let extra = wall.extra;
        let stride = wall.stride;
        debug_assert_eq!(stride, 1 + hw + extra);
        let width = SLOTS * stride;
        let pw = width
            + match (&wall.bond, bonds) {
                (Some(b), true) => bond_block(b.layout()),
                _ => 0,
            };
        let create_now =
            bonds && update && wall.bond.as_ref().is_some_and(|b| b.creates_at(wall.step));
        // Fixed-size scratch: no allocation in the pass.
        let none = Touch {
            mesh: 0,
            feature: Feature::Face(0),
            tri: 0,
            q: DVec3::ZERO,
            n: DVec3::ZERO,
            dist: 0.0,
        };
        // `surface multicontact`: the wall neither corrects nor records its contacts at a
        // run's set-up, as LIGGGHTS 3.8 (see rdem::multicontact).
        let mc = wall
            .multicontact
            .as_ref()
            .filter(|_| update)
            .map(|(m, w)| (&**m, m.read(), *w));
        let ctx = LayCtx {
            wall,
            surfaces,
            p,
            stride,
            hw,
            extra,
            flags: wall.model.kernel_flags(),
            mc: mc.as_ref().map(|(m, state, w)| (*m, &**state, *w)),
            dt,
            update,
        };
        let mut sink = LaySink {
            f,
            torque,
            last_touch,
            rec,
        };
        let mut found = [none; MAX_TOUCH];
        let mut old = [0.0f64; MAX_WIDTH];
        let hi = lo + sink.f.len();
        let a = wall.rows.partition_point(|&i| (i as usize) < lo);
        let b = a + wall.rows[a..].partition_point(|&i| (i as usize) < hi);
        for (c, &i) in wall.rows[a..b].iter().enumerate() {
            let i = i as usize;
            let k = i - lo;
            let cands = wall.candidates_of(i);
            let (h, bh) = hist[c * pw..(c + 1) * pw].split_at_mut(width);
            // An intact `bond/nonlinear` bond takes the place of the normal contact forces.
            let mut replace_normal = false;
            if bonds {
                let (bf, bt, holds) =
                    wall_bond(wall, surfaces, p, i, cands, bh, dt, update, create_now);
                sink.f[k] += bf;
                sink.torque[k] += bt;
                replace_normal = holds
                    && wall
                        .bond
                        .as_ref()
                        .is_some_and(|b| b.law().replaces_normal_contact());
            }
            let (x, r) = (p.x[i], p.radius[i]);
            let neck = if neck_law {
                wall.table.neck_reach(r)
            } else {
                0.0
            };
            let nk = touches_of(wall, surfaces, x, r, neck, cands, &mut found);
            let touches = &found[..nk];
            // Match the contacts with the slots: same feature, else an ended neighbour.
            old[..width].copy_from_slice(h);
            let slot_of = match_slots(wall, surfaces, touches, &old[..width], stride);
            // Lay the slots out anew, in the order of the contacts.
            h.fill(0.0);
            lay(
                &ctx,
                Particle {
                    i,
                    k,
                    replace_normal,
                },
                touches,
                &slot_of,
                &mut old[..width],
                h,
                &mut sink,
            );
            if !update {
                h.copy_from_slice(&old[..width]);
            }
        }
    }
}

/// What [`lay_out`] reads that stays the same over a mesh pass.
struct LayCtx<'a> {
    wall: &'a MeshWall,
    surfaces: &'a [MeshSurface],
    p: &'a View<'a>,
    /// History values per slot: its key, the law's `hw` values and `extra` ones.
    stride: usize,
    hw: usize,
    extra: usize,
    flags: crate::contact::Flags,
    /// With `surface multicontact`: the store, its last records and the wall's key.
    mc: Option<(&'a MultiContact, &'a crate::multicontact::State, u64)>,
    dt: f64,
    update: bool,
}

/// Where [`lay_out`] writes over a mesh pass.
struct LaySink<'a, 'b> {
    f: &'a mut [DVec3],
    torque: &'a mut [DVec3],
    last_touch: super::Touches<'a>,
    rec: Option<&'b mut super::mesh_local::WallContacts>,
}

/// The particle of a [`lay_out`] call: its index, its index in the pass's range, and
/// whether an intact bond takes the place of its normal contact forces.
struct Particle {
    i: usize,
    k: usize,
    replace_normal: bool,
}

/// One kernel's [`lay_out`].
type LayFn =
    dyn Fn(&LayCtx, Particle, &[Touch], &[usize; SLOTS], &mut [f64], &mut [f64], &mut LaySink);

/// The contacts `touches` of one particle with kernel `K`: each goes on from its slot of
/// the previous history `old` (`slot_of`, from [`match_slots`]) into the next free slot
/// of the cleared history `h`, in the order of the contacts; its force and torque go to
/// the particle. A JKR contact apart goes on only while its neck holds.
#[allow(clippy::too_many_arguments)]
fn lay_out<K: ContactKernel>(
    ctx: &LayCtx,
    pt: Particle,
    touches: &[Touch],
    slot_of: &[usize; SLOTS],
    old: &mut [f64],
    h: &mut [f64],
    sink: &mut LaySink,
) {
    let LayCtx {
        wall,
        surfaces,
        p,
        stride,
        hw,
        extra,
        flags,
        mc,
        dt,
        update,
    } = *ctx;
    let Particle {
        i,
        k,
        replace_normal,
    } = pt;
    let r = p.radius[i];
    let mut ns = 0;
    for (c, t) in touches.iter().enumerate() {
        let surface = &surfaces[wall.meshes[t.mesh as usize]];
        if K::NECK && t.dist >= r {
            // Apart: only a JKR neck that holds goes on.
            let s = slot_of[c];
            let coeff = wall.table.get(p.ty[i], surface.wall_type);
            let held = s != usize::MAX && {
                let hn = &mut old[s * stride + 1..s * stride + 1 + hw];
                K::holds(r - t.dist, r, coeff, hn, update)
            };
            if !held {
                continue;
            }
        }
        let hs = &mut h[ns * stride..(ns + 1) * stride];
        ns += 1;
        hs[0] = key(t.mesh, t.feature);
        if slot_of[c] != usize::MAX {
            let s = slot_of[c];
            hs[1..].copy_from_slice(&old[s * stride + 1..(s + 1) * stride]);
        }
        let v_wall = surface.wall_velocity(t.tri, t.q);
        let vr = p.v[i] - v_wall;
        let mut g = Geom::wall(t.n, t.dist, r, p.mcontact[i], vr, p.omega[i], dt, update);
        let mc_key = mc.map(|(_, _, w)| MultiContact::wall_key(w, t.mesh, t.tri));
        if let (Some((_, state, _)), Some(key)) = (mc, mc_key) {
            if !state.shape_wall(&mut g, (p.tag[i], p.ty[i], p.x[i]), key) {
                continue;
            }
        }
        let coeff = wall.table.get(p.ty[i], surface.wall_type);
        let mut out = K::contact(&g, coeff, flags, &mut hs[1..1 + hw]);
        if replace_normal {
            out.f_i -= out.fn_total * g.n;
            out.fn_total = 0.0;
        }
        sink.last_touch.note(
            k,
            super::touch::pack_triangle(wall.meshes[t.mesh as usize], t.tri),
        );
        if let (Some((store, _, _)), Some(key)) = (mc, mc_key) {
            store.record_wall((p.tag[i], p.x[i]), key, t.n, t.dist, out.fn_total);
        }
        sink.f[k] += out.f_i;
        sink.torque[k] += out.t_i;
        if let Some(rec) = sink.rec.as_deref_mut() {
            rec.push(
                i,
                t.mesh,
                t.tri,
                t.q,
                t.n,
                t.dist,
                v_wall,
                &out,
                &hs[1..1 + hw],
            );
        }
        if extra > 0 {
            if let Some(st) = &surface.stress {
                crate::wall::mesh_stress::record(
                    &mut hs[1 + hw..],
                    st,
                    t.tri,
                    t.q,
                    t.n,
                    out.f_i,
                    vr,
                    dt,
                );
            }
        }
    }
}
