//! `fix ID group speedcontrol vx vy vz [region ID] [gain K]` (LIGGGHTS-PFM): a
//! proportional controller that pulls the velocity of each particle of the group (inside
//! the region, if one is given) towards a set velocity. Per axis whose set value is not
//! NULL, the force gets
//!
//! f −= K · m / dt · (v − v_set),
//!
//! with the particle's mass m and the timestep dt; K (`gain`) is 0.1 by default. With the
//! force computed from the velocity at the force pass (after the first half kick), one
//! step takes the velocity error e to (1 − K) e between force passes.
//!
//! The set velocities and the gain may be `v_name` equal-style variables, evaluated before
//! each step at that step; a moving region is placed at that step too. Atom-style
//! variables stop the run with an error (not supported yet). The fix keeps no state in
//! restart files, as in LIGGGHTS-PFM.
//!
//! This is the whole fix: it acts through the engine's post-force extension point
//! ([`rdem::fix::ForceFix`]), in definition order with the other post-force fixes.

use crate::error::Error;
use glam::DVec3;
use rdem::fix::ForceFix;
use rdem::par::View;
use rdem::region::Region;
use rdem::{Fix, FixKind};

use super::engine::InEngine;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Accept, Args, CmdResult, NumOrVar};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "speedcontrol",
    parse,
    Stages::ENGINE.and(Stages::PRE_STEP),
    "`vx vy vz` (numbers, NULL or v_name) `[region ID] [gain K]` (LIGGGHTS-PFM): f −= K·m/dt·(v − v_set), K 0.1 by default",
)
.notes("atom-style variables are not supported yet (an error when the run starts)");

/// The controller as the engine runs it.
#[derive(Debug, Clone)]
struct Controller {
    /// Set velocity per axis; `None` (NULL) leaves that axis alone.
    set: [Option<f64>; 3],
    /// Proportional gain K.
    gain: f64,
    /// Only particles inside it are controlled.
    region: Option<Region>,
}

impl ForceFix for Controller {
    fn apply(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        _torque: &mut [DVec3],
        groupbit: u32,
        dt: f64,
    ) {
        for (k, f) in f.iter_mut().enumerate() {
            let i = lo + k;
            if p.mask[i] & groupbit == 0 {
                continue;
            }
            if let Some(r) = &self.region {
                if !r.contains(p.x[i]) {
                    continue;
                }
            }
            let c = self.gain * p.rmass[i] / dt;
            for (a, set) in self.set.iter().enumerate() {
                if let Some(vs) = set {
                    f[a] -= c * (p.v[i][a] - vs);
                }
            }
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
struct SpeedControl {
    inner: InEngine,
    /// vx, vy, vz.
    set: [NumOrVar; 3],
    /// K.
    gain: NumOrVar,
    /// The region's ID when it moves (placed before each step).
    moving_region: Option<String>,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let set = [
        a.num_or_var("vx", Accept::NullOrVar)?,
        a.num_or_var("vy", Accept::NullOrVar)?,
        a.num_or_var("vz", Accept::NullOrVar)?,
    ];
    let mut gain = NumOrVar::Num(0.1);
    let mut region = None;
    let mut moving_region = None;
    while !a.is_done() {
        match a.keyword("speedcontrol keyword", &["region", "gain"])? {
            "region" => {
                let (r, moving) = crate::regions::fix_region(sim, a)?;
                (region, moving_region) = (Some(r), moving);
            }
            _ => gain = a.num_or_var("gain", Accept::Var)?,
        }
    }
    sim.world_ref(a)?;
    // Variables are evaluated before each step (and the set-up); until then they are 0.
    let controller = Controller {
        set: [0, 1, 2].map(|k| match &set[k] {
            NumOrVar::Null => None,
            value => Some(value.num().unwrap_or(0.0)),
        }),
        gain: gain.num().unwrap_or(0.0),
        region,
    };
    let fix = Fix::new(
        &head.id,
        head.groupbit,
        FixKind::Force(Box::new(controller)),
    )
    .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(SpeedControl {
        inner: InEngine::new(fix),
        set,
        gain,
        moving_region,
    }))
}

impl ScriptFix for SpeedControl {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// The set velocities and gain of the coming step (or of the set-up) from their
    /// variables, and the moving region where it is at that step.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let values = [&self.set[0], &self.set[1], &self.set[2], &self.gain];
        if values.iter().all(|v| v.var().is_none()) && self.moving_region.is_none() {
            return Ok(());
        }
        let who = "fix speedcontrol";
        let hint = " (atom-style is not supported yet)";
        let now = ctx.values_at(&values, who, hint)?;
        let region = match &self.moving_region {
            Some(id) => Some(ctx.at_step(who, |sim| crate::regions::region_now(sim, id))??),
            None => None,
        };
        let gain = now[3].expect("the gain is a number or a variable");
        if !gain.is_finite() || now[..3].iter().flatten().any(|v| !v.is_finite()) {
            return Err(format!(
                "fix speedcontrol: the variables give a value that is not finite (set velocity {:?}, gain {gain})",
                &now[..3]
            ).into());
        }
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix speedcontrol is not in the engine")?;
        if let FixKind::Force(force) = &mut fix.kind {
            if let Some(c) = force.as_any_mut().downcast_mut::<Controller>() {
                c.set = [now[0], now[1], now[2]];
                c.gain = gain;
                if region.is_some() {
                    c.region = region;
                }
            }
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}
