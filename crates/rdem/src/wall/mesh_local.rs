//! The contacts of a mesh wall one by one, for per-contact output (`compute
//! wall/gran/local`). As LIGGGHTS 3.8 does when such a compute is invoked, the wall's
//! contact model is evaluated again from the current positions, velocities and stored
//! history, without changing the history (the mesh pass with `update` off on a copy of
//! the history): at the end of a step this is the state the output describes.

use glam::DVec3;

use super::mesh::{MeshPass, MeshSurface, MeshWall};
use crate::contact::ContactForce;
use crate::par::View;
use crate::particles::Particles;

/// One particle–mesh contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallContact {
    /// Local index of the particle (owned).
    pub i: u32,
    /// The mesh's position among the wall's meshes (0 first).
    pub mesh: u32,
    /// The triangle (its order in the mesh file).
    pub tri: u32,
    /// The closest point of the wall.
    pub q: DVec3,
    /// Unit normal from the wall to the particle's centre.
    pub n: DVec3,
    /// Distance from the closest point to the centre.
    pub dist: f64,
    /// The wall's velocity at the closest point.
    pub v_wall: DVec3,
    /// Contact force on the particle (the contact law's; a wall bond not included).
    pub f: DVec3,
    /// Torque on the particle from the contact law.
    pub t: DVec3,
}

/// The contacts of a mesh wall: ordered by mesh, triangle, then particle, as LIGGGHTS
/// 3.8 lists them (it loops over the triangles and their particles).
#[derive(Debug, Clone, Default)]
pub struct WallContacts {
    /// The contacts.
    pub rows: Vec<WallContact>,
    /// Contact history values of the contact law, [`WallContacts::width`] per contact.
    pub hist: Vec<f64>,
    /// History values per contact.
    pub width: usize,
}

impl WallContacts {
    /// Records one contact (called by the mesh pass).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn push(
        &mut self,
        i: usize,
        mesh: u32,
        tri: u32,
        q: DVec3,
        n: DVec3,
        dist: f64,
        v_wall: DVec3,
        out: &ContactForce,
        hist: &[f64],
    ) {
        self.width = hist.len();
        self.rows.push(WallContact {
            i: i as u32,
            mesh,
            tri,
            q,
            n,
            dist,
            v_wall,
            f: out.f_i,
            t: out.t_i,
        });
        self.hist.extend_from_slice(hist);
    }

    /// Sorts by (mesh, triangle, particle), keeping each row's history with it.
    fn sort(&mut self) {
        let mut order: Vec<usize> = (0..self.rows.len()).collect();
        order.sort_by_key(|&k| {
            let r = &self.rows[k];
            (r.mesh, r.tri, r.i)
        });
        let w = self.width;
        self.rows = order.iter().map(|&k| self.rows[k]).collect();
        self.hist = order
            .iter()
            .flat_map(|&k| self.hist[k * w..(k + 1) * w].iter().copied())
            .collect();
    }
}

impl MeshWall {
    /// The contacts of the owned particles with this wall's meshes (`all`: the world's
    /// meshes), evaluated as a force pass that does not advance the history would give
    /// them. The candidates must be current (as after a force pass).
    pub fn contacts(&self, all: &[MeshSurface], p: &Particles, dt: f64) -> WallContacts {
        let n = p.nlocal();
        let mut out = WallContacts {
            width: self.model.contact_history_width(),
            ..WallContacts::default()
        };
        let Some(id) = self.history_prop() else {
            return out;
        };
        let mut hist = p.sparse[id.0].data.clone();
        let mut f = vec![DVec3::ZERO; n];
        let mut torque = vec![DVec3::ZERO; n];
        let view = View {
            x: &p.x,
            v: &p.v,
            omega: &p.omega,
            radius: &p.radius,
            rmass: &p.rmass,
            mcontact: p.contact_mass(),
            ty: &p.ty,
            mask: &p.mask,
            tag: &p.tag,
        };
        if !self.has_candidates_for(n) {
            return out;
        }
        let model = self.model;
        model.dispatch(MeshPass {
            wall: self,
            all,
            view: &view,
            lo: 0,
            f: &mut f,
            torque: &mut torque,
            hist: &mut hist,
            touches: super::Touches::none(),
            dt,
            update: false,
            rec: Some(&mut out),
        });
        out.sort();
        out
    }
}
