//! `fix insert/stream`: particles poured through a planar face (a mesh of
//! `fix mesh/surface`) at a given rate.
//!
//! The insertion volume is the face extruded upstream (against the insertion velocity)
//! by `extrude_length` (without `all_in` the centres lie one radius further upstream,
//! so each sphere starts wholly behind the face, as in LIGGGHTS). Every `insert_every` steps — the time the stream needs to cross
//! the extrusion, `extrude_length / (v·n dt)` steps when the length is given — a packet
//! of `rate · insert_every · dt` particles (a fractional count rounded up with
//! probability equal to its fraction, as LIGGGHTS does) is placed at random in the
//! volume. Until a particle reaches the face it moves straight along the face normal, at
//! the normal part of its insertion velocity, and spins at its insertion spin, feeling no
//! force (its force and torque are zeroed after all forces, see [`HOLD_PROPERTY`]); when
//! it reaches the face it gains the rest of its insertion velocity ([`TANGENT_PROPERTY`]),
//! so it leaves the face where it was placed behind it, at the velocity asked for. That is
//! what LIGGGHTS 3.8 does: with an oblique `vel`, a held sphere or clump moved at the
//! normal part only and took the full velocity on crossing the face (measured on a
//! horizontal face, `vel constant 0 -0.5 -2` and `0 0.5 -1`).

use glam::DVec3;
use rand::Rng;

use super::place::{add_placed, choose, OverlapGrid, Placed, TagCursor};
use super::{Distribution, InsertReport, InsertRng, VelocityLaw};
use crate::error::{Error, Result};
use crate::mesh::TriMesh;
use crate::world::World;

/// Per-particle property holding the step from which a streamed particle moves freely;
/// before it, `hold_streamed` zeroes its force and torque after all forces (so it flies
/// ballistically through the insertion volume).
pub const HOLD_PROPERTY: &str = "insert_stream_release";

/// Per-particle property holding a streamed particle's release step as LIGGGHTS 3.8
/// records it (its `release_fix_insert_stream[5]`): the insertion step plus
/// ⌊(d + 10⁻¹⁴)/(v_n dt)⌋, d the centre's distance behind the face. (The particle moves
/// freely from the step after it, as [`HOLD_PROPERTY`] has it.) `fix
/// property/atom/tracer/stream` reads it.
pub const RELEASE_STEP_PROPERTY: &str = "insert_stream_release_step";

/// Per-particle property holding the part of a streamed particle's insertion velocity
/// along the face, which it gains when released (then zero). A clump's spheres carry
/// their body's; [`crate::world::World`]'s body sums hand it to the body.
pub const TANGENT_PROPERTY: &str = "insert_stream_tangent";

/// Zeroes the force and torque of the owned particles an `insert/stream` still holds at
/// `step`, and gives each free sphere released by then the rest of its insertion
/// velocity (stage 10 of [`crate::step`]: after the post-force fixes). A clump's spheres
/// are left to their body (see `World::sum_body_forces`).
pub(crate) fn hold_streamed(p: &mut crate::particles::Particles, step: u64) {
    let Some(id) = p.property(HOLD_PROPERTY) else {
        return;
    };
    let tangent = p.property(TANGENT_PROPERTY);
    let body = p.property(crate::multisphere::bodies::BODY_PROP);
    let step = step as f64;
    let n = p.nlocal();
    for i in 0..n {
        if p.props[id.0].data[i] > step {
            p.f[i] = DVec3::ZERO;
            p.torque[i] = DVec3::ZERO;
        } else if let Some(t) = tangent {
            if body.is_some_and(|b| p.props[b.0].data[i] != 0.0) {
                continue;
            }
            let d = &mut p.props[t.0].data[3 * i..3 * i + 3];
            if d.iter().any(|&c| c != 0.0) {
                p.v[i] += DVec3::from_slice(d);
                d.fill(0.0);
            }
        }
    }
}

/// How the insertion volume's depth is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Extrusion {
    /// `extrude_length L`: the packet interval follows from the normal velocity.
    Length(f64),
    /// `insert_every N`: the depth is what the stream crosses in N steps.
    Every(u64),
    /// `insert_every N duration D`: a pulsed stream, each packet (N steps' worth of
    /// particles) poured in D steps, then a pause.
    Pulsed {
        /// Steps between packets.
        every: u64,
        /// Steps a packet takes to pour.
        duration: u64,
    },
}

