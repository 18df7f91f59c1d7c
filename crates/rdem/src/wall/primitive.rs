//! `fix wall/gran ... primitive type T xplane|yplane|zplane|xcylinder|ycylinder|zcylinder`:
//! a flat or cylindrical wall of infinite radius and mass, with the particle–particle
//! contact law and one history slot per particle near the wall, stored as a sparse
//! per-particle property ([`crate::particles::SparseProperty`]) so it moves with its
//! particle through sorting and migration.

use glam::DVec3;

use crate::bond::{self, BondEvents, BondGeom, BondTable, Event};
use crate::contact::{
    clear_history, CoeffTable, ContactKernel, ContactModel, Geom, Materials, Visitor,
};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::multicontact::MultiContact;
use crate::par::{parallel, View, CHUNK};
use crate::particles::{Particles, PropId, SparseId};

/// Shape of a primitive wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WallShape {
    /// Plane normal to `axis` (0 = x) at coordinate `pos`; particles on either side.
    Plane {
        /// Normal axis.
        axis: usize,
        /// Position along it.
        pos: f64,
    },
    /// Cylinder parallel to `axis` with the given radius, its axis through (c1, c2) in the
    /// other two coordinates in cyclic order (xcylinder: y z; ycylinder: z x; zcylinder:
    /// x y); particles inside or outside.
    Cylinder {
        /// Axis direction.
        axis: usize,
        /// Radius.
        radius: f64,
        /// First other coordinate of the axis.
        c1: f64,
        /// Second other coordinate of the axis.
        c2: f64,
    },
    /// `general_plane` (LIGGGHTS-PFM): the plane through `point` normal to `normal` (a unit
    /// vector); particles on either side.
    GeneralPlane {
        /// A point of the plane.
        point: DVec3,
        /// Unit normal.
        normal: DVec3,
    },
    /// `general_cylinder` (LIGGGHTS-PFM): the cylinder of `radius` about the line through
    /// `point` along `axis` (a unit vector); particles inside or outside.
    GeneralCylinder {
        /// Radius.
        radius: f64,
        /// A point of the axis.
        point: DVec3,
        /// Unit axis direction.
        axis: DVec3,
    },
    /// `general_cone` (LIGGGHTS-PFM): the mantle of the frustum between the circle of
    /// radius `r1` about `p1` and that of radius `r2` about `p2` (both normal to p2 − p1),
    /// without its end discs; particles on either side. Beyond the ends the nearest point
    /// is on the rim circle.
    GeneralCone {
        /// Radius at `p1`.
        r1: f64,
        /// Centre of the first rim.
        p1: DVec3,
        /// Centre of the second rim.
        p2: DVec3,
        /// Radius at `p2`.
        r2: f64,
    },
}

impl WallShape {
    /// Distance from the wall to `x` and the unit normal from the wall towards `x`.
    #[inline(always)]
    pub fn distance(&self, x: DVec3) -> (f64, DVec3) {
        match *self {
            WallShape::Plane { axis, pos } => {
                let d = x[axis] - pos;
                let mut n = DVec3::ZERO;
                n[axis] = if d >= 0.0 { 1.0 } else { -1.0 };
                (d.abs(), n)
            }
            WallShape::Cylinder {
                axis,
                radius,
                c1,
                c2,
            } => {
                let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
                // c1, c2 follow the cyclic order (x: y z, y: z x, z: x y), as in LIGGGHTS.
                let (o1, o2) = (c1, c2);
                let mut r = DVec3::ZERO;
                r[a1] = x[a1] - o1;
                r[a2] = x[a2] - o2;
                cylinder_distance(r, radius)
            }
            WallShape::GeneralPlane { point, normal } => {
                let d = (x - point).dot(normal);
                (d.abs(), if d >= 0.0 { normal } else { -normal })
            }
            WallShape::GeneralCylinder {
                radius,
                point,
                axis,
            } => {
                let w = x - point;
                cylinder_distance(w - w.dot(axis) * axis, radius)
            }
            WallShape::GeneralCone { r1, p1, p2, r2 } => cone_distance(x, r1, p1, p2, r2),
        }
    }

