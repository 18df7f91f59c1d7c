//! The multi-contact model of Brodu, Dijksman & Behringer (Phys. Rev. E 91, 032201,
//! 2015): `surface multicontact` in `pair_style gran` and `fix wall/gran`, with
//! `fix multicontact/halfspace`.
//!
//! A soft particle pressed at several points deforms at each of them because of the
//! others. At its contact `ij`, particle i's radius becomes r_i + Σ_{k≠j} δ_{ij←ik}, where
//! δ_{ij←ik} is the displacement along the contact normal that the force F_ik at contact
//! `ik` causes at contact `ij` in an elastic half space (Boussinesq):
//!
//! δ_{ij←ik} = −γ (1+ν) F_ik / (2π Y d) · [ (n_ik·u)(n_ij·u) + (3−4ν) n_ik·n_ij
//!             − (1−2ν) (n_ik+u)·n_ij / (1 + n_ik·u) ],
//!
//! with γ the `geometric_prefactor`, Y and ν particle i's Young's modulus and Poisson's
//! ratio, n the unit normals pointing into i at each contact, d the distance between the
//! two contact points and u the unit vector from contact `ik` to contact `ij`. The overlap
//! of contact `ij` grows by the corrections of both particles.
//!
//! What LIGGGHTS 3.8 does beyond its manual, measured on static and spinning three- and
//! four-particle arrangements with walls, where rdem now gives the same forces and
//! torques to 1e-12 over every step (`tests/multicontact.rs`):
//!
//! - The corrections of a step come from the contacts of the previous step: their points,
//!   normals and normal forces (elastic plus damping). A run's set-up records nothing, so
//!   the first step of the first run has no correction. The set-up of a later run
//!   corrects its pair contacts with the records of the last step (which the run's first
//!   step then reads again) and leaves its wall contacts uncorrected.
//! - A pair's effective radius R* and its contact point take the corrected radius of the
//!   pair's second particle only (LIGGGHTS' `j`, the higher tag here): R* =
//!   r_a r_b'/(r_a + r_b'), and the contact point is midway between a's undeformed surface
//!   and b's corrected one. The tangential force's lever arms are r_a − δ'/2 and
//!   r_b' − δ'/2 (δ' the corrected overlap). For a wall, R* is the corrected radius, the
//!   lever arm r' − δ'/2, and the contact point lies on the wall.
//! - When the particle has moved since the records were made, its own contact moves with
//!   it and the others stay where they were: with that, 400 steps of falling spheres
//!   follow LIGGGHTS to 1e-9 m (relative positions alone: 3e-9 m).
//! - A contact forms where the corrected radii overlap, even if the plain ones do not (a
//!   pair within the neighbor list, a particle near a primitive wall); a mesh wall still
//!   finds its contacts with the plain radius.
//!
//! Not matched: with a wall overlap of 28–42 % of the radius, in one measured arrangement,
//! LIGGGHTS' correction of a pair contact from the wall was 7–12 times smaller than the
//! formula gives, and equal to it below and above that band; rdem applies the formula.
//!
//! Known differences, measured on LIGGGHTS' `hydrogel_multicontact` tutorial (see
//! docs/parity.md):
//! - LIGGGHTS' `j` is the particle of the higher *local index*, and LIGGGHTS sorts its
//!   atoms spatially (`atom_modify sort`, every 1000 steps by default), so its `j` is not
//!   always the higher tag. With LIGGGHTS' sort off the tutorial's pair forces agree to
//!   6e-7 of the largest at the first corrected step (4e-4 with it on).
//! - A particle within a wall's reach that does not touch it drops, in LIGGGHTS, the wall
//!   contact of the next touching particle in its storage order from the next step's
//!   corrections (three spheres near an `xplane`: leaving that one record out reproduces
//!   LIGGGHTS' forces to 1e-16; listed last, the non-touching sphere changes nothing).
//!   That follows the storage order, not the physics; rdem keeps every record.
//!
//! Pairs are listed up to 2 (r_i + r_j) + skin, as LIGGGHTS does under this model. Where
//! a far pair's contact point lies beyond another contact on the same line, the
//! Boussinesq term is 0/0; the pair then does not touch, as in LIGGGHTS (whose overlap
//! test is false for NaN).
//!
//! The records carry the contact points relative to the particle's centre, so periodic
//! images of a particle see the same records. The store is filled by the force passes
//! (several threads push at once) and sorted by particle and partner before it is read,
//! so the result does not depend on the thread count. One MPI rank only: a ghost's
//! records would come from another rank.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, RwLock, RwLockReadGuard, RwLockWriteGuard};

