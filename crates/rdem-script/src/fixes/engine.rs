//! The fixes the engine runs every step, which the script only parses: `nve/sphere`,
//! `nve/limit` and `nve/noforce` (integration), `freeze`, `viscous`, `setforce`, `aveforce`, `enforce2d` (post-force);
//! `addforce` with numbers (its file: [`super::addforce`]).
//! Each becomes an engine [`Fix`] in `World::fixes`; [`InEngine`] is its entry in the
//! script's fix list (`unfix` removes it from the world).

use crate::error::Error;
use glam::DVec3;
use rdem::{Fix, FixKind};

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Accept, Args, CmdResult, NumOrVar};
use crate::sim::Sim;

/// The registry row of `nve/sphere`.
pub(super) const ROW_NVE: FixRow = style(
    "nve/sphere",
    nve_sphere,
    Stages::ENGINE,
    "velocity Verlet for spheres (translation and rotation)",
);
/// The registry row of `nve/limit`.
pub(super) const ROW_NVE_LIMIT: FixRow = style(
    "nve/limit",
    nve_limit,
    Stages::ENGINE.and(Stages::VALUES),
    "`absolute|radius_ratio xmax`: velocity Verlet for translation only, the speed capped after each half kick at xmax/dt (xmax·r/dt with radius_ratio); `f_ID` the resets since the run's start",
);
/// The registry row of `nve/noforce`.
pub(super) const ROW_NVE_NOFORCE: FixRow = style(
    "nve/noforce",
    nve_noforce,
    Stages::ENGINE,
    "positions advance with the velocities; forces are ignored and velocities and spins stay (walls of particles moved at a set velocity)",
);
/// The registry row of `freeze`.
pub(super) const ROW_FREEZE: FixRow = style(
    "freeze",
    freeze,
    Stages::ENGINE,
    "force and torque held at zero; contacts take a frozen particle as infinitely heavy (one fix freeze only)",
);
/// The registry row of `viscous`.
pub(super) const ROW_VISCOUS: FixRow = style(
    "viscous",
    viscous,
    Stages::ENGINE,
    "`gamma [scale type ratio ...]`: a drag force −γ v, γ scaled per atom type",
);
/// The registry row of `setforce`.
pub(super) const ROW_SETFORCE: FixRow = style(
    "setforce",
    setforce,
    Stages::ENGINE,
    "`fx fy fz` (numbers or NULL)",
);

/// The registry row of `enforce2d`.
pub(super) const ROW_ENFORCE2D: FixRow = style(
    "enforce2d",
    enforce2d,
    Stages::ENGINE,
    "z velocity and force, x and y angular velocity and torque held at zero (`dimension 2`)",
)
.notes("acts where it stands among the post-force fixes, as LIGGGHTS: define it after the walls and force fixes. Known difference: after a contact, a 2d case (tests/data/dim2/in.2d) departs from LIGGGHTS 3.8 (kinetic energy by 0.1%, rotational by 40% at the first wall contact), not yet explained; free motion matches to round-off");

/// The registry row of `aveforce`.
pub(super) const ROW_AVEFORCE: FixRow = style(
    "aveforce",
    aveforce,
    Stages::ENGINE.and(Stages::VALUES).and(Stages::PRE_STEP),
    "`fx fy fz` (numbers, NULL or v_name of an equal-style variable, evaluated before each step): the group's mean force plus these; `f_ID[1..3]` the total before",
)
.notes("the `region` keyword is not supported yet (a located error)");

/// A fix the engine runs: parsed into an engine [`Fix`], which [`ScriptFix::install`]
/// hands to `World::fixes` (the one owner of its state from then on; the script's entry
/// keeps its ID, style and group for `unfix` and redefinitions).
pub struct InEngine {
    /// The parsed fix, until it is installed.
    fix: Option<Fix>,
}

impl InEngine {
    /// The entry of `fix`, which [`ScriptFix::install`] hands to the world.
    pub(super) fn new(fix: Fix) -> Self {
        Self { fix: Some(fix) }
    }
}

impl ScriptFix for InEngine {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        if let Some(fix) = self.fix.take() {
            sim.world_mut(a)?
                .add_fix(fix)
                .map_err(|e| a.error_cmd(e.to_string(), None))?;
        }
        Ok(())
    }

    /// `fix aveforce`'s vector: the group's total force before the fix acted, at the last
    /// force evaluation (0 before any).
    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        match w.fixes.iter().find(|f| f.id == head.id).map(|f| &f.kind) {
            Some(FixKind::AveForce { total, .. }) => Ok(total.to_array().to_vec()),
            Some(FixKind::NveLimit(l)) => Ok(vec![w.comm.sum_count(l.resets) as f64]),
            _ => Err("computes no global values".into()),
        }
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.remove_fix(&head.id);
        }
    }
}

/// An engine fix of `kind` (a box must exist).
pub(super) fn engine_fix(
    sim: &Sim,
    a: &Args,
    head: &FixHead,
    kind: FixKind,
) -> CmdResult<Box<dyn ScriptFix>> {
    sim.world_ref(a)?;
    let fix =
        Fix::new(&head.id, head.groupbit, kind).map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(InEngine { fix: Some(fix) }))
}

fn nve_sphere(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    if !a.is_done() {
        let w = a.word("")?;
        return Err(a.error_prev(
            format!("nve/sphere: unexpected argument '{w}'"),
            Some("rdem's nve/sphere takes no options".into()),
        ));
    }
    engine_fix(sim, a, head, FixKind::NveSphere)
}

/// `fix ID group nve/noforce` (LIGGGHTS 3.8): x += dt v at each step's first stage.
fn nve_noforce(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    a.done()?;
    engine_fix(sim, a, head, FixKind::NveNoforce)
}