    /// Checks the shape's numbers.
    pub fn validate(&self) -> Result<()> {
        match *self {
            WallShape::Plane { axis, pos } => {
                if axis > 2 || !pos.is_finite() {
                    return Err(Error::Invalid {
                        what: "wall plane",
                        reason: format!("axis {axis}, position {pos}"),
                    });
                }
            }
            WallShape::Cylinder {
                axis,
                radius,
                c1,
                c2,
            } => {
                if axis > 2
                    || radius.is_nan()
                    || radius <= 0.0
                    || !radius.is_finite()
                    || !c1.is_finite()
                    || !c2.is_finite()
                {
                    return Err(Error::Invalid {
                        what: "wall cylinder",
                        reason: format!("needs a finite radius > 0 and a finite axis position (axis {axis}, radius {radius}, centre {c1} {c2})"),
                    });
                }
            }
            WallShape::GeneralPlane { point, normal } => {
                if !point.is_finite()
                    || !normal.is_finite()
                    || (normal.length() - 1.0).abs() > 1e-12
                {
                    return Err(Error::Invalid {
                        what: "wall general_plane",
                        reason: format!("needs a finite point and a unit normal (point {point}, normal {normal})"),
                    });
                }
            }
            WallShape::GeneralCylinder {
                radius,
                point,
                axis,
            } => {
                let ok = radius > 0.0
                    && radius.is_finite()
                    && point.is_finite()
                    && axis.is_finite()
                    && (axis.length() - 1.0).abs() <= 1e-12;
                if !ok {
                    return Err(Error::Invalid {
                        what: "wall general_cylinder",
                        reason: format!("needs a finite radius > 0, a finite point and a unit axis (radius {radius}, point {point}, axis {axis})"),
                    });
                }
            }
            WallShape::GeneralCone { r1, p1, p2, r2 } => {
                let radii_ok =
                    r1 >= 0.0 && r2 >= 0.0 && r1.is_finite() && r2.is_finite() && r1 + r2 > 0.0;
                if !radii_ok || !p1.is_finite() || !p2.is_finite() || p1 == p2 {
                    return Err(Error::Invalid {
                        what: "wall general_cone",
                        reason: format!("needs radii >= 0, not both 0, and two different finite rim centres (radii {r1} {r2}, centres {p1} {p2})"),
                    });
                }
            }
        }
        Ok(())
    }
}

/// Distance to a cylinder of `radius` from a point `r` away from its axis (normal to
/// it), and the unit normal towards the point: inwards inside, outwards outside. Exactly
/// on the axis there is no direction: no contact (as LIGGGHTS).
fn cylinder_distance(r: DVec3, radius: f64) -> (f64, DVec3) {
    let d = r.length();
    if d == 0.0 {
        return (f64::INFINITY, DVec3::ZERO);
    }
    let u = r / d;
    if d <= radius {
        (radius - d, -u)
    } else {
        (d - radius, u)
    }
}

/// Distance from `x` to the mantle of the frustum of [`WallShape::GeneralCone`] and the
/// unit normal from the mantle towards `x`. In the plane of the axis and `x` (radial
/// coordinate ρ, axial coordinate ζ from `p1`), the mantle is the segment from (r1, 0)
/// to (r2, L); the nearest point is `x`'s projection on the segment's line, clamped to
/// its ends (the rims). On the axis (ρ = 0) there is no radial direction: no contact.
fn cone_distance(x: DVec3, r1: f64, p1: DVec3, p2: DVec3, r2: f64) -> (f64, DVec3) {
    let axis = p2 - p1;
    let len = axis.length();
    let t = axis / len;
    let w = x - p1;
    let zeta = w.dot(t);
    let radial = w - zeta * t;
    let rho = radial.length();
    if rho == 0.0 {
        return (f64::INFINITY, DVec3::ZERO);
    }
    let e = radial / rho;
    // The generator's unit direction in (ρ, ζ), and x's projection onto it.
    let (gr, gz) = (r2 - r1, len);
    let glen = (gr * gr + gz * gz).sqrt();
    let (gr, gz) = (gr / glen, gz / glen);
    let s = (rho - r1) * gr + zeta * gz;
    let (mut cr, mut cz) = (r1 + s * gr, s * gz);
    if cz > len {
        (cr, cz) = (r2, len);
    } else if cz <= 0.0 {
        (cr, cz) = (r1, 0.0);
    }
    // From the nearest point to x.
    let v = (rho - cr) * e + (zeta - cz) * t;
    let d = v.length();
    if d == 0.0 {
        return (0.0, DVec3::ZERO);
    }
    (d, v / d)
}