use glam::DVec3;

use crate::contact::Geom;
use crate::particles::Tag;

/// Partner keys of walls have this bit set (pair partners are particle tags).
const WALL_BIT: u64 = 1 << 63;

/// One contact of one particle, as the last force evaluation left it.
#[derive(Debug, Clone, Copy, Default)]
struct Record {
    /// The particle's tag.
    owner: Tag,
    /// The partner: a particle's tag, or a wall key ([`MultiContact::wall_key`]).
    key: u64,
    /// Contact point minus the particle's centre.
    p: DVec3,
    /// The particle's centre.
    x: DVec3,
    /// Unit normal pointing into the particle.
    n: DVec3,
    /// Magnitude of the normal force.
    f: f64,
}

/// The contacts of every particle at the last force evaluation, and those of the current
/// one as they come (`fix multicontact/halfspace`). Shared by the pair style and the walls
/// whose model has `surface multicontact`; each force pass reads [`MultiContact::read`]
/// once and pushes its contacts with [`MultiContact::record_pair`] and
/// [`MultiContact::record_wall`].
#[derive(Debug, Default)]
pub struct MultiContact {
    /// What the passes read.
    state: RwLock<State>,
    /// The current evaluation's records, unordered.
    next: Mutex<Vec<Record>>,
    /// Walls registered so far.
    walls: AtomicU64,
}

/// The prefactor, the elastic constants and the last evaluation's records.
#[derive(Debug, Default)]
pub struct State {
    /// The geometric prefactor γ.
    pub gamma: f64,
    /// Young's modulus per type (index type − 1).
    youngs: Vec<f64>,
    /// Poisson's ratio per type.
    poisson: Vec<f64>,
    /// Last evaluation's records, sorted by (owner, key).
    last: Vec<Record>,
    /// Where each tag's records start in `last` (indexed by tag; one past the largest
    /// tag holds the end).
    first: Vec<u32>,
    /// Scratch of [`MultiContact::advance`] (kept: no allocation per step).
    at: Vec<u32>,
    /// Per tag, what [`State::correction_bound`] needs of its records.
    summary: Vec<Summary>,
}

/// A particle's records at a glance: the sum of their normal forces, the largest distance
/// of a contact point from the centre, and the centre they were made at (`None` when
/// they were not all made at one centre, e.g. across a periodic boundary).
#[derive(Debug, Clone, Copy, Default)]
struct Summary {
    fsum: f64,
    reach: f64,
    x: Option<DVec3>,
}

/// The geometry and force of a pair contact under the model, seen from the pair's first
/// particle `a` (the lower tag).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairShape {
    /// Corrected overlap.
    pub delta: f64,
    /// Effective radius.
    pub r_star: f64,
    /// Contact point minus a's centre.
    pub p_a: DVec3,
    /// The lever arms of a and b for the tangential force: r_a and r_b' (b's radius
    /// corrected, as for R*), each less half the corrected overlap.
    pub levers: (f64, f64),
}

impl MultiContact {
    /// A store with prefactor `gamma`.
    pub fn new(gamma: f64) -> Self {
        let m = Self::default();
        m.write().gamma = gamma;
        m
    }

