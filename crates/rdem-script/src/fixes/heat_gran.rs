//! `fix ID group heat/gran/conduction initial_temperature T0 [contact_area overlap|
//! projection|constant A] [area_correction yes|no] [store_contact_data no]` (and its alias
//! `heat/gran`, which also takes LIGGGHTS 1.x's `heat/gran T0`, with a warning): heat
//! conduction through the contacts, and from walls with a
//! `temperature`, computed by the engine ([`rdem::heat`], which states the model).
//!
//! What the definition brings, as in LIGGGHTS 3.8: the per-particle properties `Temp`
//! (default T0, forwarded to ghosts every step), `heatFlux`, `heatSource` and
//! `directionalHeatFlux` (3 values), each as a `fix property/atom` whose ID is its name,
//! so that `f_Temp`, `f_heatFlux`, `set ... property/atom Temp 350` and the like work. A
//! `fix Temp all property/atom Temp ...` defined before is replaced, its values reset to T0
//! (LIGGGHTS 3.8 does the same: measured, all temperatures T0 after the definition); the
//! same name held by a fix of another ID is an error (LIGGGHTS: "there is already a fix
//! that registers a variable of the same name"). The per-type `thermalConductivity` and
//! `thermalCapacity` (`fix property/global ... peratomtype`) are read when a run starts;
//! `area_correction yes` also reads `youngsModulus`, `poissonsRatio` and
//! `youngsModulusOriginal`.
//!
//! `f_ID` is the thermal energy Σ m c T of *all* particles (LIGGGHTS 3.8's sum runs over
//! every particle whatever the fix's group); `f_ID` per atom (and `f_ID[0]`, LIGGGHTS' old
//! spelling) is the temperature.

use crate::error::Error;
use rdem::heat::{self, ContactArea, HeatConduction, HeatProps};

use super::property_atom::{self, PropertyAtom};
use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

const HELP: &str = "`initial_temperature T0`, `contact_area overlap\\|projection\\|constant A`, `area_correction yes\\|no`, `store_contact_data no`: conduction through the contacts and from walls with a `temperature`; per-type `thermalConductivity`, `thermalCapacity`; `Temp`, `heatFlux`, `heatSource`, `directionalHeatFlux` per particle; `f_ID` the thermal energy Σ m c T";
const NOTES: &str = "an unknown keyword is an error, as in LIGGGHTS 3.8; `store_contact_data yes` is not supported yet; `projection` uses the larger radius, as LIGGGHTS 3.8's code (its manual says the smaller); `unfix` stops conduction and the temperature update (LIGGGHTS keeps integrating the heat sources); with `heat/gran/radiation` defined the temperatures go on";

/// The registry row of `heat/gran/conduction`.
pub(super) const ROW: FixRow = style(
    "heat/gran/conduction",
    parse,
    Stages::PRE_STEP.and(Stages::VALUES),
    HELP,
)
.notes(NOTES);

/// The registry row of the alias `heat/gran`.
pub(super) const ROW_ALIAS: FixRow = style(
    "heat/gran",
    parse,
    Stages::PRE_STEP.and(Stages::VALUES),
    "as `heat/gran/conduction`; also LIGGGHTS 1.x's `heat/gran T0` (with a warning)",
)
.notes("as LIGGGHTS 3.8, the first word after `initial_temperature T0` that is not a keyword ends the line: it and the words after it are ignored, with a warning naming them (`heat/gran/conduction` stops with an error)");

/// The per-particle properties the fix defines: name, number of values, forwarded.
const PROPS: [(&str, usize, bool); 4] = [
    (heat::TEMP, 1, true),
    (heat::HEAT_FLUX, 1, false),
    (heat::HEAT_SOURCE, 1, false),
    (heat::DIRECTIONAL_HEAT_FLUX, 3, false),
];

