//! Fixes: per-step operations on a group, each declaring the stages it acts in. A fix is a
//! typed value built once from its command; the step calls it only in its stages.

pub mod integrate;
pub mod motion;

use glam::DVec3;

use rayon::prelude::*;

use crate::error::{check, Error, Result};
use crate::par::{all_finite, parallel, View, CHUNK};
use crate::particles::Particles;
use crate::wall::primitive::chunk_hist;
use crate::wall::{PrimitiveWall, TOUCH_WIDTH};

/// What a fix does.
#[derive(Debug, Clone)]
pub enum FixKind {
    /// `fix nve/sphere`: velocity Verlet for translation and rotation.
    NveSphere,
    /// `fix nve/limit`: velocity Verlet for translation with a speed cap.
    NveLimit(integrate::NveLimit),
    /// `fix nve/noforce`: positions advance with the velocities; forces are ignored and
    /// velocities (and spins) are not updated.
    NveNoforce,
    /// `fix gravity g vector x y z`: force m·g along the unit vector.
    Gravity {
        /// Acceleration vector (magnitude × unit direction).
        accel: DVec3,
    },
    /// `fix freeze`: zero force and torque.
    Freeze,
    /// `fix viscous gamma`: F −= γ v.
    Viscous {
        /// Damping coefficient (force/velocity).
        gamma: f64,
    },
    /// `fix viscous gamma scale type ratio ...`: F −= γ_t v with γ per atom type.
    ViscousScaled {
        /// γ of each type, indexed by type (entry 0 unused).
        gamma: Vec<f64>,
    },
    /// `fix aveforce fx fy fz`: every particle of the group gets the group's mean force
    /// plus the given component (NULL components, `None`, are left alone).
    AveForce {
        /// Components added to the mean force.
        force: [Option<f64>; 3],
        /// The group's total force before the fix acted, at the last force evaluation
        /// (summed over ranks): the fix's global vector `f_ID[1..3]`.
        total: DVec3,
    },
    /// `fix addforce fx fy fz`: adds a constant force.
    AddForce {
        /// Force added to every particle of the group.
        force: DVec3,
    },
    /// `fix setforce fx fy fz` (NULL components are `None` and left alone).
    SetForce {
        /// Components to impose.
        force: [Option<f64>; 3],
    },
    /// `fix enforce2d`: zero z velocity and force, x and y angular velocity and torque
    /// (LAMMPS' `post_force`, in definition order with the other post-force fixes).
    Enforce2d,
    /// `fix move`: a prescribed motion instead of integration.
    Move(Box<motion::Move>),
    /// `fix wall/gran ... primitive ...`.
    WallGran(Box<PrimitiveWall>),
    /// `fix wall/gran ... mesh n_meshes k meshes ...`.
    MeshWall(Box<crate::wall::MeshWall>),
    /// The SPH fixes: density, Shepard filter, pressure, integration ([`crate::sph`]).
    Sph(crate::sph::SphFix),
    /// `fix wall/sph` (post-force).
    WallSph(crate::sph::SphWall),
    /// `fix wall/region/sph` (post-force, acting alone between the post-force passes:
    /// it reads the SPH pressure).
    WallRegionSph(crate::sph::SphRegionWall),
    /// A post-force fix that a front end defines ([`ForceFix`]; e.g. `fix speedcontrol`).
    Force(Box<dyn ForceFix>),
}

/// A post-force fix defined outside the engine: step 9 of [`crate::step`] calls it in
/// definition order with the built-in post-force fixes, on chunks of the owned particles
/// in parallel. A front end adds a force fix as one type that implements this trait,
/// without an engine edit; it changes the fix's parameters between steps through
/// [`ForceFix::as_any_mut`] (e.g. variables evaluated before each step).
pub trait ForceFix: std::fmt::Debug + Send + Sync {
    /// Acts on the particles `lo..lo + f.len()` that are in the group `groupbit`: `p` is
    /// indexed by particle, `f` and `torque` start at particle `lo`; `dt` is the
    /// timestep. Each particle is treated alone (no sum over particles), so that the
    /// result does not depend on the thread count.
    fn apply(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        groupbit: u32,
        dt: f64,
    );