/// The planar insertion face: its triangles, their areas and the unit normal pointing
/// downstream (along the insertion velocity's normal component).
#[derive(Debug, Clone)]
pub struct StreamFace {
    /// Triangles' corners.
    pub tris: Vec<[DVec3; 3]>,
    /// Cumulative areas (for drawing a triangle by area).
    cum_area: Vec<f64>,
    /// Unit normal, pointing downstream.
    pub normal: DVec3,
    /// Edges that belong to one triangle only (the face's outline).
    outline: Vec<(DVec3, DVec3)>,
}

/// Relative tolerance of the planarity test (of the mesh's extent).
const PLANAR_TOL: f64 = 1e-6;

impl StreamFace {
    /// The face of `mesh` for a stream of mean velocity `v`; errors if the mesh is not
    /// planar or `v` runs along it.
    pub fn new(mesh: &TriMesh, v: DVec3) -> Result<Self> {
        let tris: Vec<[DVec3; 3]> = (0..mesh.tris.len() as u32)
            .map(|t| mesh.corners(t))
            .collect();
        let Some(first) = tris.first() else {
            return Err(Error::Invalid {
                what: "insertion_face",
                reason: "the mesh has no triangles".into(),
            });
        };
        // The normal of the largest triangle, then every vertex must be in its plane.
        let mut n = DVec3::ZERO;
        for t in &tris {
            let c = (t[1] - t[0]).cross(t[2] - t[0]);
            if c.length() > n.length() {
                n = c;
            }
        }
        let n = n.normalize();
        let (lo, hi) = mesh.bounds();
        let size = (hi - lo).length();
        let off = |p: DVec3| (p - first[0]).dot(n);
        if tris
            .iter()
            .flatten()
            .any(|&p| off(p).abs() > PLANAR_TOL * size)
        {
            return Err(Error::Invalid {
                what: "insertion_face",
                reason: "the mesh is not planar (use a fix mesh/surface/planar face)".into(),
            });
        }
        let vn = v.dot(n);
        if vn.abs() <= 1e-12 * v.length().max(1e-300) || vn == 0.0 {
            return Err(Error::Invalid {
                what: "vel",
                reason: "the insertion velocity has no component normal to the insertion face"
                    .into(),
            });
        }
        let normal = if vn > 0.0 { n } else { -n };
        let mut acc = 0.0;
        let cum_area = tris
            .iter()
            .map(|t| {
                acc += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
                acc
            })
            .collect();
        let outline = (0..mesh.edges.len() as u32)
            .filter(|&e| mesh.triangles_of_edge(e).len() == 1)
            .map(|e| {
                let [a, b] = mesh.edges[e as usize];
                (mesh.verts[a as usize], mesh.verts[b as usize])
            })
            .collect();
        Ok(Self {
            tris,
            cum_area,
            normal,
            outline,
        })
    }

    /// Area of the face.
    pub fn area(&self) -> f64 {
        self.cum_area.last().copied().unwrap_or(0.0)
    }

    /// A uniformly drawn point of the face.
    fn sample(&self, rng: &mut InsertRng) -> DVec3 {
        let a: f64 = rng.gen::<f64>() * self.area();
        let k = self
            .cum_area
            .partition_point(|&c| c < a)
            .min(self.tris.len() - 1);
        let [p0, p1, p2] = self.tris[k];
        let (u, w): (f64, f64) = (rng.gen(), rng.gen());
        let s = u.sqrt();
        p0 * (1.0 - s) + p1 * (s * (1.0 - w)) + p2 * (s * w)
    }