/// A primitive granular wall.
#[derive(Debug, Clone)]
pub struct PrimitiveWall {
    /// Contact model (must match the pair style's, as LIGGGHTS requires).
    pub model: ContactModel,
    /// Material type of the wall (1-based).
    pub wall_type: u32,
    /// Geometry.
    pub shape: WallShape,
    /// In-plane velocity of the wall surface (LIGGGHTS keyword `shear`).
    pub velocity: DVec3,
    /// Name of the per-particle history property.
    pub history_name: String,
    /// With `store_force yes`: the name of the per-particle property (3 values) that
    /// receives the wall's total force on each particle at every force pass
    /// (`force_ID` in LIGGGHTS).
    pub store_force: Option<String>,
    store: Option<PropId>,
    /// Fixed temperature of the wall for heat conduction (`temperature T`), if any.
    pub temperature: Option<f64>,
    table: CoeffTable,
    hist: Option<SparseId>,
    /// Owned particles of the group within r + skin of the wall at the last
    /// re-neighboring: the only ones that can touch it before the next (the wall is
    /// fixed and no particle moves more than skin/2 in between).
    candidates: Vec<u32>,
    /// With `cohesion bond`: the bond parameters (particle type × wall type).
    bond: Option<BondTable>,
    /// Wall bonds created and broken on this rank so far.
    pub bond_events: BondEvents,
    /// The current step (set before each force pass; bonds are created at
    /// `tsCreateBond`).
    pub step: u64,
    /// With `surface multicontact`: the contacts' store and this wall's number in it.
    pub multicontact: Option<(std::sync::Arc<crate::multicontact::MultiContact>, u64)>,
}

impl PrimitiveWall {
    /// A wall called `id` (the fix ID) of material `wall_type`.
    pub fn new(id: &str, model: ContactModel, wall_type: u32, shape: WallShape) -> Result<Self> {
        shape.validate()?;
        if wall_type == 0 {
            return Err(Error::Invalid {
                what: "wall type",
                reason: "types start at 1".into(),
            });
        }
        Ok(Self {
            model,
            wall_type,
            shape,
            velocity: DVec3::ZERO,
            history_name: format!("wallhist_{id}"),
            store_force: None,
            store: None,
            temperature: None,
            table: CoeffTable::default(),
            hist: None,
            candidates: Vec::new(),
            bond: None,
            bond_events: BondEvents::default(),
            step: 0,
            multicontact: None,
        })
    }

    /// The owned particles that may touch the wall until the next re-neighboring (listed
    /// by [`PrimitiveWall::build_candidates`]).
    pub fn candidate_list(&self) -> &[u32] {
        &self.candidates
    }

    /// Mixes the material table and registers the history property; called before a run.
    pub fn setup(&mut self, materials: &Materials, p: &mut Particles) -> Result<()> {
        self.model.resolve_jkr(materials)?;
        self.table = CoeffTable::new(materials, self.model.needs())?;
        if self.wall_type as usize > materials.ntypes {
            return Err(Error::TypeOutOfRange {
                ty: self.wall_type,
                ntypes: materials.ntypes as u32,
            });
        }
        self.bond = BondTable::for_model(&self.model, materials)?;
        let w = self.model.wall_history_width();
        self.hist = if w > 0 {
            Some(p.add_sparse_property(&self.history_name, w)?)
        } else {
            None
        };
        self.store = super::store_prop(self.store_force.as_deref(), p)?;
        Ok(())
    }

    /// Lists the owned particles of group `groupbit` within max(r, bond reach) + `skin` (+
    /// the JKR neck's reach) of the wall (call at every re-neighboring) and gives history rows to them alone (the
    /// others' history is dropped). In parallel over chunks of particles, the lists
    /// joined in chunk order.
    pub fn build_candidates(&mut self, p: &mut Particles, groupbit: u32, skin: f64) {
        let reach = self.bond.as_ref().map_or(0.0, |b| b.wall_reach);
        self.candidates.clear();
        let n = p.nlocal();
        let (x, radius, mask) = (&p.x[..n], &p.radius[..n], &p.mask[..n]);
        let (shape, table) = (self.shape, &self.table);
        // Appends the candidates among particles lo..lo + len to `out`. A JKR neck holds
        // beyond contact, by up to its δ_c for R* = r (0 for other laws).
        let scan = |lo: usize, len: usize, out: &mut Vec<u32>| {
            for i in lo..lo + len {
                let r = radius[i];
                let lim = r.max(reach) + skin + table.neck_reach(r);
                let near = mask[i] & groupbit != 0 && shape.distance(x[i]).0 < lim;
                if near {
                    out.push(i as u32);
                }
            }
        };
        if !parallel(n) {
            scan(0, n, &mut self.candidates);
        } else {
            let parts: Vec<Vec<u32>> = (0..n.div_ceil(CHUNK))
                .into_par_iter()
                .map(|c| {
                    let lo = c * CHUNK;
                    let mut out = Vec::new();
                    scan(lo, CHUNK.min(n - lo), &mut out);
                    out
                })
                .collect();
            for part in parts {
                self.candidates.extend_from_slice(&part);
            }
        }
        if let Some(id) = self.hist {
            let cand = &self.candidates;
            p.sparse[id.0].keep_rows(cand.iter().map(|&i| i as usize), cand.len());
        }
    }