    /// A boxed copy (fixes are cloned with the world).
    fn clone_box(&self) -> Box<dyn ForceFix>;

    /// The fix as `Any`, for the front end to update its parameters.
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any;
}

impl Clone for Box<dyn ForceFix> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// A fix: an ID, a group (bit mask) and what it does.
#[derive(Debug, Clone)]
pub struct Fix {
    /// Fix ID.
    pub id: String,
    /// Group bit mask.
    pub groupbit: u32,
    /// Behaviour.
    pub kind: FixKind,
    /// Seconds spent in this fix since the run started, counted only while
    /// [`crate::World::fix_timing`] is on (`modify_timing`).
    pub seconds: f64,
}

impl Fix {
    /// A fix with validation of its parameters.
    pub fn new(id: &str, groupbit: u32, kind: FixKind) -> Result<Self> {
        match &kind {
            FixKind::Gravity { accel } => {
                if !accel.is_finite() {
                    return Err(Error::Invalid {
                        what: "gravity",
                        reason: format!("{accel} is not finite"),
                    });
                }
            }
            FixKind::Viscous { gamma } => {
                check("viscous gamma", *gamma, *gamma >= 0.0, "must be >= 0")?;
            }
            FixKind::ViscousScaled { gamma } => {
                for g in gamma {
                    check("viscous gamma", *g, *g >= 0.0, "must be >= 0")?;
                }
            }
            FixKind::AveForce { force, .. } => {
                if force.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(Error::Invalid {
                        what: "aveforce",
                        reason: "components must be finite or NULL".into(),
                    });
                }
            }
            FixKind::AddForce { force } => {
                if !force.is_finite() {
                    return Err(Error::Invalid {
                        what: "addforce",
                        reason: format!("{force} is not finite"),
                    });
                }
            }
            FixKind::SetForce { force } => {
                if force.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(Error::Invalid {
                        what: "setforce",
                        reason: "components must be finite or NULL".into(),
                    });
                }
            }
            FixKind::Move(m) => check_motion(&m.style)?,
            FixKind::Sph(crate::sph::SphFix::Shepard { every, .. }) => {
                if *every == 0 {
                    return Err(Error::Invalid {
                        what: "sph/density/corr every",
                        reason: "must be > 0".into(),
                    });
                }
            }
            FixKind::WallSph(w) => {
                check("wall/sph r0", w.r0, w.r0 > 0.0, "must be > 0")?;
                check("wall/sph D", w.d, true, "must be finite")?;
                for v in w.planes.iter().flatten() {
                    check("wall/sph plane", *v, true, "must be finite")?;
                }
            }
            FixKind::WallRegionSph(w) => {
                check("wall/region/sph r0", w.r0, w.r0 > 0.0, "must be > 0")?;
                check("wall/region/sph D", w.d, true, "must be finite")?;
            }
            FixKind::NveLimit(l) => {
                check("nve/limit xmax", l.xmax, l.xmax > 0.0, "must be > 0")?;
            }
            FixKind::NveSphere
            | FixKind::NveNoforce
            | FixKind::Freeze
            | FixKind::Enforce2d
            | FixKind::Sph(_)
            | FixKind::WallGran(_)
            | FixKind::MeshWall(_)
            | FixKind::Force(_) => {}
        }
        Ok(Self {
            id: id.to_string(),
            groupbit,
            kind,
            seconds: 0.0,
        })
    }

    /// `fix ID group gravity magnitude vector x y z`.
    pub fn gravity(id: &str, groupbit: u32, magnitude: f64, dir: DVec3) -> Result<Self> {
        check("gravity magnitude", magnitude, true, "must be finite")?;
        let accel = gravity_accel(magnitude, dir).ok_or_else(|| Error::Invalid {
            what: "gravity direction",
            reason: format!("{dir} has no direction"),
        })?;
        Self::new(id, groupbit, FixKind::Gravity { accel })
    }

    /// The per-particle post-force action on the owned particles (`dt`: the timestep).
    pub fn apply_post_force(&self, p: &mut Particles, dt: f64) {
        let n = p.nlocal();
        let (view, f, torque, _, _) = View::split(p);
        self.post_force_range(&view, 0, &mut f[..n], &mut torque[..n], dt);
    }

    /// [`Fix::apply_post_force`] on the particles `lo..lo + f.len()`; `f` and `torque`
    /// start at particle `lo`. This match is the one place that says which fixes act
    /// per particle after the forces; the walls have their own pass
    /// ([`post_force_pass`]), and the fixes that act alone between the passes are listed
    /// in [`acts_alone`].
    fn post_force_range(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        dt: f64,
    ) {
        let n = f.len();
        let bit = self.groupbit;
        let mask = &p.mask[lo..lo + n];
        match &self.kind {
            FixKind::Gravity { accel } => {
                let rmass = &p.rmass[lo..lo + n];
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] += rmass[k] * *accel;
                    }
                }
            }
            FixKind::Freeze => {
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] = DVec3::ZERO;
                        torque[k] = DVec3::ZERO;
                    }
                }
            }
            FixKind::Viscous { gamma } => {
                let v = &p.v[lo..lo + n];
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] -= *gamma * v[k];
                    }
                }
            }
            FixKind::ViscousScaled { gamma } => {
                let v = &p.v[lo..lo + n];
                let ty = &p.ty[lo..lo + n];
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] -= gamma.get(ty[k] as usize).copied().unwrap_or(0.0) * v[k];
                    }
                }
            }
            FixKind::AddForce { force } => {
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] += *force;
                    }
                }
            }
            FixKind::SetForce { force } => {
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        for (a, value) in force.iter().enumerate() {
                            if let Some(v) = value {
                                f[k][a] = *v;
                            }
                        }
                    }
                }
            }
            FixKind::WallSph(wall) => {
                let x = &p.x[lo..lo + n];
                for k in 0..n {
                    if mask[k] & bit != 0 {
                        f[k] += wall.force(x[k]);
                    }
                }
            }
            FixKind::Force(fix) => fix.apply(p, lo, f, torque, bit, dt),
            FixKind::NveSphere
            | FixKind::NveLimit(_)
            | FixKind::NveNoforce
            | FixKind::AveForce { .. }
            | FixKind::Enforce2d
            | FixKind::Move(_)
            | FixKind::Sph(_)
            | FixKind::WallRegionSph(_)
            | FixKind::WallGran(_)
            | FixKind::MeshWall(_) => {}
        }
    }
}

