//! `fix ID group multisphere [allow_group_and_set yes|no] [allow_heatsource yes|no]`: the
//! rigid clumps that insertion fixes make from `particletemplate/multisphere` templates
//! are integrated as rigid bodies (`rdem::multisphere`): each step a body's force and
//! torque are the sums over its spheres, its centre of mass and orientation move with
//! them, and its spheres follow. As in LIGGGHTS, clumps join this fix whatever its group,
//! there is one such fix at most, and `fix_modify ID fflag fx fy fz tflag tx ty tz` sets
//! the translational and rotational switches of every clump there is.

use super::{style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "multisphere",
    parse,
    Stages::NONE,
    "`allow_group_and_set yes\\|no`, `allow_heatsource no`; `fix_modify ID fflag on\\|off ×3 tflag on\\|off ×3`",
)
.notes("`set` is refused without `allow_group_and_set yes`, as in LIGGGHTS 3.8 (`group` is not); with it, a clump's spheres still move with their body; `allow_heatsource yes` and `CAddRhoFluid` stop with an error");

/// The fix: its state is the world's clumps (`World::multisphere`).
pub struct MultisphereFix {
    /// `allow_group_and_set yes`: the `set` command may change the spheres.
    pub allow_set: bool,
}

/// The error of a `set` command while a fix multisphere without `allow_group_and_set
/// yes` is defined (LIGGGHTS 3.8 refuses it so: "Set command may not be used together
/// with fix multisphere"), `None` if `set` may run.
pub fn refuses_set(sim: &Sim) -> Option<String> {
    let f = sim
        .defs
        .fixes
        .iter()
        .find(|f| f.head.style == "multisphere")?;
    let ms = f.downcast::<MultisphereFix>()?;
    (!ms.allow_set).then(|| {
        format!(
            "set may not be used together with fix multisphere '{}' (it would change a \
             clump's spheres behind its body's back)",
            f.id()
        )
    })
}

fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    if sim.setup.dimension == 2 {
        return Err(a.error_at(
            STYLE_WORD,
            "fix multisphere is for 3d simulations only",
            None,
        ));
    }
    let others = sim
        .defs
        .fixes
        .iter()
        .filter(|f| f.head.style == "multisphere");
    if let Some(f) = others.into_iter().next() {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "there is a fix multisphere already ('{}'); only one is allowed",
                f.id()
            ),
            None,
        ));
    }
    let mut allow_set = false;
    while !a.is_done() {
        match a.keyword(
            "fix multisphere keyword",
            &["allow_group_and_set", "allow_heatsource", "CAddRhoFluid"],
        )? {
            "allow_group_and_set" => {
                allow_set = a.yes_no("allow_group_and_set")?;
            }
            "allow_heatsource" => {
                if a.yes_no("allow_heatsource")? {
                    return Err(
                        a.error_prev("heat sources in clumps are not supported by rdem yet", None)
                    );
                }
            }
            _ => return Err(a.error_prev(
                "CAddRhoFluid (the added mass of CFD-DEM coupling) is not supported by rdem yet",
                None,
            )),
        }
    }
    sim.world_ref(a)?;
    Ok(Box::new(MultisphereFix { allow_set }))
}

impl ScriptFix for MultisphereFix {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        w.multisphere.get_or_insert_with(Default::default);
        Ok(())
    }

    fn modify(
        &mut self,
        sim: &mut Sim,
        _head: &FixHead,
        keyword: &str,
        a: &mut Args,
    ) -> CmdResult<bool> {
        if keyword != "fflag" && keyword != "tflag" {
            return Ok(false);
        }
        let mut f = [true; 3];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            f[k] = a.yes_no(&format!("{keyword} {axis} (on or off)"))?;
        }
        let w = sim.world_mut(a)?;
        if let Some(ms) = &mut w.multisphere {
            for b in &mut ms.bodies {
                if keyword == "fflag" {
                    b.fflag = f;
                } else {
                    b.tflag = f;
                }
            }
        }
        Ok(true)
    }

    fn check_unfix(&self, sim: &Sim, _head: &FixHead) -> Result<(), Error> {
        let n = sim
            .world
            .as_ref()
            .and_then(|w| w.multisphere.as_ref())
            .map_or(0, |ms| ms.bodies.len());
        if n > 0 {
            return Err(format!(
                "fix multisphere cannot be removed while {n} clump(s) exist (delete them first)"
            )
            .into());
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.multisphere = None;
        }
    }
}
