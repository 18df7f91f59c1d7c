//! `fix ID group move style args [units box|lattice]`: the particles of the group follow
//! a prescribed motion (`linear`, `wiggle`, `rotate`, `variable`) instead of being
//! integrated; the motion runs in the engine (`rdem::fix::motion`), from the positions
//! the particles have when the fix is defined.
//!
//! `units lattice` is the default, as in LIGGGHTS (without a `lattice` command the
//! spacing is 1, LIGGGHTS' default lattice `none 1.0`); it scales the `linear` velocity,
//! the `wiggle` amplitudes and the `rotate` point. `variable` takes equal-style variables,
//! evaluated before each step at that step's time and step number.

use crate::error::Error;
use glam::DVec3;
use rdem::fix::motion::{Move, MoveStyle};
use rdem::FixKind;

use super::engine::InEngine;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Accept, Args, CmdResult};
use crate::sim::Sim;
use crate::variables::Variable;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "move",
    parse,
    Stages::ENGINE.and(Stages::PRE_STEP),
    "`linear`, `wiggle`, `rotate`, `variable` (equal-style), NULL components integrated; `units box\\|lattice`",
)
.notes("`variable` with atom-style variables stops with an error (not supported yet)");

/// A `fix move`: the engine fix, and for `variable` the names of its six variables.
pub struct FixMove {
    inner: InEngine,
    /// `variable` style: displacement then velocity variable names (`None` for NULL).
    vars: Option<[Option<String>; 6]>,
}

impl ScriptFix for FixMove {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// The step the motion started at (its time origin) and, for `variable`, the
    /// displacement of the last step: with the original positions (a per-particle
    /// property, in the restart file with every particle) a continued run moves the
    /// particles on as the unbroken run does.
    fn save_state(&self, sim: &Sim, head: &FixHead) -> Option<Vec<u8>> {
        let m = engine_move(sim.world.as_ref()?, &head.id)?;
        let previous = match &m.style {
            MoveStyle::Variable { previous, .. } => *previous,
            _ => [None; 3],
        };
        postcard::to_stdvec(&(m.origin_step, previous)).ok()
    }

    fn restore_state(&mut self, sim: &mut Sim, head: &FixHead, state: &[u8]) -> Result<(), Error> {
        let (origin_step, prev): (u64, [Option<f64>; 3]) = super::decode_state(state)?;
        let w = sim.world.as_mut().ok_or("no simulation box")?;
        let fix = w.fix_mut(&head.id);
        let Some(FixKind::Move(m)) = fix.map(|f| &mut f.kind) else {
            return Err("fix move is not in the engine".into());
        };
        m.origin_step = origin_step;
        if let MoveStyle::Variable { previous, .. } = &mut m.style {
            *previous = prev;
        }
        Ok(())
    }

    /// `variable`: the displacement and velocity of the coming step, from the variables
    /// evaluated at that step (as LAMMPS evaluates them in its initial integration).
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        let Some(vars) = &self.vars else {
            return Ok(());
        };
        if ctx.setup {
            return Ok(());
        }
        let names: Vec<Option<&str>> = vars.iter().map(|n| n.as_deref()).collect();
        let v = ctx.eval_equal_at(&names, "fix move", " (atom-style is not supported yet)")?;
        let vals: [Option<f64>; 6] = [v[0], v[1], v[2], v[3], v[4], v[5]];
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix move is not in the engine")?;
        if let FixKind::Move(m) = &mut fix.kind {
            let previous = match &m.style {
                MoveStyle::Variable { displacement, .. } => *displacement,
                _ => [None; 3],
            };
            m.style = MoveStyle::Variable {
                displacement: [vals[0], vals[1], vals[2]],
                velocity: [vals[3], vals[4], vals[5]],
                previous,
            };
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&Move::property_name(&head.id));
        }
    }
}

/// The engine's `fix move` of ID `id`.
fn engine_move<'a>(w: &'a rdem::World, id: &str) -> Option<&'a Move> {
    match &w.fixes.iter().find(|f| f.id == id)?.kind {
        FixKind::Move(m) => Some(m),
        _ => None,
    }
}

