//! `fix ID all heat/gran/radiation initial_temperature T0 [background_temperature T_B]
//! [max_bounces N] cutoff c seed S` (LIGGGHTS-PFM): radiation between the particles and
//! with a background, by Monte Carlo ray tracing, computed by the engine
//! ([`rdem::heat_radiation`], which states the model).
//!
//! As in the fork: the group must be `all`; `cutoff` and `seed` are required (its manual
//! leaves them out, its code stops without them); `background_temperature` defaults to
//! T0 and `max_bounces` to 100; the per-type `thermalEmissivity` (each in [0, 1]) and
//! `thermalCapacity` are read when a run starts. The fix shares `Temp`, `heatFlux` and
//! `heatSource` with `heat/gran/conduction`: defined alone it creates them (`Temp` at T0),
//! and when they exist already (conduction defined before, or unfixed before, as the
//! fork's examples do) the temperatures are kept. With both fixes the two heat flows add
//! up and the temperatures are integrated once, over conduction's group. `f_ID` is the
//! thermal energy Σ m c T, `f_ID` per atom the temperature.

use crate::error::Error;
use rdem::heat::{ContactArea, HeatConduction};
use rdem::heat_radiation::HeatRadiation;

use super::heat_gran::{define_properties, per_type, temperatures, thermal_energy};
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

const HELP: &str = "`initial_temperature T0`, `background_temperature T_B` (default T0), `max_bounces N` (default 100), `cutoff c`, `seed S`: LIGGGHTS-PFM's Monte Carlo radiation, one ray per particle and step; per-type `thermalEmissivity`, `thermalCapacity`; group `all`; `f_ID` the thermal energy Σ m c T";
const NOTES: &str = "rays reach `cutoff` from their origin (the fork's bin walk reaches up to one neighbor stencil further); only owned particles emit (the fork's ghosts emit too); random numbers differ from the fork's, so runs agree with it in the mean, not particle by particle; on MPI ranks `cutoff` plus the largest radius must fit in a subdomain (an error says so)";

/// The registry row of `heat/gran/radiation`.
pub(super) const ROW: FixRow = style(
    "heat/gran/radiation",
    parse,
    Stages::PRE_STEP.and(Stages::VALUES),
    HELP,
)
.notes(NOTES);

/// A defined `heat/gran/radiation`: the engine's [`HeatRadiation`] lives in
/// `World::radiation`.
#[derive(Debug)]
pub struct HeatRadiationFix {
    /// Initial temperature.
    pub t0: f64,
    /// Background temperature (`None`: T0).
    pub background: Option<f64>,
    /// Largest number of reflections of a ray.
    pub max_bounces: u32,
    /// Reach of a ray.
    pub cutoff: f64,
    /// Seed of the random numbers.
    pub seed: u64,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    if a.words().get(2).is_some_and(|g| g.text != "all") {
        return Err(a.error_at(
            2,
            "heat/gran/radiation: the group must be 'all'",
            Some("as in LIGGGHTS-PFM; set the emissivity of a type to 0 to keep its particles out of radiation".into()),
        ));
    }
    a.keyword("heat/gran/radiation keyword", &["initial_temperature"])?;
    let t0 = a.non_negative("initial temperature T0")?;
    let mut background = None;
    let mut max_bounces = 100;
    let mut cutoff = None;
    let mut seed = None;
    const KEYWORDS: [&str; 4] = ["background_temperature", "max_bounces", "cutoff", "seed"];
    while a.peek().is_some() {
        match a.keyword("heat/gran/radiation keyword", &KEYWORDS)? {
            "background_temperature" => {
                background = Some(a.non_negative("background temperature")?)
            }
            "max_bounces" => {
                let n = a.u64("max_bounces")?;
                max_bounces = u32::try_from(n)
                    .map_err(|_| a.error_prev(format!("max_bounces {n} is too large"), None))?;
            }
            "cutoff" => cutoff = Some(a.positive("cutoff")?),
            _ => {
                let s = a.u64("seed")?;
                if s == 0 {
                    return Err(a.error_prev("seed must be a positive integer, not 0", None));
                }
                seed = Some(s);
            }
        }
    }
    let need = |what: &str, example: &str| {
        a.error_at(
            STYLE_WORD,
            format!("heat/gran/radiation needs the keyword '{what}'"),
            Some(format!(
                "add e.g. '{example}' (LIGGGHTS-PFM requires it too)"
            )),
        )
    };
    let cutoff = cutoff.ok_or_else(|| need("cutoff", "cutoff 0.025, the reach of a ray"))?;
    let seed = seed.ok_or_else(|| need("seed", "seed 5335"))?;
    if w.radiation.is_some() && sim.fix_index(&head.id).is_none() {
        return Err(a.error_at(
            STYLE_WORD,
            "heat/gran/radiation: there is already a radiation fix",
            Some("one heat/gran/radiation per script, as LIGGGHTS-PFM".into()),
        ));
    }
    Ok(Box::new(HeatRadiationFix {
        t0,
        background,
        max_bounces,
        cutoff,
        seed,
    }))
}