    /// What a force pass reads (held for the pass).
    pub fn read(&self) -> RwLockReadGuard<'_, State> {
        self.state.read().unwrap_or_else(|e| e.into_inner())
    }

    fn write(&self) -> RwLockWriteGuard<'_, State> {
        self.state.write().unwrap_or_else(|e| e.into_inner())
    }

    /// Takes the particle types' elastic constants (before a run).
    pub fn set_materials(&self, youngs: &[f64], poisson: &[f64]) {
        let mut s = self.write();
        s.youngs = youngs.to_vec();
        s.poisson = poisson.to_vec();
    }

    /// A new wall's number, for [`MultiContact::wall_key`].
    pub fn register_wall(&self) -> u64 {
        self.walls.fetch_add(1, Ordering::Relaxed) + 1
    }

    /// The partner key of triangle `tri` of mesh `mesh` of wall `wall` (0, 0 for a
    /// primitive wall).
    pub fn wall_key(wall: u64, mesh: u32, tri: u32) -> u64 {
        WALL_BIT | (wall << 44) | (u64::from(mesh) << 32) | u64::from(tri)
    }

    /// Makes the records of the evaluation that just ended the ones the next evaluation
    /// reads (call once per step, before its forces; not at a run's set-up).
    pub fn advance(&self) {
        self.take_latest(false);
    }

    /// At a run's set-up: the pair contacts read the records of the last step's
    /// evaluation, which stay the ones the run's first step reads (the set-up records
    /// nothing).
    pub fn peek_latest(&self) {
        self.take_latest(true);
    }

    /// Sorts the records of the evaluation that just ended into the read state; `keep`
    /// leaves them to be taken again.
    fn take_latest(&self, keep: bool) {
        let mut next = self.next.lock().unwrap_or_else(|e| e.into_inner());
        let mut guard = self.write();
        let s = &mut *guard;
        // A counting sort by owner tag (records of one owner stay together), then each
        // owner's few records by partner key: the order does not depend on which thread
        // pushed first.
        let ntag = next.iter().map(|r| r.owner as usize + 1).max().unwrap_or(0);
        s.first.clear();
        s.first.resize(ntag + 1, 0);
        for r in next.iter() {
            s.first[r.owner as usize + 1] += 1;
        }
        for t in 1..s.first.len() {
            s.first[t] += s.first[t - 1];
        }
        s.last.clear();
        s.last.resize(next.len(), Record::default());
        s.at.clone_from(&s.first);
        for r in next.iter() {
            let k = &mut s.at[r.owner as usize];
            s.last[*k as usize] = *r;
            *k += 1;
        }
        if !keep {
            next.clear();
        }
        s.summary.clear();
        s.summary.resize(ntag, Summary::default());
        for t in 0..ntag {
            let (a, b) = (s.first[t] as usize, s.first[t + 1] as usize);
            if b - a > 1 {
                s.last[a..b].sort_unstable_by_key(|r| r.key);
            }
            let recs = &s.last[a..b];
            let x = recs.first().map(|r| r.x);
            s.summary[t] = Summary {
                fsum: recs.iter().map(|r| r.f).sum(),
                reach: recs
                    .iter()
                    .filter(|r| r.f != 0.0)
                    .map(|r| r.p.length())
                    .fold(0.0, f64::max),
                x: x.filter(|&x| recs.iter().all(|r| r.x == x)),
            };
        }
    }

    /// Records a pair contact that [`State::pair`] shaped, with normal force `f`.
    pub fn record_pair(
        &self,
        (tag_a, xa): (Tag, DVec3),
        (tag_b, xb): (Tag, DVec3),
        dist: f64,
        s: &PairShape,
        f: f64,
    ) {
        let d = xb - xa;
        let n_ab = d / dist;
        let mut next = self.next.lock().unwrap_or_else(|e| e.into_inner());
        next.push(Record {
            owner: tag_a,
            key: tag_b,
            p: s.p_a,
            x: xa,
            n: -n_ab,
            f: f.abs(),
        });
        next.push(Record {
            owner: tag_b,
            key: tag_a,
            p: s.p_a - d,
            x: xb,
            n: n_ab,
            f: f.abs(),
        });
    }

    /// Records a wall contact (as [`State::wall_radius`]) with normal force `f`.
    pub fn record_wall(&self, (tag, x): (Tag, DVec3), key: u64, n: DVec3, dist: f64, f: f64) {
        self.next
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(Record {
                owner: tag,
                key,
                p: -dist * n,
                x,
                n,
                f: f.abs(),
            });
    }
}

/// How far a particle (centre `x`, radius `r`) moved since a record made at centre
/// `then`. A record made on a periodic image is farther than a step's motion: it counts as
/// not moved.
fn moved_since(x: DVec3, then: DVec3, r: f64) -> DVec3 {
    let moved = x - then;
    if moved.length_squared() < r * r {
        moved
    } else {
        DVec3::ZERO
    }
}

