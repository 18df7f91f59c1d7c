//! `fix mesh/surface/stress`: the force the particles exert on each triangle, its normal
//! and shear stress, the total force and torque on the mesh, and Finnie's erosive wear.
//!
//! The contact pass runs in parallel over particles, so it only writes what each contact
//! did into the particle's own history slot (after the contact model's history: the
//! triangle, the force on the wall, the wear increment and the contact point, see
//! [`record`]). [`accumulate`] then adds the slots up per triangle in particle order,
//! serially: the sums do not depend on the thread count.
//!
//! Wear (LIGGGHTS' soft-sphere form of Finnie's model): while a particle approaches the
//! wall (its relative velocity `v` points into the wall), a contact adds
//! `2 k |v| f(γ) |F| dt / A` to its triangle, `F` the contact force, `A` the triangle's
//! area, `k` the `k_finnie` of the particle and wall types, `γ` the impact angle between
//! `v` and the surface and `f(γ) = cos²γ / 3` when `tan γ > 1/3`, else
//! `sin 2γ − 3 sin²γ`.

use glam::DVec3;

use crate::particles::Particles;
use crate::wall::MeshSurface;

/// Values per contact slot after the contact history: triangle + 1 (0: none), the force
/// on the wall (3), the wear increment for k = 1 before division by the area, the
/// contact point (3), the normal force pressing on the wall.
pub const EXTRA: usize = 9;

/// Stress and wear state of one mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshStress {
    /// `wear finnie`.
    pub finnie: bool,
    /// `k_finnie` by (particle type − 1) · ntypes + (wall type − 1); empty without wear.
    pub k_finnie: Vec<f64>,
    /// Number of atom types of `k_finnie`.
    pub ntypes: usize,
    /// Reference point of the torque.
    pub reference_point: DVec3,
    /// Force on each triangle at the last step.
    pub force: Vec<DVec3>,
    /// Normal force pressing on each triangle at the last step.
    pub pressing: Vec<f64>,
    /// Accumulated wear of each triangle.
    pub wear: Vec<f64>,
    /// Total force on the mesh at the last step.
    pub total_force: DVec3,
    /// Total torque about the reference point at the last step.
    pub total_torque: DVec3,
}

impl MeshStress {
    /// Stress tracking for a mesh of `ntri` triangles.
    pub fn new(ntri: usize, finnie: bool) -> Self {
        Self {
            finnie,
            force: vec![DVec3::ZERO; ntri],
            pressing: vec![0.0; ntri],
            wear: vec![0.0; ntri],
            ..Default::default()
        }
    }

    fn k(&self, ptype: u32, wtype: u32) -> f64 {
        let (i, j) = (ptype as usize, wtype as usize);
        if i == 0 || j == 0 || i > self.ntypes || j > self.ntypes {
            return 0.0;
        }
        self.k_finnie
            .get((i - 1) * self.ntypes + j - 1)
            .copied()
            .unwrap_or(0.0)
    }
}

/// Finnie's angle function of the impact angle `gamma` (radians, 0 = grazing).
pub fn finnie_f(gamma: f64) -> f64 {
    if gamma.tan() > 1.0 / 3.0 {
        gamma.cos().powi(2) / 3.0
    } else {
        (2.0 * gamma).sin() - 3.0 * gamma.sin().powi(2)
    }
}

/// Writes one contact's share into its slot's extra values `out` (see [`EXTRA`]):
/// triangle `tri`, contact point `q`, unit normal `n` (wall to particle), the force
/// `f_particle` on the particle, relative velocity `v` of the particle to the wall.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn record(
    out: &mut [f64],
    st: &MeshStress,
    tri: u32,
    q: DVec3,
    n: DVec3,
    f_particle: DVec3,
    v: DVec3,
    dt: f64,
) {
    out[0] = tri as f64 + 1.0;
    out[1] = -f_particle.x;
    out[2] = -f_particle.y;
    out[3] = -f_particle.z;
    let vn = v.dot(n);
    let speed = v.length();
    out[4] = if st.finnie && vn < 0.0 && speed > 0.0 {
        let gamma = (-vn / speed).clamp(0.0, 1.0).asin();
        2.0 * speed * finnie_f(gamma) * f_particle.length() * dt
    } else {
        0.0
    };
    out[5] = q.x;
    out[6] = q.y;
    out[7] = q.z;
    out[8] = f_particle.dot(n);
}

