//! `fix ID group gravity magnitude style args`: an acceleration on every particle of the
//! group, along `vector x y z`, `chute angle` or `spherical phi theta`, as LIGGGHTS 3.8
//! (LAMMPS' fix gravity) defines them:
//!
//! - `chute θ`: (sin θ, 0, −cos θ), the tilt away from −z towards +x (degrees);
//! - `spherical φ θ`: (sin θ cos φ, sin θ sin φ, cos θ), φ from +x, θ from +z (degrees);
//! - `vector x y z`: the direction of (x, y, z), its length ignored.
//!
//! Any value may be an equal-style variable `v_name`, evaluated before each step (and
//! before a run's set-up forces) at that step, as LIGGGHTS evaluates it in its post-force
//! stage. `gradient`, which LIGGGHTS 3.8's manual names without arguments, stops there with
//! "Illegal fix gravity command" (checked on LIGGGHTS 3.8), and here with an error.

use crate::error::Error;
use std::f64::consts::PI;

use glam::DVec3;
use rdem::{Fix, FixKind};

use super::engine::InEngine;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Accept, Args, CmdResult, NumOrVar};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "gravity",
    parse,
    Stages::ENGINE.and(Stages::PRE_STEP),
    "`G vector x y z`, `G chute angle`, `G spherical phi theta` (degrees); any value an equal-style `v_name`, evaluated every step",
)
.notes("`gradient` stops with an error, as in LIGGGHTS 3.8 (its manual names it, its code refuses it)");

/// How the direction is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Style {
    Vector,
    Chute,
    Spherical,
}

/// A `fix gravity`: the engine fix, and the values that are variables.
pub struct Gravity {
    inner: InEngine,
    style: Style,
    /// `dimension 2`: the direction lies in the xy plane.
    flat: bool,
    /// Magnitude, then the style's arguments.
    values: Vec<NumOrVar>,
}

/// The acceleration of `style` with magnitude `g` and arguments `args`, computed as
/// LAMMPS' fix gravity does (chute and spherical from degrees, vector normalised); `None`
/// for a vector of zero length. In 2d (`flat`) the direction lies in the xy plane, as
/// LAMMPS takes it: a vector's z component is dropped before it is normalised (checked on
/// LIGGGHTS 3.8: `vector 0 -1 0.3` in 2d moves as `vector 0 -1 0`, tests/dim2.rs); chute
/// and spherical give (sin θ, cos θ, 0) of their polar angle.
fn accel(style: Style, g: f64, args: &[f64], flat: bool) -> Option<DVec3> {
    let rad = PI / 180.0;
    if flat && style != Style::Vector {
        let theta = match style {
            Style::Chute => rad * (180.0 - args[0]),
            _ => rad * args[1],
        };
        return Some(g * DVec3::new(theta.sin(), theta.cos(), 0.0));
    }
    let dir = match style {
        Style::Chute => {
            let t = rad * args[0];
            DVec3::new(t.sin(), 0.0, -t.cos())
        }
        Style::Spherical => {
            let (phi, theta) = (rad * args[0], rad * args[1]);
            DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
        }
        Style::Vector => {
            let d = DVec3::new(args[0], args[1], if flat { 0.0 } else { args[2] });
            return rdem::fix::gravity_accel(g, d);
        }
    };
    Some(g * dir)
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut values = vec![a.num_or_var("gravity magnitude", Accept::Var)?];
    let style_at = a.pos();
    if a.peek() == Some("gradient") {
        return Err(a.error_at(
            style_at,
            "gravity style 'gradient' is not supported: LIGGGHTS 3.8 refuses it too (\"Illegal fix gravity command\")",
            Some("use 'chute', 'spherical' or 'vector', with v_name values for a field that changes in time".into()),
        ));
    }
    let style = match a.keyword("gravity style", &["vector", "chute", "spherical"])? {
        "chute" => {
            values.push(a.num_or_var("chute angle (degrees)", Accept::Var)?);
            Style::Chute
        }
        "spherical" => {
            values.push(a.num_or_var("phi (degrees from +x)", Accept::Var)?);
            values.push(a.num_or_var("theta (degrees from +z)", Accept::Var)?);
            Style::Spherical
        }
        _ => {
            for c in ["x", "y", "z"] {
                values.push(a.num_or_var(&format!("gravity vector {c}"), Accept::Var)?);
            }
            Style::Vector
        }
    };
    a.done()?;
    sim.world_ref(a)?;
    let flat = sim.setup.dimension == 2;
    // With variables the acceleration is set before each step; until then it is zero.
    let nums: Option<Vec<f64>> = values.iter().map(NumOrVar::num).collect();
    let acc = match nums {
        Some(n) => accel(style, n[0], &n[1..], flat).ok_or_else(|| {
            a.error_at(
                style_at + 1,
                "the gravity vector has no direction (length 0)",
                None,
            )
        })?,
        None => DVec3::ZERO,
    };
    let fix = Fix::new(&head.id, head.groupbit, FixKind::Gravity { accel: acc })
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(Gravity {
        inner: InEngine::new(fix),
        style,
        flat,
        values,
    }))
}

impl ScriptFix for Gravity {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// With variables: the acceleration of the coming step (or of the set-up), from the
    /// variables evaluated at that step.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if self.values.iter().all(|v| v.var().is_none()) {
            return Ok(());
        }
        let values: Vec<&NumOrVar> = self.values.iter().collect();
        let nums: Vec<f64> = ctx
            .values_at(&values, "fix gravity", "")?
            .into_iter()
            .map(|x| x.expect("a number or an evaluated variable"))
            .collect();
        let acc = accel(self.style, nums[0], &nums[1..], self.flat)
            .filter(|g| g.is_finite())
            .ok_or_else(|| {
                format!(
                    "fix gravity: the variables give no finite direction ({:?})",
                    &nums[1..]
                )
            })?;
        let fix = ctx
            .world()
            .fix_mut(&head.id)
            .ok_or("fix gravity is not in the engine")?;
        if let FixKind::Gravity { accel } = &mut fix.kind {
            *accel = acc;
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}