impl State {
    /// The records of particle `owner`.
    fn of(&self, owner: Tag) -> &[Record] {
        let t = owner as usize;
        if t + 1 >= self.first.len() {
            return &[];
        }
        &self.last[self.first[t] as usize..self.first[t + 1] as usize]
    }

    /// The change of radius of particle `owner` (type `ty`, centre `x`, radius `r`) at its
    /// contact with `key`, caused by its other contacts of the last evaluation. The
    /// contact's own point and inward normal are taken from that evaluation too, moved
    /// with the particle since; a contact that is new uses `p` (relative to the centre)
    /// and `n` as they are now.
    pub fn correction(
        &self,
        (owner, ty, x, r): (Tag, u32, DVec3, f64),
        key: u64,
        p: DVec3,
        n: DVec3,
    ) -> f64 {
        let recs = self.of(owner);
        if recs.is_empty() {
            return 0.0;
        }
        let (p, n) = recs
            .iter()
            .find(|rec| rec.key == key)
            .map_or((p, n), |rec| (rec.p, rec.n));
        let t = ty as usize - 1;
        let (y, nu) = (self.youngs[t], self.poisson[t]);
        let mut sum = 0.0;
        for rec in recs {
            if rec.key == key || rec.f == 0.0 {
                continue;
            }
            // The other contact stays where it was; this one moves with the particle.
            let u = p + moved_since(x, rec.x, r) - rec.p;
            let d = u.length();
            if d == 0.0 {
                continue;
            }
            let u = u / d;
            let nu_k = rec.n.dot(u);
            let bracket = nu_k * n.dot(u) + (3.0 - 4.0 * nu) * rec.n.dot(n)
                - (1.0 - 2.0 * nu) * (rec.n + u).dot(n) / (1.0 + nu_k);
            sum -= rec.f * bracket / d;
        }
        sum * self.gamma * (1.0 + nu) / (2.0 * std::f64::consts::PI * y)
    }

    /// An upper bound of |[`State::correction`]| for a contact without a record of its
    /// own, cheap enough to skip pairs far apart (one square root per particle): with
    /// ν = 1/2 the Boussinesq bracket is at most 1 + |3 − 4ν| in magnitude (its last term
    /// vanishes), the forces sum to the particle's total, and every distance from the
    /// contact point is at least its distance from the centre (moved by
    /// [`moved_since`]) less the farthest recorded point. Twice that, against rounding.
    /// Infinite (no bound) for ν ≠ 1/2, for records made at several centres, or when
    /// the contact has a record, whose point the correction would use instead of `p`.
    fn correction_bound(
        &self,
        (owner, ty, x, r): (Tag, u32, DVec3, f64),
        key: u64,
        p: DVec3,
    ) -> f64 {
        let recs = self.of(owner);
        if recs.is_empty() {
            return 0.0;
        }
        let sum = self.summary[owner as usize];
        if sum.fsum == 0.0 {
            return 0.0;
        }
        let t = ty as usize - 1;
        let (y, nu) = (self.youngs[t], self.poisson[t]);
        let Some(x0) = sum.x else {
            return f64::INFINITY;
        };
        if 1.0 - 2.0 * nu != 0.0 || recs.iter().any(|rec| rec.key == key) {
            return f64::INFINITY;
        }
        let d = (p + moved_since(x, x0, r)).length() - sum.reach;
        if d <= 0.0 {
            return f64::INFINITY;
        }
        let k = (self.gamma * (1.0 + nu) / (2.0 * std::f64::consts::PI * y)).abs();
        2.0 * k * (1.0 + (3.0 - 4.0 * nu).abs()) * sum.fsum / d
    }