impl ScriptFix for HeatRadiationFix {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        // Temperatures that exist (from conduction, defined or unfixed before) are kept.
        // (A redefinition of this fix's ID was unfixed before this install.)
        let props = match sim.world_ref(a)?.heat.as_ref().map(|h| h.props) {
            Some(p) => p,
            None if sim
                .world_ref(a)?
                .particles
                .property(rdem::heat::TEMP)
                .is_some() =>
            {
                let w = sim.world_mut(a)?;
                rdem::heat::HeatProps::register(&mut w.particles, self.t0)
                    .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))?
            }
            None => define_properties(sim, a, self.t0)?,
        };
        let w = sim.world_mut(a)?;
        if w.heat.is_none() {
            let mut heat = HeatConduction::new(head.groupbit, ContactArea::Overlap, props)
                .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))?;
            heat.conducts = false;
            w.heat = Some(heat);
        }
        let rank = w.comm.rank();
        let rad = HeatRadiation::new(
            self.background.unwrap_or(self.t0),
            self.max_bounces,
            self.cutoff,
            self.seed,
            rank,
        )
        .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))?;
        w.radiation = Some(rad);
        Ok(())
    }

    /// At a run's set-up: the emissivities, and the capacities when no conduction reads
    /// them.
    fn pre_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if !ctx.setup {
            return Ok(());
        }
        let sim = ctx.view();
        let n = sim.ntypes();
        let eps = per_type(sim, "heat/gran/radiation", "thermalEmissivity", n)?;
        let alone = ctx.world_ref().heat.as_ref().is_some_and(|h| !h.conducts);
        let capacity = if alone {
            Some(per_type(
                ctx.view(),
                "heat/gran/radiation",
                "thermalCapacity",
                n,
            )?)
        } else {
            None
        };
        if ctx.world_ref().pair.is_none() {
            return Err(
                "heat/gran/radiation needs a granular pair style (pair_style gran ...)".into(),
            );
        }
        let w = ctx.world();
        let rad = w.radiation.as_mut().ok_or("heat radiation is gone")?;
        rad.set_emissivity(eps)
            .map_err(|e| Error::invalid(format!("heat/gran/radiation: {e}")))?;
        if let Some(c) = capacity {
            let heat = w.heat.as_mut().ok_or("heat integration is gone")?;
            heat.set_coefficients(vec![0.0; n], c, None)
                .map_err(|e| Error::invalid(format!("heat/gran/radiation: {e}")))?;
        }
        Ok(())
    }

    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        thermal_energy(sim)
    }

    /// One value per atom (the temperature), at every step.
    fn peratom_shape(&self) -> Option<(usize, u64)> {
        Some((0, 1))
    }

    fn peratom(&self, sim: &Sim, _head: &FixHead, _col: Option<usize>) -> Result<Vec<f64>, Error> {
        temperatures(sim)
    }

    /// Radiation stops; the temperatures go on being integrated only with conduction.
    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.radiation = None;
            if w.heat.as_ref().is_some_and(|h| !h.conducts) {
                w.heat = None;
            }
        }
    }
}
