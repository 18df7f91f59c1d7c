//! `fix massflow/mesh`: the mass and number of particles crossing a planar mesh face
//! from its inner to its outer side (the side `vec_side` points to).
//!
//! Each particle remembers the side of the face's plane it was on at the end of the
//! previous step (a per-particle property, so it travels with the particle). A particle
//! that was inside and is now outside, and whose centre now projects onto one of the
//! face's triangles, has crossed the face; with `count once` it is then marked and never
//! counted again. With `delete_atoms yes` it is removed at the next re-neighboring (as
//! in LIGGGHTS), acting on its neighbours until then.

use glam::DVec3;

use crate::error::{Error, Result};
use crate::mesh::TriMesh;
use crate::particles::PropId;
use crate::world::World;

/// Settings and totals of one `fix massflow/mesh`.
#[derive(Debug, Clone)]
pub struct MassFlow {
    /// Fix ID (the per-particle property is `massflow_ID`).
    pub id: String,
    /// The face: an index into [`World::meshes`].
    pub mesh: usize,
    /// Particles of this group are counted.
    pub groupbit: u32,
    /// The outer side.
    pub side: DVec3,
    /// `count once`: a particle is counted at most once.
    pub once: bool,
    /// `delete_atoms yes`: particles are removed once counted.
    pub delete: bool,
    /// Mass that has crossed.
    pub mass: f64,
    /// Particles that have crossed.
    pub count: u64,
    /// Mass deleted.
    pub deleted_mass: f64,
    /// Particles deleted.
    pub deleted: u64,
    /// Keep the local indices of the particles counted by each [`MassFlow::update`] in
    /// [`MassFlow::crossed`] (for `file`/`append`, which write one line per particle).
    pub record: bool,
    /// With `record`: the local indices counted by the last update (valid until the next
    /// re-neighboring).
    pub crossed: Vec<usize>,
    prop: Option<PropId>,
}

/// Relative tolerance of the planarity test.
const PLANAR_TOL: f64 = 1e-6;

/// Unit normal of a planar mesh, oriented along `side`.
fn plane_normal(mesh: &TriMesh, side: DVec3) -> Result<(DVec3, DVec3)> {
    let bad = |reason: &str| Error::Invalid {
        what: "massflow/mesh",
        reason: reason.into(),
    };
    let mut n = DVec3::ZERO;
    for t in 0..mesh.tris.len() as u32 {
        let c = mesh.corners(t);
        let a = (c[1] - c[0]).cross(c[2] - c[0]);
        if a.length() > n.length() {
            n = a;
        }
    }
    if n == DVec3::ZERO {
        return Err(bad("the mesh has no triangles"));
    }
    let n = n.normalize();
    let p0 = mesh.verts[0];
    let (lo, hi) = mesh.bounds();
    if mesh
        .verts
        .iter()
        .any(|&v| (v - p0).dot(n).abs() > PLANAR_TOL * (hi - lo).length())
    {
        return Err(bad(
            "with vec_side the mesh must be planar (use a planar face)",
        ));
    }
    let s = side.dot(n);
    if s.abs() <= 1e-9 * side.length() {
        return Err(bad("vec_side lies in the plane of the mesh"));
    }
    Ok((if s > 0.0 { n } else { -n }, p0))
}

/// True if `p` (in the plane of triangle `c`) lies in the triangle.
fn in_triangle(c: [DVec3; 3], p: DVec3, n: DVec3) -> bool {
    (0..3).all(|k| {
        let (a, b) = (c[k], c[(k + 1) % 3]);
        let s = (b - a).cross(p - a).dot(n);
        let o = (b - a).cross(c[(k + 2) % 3] - a).dot(n);
        s * o >= 0.0
    })
}

impl MassFlow {
    /// Counting through the world's mesh number `mesh` towards `side`.
    pub fn new(id: &str, mesh: usize, face: &TriMesh, groupbit: u32, side: DVec3) -> Result<Self> {
        plane_normal(face, side)?;
        Ok(Self {
            id: id.to_string(),
            mesh,
            groupbit,
            side,
            once: false,
            delete: false,
            mass: 0.0,
            count: 0,
            deleted_mass: 0.0,
            deleted: 0,
            record: false,
            crossed: Vec::new(),
            prop: None,
        })
    }