/// The acceleration of `fix gravity`: `magnitude` along `dir`, computed as (g d) / |d|
/// (the one place gravity is normalised); `None` when `dir` has no direction (zero,
/// NaN or infinite).
pub fn gravity_accel(magnitude: f64, dir: DVec3) -> Option<DVec3> {
    let len = dir.length();
    if len.is_nan() || len <= 0.0 || !dir.is_finite() {
        return None;
    }
    Some(magnitude * dir / len)
}

/// Checks the numbers of a `fix move` motion: finite, a rotation axis of unit length.
fn check_motion(style: &motion::MoveStyle) -> Result<()> {
    use motion::MoveStyle as S;
    let bad = |reason: String| Error::Invalid {
        what: "fix move",
        reason,
    };
    match style {
        S::Linear { v } => {
            if v.iter().flatten().any(|c| !c.is_finite()) {
                return Err(bad("velocity components must be finite or NULL".into()));
            }
        }
        S::Wiggle { amplitude, omega } => {
            if amplitude.iter().flatten().any(|c| !c.is_finite()) || !omega.is_finite() {
                return Err(bad("amplitudes and period must be finite".into()));
            }
        }
        S::Rotate { point, axis, omega } => {
            if !point.is_finite() || !omega.is_finite() || (axis.length() - 1.0).abs() > 1e-12 {
                return Err(bad("needs a finite point and period and a unit axis".into()));
            }
        }
        S::Variable { .. } => {}
    }
    Ok(())
}