    /// Where a particle's wall bond flag sits in its history (with `cohesion bond`).
    pub(crate) fn bond_flag_at(&self) -> Option<usize> {
        self.bond
            .as_ref()
            .map(|b| self.model.wall_history_width() - b.layout().wall_tail)
    }

    /// Intact bonds of owned particles with this wall.
    pub fn count_bonds(&self, p: &Particles) -> u64 {
        super::count_bonded(p, self.hist, self.bond_flag_at())
    }

    /// The particles listed by the last [`PrimitiveWall::build_candidates`].
    pub fn candidates(&self) -> &[u32] {
        &self.candidates
    }

    /// Adds the wall forces and torques on the owned particles listed by the last
    /// [`PrimitiveWall::build_candidates`].
    pub fn apply(&mut self, p: &mut Particles, dt: f64, update: bool) {
        let n = p.nlocal();
        let (view, f, torque, props, sparse) = View::split(p);
        let mut store = self
            .store
            .map(|id| std::mem::take(&mut props[id.0].data))
            .unwrap_or_default();
        let hist: &mut [f64] = match self.hist {
            Some(id) => &mut sparse[id.0].data,
            None => &mut [],
        };
        if self.store.is_some() {
            super::store_begin(&mut f[..n], &mut store[..3 * n]);
        }
        let touches = super::Touches::none();
        self.apply_range(
            &view,
            0,
            &mut f[..n],
            &mut torque[..n],
            hist,
            touches,
            dt,
            update,
        );
        if let Some(id) = self.store {
            super::store_end(&mut f[..n], &mut store[..3 * n]);
            props[id.0].data = store;
        }
    }

    /// The history property's ID, if the model has history.
    pub(crate) fn history_prop(&self) -> Option<SparseId> {
        self.hist
    }

    /// The `store_force` property's ID (after [`PrimitiveWall::setup`]).
    pub(crate) fn store_prop(&self) -> Option<PropId> {
        self.store
    }

    /// [`PrimitiveWall::apply`] on the particles `lo..lo + f.len()`: `f` and `torque`
    /// start at particle `lo`, `hist` (the history rows, or empty without history) at the
    /// row of the first candidate from `lo` on (see [`super::chunk_rows`]).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn apply_range(
        &self,
        view: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        hist: &mut [f64],
        touches: super::Touches,
        dt: f64,
        update: bool,
    ) {
        let hi = lo + f.len();
        let a = self.candidates.partition_point(|&i| (i as usize) < lo);
        let b = a + self.candidates[a..].partition_point(|&i| (i as usize) < hi);
        let model = self.model;
        model.dispatch(WallPass {
            wall: self,
            cand: &self.candidates[a..b],
            view,
            lo,
            f,
            torque,
            hist,
            touches,
            dt,
            update,
        });
    }
}

/// The history values of particles 0..n (`w` each, or `hist` empty) in chunks of
/// [`CHUNK`] particles (empty slices without history).
pub(crate) fn chunk_hist(hist: &mut [f64], n: usize, w: usize) -> Vec<&mut [f64]> {
    if w > 0 && !hist.is_empty() {
        hist[..n * w].chunks_mut(CHUNK * w).collect()
    } else {
        (0..n.div_ceil(CHUNK)).map(|_| Default::default()).collect()
    }
}

struct WallPass<'a> {
    wall: &'a PrimitiveWall,
    cand: &'a [u32],
    view: &'a View<'a>,
    lo: usize,
    f: &'a mut [DVec3],
    torque: &'a mut [DVec3],
    hist: &'a mut [f64],
    touches: super::Touches<'a>,
    dt: f64,
    update: bool,
}

impl Visitor for WallPass<'_> {
    type Output = ();
    fn visit<K: ContactKernel>(self) {
        debug_assert_eq!(self.wall.bond.is_some(), K::BONDS);
        // `K::BONDS` is a constant: each kernel is compiled with or without bonds, not both.
        if K::BONDS {
            self.run::<K, true>()
        } else {
            self.run::<K, false>()
        }
    }
}