/// `fix ID group nve/limit absolute|radius_ratio xmax` ([`rdem::fix::integrate::NveLimit`]).
fn nve_limit(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let style = a.keyword("nve/limit limit style", &["absolute", "radius_ratio"])?;
    let xmax = a.positive("xmax")?;
    a.done()?;
    let kind = FixKind::NveLimit(rdem::fix::integrate::NveLimit::new(
        xmax,
        style == "radius_ratio",
    ));
    engine_fix(sim, a, head, kind)
}

/// `fix ID group freeze`. One only, as in LIGGGHTS 3.8 ("More than one fix freeze"):
/// contacts with a frozen particle take it as infinitely heavy, so they must know the
/// one frozen group.
fn freeze(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    a.done()?;
    let other = sim
        .defs
        .fixes
        .iter()
        .find(|f| f.head.style == "freeze" && f.head.id != head.id);
    if let Some(other) = other {
        return Err(a.error_at(
            super::STYLE_WORD,
            format!(
                "more than one fix freeze: fix {} is one already",
                other.head.id
            ),
            Some(
                "contacts take a frozen particle as infinitely heavy and need the one frozen \
                 group: put every frozen particle in one group, or unfix the other first"
                    .into(),
            ),
        ));
    }
    engine_fix(sim, a, head, FixKind::Freeze)
}

/// `fix ID group enforce2d` (LIGGGHTS 3.8: "Cannot use fix enforce2d with 3d
/// simulation").
fn enforce2d(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    a.done()?;
    if sim.setup.dimension != 2 {
        return Err(a.error_at(
            super::STYLE_WORD,
            "fix enforce2d needs a 2d simulation",
            Some("give 'dimension 2' before the box is made".into()),
        ));
    }
    engine_fix(sim, a, head, FixKind::Enforce2d)
}

fn viscous(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let gamma = a.non_negative("damping coefficient gamma")?;
    if a.is_done() {
        return engine_fix(sim, a, head, FixKind::Viscous { gamma });
    }
    // `scale type ratio`, repeatable: γ of that type is γ · ratio (LIGGGHTS: a later
    // scale of the same type replaces the earlier one).
    let ntypes = sim.world_ref(a)?.materials.ntypes;
    let mut per_type = vec![gamma; ntypes + 1];
    while !a.is_done() {
        a.keyword("viscous keyword", &["scale"])?;
        let t = a.u64("atom type")?;
        if t == 0 || t as usize > ntypes {
            return Err(a.error_prev(
                format!("atom type {t} is not a type of the box"),
                Some(format!("types are 1..{ntypes} (create_box {ntypes} ...)")),
            ));
        }
        let ratio = a.non_negative("scale ratio")?;
        per_type[t as usize] = gamma * ratio;
    }
    engine_fix(sim, a, head, FixKind::ViscousScaled { gamma: per_type })
}

fn aveforce(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut given = [NumOrVar::Null, NumOrVar::Null, NumOrVar::Null];
    for (k, c) in given.iter_mut().enumerate() {
        let what = ["fx", "fy", "fz"][k];
        *c = a.num_or_var(
            &format!("{what} (a number, NULL or v_name)"),
            Accept::NullOrVar,
        )?;
        if let NumOrVar::Var(name) = c {
            if let Some(crate::variables::Variable::Atom(_)) = sim.script.vars.get(name) {
                return Err(a.error_prev(
                    format!("aveforce takes equal-style variables; '{name}' is atom-style"),
                    Some("fix addforce takes atom-style variables".into()),
                ));
            }
        }
    }
    if !a.is_done() {
        a.keyword("aveforce keyword", &["region"])?;
        return Err(a.error_prev("aveforce region is not supported yet", None));
    }
    // Variables are evaluated before each step (and the set-up); until then they are 0.
    let kind = FixKind::AveForce {
        force: given.clone().map(|c| match c {
            NumOrVar::Null => None,
            c => Some(c.num().unwrap_or(0.0)),
        }),
        total: DVec3::ZERO,
    };
    sim.world_ref(a)?;
    let fix =
        Fix::new(&head.id, head.groupbit, kind).map_err(|e| a.error_cmd(e.to_string(), None))?;
    let inner = InEngine::new(fix);
    if given.iter().all(|c| c.var().is_none()) {
        return Ok(Box::new(inner));
    }
    Ok(Box::new(AveForceVars { inner, given }))
}

/// `fix aveforce` with equal-style variables: the engine fix, and its components
/// evaluated before each step, at that step.
struct AveForceVars {
    inner: InEngine,
    given: [NumOrVar; 3],
}

impl ScriptFix for AveForceVars {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        self.inner.values(sim, head)
    }

    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let who = "fix aveforce";
        let given = [&self.given[0], &self.given[1], &self.given[2]];
        let now = ctx.values_at(&given, who, " (aveforce takes equal-style variables)")?;
        if now.iter().flatten().any(|v| !v.is_finite()) {
            return Err(format!("{who}: a variable gives {now:?}, not a finite force").into());
        }
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix aveforce is not in the engine")?;
        if let FixKind::AveForce { force, .. } = &mut fix.kind {
            *force = [now[0], now[1], now[2]];
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}

fn setforce(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut v = [None; 3];
    for (k, c) in v.iter_mut().enumerate() {
        let what = ["fx", "fy", "fz"][k];
        *c = a
            .num_or_var(&format!("{what} (a number or NULL)"), Accept::Null)?
            .num();
    }
    a.done()?;
    engine_fix(sim, a, head, FixKind::SetForce { force: v })
}