    /// Distance from the face point `p` to the face's outline.
    fn outline_distance(&self, p: DVec3) -> f64 {
        self.outline
            .iter()
            .map(|&(a, b)| {
                let ab = b - a;
                let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                (p - (a + ab * t)).length()
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn bounding_box(&self, depth: f64) -> (DVec3, DVec3) {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &p in self.tris.iter().flatten() {
            for q in [p, p - self.normal * depth] {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
        (lo, hi)
    }
}

/// Settings and state of one `fix insert/stream`.
#[derive(Debug, Clone)]
pub struct InsertStream {
    /// Fix ID.
    pub id: String,
    /// Group bits given to inserted particles (besides `all`).
    pub groupbit: u32,
    /// Particle mix.
    pub dist: Distribution,
    /// The face's mesh: an index into [`World::meshes`].
    pub mesh: usize,
    /// Velocity law.
    pub velocity: VelocityLaw,
    /// Angular velocity (`omega constant wx wy wz`).
    pub omega: DVec3,
    /// How clumps are turned.
    pub orientation: super::Orientation,
    /// `overlapcheck yes`.
    pub overlap_check: bool,
    /// `all_in yes`: whole spheres inside the insertion volume.
    pub all_in: bool,
    /// `maxattempt`.
    pub max_attempt: usize,
    /// First insertion step (`start`; default: the first step of the run).
    pub start: Option<u64>,
    /// Particles to insert in all (`None`: no end).
    pub limit: Option<u64>,
    /// Steps between packets.
    pub every: u64,
    /// Depth of the insertion volume.
    pub extrude: f64,
    /// Particles per packet (fractional).
    pub per_insertion: f64,
    /// Particles inserted so far.
    pub inserted: u64,
    rng: InsertRng,
    last: Option<u64>,
    /// Particles per time unit.
    rate: f64,
    /// How the insertion volume's depth is given.
    extrusion: Extrusion,
    /// The mean velocity along the face normal.
    vn: f64,
}

impl InsertStream {
    /// An insert/stream fix through the planar mesh `face` (the world's mesh number
    /// `mesh`) at `rate` particles per time unit, `dt` the timestep.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        id: &str,
        seed: u64,
        groupbit: u32,
        dist: Distribution,
        mesh: usize,
        face: &TriMesh,
        velocity: VelocityLaw,
        rate: f64,
        extrusion: Extrusion,
        dt: f64,
    ) -> Result<Self> {
        crate::error::check("particle rate", rate, rate > 0.0, "must be > 0")?;
        let f = StreamFace::new(face, mean_velocity(velocity))?;
        let vn = mean_velocity(velocity).dot(f.normal);
        let mut st = Self {
            id: id.to_string(),
            groupbit,
            dist,
            mesh,
            velocity,
            omega: DVec3::ZERO,
            orientation: super::Orientation::Template,
            overlap_check: true,
            all_in: false,
            max_attempt: 50,
            start: None,
            limit: None,
            every: 0,
            extrude: 0.0,
            per_insertion: 0.0,
            inserted: 0,
            rng: super::rng(seed),
            last: None,
            rate,
            extrusion,
            vn,
        };
        st.set_timestep(dt)?;
        Ok(st)
    }

    /// Sets the steps between packets, the depth of the insertion volume and the
    /// particles per packet for time step `dt`. LIGGGHTS 3.8 takes them from the time
    /// step of the run (a `timestep` after the fix counts): call it at each run's set-up.
    pub fn set_timestep(&mut self, dt: f64) -> Result<()> {
        crate::error::check("timestep", dt, dt > 0.0, "must be > 0")?;
        let vn = self.vn;
        let (every, extrude) = match self.extrusion {
            Extrusion::Length(l) => {
                crate::error::check("extrude_length", l, l > 0.0, "must be > 0")?;
                // Rounded: 0.6 / (2 · 1e-5) is 29999.999... in floating point, 30000 steps.
                let every = (l / (vn * dt)).round() as u64;
                if every == 0 {
                    return Err(Error::Invalid {
                        what: "extrude_length",
                        reason: format!(
                            "the stream crosses {l} in less than one step (normal velocity {vn}): make it longer"
                        ),
                    });
                }
                (every, l)
            }
            Extrusion::Every(n) => {
                if n == 0 {
                    return Err(Error::Invalid {
                        what: "insert_every",
                        reason: "must be >= 1".into(),
                    });
                }
                (n, n as f64 * dt * vn)
            }
            Extrusion::Pulsed { every, duration } => {
                if duration == 0 || duration > every {
                    return Err(Error::Invalid {
                        what: "duration",
                        reason: format!("must be in 1..={every} (insert_every)"),
                    });
                }
                (every, duration as f64 * dt * vn)
            }
        };
        self.every = every;
        self.extrude = extrude;
        self.per_insertion = self.rate * every as f64 * dt;
        Ok(())
    }

    /// Steps between packets (for the run's time step, after [`InsertStream::set_timestep`]).
    pub fn packet_every(&self) -> u64 {
        self.every
    }

    /// Particles per time unit.
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// True if a packet is due at `step`.
    pub fn due(&self, step: u64) -> bool {
        if self.limit.is_some_and(|l| self.inserted >= l) {
            return false;
        }
        if step < self.start.unwrap_or(step) {
            return false;
        }
        self.last.is_none_or(|last| step >= last + self.every)
    }

    /// Inserts one packet into `world` at its current step (call when
    /// [`InsertStream::due`]).
    pub fn insert(&mut self, world: &mut World) -> Result<InsertReport> {
        self.last = Some(world.step);
        let face = StreamFace::new(&world.meshes[self.mesh].mesh, mean_velocity(self.velocity))?;
        let u: f64 = self.rng.gen();
        let mut wanted = (self.per_insertion + u).floor() as u64;
        if let Some(l) = self.limit {
            wanted = wanted.min(l.saturating_sub(self.inserted));
        }
        let rbound = self.dist.max_radius();
        let depth = self.extrude;
        let mut grid = self
            .overlap_check
            .then(|| OverlapGrid::gather(world, Some(face.bounding_box(depth + rbound)), rbound));
        let all_in = self.all_in;
        let n = face.normal;
        let placed = choose(
            &mut self.dist,
            &mut self.rng,
            wanted,
            wanted.saturating_mul(self.max_attempt.max(1) as u64),
            grid.as_mut(),
            self.orientation,
            |rng, r| {
                for _ in 0..1000 {
                    let p = face.sample(rng);
                    let d: f64 = rng.gen::<f64>() * depth;
                    if all_in && (d < r || d > depth - r || face.outline_distance(p) < r) {
                        continue;
                    }
                    // Without all_in the sphere starts wholly upstream of the face (its
                    // centre one radius further back), as LIGGGHTS places it.
                    let d = if all_in { d } else { d + r };
                    return Some(p - n * d);
                }
                None
            },
            self.velocity,
        );
        let hold = world.particles.add_property(HOLD_PROPERTY, 1, &[0.0])?;
        let release = world
            .particles
            .add_property(RELEASE_STEP_PROPERTY, 1, &[0.0])?;
        let tangent = world
            .particles
            .add_property(TANGENT_PROPERTY, 3, &[0.0; 3])?;
        let p0 = face.tris[0][0];
        let (mut inserted, mut mass) = (0u64, 0.0);
        let step = world.step;
        let dt = world.dt;
        let mut tags = TagCursor::new(world);
        for pl in &placed {
            // Held, it moves along the normal only; the rest comes at the face.
            let vn = pl.v.dot(n);
            let along = Placed { v: n * vn, ..*pl };
            let (m, added) = add_placed(
                world,
                &self.dist,
                &along,
                self.omega,
                self.groupbit,
                &mut tags,
            )?;
            mass += m;
            inserted += 1;
            if let Some(added) = added {
                // Steps until the centre reaches the face.
                let depth = (p0 - pl.x).dot(n).max(0.0);
                let steps = if vn > 0.0 {
                    (depth / (vn * dt)).ceil()
                } else {
                    0.0
                };
                let released = if vn > 0.0 {
                    ((depth + 1e-14) / (vn * dt)).floor()
                } else {
                    0.0
                };
                let props = &mut world.particles.props;
                props[hold.0].data[added.clone()].fill(step as f64 + steps);
                props[release.0].data[added.clone()].fill(step as f64 + released);
                let rest = (pl.v - n * vn).to_array();
                for i in added {
                    props[tangent.0].data[3 * i..3 * i + 3].copy_from_slice(&rest);
                }
            }
        }
        world.extend_tags();
        self.inserted += inserted;
        Ok(InsertReport {
            wanted,
            inserted,
            mass,
        })
    }
}

/// The mean of a velocity law.
fn mean_velocity(v: VelocityLaw) -> DVec3 {
    match v {
        VelocityLaw::Constant(m) | VelocityLaw::Uniform(m, _) | VelocityLaw::Gaussian(m, _) => m,
    }
}

impl InsertStream {
    /// Where the fix stands (restart files).
    pub fn progress(&self) -> super::InsertProgress {
        super::InsertProgress {
            rng: self.rng.clone(),
            dist: self.dist.rngs(),
            last: self.last,
            start: self.start,
            inserted: self.inserted,
        }
    }

    /// Takes back what [`InsertStream::progress`] gave; false if it belongs to another
    /// distribution.
    pub fn set_progress(&mut self, p: &super::InsertProgress) -> bool {
        if !self.dist.set_rngs(&p.dist) {
            return false;
        }
        self.rng = p.rng.clone();
        self.last = p.last;
        self.start = p.start;
        self.inserted = p.inserted;
        true
    }
}