/// A number or NULL.
fn opt(a: &mut Args, what: &str) -> CmdResult<Option<f64>> {
    Ok(
        a.num_or_var(&format!("{what} (a number or NULL)"), Accept::Null)?
            .num(),
    )
}

/// A `v_name` of an equal-style variable or NULL.
fn var(sim: &Sim, a: &mut Args, what: &str) -> CmdResult<Option<String>> {
    let w = a.word(what)?;
    if w == "NULL" {
        return Ok(None);
    }
    let Some(name) = w.strip_prefix("v_") else {
        return Err(a.error_prev(
            format!("fix move variable: {what} must be v_name or NULL, not '{w}'"),
            None,
        ));
    };
    match sim.script.vars.get(name) {
        Some(Variable::Equal(_)) => Ok(Some(name.to_string())),
        Some(Variable::Atom(_)) => Err(a.error_prev(
            format!("fix move variable with the atom-style variable '{name}' is not supported yet"),
            Some("use an equal-style variable".into()),
        )),
        Some(_) => Err(a.error_prev(
            format!("variable '{name}' is not equal-style"),
            Some("fix move variable takes equal-style variables".into()),
        )),
        None => Err(a.error_prev(
            format!("no variable '{name}'"),
            Some(crate::args::id_help(
                "variable",
                name,
                &sim.script.vars.names(),
            )),
        )),
    }
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let step = sim.world_ref(a)?.step;
    let kind = a.keyword(
        "fix move style",
        &["linear", "wiggle", "rotate", "variable"],
    )?;
    enum Raw {
        Linear([Option<f64>; 3]),
        Wiggle([Option<f64>; 3], f64),
        Rotate(DVec3, DVec3, f64),
        Variable([Option<String>; 6]),
    }
    let raw = match kind {
        "linear" => Raw::Linear([opt(a, "Vx")?, opt(a, "Vy")?, opt(a, "Vz")?]),
        "wiggle" => {
            let amp = [opt(a, "Ax")?, opt(a, "Ay")?, opt(a, "Az")?];
            Raw::Wiggle(amp, a.positive("period")?)
        }
        "rotate" => {
            let p = a.vec3("point")?;
            let at = a.pos();
            let r = a.vec3("axis")?;
            if r.length_squared() == 0.0 {
                return Err(a.error_at(at, "fix move rotate: zero length rotation axis", None));
            }
            Raw::Rotate(p, r.normalize(), a.positive("period")?)
        }
        _ => {
            let names = ["v_dx", "v_dy", "v_dz", "v_vx", "v_vy", "v_vz"];
            let mut v: [Option<String>; 6] = Default::default();
            for (k, slot) in v.iter_mut().enumerate() {
                *slot = var(sim, a, names[k])?;
            }
            Raw::Variable(v)
        }
    };
    let mut lattice_units = true;
    while !a.is_done() {
        a.keyword("fix move keyword", &["units"])?;
        lattice_units = a.keyword("units", &["box", "lattice"])? == "lattice";
    }
    let scale = sim
        .defs
        .lattice
        .as_ref()
        .filter(|_| lattice_units)
        .map_or(DVec3::ONE, |l| l.spacing());
    let scaled = |v: [Option<f64>; 3]| [0, 1, 2].map(|d| v[d].map(|c| c * scale[d]));
    let two_pi = 2.0 * std::f64::consts::PI;
    let (style, vars) = match raw {
        Raw::Linear(v) => (MoveStyle::Linear { v: scaled(v) }, None),
        Raw::Wiggle(amp, period) => (
            MoveStyle::Wiggle {
                amplitude: scaled(amp),
                omega: two_pi / period,
            },
            None,
        ),
        Raw::Rotate(p, axis, period) => (
            MoveStyle::Rotate {
                point: p * scale,
                axis,
                omega: two_pi / period,
            },
            None,
        ),
        Raw::Variable(v) => (
            MoveStyle::Variable {
                displacement: [None; 3],
                velocity: [None; 3],
                previous: [None; 3],
            },
            Some(v),
        ),
    };
    let kind = FixKind::Move(Box::new(Move::new(&head.id, style, step)));
    let fix = rdem::Fix::new(&head.id, head.groupbit, kind)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(FixMove {
        inner: InEngine::new(fix),
        vars,
    }))
}