    /// The pair contact of `a` and `b` (a's tag lower; tag, type, centre, radius each),
    /// `dist` apart, under the model: the corrected overlap, R*, contact point and lever
    /// arms. `None` when the corrected overlap is not positive, or not a number (a far
    /// pair in line with another contact).
    pub fn pair(
        &self,
        (tag_a, ty_a, xa, r_a): (Tag, u32, DVec3, f64),
        (tag_b, ty_b, xb, r_b): (Tag, u32, DVec3, f64),
        dist: f64,
    ) -> Option<PairShape> {
        let d = xb - xa;
        let n_ab = d / dist;
        let delta = r_a + r_b - dist;
        // The plain contact point, for a contact without a record.
        let p_a = (r_a - 0.5 * delta) * n_ab;
        // A pair apart (the lists reach twice the contact distance) that the corrections
        // cannot close: skipped without computing them (the same outcome, far cheaper).
        if delta < 0.0
            && delta
                + self.correction_bound((tag_a, ty_a, xa, r_a), tag_b, p_a)
                + self.correction_bound((tag_b, ty_b, xb, r_b), tag_a, p_a - d)
                <= 0.0
        {
            return None;
        }
        let c_a = self.correction((tag_a, ty_a, xa, r_a), tag_b, p_a, -n_ab);
        let c_b = self.correction((tag_b, ty_b, xb, r_b), tag_a, p_a - d, n_ab);
        let delta = delta + c_a + c_b;
        // NaN (a far pair in line with another contact) forms no contact either.
        if delta.is_nan() || delta <= 0.0 {
            return None;
        }
        let rb = r_b + c_b;
        Some(PairShape {
            delta,
            r_star: r_a * rb / (r_a + rb),
            p_a: (r_a - 0.5 * (r_a + rb - dist)) * n_ab,
            levers: (r_a - 0.5 * delta, rb - 0.5 * delta),
        })
    }