/// The settings of a post-force stage ([`post_force`]).
#[derive(Clone, Copy)]
pub(crate) struct PostForce {
    /// The timestep.
    pub dt: f64,
    /// False at a run's set-up (contact histories not advanced).
    pub update: bool,
    /// The step.
    pub step: u64,
    /// `modify_timing`: each fix acts alone and is timed.
    pub timing: bool,
}

/// Step 9 of [`crate::step`]: the post-force fixes, walls included, in definition order on
/// the owned particles; returns false when some force or torque is then not finite (the
/// caller finds which). Every fix acts on each particle alone, so the pass runs all fixes
/// chunk by chunk in parallel (see [`crate::par`]): each particle sees the fixes in the
/// same order whatever the thread count.
///
/// A `fix enforce2d` changes velocities as well as forces: it acts alone between the
/// passes, in the same way.
///
/// A `fix aveforce` needs the group's total force after the fixes before it, summed over
/// ranks: the fixes between two aveforce fixes run as one pass, and each aveforce acts
/// alone between the passes (in particle order, so its sum does not depend on the thread
/// count).
pub(crate) fn post_force(
    fixes: &mut [Fix],
    meshes: &[crate::wall::MeshSurface],
    p: &mut Particles,
    comm: &dyn crate::comm::Comm,
    pass: PostForce,
) -> bool {
    let PostForce {
        dt,
        update,
        step,
        timing,
    } = pass;
    let at = |start: usize| At { start, step };
    if timing {
        // One fix at a time, each timed: the same operations per particle in the same
        // order as the fused passes, so the same forces.
        let mut ok = true;
        for k in 0..fixes.len() {
            let t0 = std::time::Instant::now();
            if acts_alone(&fixes[k].kind) {
                fixes[k].act_alone(p, comm);
            } else if fixes[k].kind.acts_after_forces() {
                ok &= post_force_pass(&fixes[k..k + 1], at(k), meshes, p, dt, update);
            }
            fixes[k].seconds += t0.elapsed().as_secs_f64();
        }
        return ok
            & post_force_pass(
                &fixes[fixes.len()..],
                at(fixes.len()),
                meshes,
                p,
                dt,
                update,
            );
    }
    let mut start = 0;
    let mut ok = true;
    for k in 0..fixes.len() {
        if acts_alone(&fixes[k].kind) {
            if start < k {
                ok &= post_force_pass(&fixes[start..k], at(start), meshes, p, dt, update);
            }
            fixes[k].act_alone(p, comm);
            start = k + 1;
        }
    }
    // The last pass runs also without fixes: it checks that every force is finite.
    ok & post_force_pass(&fixes[start..], at(start), meshes, p, dt, update)
}

impl FixKind {
    /// True for the fixes [`post_force_pass`] acts with: the per-particle post-force
    /// fixes and the walls.
    fn acts_after_forces(&self) -> bool {
        !matches!(
            self,
            FixKind::NveSphere
                | FixKind::NveLimit(_)
                | FixKind::NveNoforce
                | FixKind::Move(_)
                | FixKind::Sph(_)
                | FixKind::AveForce { .. }
                | FixKind::Enforce2d
                | FixKind::WallRegionSph(_)
        )
    }
}

/// The post-force fixes that act alone between the parallel passes: `aveforce` (a sum over
/// the group), `enforce2d` (it changes velocities) and `wall/region/sph`.
fn acts_alone(kind: &FixKind) -> bool {
    matches!(
        kind,
        FixKind::AveForce { .. } | FixKind::Enforce2d | FixKind::WallRegionSph(_)
    )
}