    /// Counts the particles of `world` that crossed since the last call (call at the end
    /// of every step; the first call only records sides). Removes them with
    /// `delete_atoms yes`.
    pub fn update(&mut self, world: &mut World) -> Result<()> {
        let mesh = &world.meshes[self.mesh].mesh;
        let (n, p0) = plane_normal(mesh, self.side)?;
        let id = match self.prop {
            Some(id) => id,
            None => {
                // [side: +1 outer, -1 inner, 0 unknown; counted]
                let id = world.particles.add_property(
                    &format!("massflow_{}", self.id),
                    2,
                    &[0.0, 0.0],
                )?;
                self.prop = Some(id);
                id
            }
        };
        let p = &mut world.particles;
        let nlocal = p.nlocal();
        let (mut mass, mut count) = (0.0, 0u64);
        self.crossed.clear();
        let mut remove = Vec::new();
        for i in 0..nlocal {
            if p.mask[i] & self.groupbit == 0 {
                continue;
            }
            let d = (p.x[i] - p0).dot(n);
            let side = if d > 0.0 { 1.0 } else { -1.0 };
            let h = &mut p.props[id.0].data[2 * i..2 * i + 2];
            // A particle awaiting deletion is not counted again.
            let crossed =
                h[0] == -1.0 && side == 1.0 && !((self.once || self.delete) && h[1] != 0.0);
            h[0] = side;
            if !crossed {
                continue;
            }
            let q = p.x[i] - n * d;
            let inside = (0..mesh.tris.len() as u32).any(|t| in_triangle(mesh.corners(t), q, n));
            if !inside {
                continue;
            }
            h[1] = 1.0;
            mass += p.rmass[i];
            count += 1;
            if self.record {
                self.crossed.push(i);
            }
            if self.delete {
                remove.push(i);
            }
        }
        let mass = world.comm.sum(mass);
        let count = world.comm.sum_count(count);
        self.mass += mass;
        self.count += count;
        if self.delete {
            // Removed at the next re-neighboring, as LIGGGHTS does.
            self.deleted_mass += mass;
            self.deleted += count;
            for i in remove {
                world.remove_at_reneighbor(i)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::NewParticle;
    use crate::{Boundary, Domain};

    fn square(z: f64) -> TriMesh {
        let v = |x: f64, y: f64| DVec3::new(x, y, z);
        let soup = [
            [v(-0.5, -0.5), v(0.5, -0.5), v(0.5, 0.5)],
            [v(-0.5, -0.5), v(0.5, 0.5), v(-0.5, 0.5)],
        ];
        TriMesh::from_triangles(&soup, 1e-9, false).unwrap().0
    }

    /// Particles falling through a square face are counted once each, those falling
    /// beside it not at all, and `delete_atoms` removes the counted ones.
    #[test]
    fn counts_particles_through_the_face() {
        for delete in [false, true] {
            let mut w = World::new(
                Domain::new(DVec3::splat(-2.0), DVec3::splat(2.0), [Boundary::Fixed; 3]).unwrap(),
            );
            w.add_mesh(crate::wall::MeshSurface::new("face", square(0.0), 1));
            let xs = [(0.0, 0.0), (0.3, -0.2), (0.9, 0.0), (-0.4, 0.45)];
            for (x, y) in xs {
                w.add_particle(
                    &NewParticle::at(DVec3::new(x, y, 0.05), 0.01, 1000.0)
                        .with_v(DVec3::new(0.0, 0.0, -1.0)),
                )
                .unwrap();
            }
            let mut mf =
                MassFlow::new("mf", 0, &w.meshes[0].mesh, 1, DVec3::new(0.0, 0.0, -1.0)).unwrap();
            mf.delete = delete;
            mf.record = true;
            mf.update(&mut w).unwrap();
            assert_eq!(mf.count, 0);
            let mut crossed = Vec::new();
            for _ in 0..10 {
                for x in &mut w.particles.x {
                    x.z -= 0.01;
                }
                mf.update(&mut w).unwrap();
                crossed.extend(mf.crossed.iter().copied());
            }
            // The three above the face, each recorded in the step it crossed.
            crossed.sort_unstable();
            assert_eq!(crossed, [0, 1, 3]);
            let m = crate::particles::sphere_mass(1000.0, 0.01);
            assert_eq!(mf.count, 3);
            assert!((mf.mass - 3.0 * m).abs() < 1e-15);
            // Deleted at the next re-neighboring.
            assert_eq!(w.particles.nlocal(), 4);
            w.reneighbor().unwrap();
            assert_eq!(w.particles.nlocal(), if delete { 1 } else { 4 });
            // Back up and down again: counted again (count multiple).
            if !delete {
                for x in &mut w.particles.x {
                    x.z = 0.05;
                }
                mf.update(&mut w).unwrap();
                for x in &mut w.particles.x {
                    x.z = -0.05;
                }
                mf.update(&mut w).unwrap();
                assert_eq!(mf.count, 6);
            }
        }
    }
}