/// [`WallShape::distance`] for the force pass, compiled once rather than into each
/// kernel's pass.
#[inline(never)]
fn shape_distance(shape: &WallShape, x: DVec3) -> (f64, DVec3) {
    shape.distance(x)
}

/// The wall bond of owned particle `i` at distance and normal `dn` from the wall (bond
/// history `vecs` and `tail`): created when `create_now` and close enough, then loaded;
/// returns its force and torque on the particle, and whether it takes the place of the
/// normal contact force. Not generic over the contact law, so that it is compiled once,
/// not once per kernel.
#[allow(clippy::too_many_arguments)]
fn wall_bond(
    wall: &PrimitiveWall,
    p: &View,
    i: usize,
    (d, n): (f64, DVec3),
    vecs: &mut [f64],
    tail: &mut [f64],
    create_now: bool,
    dt: f64,
    update: bool,
) -> (DVec3, DVec3, bool) {
    let table = wall.bond.as_ref().expect("bond table");
    let c = table.get(p.ty[i], wall.wall_type);
    let mut bonded = bond::is_bonded(tail);
    if !bonded && bond::creates(c, create_now, 2.0 * d) {
        bond::create(vecs, tail, d);
        let anchor = p.x[i] - d * n;
        tail[2..5].copy_from_slice(&anchor.to_array());
        wall.bond_events.count(Event::Created);
        bonded = true;
    }
    if !bonded {
        return (DVec3::ZERO, DVec3::ZERO, false);
    }
    let mut anchor = DVec3::from_slice(&tail[2..5]);
    if update {
        anchor += wall.velocity * dt;
        tail[2..5].copy_from_slice(&anchor.to_array());
    }
    let g = BondGeom::wall(
        p.x[i] - anchor,
        p.radius[i],
        p.v[i] - wall.velocity,
        p.omega[i],
        dt,
        update,
        table.wall_reach,
    );
    let (b, e) = table.force(&g, p.ty[i], wall.wall_type, wall.model.bond, vecs, tail);
    wall.bond_events.count(e);
    let replace = e != Event::Broken && table.law().replaces_normal_contact();
    (b.f_i, b.t_i, replace)
}