/// Sums the slots of `p` (the owned particles, in order) into the triangles of the
/// stress meshes of the mesh walls among `fixes`; `update` false (a run's set-up) leaves the wear alone.
pub fn accumulate(
    fixes: &[crate::fix::Fix],
    meshes: &mut [MeshSurface],
    p: &Particles,
    update: bool,
) {
    for m in meshes.iter_mut() {
        if let Some(st) = &mut m.stress {
            st.force.iter_mut().for_each(|f| *f = DVec3::ZERO);
            st.pressing.iter_mut().for_each(|f| *f = 0.0);
            st.total_force = DVec3::ZERO;
            st.total_torque = DVec3::ZERO;
        }
    }
    let n = p.nlocal();
    let walls = fixes.iter().filter_map(|f| match &f.kind {
        crate::fix::FixKind::MeshWall(w) => Some(&**w),
        _ => None,
    });
    for wall in walls {
        let (Some(id), true) = (wall.history_prop(), wall.extra > 0) else {
            continue;
        };
        let hist = &p.sparse[id.0];
        let stride = wall.stride;
        let hw = stride - 1 - wall.extra;
        for i in 0..n {
            let h = hist.get(i);
            for s in 0..super::mesh::SLOTS {
                let slot = &h[s * stride..(s + 1) * stride];
                let Some((mi, _)) = super::mesh::unkey(slot[0]) else {
                    continue;
                };
                let x = &slot[1 + hw..];
                if x[0] == 0.0 {
                    continue;
                }
                let m = &mut meshes[wall.meshes[mi as usize]];
                let tri = x[0] as usize - 1;
                let area = {
                    let [a, b, c] = m.mesh.corners(tri as u32);
                    0.5 * (b - a).cross(c - a).length()
                };
                let wall_type = m.wall_type;
                let Some(st) = &mut m.stress else { continue };
                let f = DVec3::new(x[1], x[2], x[3]);
                let q = DVec3::new(x[5], x[6], x[7]);
                st.force[tri] += f;
                st.pressing[tri] += x[8];
                st.total_force += f;
                st.total_torque += (q - st.reference_point).cross(f);
                if update && x[4] != 0.0 && area > 0.0 {
                    // The type pair's constant, applied here (the slot holds k = 1 · ...).
                    let k = st.k(p.ty[i], wall_type);
                    st.wear[tri] += k * x[4] / area;
                }
            }
        }
    }
}

/// Per-triangle normal stress (the normal force pressing on the triangle over its area)
/// and shear stress (the force's component along the triangle over its area) of a stress
/// mesh.
pub fn stresses(m: &MeshSurface) -> (Vec<f64>, Vec<f64>) {
    let Some(st) = &m.stress else {
        return (Vec::new(), Vec::new());
    };
    let mut normal = Vec::with_capacity(st.force.len());
    let mut shear = Vec::with_capacity(st.force.len());
    for (t, f) in st.force.iter().enumerate() {
        let [a, b, c] = m.mesh.corners(t as u32);
        let area = 0.5 * (b - a).cross(c - a).length();
        let nrm = m.mesh.normals[t];
        let ft = (*f - nrm * f.dot(nrm)).length();
        if area > 0.0 {
            normal.push(st.pressing[t] / area);
            shear.push(ft / area);
        } else {
            normal.push(0.0);
            shear.push(0.0);
        }
    }
    (normal, shear)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Finnie's function is continuous at tan γ = 1/3 (both branches give 0.3), zero for
    /// a grazing and for a normal impact, cos²45°/3 at 45°.
    #[test]
    fn finnie_function() {
        let g0 = (1.0f64 / 3.0).atan();
        assert!((finnie_f(g0 - 1e-12) - 0.3).abs() < 1e-9);
        assert!((finnie_f(g0 + 1e-12) - 0.3).abs() < 1e-9);
        assert_eq!(finnie_f(0.0), 0.0);
        assert!(finnie_f(std::f64::consts::FRAC_PI_2).abs() < 1e-16);
        assert!((finnie_f(std::f64::consts::FRAC_PI_4) - 0.5 / 3.0).abs() < 1e-15);
    }

    /// One contact's record: the force on the wall, the pressing force, and while the
    /// particle approaches the wall the wear increment 2 |v| f(γ) |F| dt (k = 1); none
    /// while it moves away.
    #[test]
    fn a_contact_records_its_share() {
        let st = MeshStress::new(4, true);
        let mut out = [0.0; EXTRA];
        let n = DVec3::Z;
        let f = DVec3::new(0.3, 0.0, 4.0);
        // 30° below the surface: v = (cos 30°, 0, −sin 30°) · 2.
        let v = DVec3::new(3f64.sqrt(), 0.0, -1.0);
        record(&mut out, &st, 2, DVec3::new(0.1, 0.2, 0.0), n, f, v, 1e-5);
        assert_eq!(out[0], 3.0);
        assert_eq!(&out[1..4], &[-0.3, 0.0, -4.0]);
        let gamma = std::f64::consts::FRAC_PI_6;
        let want = 2.0 * 2.0 * finnie_f(gamma) * f.length() * 1e-5;
        assert!(
            (out[4] - want).abs() < 1e-15 * want.max(1.0),
            "{} {want}",
            out[4]
        );
        assert_eq!(&out[5..8], &[0.1, 0.2, 0.0]);
        assert_eq!(out[8], 4.0);
        record(&mut out, &st, 2, DVec3::ZERO, n, f, -v, 1e-5);
        assert_eq!(out[4], 0.0);
    }
}