impl Fix {
    /// A fix that [`acts_alone`] between the post-force passes.
    fn act_alone(&mut self, p: &mut Particles, comm: &dyn crate::comm::Comm) {
        match &self.kind {
            FixKind::WallRegionSph(w) => w.apply(p, self.groupbit),
            FixKind::Enforce2d => self.apply_enforce2d(p),
            _ => self.apply_aveforce(p, comm),
        }
    }

    /// `fix enforce2d`: the group's owned particles lose their z velocity and force and
    /// their x and y angular velocity and torque, so that they stay in their plane.
    fn apply_enforce2d(&self, p: &mut Particles) {
        let bit = self.groupbit;
        for i in 0..p.nlocal() {
            if p.mask[i] & bit != 0 {
                p.v[i].z = 0.0;
                p.f[i].z = 0.0;
                p.omega[i].x = 0.0;
                p.omega[i].y = 0.0;
                p.torque[i].x = 0.0;
                p.torque[i].y = 0.0;
            }
        }
    }

    /// `fix aveforce`: the group's total force (summed over ranks) is recorded, and each
    /// particle of the group gets the mean force plus the fix's components (NULL
    /// components untouched); an empty group changes nothing.
    fn apply_aveforce(&mut self, p: &mut Particles, comm: &dyn crate::comm::Comm) {
        let FixKind::AveForce { force, total } = &mut self.kind else {
            return;
        };
        let n = p.nlocal();
        let bit = self.groupbit;
        let mut sum = [0.0; 4];
        for i in 0..n {
            if p.mask[i] & bit != 0 {
                sum[0] += p.f[i].x;
                sum[1] += p.f[i].y;
                sum[2] += p.f[i].z;
                sum[3] += 1.0;
            }
        }
        comm.sum_slice(&mut sum);
        *total = DVec3::new(sum[0], sum[1], sum[2]);
        if sum[3] == 0.0 {
            return;
        }
        let mean = *total / sum[3];
        for i in 0..n {
            if p.mask[i] & bit != 0 {
                for (a, value) in force.iter().enumerate() {
                    if let Some(v) = value {
                        p.f[i][a] = mean[a] + v;
                    }
                }
            }
        }
    }
}

/// The first `n` particles' values of a taken-out property (`id`: its ID and width), or
/// an empty slice for none.
fn cut<'a>(v: &'a mut [f64], id: &Option<(usize, usize)>, n: usize) -> &'a mut [f64] {
    match id {
        Some((_, w)) => &mut v[..n * w],
        None => Default::default(),
    }
}

/// Where a pass of [`post_force_pass`] is: the index of its first fix in the world's
/// fixes, and the step (for the walls' last-touch records, [`crate::wall::touch`]).
#[derive(Clone, Copy)]
struct At {
    start: usize,
    step: u64,
}