impl WallPass<'_> {
    /// The pass with kernel `K`, and with `BOND` the wall bonds.
    #[inline(always)]
    fn run<K: ContactKernel, const BOND: bool>(self) {
        let WallPass {
            wall,
            cand,
            view: p,
            lo,
            f,
            torque,
            hist: hist_data,
            mut touches,
            dt,
            update,
        } = self;
        let flags = wall.model.kernel_flags();
        let mut empty: [f64; 0] = [];
        let layout = wall.bond.as_ref().filter(|_| BOND).map(|b| b.layout());
        let w = match layout {
            Some(l) => l.vec + K::HIST + l.wall_tail,
            None => K::HIST,
        };
        let create_now = update && wall.bond.as_ref().is_some_and(|b| b.creates_at(wall.step));
        // `surface multicontact`: the wall neither corrects nor records its contacts at a
        // run's set-up, as LIGGGHTS 3.8 (see rdem::multicontact).
        let mc = wall
            .multicontact
            .as_ref()
            .filter(|_| update)
            .map(|(m, w)| (&**m, m.read(), MultiContact::wall_key(*w, 0, 0)));
        for (c, &i) in cand.iter().enumerate() {
            let i = i as usize;
            let k = i - lo;
            let r = p.radius[i];
            let (d, n) = shape_distance(&wall.shape, p.x[i]);
            let hist: &mut [f64] = if w > 0 {
                &mut hist_data[c * w..(c + 1) * w]
            } else {
                &mut empty
            };
            let (hist, vecs, tail) = if let Some(l) = layout {
                let (vecs, rest) = hist.split_at_mut(l.vec);
                let (hc, tail) = rest.split_at_mut(K::HIST);
                (hc, vecs, tail)
            } else {
                (hist, &mut [][..], &mut [][..])
            };
            // An intact `bond/nonlinear` bond takes the place of the normal contact force.
            let mut replace_normal = false;
            if BOND {
                let (bf, bt, replace) =
                    wall_bond(wall, p, i, (d, n), vecs, tail, create_now, dt, update);
                replace_normal = replace;
                f[k] += bf;
                torque[k] += bt;
            }
            // Under `surface multicontact` the corrected radius decides (below); a JKR
            // neck holds apart down to δ = −δ_c.
            if d >= r && mc.is_none() {
                let c = wall.table.get(p.ty[i], wall.wall_type);
                if !(K::NECK && K::holds(r - d, r, c, hist, update)) {
                    clear_history(hist);
                    continue;
                }
            }
            let mut g = Geom::wall(
                n,
                d,
                r,
                p.mcontact[i],
                p.v[i] - wall.velocity,
                p.omega[i],
                dt,
                update,
            );
            if let Some((_, state, key)) = &mc {
                if !state.shape_wall(&mut g, (p.tag[i], p.ty[i], p.x[i]), *key) {
                    clear_history(hist);
                    continue;
                }
            }
            let c = wall.table.get(p.ty[i], wall.wall_type);
            let mut out = K::contact(&g, c, flags, hist);
            if replace_normal {
                out.f_i -= out.fn_total * g.n;
                out.fn_total = 0.0;
            }
            touches.note(k, -1.0);
            if let Some((store, _, key)) = &mc {
                store.record_wall((p.tag[i], p.x[i]), *key, n, d, out.fn_total);
            }
            f[k] += out.f_i;
            torque[k] += out.t_i;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: (f64, DVec3), b: (f64, DVec3)) {
        assert!(
            (a.0 - b.0).abs() < 1e-14,
            "distance {} against {}",
            a.0,
            b.0
        );
        assert!(
            (a.1 - b.1).length() < 1e-14,
            "normal {} against {}",
            a.1,
            b.1
        );
    }

    #[test]
    fn general_shapes_along_the_axes_are_the_plain_ones() {
        let plane = WallShape::Plane { axis: 2, pos: 0.1 };
        let general = WallShape::GeneralPlane {
            point: DVec3::new(0.3, -0.2, 0.1),
            normal: DVec3::Z,
        };
        let cyl = WallShape::Cylinder {
            axis: 2,
            radius: 0.05,
            c1: 0.01,
            c2: 0.02,
        };
        let gcyl = WallShape::GeneralCylinder {
            radius: 0.05,
            point: DVec3::new(0.01, 0.02, -0.7),
            axis: -DVec3::Z,
        };
        for x in [
            DVec3::new(0.02, 0.03, 0.13),
            DVec3::new(-0.04, 0.06, 0.05),
            DVec3::new(0.09, -0.05, 0.3),
        ] {
            close(general.distance(x), plane.distance(x));
            close(gcyl.distance(x), cyl.distance(x));
        }
    }

    #[test]
    fn a_cone_mantle_and_its_rims() {
        // A 45° frustum: radius 0.1 at z = 0 to 0.2 at z = 0.1, about the z axis.
        let cone = WallShape::GeneralCone {
            r1: 0.1,
            p1: DVec3::ZERO,
            p2: DVec3::new(0.0, 0.0, 0.1),
            r2: 0.2,
        };
        let s = std::f64::consts::FRAC_1_SQRT_2;
        // Outside the mantle, level with its foot: 0.1/√2 from it, normal outwards-down.
        close(
            cone.distance(DVec3::new(0.2, 0.0, 0.0)),
            (0.1 * s, DVec3::new(s, 0.0, -s)),
        );
        // Inside, on the other side of the axis.
        close(
            cone.distance(DVec3::new(0.0, -0.1, 0.05)),
            (0.05 * s, DVec3::new(0.0, s, s)),
        );
        // Below the foot rim: the rim circle is nearest.
        close(
            cone.distance(DVec3::new(0.1, 0.0, -0.1)),
            (0.1, DVec3::new(0.0, 0.0, -1.0)),
        );
        // Above the top rim.
        close(
            cone.distance(DVec3::new(0.0, 0.3, 0.2)),
            ((0.02f64).sqrt(), DVec3::new(0.0, s, s)),
        );
        // Equal radii: the finite cylinder, as the general cylinder along its extent.
        let tube = WallShape::GeneralCone {
            r1: 0.05,
            p1: DVec3::new(0.0, 0.0, -1.0),
            p2: DVec3::new(0.0, 0.0, 1.0),
            r2: 0.05,
        };
        let cyl = WallShape::GeneralCylinder {
            radius: 0.05,
            point: DVec3::ZERO,
            axis: DVec3::Z,
        };
        for x in [DVec3::new(0.02, 0.01, 0.3), DVec3::new(0.1, -0.07, -0.5)] {
            close(tube.distance(x), cyl.distance(x));
        }
    }
}
