//! LIGGGHTS-PFM's `coarsegraining cg [model_check error|warn]`: the script's particles are
//! cg times larger than the ones it describes (Radl et al.; Bierwisch et al.).
//!
//! What the factor changes, as LIGGGHTS-PFM's manual lists it and as the fork (d075b97)
//! does when run:
//! - lengths the script gives: the radii of `particletemplate/sphere` (`radius constant`
//!   only: a radius distribution is an error), the sphere radii and positions of
//!   `particletemplate/multiplespheres` and `multisphere` (times their `scale`), `set
//!   diameter`, and the skin of `neighbor`;
//! - `hooke/stiffness`'s tables: kn times cg, gamman over cg, gamman_abs times cg²;
//! - `fix massflow/mesh`'s file gives the described diameter, 2r/cg.
//!
//! The models and commands the fork's manual names as inconsistent with coarse graining
//! ([`INCONSISTENT_MODELS`], [`INCONSISTENT_FIXES`], `create_atoms`) stop the script with
//! `model_check error` (the default) and give a warning with `model_check warn`. Hertz's
//! law and the tangential models are consistent as they are and change nothing. rdem's
//! models that LIGGGHTS-PFM does not have are neither scaled nor checked, as the fork's
//! manual says of the models it does not list.
//!
//! The command comes before anything that gives a length: the box, any fix, `neighbor`
//! and `pair_style` (the fork checks the box, the fixes and the skin).

use crate::args::{Args, CmdResult};
use crate::sim::Sim;
use rdem::contact::names::{name_of, COHESION_MODELS, NORMAL_MODELS, ROLLING_MODELS};
use rdem::ContactModel;

/// The coarse-graining factor and what a model inconsistent with it does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoarseGraining {
    /// The factor (1: none).
    pub factor: f64,
    /// `model_check error` (true, the default) or `warn`.
    pub strict: bool,
}

impl Default for CoarseGraining {
    fn default() -> Self {
        Self {
            factor: 1.0,
            strict: true,
        }
    }
}

impl CoarseGraining {
    /// Whether the particles are coarse grained (a factor above 1).
    pub fn active(&self) -> bool {
        self.factor > 1.0
    }
}

/// Normal, cohesion and rolling models that LIGGGHTS-PFM's manual and code call
/// inconsistent with coarse graining (rdem's `jkr/pfm` is the fork's `model jkr`).
pub const INCONSISTENT_MODELS: &[&str] = &[
    "hooke",
    "hooke/hysteresis",
    "hooke/stiffness",
    "hertz/stiffness",
    "jkr",
    "jkr/pfm",
    "sjkr",
    "sjkr2",
    "hamaker",
    "morse",
    "cdt",
    "epsd",
    "epsd2",
];

/// Fix styles that LIGGGHTS-PFM calls inconsistent with coarse graining.
pub const INCONSISTENT_FIXES: &[&str] = &[
    "addforce",
    "buoyancy",
    "drag",
    "efield",
    "heat/gran",
    "heat/gran/conduction",
    "heat/gran/radiation",
    "spring",
    "spring/rg",
    "spring/self",
    "viscous",
];

/// `coarsegraining cg [model_check error|warn]`.
pub fn command(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let late = if sim.world.is_some() {
        Some("the simulation box is defined")
    } else if !sim.defs.fixes.is_empty() {
        Some("a fix is defined")
    } else if sim.setup.skin_given {
        Some("neighbor gave the skin")
    } else if sim.setup.pair.is_some() {
        Some("pair_style is given")
    } else {
        None
    };
    if let Some(why) = late {
        return Err(a.error_cmd(
            format!("coarsegraining after {why}"),
            Some(
                "give coarsegraining first in the script, before the box, neighbor, \
                 pair_style and any fix (LIGGGHTS-PFM's rule: they read lengths it scales)"
                    .into(),
            ),
        ));
    }
    let factor = a.f64("coarse-graining factor")?;
    if factor.is_nan() || factor < 1.0 || factor.is_infinite() {
        return Err(a.error_prev(
            format!("the coarse-graining factor must be >= 1, not {factor}"),
            Some("LIGGGHTS-PFM refuses a factor below 1 too".into()),
        ));
    }
    let mut strict = true;
    while !a.is_done() {
        a.keyword("coarsegraining keyword", &["model_check"])?;
        strict = a.keyword("model_check", &["error", "warn"])? == "error";
    }
    sim.setup.coarse_graining = CoarseGraining { factor, strict };
    Ok(())
}

/// What `what` (introduced by word `k`) does under coarse graining: an error with
/// `model_check error`, else a warning; nothing without coarse graining.
pub fn check(sim: &Sim, a: &Args, k: usize, what: &str) -> CmdResult {
    let cg = sim.setup.coarse_graining;
    if !cg.active() {
        return Ok(());
    }
    let message = format!(
        "{what} does not give results consistent with coarse graining (factor {})",
        cg.factor
    );
    if cg.strict {
        return Err(a.error_at(
            k,
            message,
            Some(
                "use 'coarsegraining CG model_check warn' to run it anyway, as LIGGGHTS-PFM \
                 allows"
                    .into(),
            ),
        ));
    }
    a.warn_at(k, &message);
    Ok(())
}

/// Checks the sub-models of a contact model ([`INCONSISTENT_MODELS`]) that words `from..`
/// of the command gave: an error points at the model's name (or at word `from`).
pub fn check_model(sim: &Sim, a: &Args, from: usize, m: &ContactModel) -> CmdResult {
    if !sim.setup.coarse_graining.active() {
        return Ok(());
    }
    let used = [
        ("model", name_of(NORMAL_MODELS, m.normal)),
        ("cohesion", name_of(COHESION_MODELS, m.cohesion)),
        ("rolling_friction", name_of(ROLLING_MODELS, m.rolling)),
    ];
    for (family, n) in used {
        if INCONSISTENT_MODELS.contains(&n) {
            let k = (from..a.words().len())
                .find(|&k| a.words()[k].text == n)
                .unwrap_or(from);
            check(sim, a, k, &format!("{family} {n}"))?;
        }
    }
    Ok(())
}

/// Scales the stiffness models' tables as LIGGGHTS-PFM does: kn times cg, gamman over
/// cg, gamman_abs times cg² (kt, gammat and gammat_abs as given).
pub fn scale_stiffness(m: &mut rdem::contact::materials::Materials, cg: f64) {
    m.kn.iter_mut().for_each(|v| *v *= cg);
    m.gamman.iter_mut().for_each(|v| *v /= cg);
    m.gamman_abs.iter_mut().for_each(|v| *v *= cg * cg);
}