/// A defined `heat/gran`: the engine's [`HeatConduction`] lives in `World::heat`.
#[derive(Debug)]
pub struct HeatGran {
    /// Initial temperature, as LIGGGHTS passes it on (printed with `%f`).
    pub t0: f64,
    /// Contact area of particle pairs.
    pub area: ContactArea,
    /// `area_correction yes`.
    pub area_correction: bool,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    // LIGGGHTS 1.x: `fix ID group heat/gran T0`, the temperature without its keyword.
    let old = head.style == "heat/gran" && a.peek().and_then(crate::args::parse_f64).is_some();
    if old {
        a.warn_at(
            a.pos(),
            "fix heat/gran T0 is LIGGGHTS 1.x syntax, which LIGGGHTS 3.8 refuses; rdem reads it as 'initial_temperature T0'",
        );
    } else {
        a.keyword("heat/gran keyword", &["initial_temperature"])?;
    }
    let t0 = a.f64("initial temperature T0")?;
    // LIGGGHTS hands T0 on as the text of "%f": six decimals.
    let t0 = format!("{t0:.6}").parse::<f64>().unwrap_or(t0);
    let mut area = ContactArea::Overlap;
    let mut area_correction = false;
    let mut correction_at = None;
    let mut area_at = None;
    const KEYWORDS: [&str; 3] = ["contact_area", "area_correction", "store_contact_data"];
    while let Some(word) = a.peek() {
        // LIGGGHTS 3.8's `heat/gran` stops reading its line at the first word that is not
        // one of its keywords and goes on without it (measured: `initial_temperature 300.
        // 300. contact_area constant 1e-4` conducts as `initial_temperature 300.`);
        // `heat/gran/conduction` stops with "unknown keyword". rdem does the same, and
        // warns about what it ignores.
        if head.style == "heat/gran" && !KEYWORDS.contains(&word) {
            let rest = a.words()[a.pos()..]
                .iter()
                .map(|w| w.text.as_str())
                .collect::<Vec<_>>()
                .join(" ");
            a.warn_at(
                a.pos(),
                &format!(
                    "fix heat/gran: '{word}' is not a heat/gran keyword: '{rest}' is ignored, as LIGGGHTS 3.8 ignores the rest of the line (valid: {})",
                    KEYWORDS.join(", ")
                ),
            );
            break;
        }
        match a.keyword("heat/gran keyword", &KEYWORDS)? {
            "contact_area" => {
                area_at = Some(a.pos());
                area = match a.keyword("contact_area", &["overlap", "projection", "constant"])? {
                    "overlap" => ContactArea::Overlap,
                    "projection" => ContactArea::Projection,
                    _ => ContactArea::Constant(a.positive("contact area")?),
                };
            }
            "area_correction" => {
                correction_at = Some(a.pos());
                area_correction = a.yes_no("area_correction")?;
            }
            _ => {
                if a.yes_no("store_contact_data")? {
                    return Err(a.error_prev(
                        "heat/gran: store_contact_data yes is not supported yet",
                        Some("leave it out (the default is no)".into()),
                    ));
                }
            }
        }
    }
    if area_correction && area != ContactArea::Overlap {
        return Err(a.error_at(
            correction_at.or(area_at).unwrap_or(STYLE_WORD),
            "heat/gran: area_correction works only with contact_area overlap",
            None,
        ));
    }
    // Only one heat conduction per script (a redefinition of the same ID replaces it).
    if w.heat.as_ref().is_some_and(|h| h.conducts) && sim.fix_index(&head.id).is_none() {
        let other = sim
            .defs
            .fixes
            .iter()
            .find(|f| f.downcast::<HeatGran>().is_some())
            .map_or("another fix".to_string(), |f| format!("fix {}", f.id()));
        return Err(a.error_at(
            STYLE_WORD,
            format!("heat/gran: there is already a heat conduction fix ({other})"),
            Some("one heat/gran per script, as LIGGGHTS".into()),
        ));
    }
    // The properties it defines: replaced when a property/atom of the same ID holds them,
    // an error when another fix does; taken over (values kept) when a restart file brought
    // them.
    for (name, _, _) in PROPS {
        if w.particles.property(name).is_none() || sim.defs.restored.props.contains(name) {
            continue;
        }
        let owner = sim
            .defs
            .fixes
            .iter()
            .find(|f| f.downcast::<PropertyAtom>().is_some_and(|p| p.name == name));
        match owner {
            Some(f) if f.id() == name => {}
            Some(f) => {
                return Err(a.error_at(
                    STYLE_WORD,
                    format!("heat/gran defines the per-atom property '{name}' (as fix {name}), but fix {} already holds one of that name", f.id()),
                    Some(format!("name the property/atom fix '{name}' (heat/gran then replaces it) or leave it out")),
                ))
            }
            None => {
                return Err(a.error_at(
                    STYLE_WORD,
                    format!("heat/gran: the per-atom property '{name}' is already used by rdem itself"),
                    None,
                ))
            }
        }
    }
    Ok(Box::new(HeatGran {
        t0,
        area,
        area_correction,
    }))
}

