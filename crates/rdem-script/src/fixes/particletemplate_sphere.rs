//! `fix ID all particletemplate/sphere seed atom_type T density constant RHO radius ...`:
//! a particle template that distributions and insertion fixes draw from.

use rdem::insert::{ParticleTemplate, RadiusDist};

use super::{style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "particletemplate/sphere",
    parse,
    Stages::NONE,
    "`atom_type`, `density constant`, `radius constant R`, `uniform [number] RMIN RMAX`, `gaussian MU SIGMA` (redrawn until positive), the forks' `gaussian number MU SIGMA` and `lognormal number MU SIGMA` (drawn within 3 standard deviations, of ln r for lognormal)",
)
.atoi();

/// A defined template: it lives in `Sim::templates` under the fix ID.
pub struct Template {
    parsed: Option<ParticleTemplate>,
}

impl ScriptFix for Template {
    fn install(&mut self, sim: &mut Sim, _a: &Args, head: &FixHead) -> CmdResult<()> {
        if let Some(t) = self.parsed.take() {
            sim.defs.templates.insert(head.id.clone(), t);
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, head: &FixHead) {
        sim.defs.templates.remove(&head.id);
    }
}

/// A template's `atom_type T` (the word after the keyword): a type of the box.
pub(super) fn atom_type(sim: &Sim, a: &mut Args) -> CmdResult<u32> {
    let t = a.count("atom type")?;
    if sim.ntypes() > 0 && t as usize > sim.ntypes() {
        return Err(a.error_prev(
            format!(
                "atom type {t} is larger than the box's {} type(s)",
                sim.ntypes()
            ),
            None,
        ));
    }
    Ok(t as u32)
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    // LIGGGHTS 3.8 stops too: "this fix is for 3D simulations only".
    if sim.setup.dimension == 2 {
        return Err(a.error_at(
            super::STYLE_WORD,
            "particletemplate/sphere is for 3d simulations only",
            Some("in 2d, place particles with create_atoms or read_data".into()),
        ));
    }
    let id = head.id.as_str();
    let seed = a.seed()?;
    let (mut ty, mut density, mut radius) = (1u32, None, None);
    let mut radius_at = 0;
    while !a.is_done() {
        match a.keyword(
            "particletemplate/sphere keyword",
            &["atom_type", "density", "radius", "volume_limit", "relative"],
        )? {
            "atom_type" => ty = atom_type(sim, a)?,
            "density" => {
                a.keyword("density distribution", &["constant"])?;
                density = Some(a.positive("density")?);
            }
            "radius" => {
                radius_at = a.pos();
                let style = a.keyword(
                    "radius distribution",
                    &["constant", "uniform", "gaussian", "lognormal"],
                )?;
                // The forks' forms name what the distribution counts: `number` (as
                // rdem's own forms) or `mass`, which LIGGGHTS-PFM and -INL stop on too.
                let forks = style != "constant" && matches!(a.peek(), Some("number" | "mass"));
                if forks && a.keyword("distribution basis", &["number", "mass"])? == "mass" {
                    return Err(a.error_prev(
                        format!("radius {style} mass: a mass-based radius distribution is not supported"),
                        Some(format!(
                            "write 'radius {style} number ...' (LIGGGHTS-PFM stops on 'mass' too: \"mass distribution not implemented\")"
                        )),
                    ));
                }
                radius = Some(match style {
                    "constant" => RadiusDist::Constant(a.positive("radius")?),
                    "uniform" => RadiusDist::Uniform(
                        a.positive("smallest radius")?,
                        a.positive("largest radius")?,
                    ),
                    "gaussian" if forks => RadiusDist::GaussianWithin3(
                        a.positive("mean radius")?,
                        a.non_negative("radius standard deviation")?,
                    ),
                    "gaussian" => RadiusDist::Gaussian(
                        a.positive("mean radius")?,
                        a.non_negative("radius standard deviation")?,
                    ),
                    _ if forks => RadiusDist::Lognormal(
                        a.f64("mean of the log of the radius")?,
                        a.non_negative("standard deviation of the log of the radius")?,
                    ),
                    _ => {
                        return Err(a.error_prev(
                            "radius lognormal takes 'number mu sigma' (the forks' form)",
                            Some(
                                "write 'radius lognormal number MU SIGMA' (mu, sigma of ln r)"
                                    .into(),
                            ),
                        ))
                    }
                });
            }
            "volume_limit" => {
                a.positive("volume limit")?;
            }
            _ => {
                if a.yes_no("relative")? {
                    return Err(a.error_prev(
                        "a sphere template cannot be relative",
                        Some("relative templates are the fragments of fix insert/fragments: define them with particletemplate/multiplespheres".into()),
                    ));
                }
            }
        }
    }
    let density = density.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "particletemplate/sphere needs a density",
            Some("add 'density constant RHO' (kg/m^3)".into()),
        )
    })?;
    let radius = radius
        .map(|r| coarse_grained(sim, a, radius_at, r))
        .transpose()?;
    let radius = radius.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "particletemplate/sphere needs a radius",
            Some("add 'radius constant R' (m), or 'radius uniform RMIN RMAX'".into()),
        )
    })?;
    let mut t = ParticleTemplate::new(id, seed, ty, density, radius)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    // Inserted spheres join the template's group too, as in LIGGGHTS 3.8.
    t.groupbit = head.groupbit;
    Ok(Box::new(Template { parsed: Some(t) }))
}

/// The radius under LIGGGHTS-PFM's coarse graining: a constant radius times the factor; a
/// distribution is an error there, whatever `model_check` says (word `at`: its style).
fn coarse_grained(sim: &Sim, a: &Args, at: usize, r: RadiusDist) -> CmdResult<RadiusDist> {
    let cg = sim.setup.coarse_graining;
    if !cg.active() {
        return Ok(r);
    }
    match r {
        RadiusDist::Constant(v) => Ok(RadiusDist::Constant(v * cg.factor)),
        _ => Err(a.error_at(
            at,
            format!(
                "a radius distribution cannot be coarse grained (coarsegraining {})",
                cg.factor
            ),
            Some("use 'radius constant R' with coarsegraining, as LIGGGHTS-PFM requires".into()),
        )),
    }
}
