//! `fix ID group buoyancy dim x|y|z [level L] [density ρ_f] [region ID]` (LIGGGHTS 3.8):
//! the weight of the displaced fluid on each particle of the group (inside the region, if
//! one is given). The fluid fills the half-space beyond the plane `dim = L` on the side
//! gravity points to; a sphere of radius r submerged to the depth h (0 ≤ h ≤ 2r) displaces
//! the cap V = π h² (3r − h) / 3 and gets F = −ρ_f V g along the axis, g the component of
//! the first `fix gravity`'s acceleration on it. Defaults: level 0, density 0 (as
//! LIGGGHTS).
//!
//! As LIGGGHTS 3.8 requires: a `fix gravity` must exist when a run starts, along the
//! `dim` axis (its other components zero). `f_ID[1..3]` is the total buoyancy force on the
//! group (summed over ranks). The fix acts through the engine's post-force extension
//! point ([`rdem::fix::ForceFix`]), in definition order with the other post-force fixes.

use crate::error::Error;
use glam::DVec3;
use rdem::fix::ForceFix;
use rdem::par::View;
use rdem::region::Region;
use rdem::{Fix, FixKind};

use super::engine::InEngine;
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "buoyancy",
    parse,
    Stages::ENGINE.and(Stages::PRE_STEP).and(Stages::VALUES),
    "`dim x\\|y\\|z` (required), `level L` (default 0), `density ρ_f` (default 0), `region ID`: the weight of the displaced fluid (a spherical cap when partly submerged) against the first `fix gravity`; `f_ID[1..3]` the total buoyancy force",
)
.notes("needs a `fix gravity` along `dim` when a run starts, as LIGGGHTS 3.8; a moving region is placed where it is at the definition");

/// The force as the engine applies it.
#[derive(Debug, Clone)]
struct Floater {
    /// Axis of the fluid's surface normal.
    axis: usize,
    /// Surface position along the axis.
    level: f64,
    /// Fluid density.
    density: f64,
    /// Gravity's component along the axis (set when a run starts).
    g: f64,
    /// Only particles inside it feel the fluid.
    region: Option<Region>,
}

impl Floater {
    /// The buoyancy force on a sphere of radius `r` centred at `x`.
    fn force(&self, x: DVec3, r: f64) -> f64 {
        let c = x[self.axis];
        // Submerged depth: the fluid lies beyond the level on the side gravity points to.
        let h = if self.g < 0.0 {
            self.level - (c - r)
        } else {
            (c + r) - self.level
        }
        .clamp(0.0, 2.0 * r);
        let volume = std::f64::consts::PI * h * h * (3.0 * r - h) / 3.0;
        -self.density * volume * self.g
    }

    /// Whether a particle of mask `mask` at `x` feels the fluid.
    fn acts_on(&self, mask: u32, x: DVec3, groupbit: u32) -> bool {
        mask & groupbit != 0 && self.region.as_ref().is_none_or(|r| r.contains(x))
    }
}

impl ForceFix for Floater {
    fn apply(
        &self,
        p: &View,
        lo: usize,
        f: &mut [DVec3],
        _torque: &mut [DVec3],
        groupbit: u32,
        _dt: f64,
    ) {
        for (k, f) in f.iter_mut().enumerate() {
            let i = lo + k;
            if self.acts_on(p.mask[i], p.x[i], groupbit) {
                f[self.axis] += self.force(p.x[i], p.radius[i]);
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

/// The script's entry.
struct Buoyancy {
    inner: InEngine,
    axis: usize,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let mut axis = None;
    let mut level = 0.0;
    let mut density = 0.0;
    let mut region = None;
    while !a.is_done() {
        match a.keyword("buoyancy keyword", &["dim", "level", "density", "region"])? {
            "dim" => {
                axis = Some(match a.keyword("dim", &["x", "y", "z"])? {
                    "x" => 0,
                    "y" => 1,
                    _ => 2,
                })
            }
            "level" => level = a.f64("level")?,
            "density" => density = a.non_negative("fluid density")?,
            _ => region = Some(crate::regions::fix_region(sim, a)?.0),
        }
    }
    let axis = axis.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "fix buoyancy needs the keyword 'dim' (x, y or z: the axis of the fluid's surface)",
            Some("e.g. fix bu all buoyancy level 0.06 dim z density 1000".into()),
        )
    })?;
    sim.world_ref(a)?;
    let floater = Floater {
        axis,
        level,
        density,
        g: 0.0,
        region,
    };
    let fix = Fix::new(&head.id, head.groupbit, FixKind::Force(Box::new(floater)))
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(Box::new(Buoyancy {
        inner: InEngine::new(fix),
        axis,
    }))
}

impl ScriptFix for Buoyancy {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        self.inner.install(sim, a, head)
    }

    /// At a run's set-up: gravity's component along the axis, from the first `fix
    /// gravity`, which must point along it.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if !ctx.setup {
            return Ok(());
        }
        let w = ctx.world();
        let accel = w
            .fixes
            .iter()
            .find_map(|f| match &f.kind {
                FixKind::Gravity { accel } => Some(*accel),
                _ => None,
            })
            .ok_or(
                "fix buoyancy needs a fix gravity (buoyancy is the weight of the displaced fluid)",
            )?;
        let axis = self.axis;
        if (0..3).any(|a| a != axis && accel[a] != 0.0) {
            return Err(format!(
                "fix buoyancy: gravity ({}, {}, {}) must point along the {} axis given by 'dim'",
                accel.x,
                accel.y,
                accel.z,
                ["x", "y", "z"][axis]
            )
            .into());
        }
        let fix = w
            .fix_mut(&head.id)
            .ok_or("fix buoyancy is not in the engine")?;
        if let FixKind::Force(force) = &mut fix.kind {
            if let Some(b) = force.as_any_mut().downcast_mut::<Floater>() {
                b.g = accel[axis];
            }
        }
        Ok(())
    }

    /// The total buoyancy force on the group, summed over ranks.
    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no simulation box")?;
        let fix = w
            .fixes
            .iter()
            .find(|f| f.id == head.id)
            .ok_or("fix buoyancy is not in the engine")?;
        let FixKind::Force(force) = &fix.kind else {
            return Err("fix buoyancy is not a force fix".into());
        };
        let mut copy = force.clone_box();
        let b = copy
            .as_any_mut()
            .downcast_mut::<Floater>()
            .ok_or("fix buoyancy holds another fix")?;
        let p = &w.particles;
        let mut total = 0.0;
        for i in 0..p.nlocal() {
            if b.acts_on(p.mask[i], p.x[i], fix.groupbit) {
                total += b.force(p.x[i], p.radius[i]);
            }
        }
        let mut out = vec![0.0; 3];
        out[self.axis] = w.comm.sum(total) + 0.0;
        Ok(out)
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        self.inner.unfix(sim, head);
    }
}