impl ScriptFix for HeatGran {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        // Radiation defined before made the temperatures already (LIGGGHTS' scalar
        // transport equation exists then, and conduction takes it as it is).
        let radiating = sim
            .world_ref(a)?
            .heat
            .as_ref()
            .filter(|h| !h.conducts)
            .map(|h| h.props);
        let props = match radiating {
            Some(props) => props,
            None => define_properties(sim, a, self.t0)?,
        };
        let w = sim.world_mut(a)?;
        let heat = HeatConduction::new(head.groupbit, self.area, props)
            .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))?;
        w.heat = Some(heat);
        Ok(())
    }

    /// At a run's set-up: the per-type tables from the `fix property/global` values.
    fn pre_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if !ctx.setup {
            return Ok(());
        }
        let sim = ctx.view();
        let n = sim.ntypes();
        let k = per_type(sim, "heat/gran", "thermalConductivity", n)?;
        if let Some(bad) = k.iter().find(|k| **k < 0.0) {
            return Err(format!(
                "heat/gran: thermal conductivity must not be < 0 (thermalConductivity has {bad})"
            )
            .into());
        }
        let c = per_type(sim, "heat/gran", "thermalCapacity", n)?;
        let Some(pair) = &ctx.world_ref().pair else {
            return Err("heat/gran needs a granular pair style (pair_style gran ...)".into());
        };
        let ratio = if self.area_correction {
            // The stress–strain exponent of the contact model: δ ~ F^(1/p).
            let p = pair.model.normal.traits().force_exponent;
            let y = per_type(sim, "heat/gran", "youngsModulus", n)?;
            let nu = per_type(sim, "heat/gran", "poissonsRatio", n)?;
            let yo = per_type(sim, "heat/gran", "youngsModulusOriginal", n)?;
            let mut r = Vec::with_capacity(n * n);
            for i in 0..n {
                for j in 0..n {
                    let eff = |y: &[f64]| {
                        1.0 / ((1.0 - nu[i] * nu[i]) / y[i] + (1.0 - nu[j] * nu[j]) / y[j])
                    };
                    r.push((eff(&y) / eff(&yo)).powf(1.0 / p));
                }
            }
            Some(r)
        } else {
            None
        };
        let heat = ctx.world().heat.as_mut().ok_or("heat conduction is gone")?;
        heat.set_coefficients(k, c, ratio)
            .map_err(|e| Error::invalid(format!("heat/gran: {e}")))
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

    /// Conduction stops; with radiation defined the temperatures go on being integrated.
    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            match (&mut w.heat, &w.radiation) {
                (Some(heat), Some(_)) => heat.conducts = false,
                _ => w.heat = None,
            }
        }
    }
}

/// `f_ID` of the heat fixes: the thermal energy Σ m c T of all particles, summed over
/// ranks.
pub(super) fn thermal_energy(sim: &Sim) -> Result<Vec<f64>, Error> {
    let w = sim.world.as_ref().ok_or("no simulation box")?;
    let heat = w.heat.as_ref().ok_or("heat transfer is gone")?;
    Ok(vec![w.comm.sum(heat.thermal_energy(&w.particles))])
}

/// `f_ID` per atom of the heat fixes: the owned particles' temperatures.
pub(super) fn temperatures(sim: &Sim) -> Result<Vec<f64>, Error> {
    let w = sim.world.as_ref().ok_or("no simulation box")?;
    let heat = w.heat.as_ref().ok_or("heat transfer is gone")?;
    let t = &w.particles.props[heat.props.temp.0].data;
    Ok(t[..w.particles.nlocal()].to_vec())
}

/// Defines the per-particle properties of heat transfer (`Temp` at `t0`, `heatFlux`,
/// `heatSource`, `directionalHeatFlux`, each a `fix property/atom` whose ID is its name)
/// and registers them with the engine.
pub(super) fn define_properties(sim: &mut Sim, a: &Args, t0: f64) -> CmdResult<HeatProps> {
    for (name, width, forward) in PROPS {
        let defaults = if name == heat::TEMP {
            vec![t0]
        } else {
            vec![0.0; width]
        };
        property_atom::redefine(
            sim,
            a,
            PropertyAtom {
                name: name.to_string(),
                vector: width > 1,
                defaults,
                forward,
                restart: true,
            },
        )?;
    }
    let w = sim.world_mut(a)?;
    HeatProps::register(&mut w.particles, t0)
        .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))
}

/// The first `n` values of the `peratomtype` property `name`, which fix style `who` needs.
pub(super) fn per_type(sim: &Sim, who: &str, name: &str, n: usize) -> Result<Vec<f64>, Error> {
    let p = sim.defs.properties.get(name).ok_or_else(|| {
        format!("{who} needs 'fix ID all property/global {name} peratomtype' with {n} value(s) (one per atom type)")
    })?;
    if p.style != "peratomtype" || p.values.len() < n {
        return Err(format!(
            "property {name} (fix {}) must be peratomtype with {n} value(s) (one per atom type), not {} with {}",
            p.fix_id,
            p.style,
            p.values.len()
        ).into());
    }
    Ok(p.values[..n].to_vec())
}