/// The post-force fixes `fixes` (none of them `aveforce`) in one pass over the owned
/// particles; false when some force or torque is then not finite.
fn post_force_pass(
    fixes: &[Fix],
    at: At,
    meshes: &[crate::wall::MeshSurface],
    p: &mut Particles,
    dt: f64,
    update: bool,
) -> bool {
    let n = p.nlocal();
    // The walls' history (sparse property ID, width, the particles holding its rows)
    // and `store_force` property (ID, width), taken out of the particles meanwhile.
    #[allow(clippy::type_complexity)]
    let taken: Vec<(Option<(usize, usize, &[u32])>, Option<(usize, usize)>)> = fixes
        .iter()
        .map(|fix| {
            let (hist, rows, store) = match fix.kind.as_wall() {
                Some(wall) => (wall.history_prop(), wall.history_rows(), wall.store_prop()),
                None => (None, &[][..], None),
            };
            let hist = hist.map(|id| {
                let h = &p.sparse[id.0];
                debug_assert!(h.rows_match(rows), "wall history rows out of date");
                (id.0, h.width, rows)
            });
            (hist, store.map(|id| (id.0, p.props[id.0].width)))
        })
        .collect();
    // Where each particle last touched a wall, when the lost-particle report asks for it.
    let touch_id = p
        .property(crate::wall::TOUCH_PROPERTY)
        .filter(|_| fixes.iter().any(|fix| fix.kind.as_wall().is_some()));
    let (view, f, torque, props, sparse) = View::split(p);
    let mut touch_data = touch_id.map_or_else(Vec::new, |id| std::mem::take(&mut props[id.0].data));
    let mut data: Vec<[Vec<f64>; 2]> = taken
        .iter()
        .map(|(h, s)| {
            [
                h.map_or_else(Vec::new, |(id, _, _)| std::mem::take(&mut sparse[id].data)),
                s.map_or_else(Vec::new, |(id, _)| std::mem::take(&mut props[id].data)),
            ]
        })
        .collect();
    let chunk = |lo: usize,
                 f: &mut [DVec3],
                 torque: &mut [DVec3],
                 hs: &mut [[&mut [f64]; 2]],
                 touch: &mut [f64]| {
        for (k, (fix, [h, store])) in fixes.iter().zip(hs.iter_mut()).enumerate() {
            let stored = !store.is_empty();
            if stored {
                crate::wall::store_begin(f, store);
            }
            if let Some(wall) = fix.kind.as_wall() {
                let touches = crate::wall::Touches {
                    data: &mut *touch,
                    fix: at.start + k,
                    step: at.step,
                };
                wall.apply_range(meshes, &view, lo, f, torque, h, touches, dt, update);
            } else {
                fix.post_force_range(&view, lo, f, torque, dt);
            }
            if stored {
                crate::wall::store_end(f, store);
            }
        }
        all_finite(f, torque)
    };
    let ok = if !parallel(n) {
        let mut hs: Vec<[&mut [f64]; 2]> = data
            .iter_mut()
            .zip(&taken)
            .map(|([h, s], (_, sid))| [&mut h[..], cut(s, sid, n)])
            .collect();
        let touch = cut(&mut touch_data, &touch_id.map(|_| (0, TOUCH_WIDTH)), n);
        chunk(0, &mut f[..n], &mut torque[..n], &mut hs, touch)
    } else {
        let mut per: Vec<Vec<[&mut [f64]; 2]>> = (0..n.div_ceil(CHUNK))
            .map(|_| Vec::with_capacity(fixes.len()))
            .collect();
        for ([h, s], (hid, sid)) in data.iter_mut().zip(&taken) {
            let (hw, rows) = hid.map_or((0, &[][..]), |(_, w, rows)| (w, rows));
            let sw = sid.map_or(0, |(_, w)| w);
            let hists = crate::wall::chunk_rows(rows, h, hw, n);
            for (c, (hc, sc)) in per
                .iter_mut()
                .zip(hists.into_iter().zip(chunk_hist(s, n, sw)))
            {
                c.push([hc, sc]);
            }
        }
        let tw = if touch_id.is_some() { TOUCH_WIDTH } else { 0 };
        let touches = chunk_hist(&mut touch_data, n, tw);
        let oks: Vec<bool> = f[..n]
            .par_chunks_mut(CHUNK)
            .zip(torque[..n].par_chunks_mut(CHUNK))
            .zip(per)
            .zip(touches)
            .enumerate()
            .map(|(c, (((f, torque), mut hs), touch))| chunk(c * CHUNK, f, torque, &mut hs, touch))
            .collect();
        oks.into_iter().all(|ok| ok)
    };
    for ([h, s], (hid, sid)) in data.into_iter().zip(&taken) {
        if let Some((id, _, _)) = hid {
            sparse[*id].data = h;
        }
        if let Some((id, _)) = sid {
            props[*id].data = s;
        }
    }
    if let Some(id) = touch_id {
        props[id.0].data = touch_data;
    }
    ok
}
