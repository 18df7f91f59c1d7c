//! `fix ID group addforce fx fy fz [region ID]`: adds a force to each particle of the
//! group (inside the region, if one is given), as LIGGGHTS 3.8's `fix addforce`.
//!
//! Each component is a number or `v_name`:
//! - an equal-style variable is evaluated before each step, at that step (as rdem's other
//!   fixes evaluate theirs);
//! - an atom-style variable is evaluated per particle in the force pass, where the fix
//!   stands among the post-force fixes, with the positions, velocities and forces of
//!   that moment, as LIGGGHTS evaluates it in its post-force stage (see
//!   [`crate::atom_formula`] for what such a formula may read).
//!
//! With numbers only and no region, the engine's own `AddForce` acts.
//! A formula that gives a value that is not finite (a division by zero, the square root
//! of a negative value) stops the run after the step, as LIGGGHTS stops.

use std::sync::{Arc, Mutex};

use crate::error::Error;
use glam::DVec3;
use rdem::fix::ForceFix;
use rdem::par::View;
use rdem::region::Region;
use rdem::{Fix, FixKind};

use super::engine::{engine_fix, InEngine};
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Accept, Args, CmdResult, NumOrVar};
use crate::atom_formula::{At, AtomFormula};
use crate::sim::Sim;
use crate::variables::Variable;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "addforce",
    parse,
    Stages::ENGINE.and(Stages::PRE_STEP).and(Stages::END_OF_STEP),
    "`fx fy fz` (numbers or v_name: equal-style evaluated before each step, atom-style per particle in the force pass) `[region ID]`",
)
.notes("`energy` is not supported yet (a located error)");

/// One component as the engine applies it.
#[derive(Debug, Clone)]
enum Component {
    /// A number (or an equal-style variable's value at this step).
    Value(f64),
    /// An atom-style formula.
    PerParticle(AtomFormula),
}

/// The force as the engine runs it.
#[derive(Debug, Clone)]
struct VarForce {
    force: [Component; 3],
    region: Option<Region>,
    /// The first non-finite value met in the force pass (reported after the step).
    bad: Arc<Mutex<Option<String>>>,
}

impl ForceFix for VarForce {
    fn apply(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        torque: &mut [DVec3],
        groupbit: u32,
        _dt: f64,
    ) {
        for k in 0..f.len() {
            let i = lo + k;
            if p.mask[i] & groupbit == 0 {
                continue;
            }
            if let Some(r) = &self.region {
                if !r.contains(p.x[i]) {
                    continue;
                }
            }
            // All three components from the forces before this fix acted, as LIGGGHTS.
            let mut add = [0.0; 3];
            {
                let at = At { p, f, torque, lo };
                for (a, c) in self.force.iter().enumerate() {
                    add[a] = match c {
                        Component::Value(v) => *v,
                        Component::PerParticle(e) => e.eval(&at, i),
                    };
                }
            }
            if add.iter().any(|v| !v.is_finite()) {
                let mut bad = self.bad.lock().expect("not poisoned");
                if bad.is_none() {
                    *bad = Some(format!(
                        "fix addforce: the force on atom {} is not finite ({add:?}): the variable's formula divides by zero or takes an invalid root or logarithm",
                        p.tag[i]
                    ));
                }
                continue;
            }
            f[k] += DVec3::from_array(add);
        }
    }

    fn clone_box(&self) -> Box<dyn ForceFix> {
        Box::new(self.clone())
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// The script's entry: the engine fix, and what must be evaluated before each step.
struct AddForce {
    inner: InEngine,
    /// fx, fy, fz as written.
    force: [NumOrVar; 3],
    /// The region's ID when it moves (placed before each step).
    moving_region: Option<String>,
    bad: Arc<Mutex<Option<String>>>,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let force = [
        a.num_or_var("fx", Accept::Var)?,
        a.num_or_var("fy", Accept::Var)?,
        a.num_or_var("fz", Accept::Var)?,
    ];
    let (mut region, mut moving_region) = (None, None);
    while !a.is_done() {
        match a.keyword("addforce keyword", &["region", "energy"])? {
            "region" => {
                let (r, moving) = crate::regions::fix_region(sim, a)?;
                (region, moving_region) = (Some(r), moving);
            }
            k => {
                return Err(a.error_prev(
                    format!("addforce {k} is not supported yet"),
                    Some("rdem's addforce takes 'region ID'".into()),
                ))
            }
        }
    }
    let numbers: Option<Vec<f64>> = force.iter().map(|c| c.num()).collect();
    if let (Some(v), None) = (&numbers, &region) {
        let force = DVec3::new(v[0], v[1], v[2]);
        return engine_fix(sim, a, head, FixKind::AddForce { force });
    }
    sim.world_ref(a)?;
    // Variables are evaluated before each step (and the set-up); until then they are 0.
    let bad = Arc::new(Mutex::new(None));
    let engine = VarForce {
        force: force
            .clone()
            .map(|c| Component::Value(c.num().unwrap_or(0.0))),
        region,
        bad: bad.clone(),
    };
    let fix = Fix::new(&head.id, head.groupbit, FixKind::Force(Box::new(engine)))
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(AddForce {
        inner: InEngine::new(fix),
        force,
        moving_region,
        bad,
    }))
}

impl ScriptFix for AddForce {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// The components of the coming step (or of the set-up): equal-style variables
    /// evaluated, atom-style formulas prepared; a moving region placed.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if self.force.iter().all(|c| c.var().is_none()) && self.moving_region.is_none() {
            return Ok(());
        }
        let who = "fix addforce";
        let force = &self.force;
        let moving = &self.moving_region;
        let (components, region) = ctx.at_step(who, |sim| -> Result<_, Error> {
            let mut out = Vec::with_capacity(3);
            for c in force {
                out.push(match c {
                    NumOrVar::Var(name) => match sim.script.vars.get(name) {
                        Some(Variable::Atom(_)) => {
                            let e = AtomFormula::prepare(sim, name)
                                .map_err(|e| e.within(format!("{who}: variable {name}")))?;
                            match e.value_if_constant() {
                                Some(v) => Component::Value(v),
                                None => Component::PerParticle(e),
                            }
                        }
                        _ => Component::Value(
                            crate::context::eval_name_equal(
                                sim,
                                &crate::expr::Name::Variable(name.clone()),
                            )
                            .map_err(|e| e.within(who))?,
                        ),
                    },
                    other => Component::Value(other.num().unwrap_or(0.0)),
                });
            }
            let region = match moving {
                Some(id) => Some(crate::regions::region_now(sim, id)?),
                None => None,
            };
            Ok((out, region))
        })??;
        for c in &components {
            if let Component::Value(v) = c {
                if !v.is_finite() {
                    return Err(format!("{who}: a variable gives {v}, not a finite force").into());
                }
            }
        }
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix addforce is not in the engine")?;
        if let FixKind::Force(force) = &mut fix.kind {
            if let Some(c) = force.as_any_mut().downcast_mut::<VarForce>() {
                let mut it = components.into_iter();
                c.force = [0, 1, 2].map(|_| it.next().expect("three components"));
                if region.is_some() {
                    c.region = region;
                }
            }
        }
        Ok(())
    }

    /// Stops the run if the force pass met a value that is not finite.
    fn end_of_step(&mut self, _ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        match self.bad.lock().expect("not poisoned").take() {
            Some(m) => Err(m.into()),
            None => Ok(()),
        }
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}