    /// Shapes the wall contact `g` (made by [`Geom::wall`] for the particle's tag, type
    /// and centre) against wall `key` under the model: the corrected radius r' gives the
    /// overlap r' − dist, R* = r' and the lever arm r' − δ'/2, as LIGGGHTS 3.8. False
    /// when r' no longer reaches the wall.
    pub fn shape_wall(&self, g: &mut Geom, (tag, ty, x): (Tag, u32, DVec3), key: u64) -> bool {
        let r = g.ri + self.correction((tag, ty, x, g.ri), key, -g.dist * g.n, g.n);
        if r.is_nan() || r <= g.dist {
            return false;
        }
        g.delta = r - g.dist;
        g.r_star = r;
        g.ci = r - 0.5 * g.delta;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A store with one type (Y, ν) and prefactor γ = 1.
    fn store(y: f64, nu: f64) -> MultiContact {
        let m = MultiContact::new(1.0);
        m.set_materials(&[y], &[nu]);
        m
    }

    #[test]
    fn a_force_on_the_same_plane_gives_boussinesq() {
        // Two contacts on a flat face (both normals +z into the body), 2 mm apart: the
        // surface sinks by F (1 − ν²)/(π Y d) (Johnson, Contact Mechanics, eq. 3.22b).
        let (y, nu, f, d) = (1e6, 0.3, 2.0, 0.002);
        let m = store(y, nu);
        m.record_wall((1, DVec3::ZERO), 10, DVec3::Z, 0.0, f);
        m.advance();
        let c = m.read().correction(
            (1, 1, DVec3::ZERO, 1.0),
            20,
            DVec3::new(d, 0.0, 0.0),
            DVec3::Z,
        );
        let expect = -f * (1.0 - nu * nu) / (std::f64::consts::PI * y * d);
        assert!((c / expect - 1.0).abs() < 1e-14, "{c} vs {expect}");
        // The contact's own record does not act on itself, and other particles' records
        // do not count.
        assert_eq!(
            m.read()
                .correction((1, 1, DVec3::ZERO, 1.0), 10, DVec3::ZERO, DVec3::Z),
            0.0
        );
        assert_eq!(
            m.read().correction(
                (2, 1, DVec3::ZERO, 1.0),
                20,
                DVec3::new(d, 0.0, 0.0),
                DVec3::Z
            ),
            0.0
        );
    }

    #[test]
    fn the_bound_holds_for_points_outside_the_sphere() {
        // Random contacts on a unit sphere (ν = ½), each probed from points beyond the
        // surface in random directions: |correction| never exceeds half the bound (the
        // bound carries a factor 2 against rounding), and the bound is finite there.
        fn rnd(seed: &mut u64) -> f64 {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            (*seed >> 11) as f64 / (1u64 << 53) as f64
        }
        fn unit(seed: &mut u64) -> DVec3 {
            let v = DVec3::new(rnd(seed) - 0.5, rnd(seed) - 0.5, rnd(seed) - 0.5);
            if v.length() > 1e-3 {
                v.normalize()
            } else {
                DVec3::X
            }
        }
        let seed = &mut 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200 {
            let m = store(1e4, 0.5);
            let k = 1 + (rnd(seed) * 6.0) as u64;
            for key in 0..k {
                let n = unit(seed);
                m.record_wall(
                    (1, DVec3::ZERO),
                    key,
                    n,
                    0.9 + 0.1 * rnd(seed),
                    0.1 + rnd(seed),
                );
            }
            m.advance();
            let s = m.read();
            for _ in 0..50 {
                let dir = unit(seed);
                let p = dir * (1.05 + 2.0 * rnd(seed));
                let c = s.correction((1, 1, DVec3::ZERO, 1.0), 99, p, -dir);
                let b = s.correction_bound((1, 1, DVec3::ZERO, 1.0), 99, p);
                assert!(b.is_finite() && c.abs() <= 0.5 * b, "{c} vs bound {b}");
            }
            // A contact with its own record, or ν ≠ ½: no bound.
            let p = 1.5 * DVec3::X;
            assert_eq!(
                s.correction_bound((1, 1, DVec3::ZERO, 1.0), 0, p),
                f64::INFINITY
            );
        }
        let m = store(1e4, 0.3);
        m.record_wall((1, DVec3::ZERO), 1, DVec3::Z, 1.0, 1.0);
        m.advance();
        let b = m
            .read()
            .correction_bound((1, 1, DVec3::ZERO, 1.0), 2, 2.0 * DVec3::X);
        assert_eq!(b, f64::INFINITY);
    }

    #[test]
    fn a_squeezed_sphere_bulges_at_its_equator() {
        // ν = ½: a sphere pressed at its top pushes its side contact outwards (radius
        // grows, correction > 0), and its bottom contact outwards too (the half-space
        // solution straight below the load).
        let m = store(1e5, 0.5);
        let r = 0.01;
        m.record_wall((1, DVec3::ZERO), 1, -DVec3::Z, r, 1.0);
        m.advance();
        let side = m.read().correction(
            (1, 1, DVec3::ZERO, 1.0),
            2,
            DVec3::new(r, 0.0, 0.0),
            -DVec3::X,
        );
        assert!(side > 0.0);
        // Bracket (n_k·u)(n_j·u) = (1/√2)(−1/√2) = −½, d = √2 r.
        let expect = 1.5 / (2.0 * std::f64::consts::PI * 1e5 * 2f64.sqrt() * r) * 0.5;
        assert!((side / expect - 1.0).abs() < 1e-14);
        let bottom = m.read().correction(
            (1, 1, DVec3::ZERO, 1.0),
            3,
            DVec3::new(0.0, 0.0, -r),
            DVec3::Z,
        );
        // Bracket −1 − (3 − 4ν) + (1 − 2ν) = −2 at ν = ½, d = 2r.
        let expect = 1.5 / (2.0 * std::f64::consts::PI * 1e5 * 2.0 * r) * 2.0;
        assert!((bottom / expect - 1.0).abs() < 1e-14);
    }

    #[test]
    fn records_are_read_in_one_order_whatever_the_push_order() {
        let a = store(1e5, 0.3);
        let b = store(1e5, 0.3);
        let recs = [(1u64, 5u64, 0.3), (1, 2, 0.7), (1, 9, 1.1), (2, 1, 0.7)];
        for (k, &(o, key, f)) in recs.iter().enumerate() {
            let n = DVec3::new(k as f64, 1.0, 0.5).normalize();
            a.record_wall((o, DVec3::ZERO), key, n, 0.01, f);
        }
        for (k, &(o, key, f)) in recs.iter().enumerate().rev() {
            let n = DVec3::new(k as f64, 1.0, 0.5).normalize();
            b.record_wall((o, DVec3::ZERO), key, n, 0.01, f);
        }
        a.advance();
        b.advance();
        let p = DVec3::new(0.0, 0.0, -0.01);
        let ca = a
            .read()
            .correction((1, 1, DVec3::ZERO, 1.0), 77, p, DVec3::Z);
        let cb = b
            .read()
            .correction((1, 1, DVec3::ZERO, 1.0), 77, p, DVec3::Z);
        assert_eq!(ca.to_bits(), cb.to_bits());
        assert_ne!(ca, 0.0);
    }
}
