//! `fix ID group property/atom NAME scalar|vector restart ghost reverse defaults...`: a
//! named per-particle value (or vector of values) held by the engine's particle container
//! ([`rdem::Particles::add_property`]), so that it moves with its particle through
//! re-neighboring, sorting, removal and migration between ranks, and engine code (heat
//! transfer, for one) finds it by name. Existing and new particles get the defaults;
//! `set ... property/atom NAME values` changes them; `f_ID` (scalar) and `f_ID[i]` (vector)
//! read them in atom-style variables, dumps and `compute reduce`.
//!
//! As the LIGGGHTS manual says, the fix applies to all particles whatever its group. The
//! three yes/no flags (restart, forward and reverse ghost communication) are read and
//! checked: values of particles read from a restart file are kept with `restart yes` and
//! set to the defaults with `no`; ghosts carry the values when they are made, and
//! with the second flag `yes` forward communication refreshes them every step too (as
//! LIGGGHTS does for a temperature that pair computations read on ghosts).

use super::{count_error, style, FixEntry, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "property/atom",
    parse,
    Stages::NONE,
    "`NAME scalar\\|vector yes\\|no yes\\|no yes\\|no defaults...`: named per-particle values (`set property/atom`, `f_ID`, `f_ID[i]`)",
)
.notes("applies to all particles (as LIGGGHTS); values come back from restart files with the restart flag `yes`; `set` needs no `run 0` after it (LIGGGHTS 3.8 asks for one)");

/// A defined per-particle property: its values live in the world's particles under `name`.
#[derive(Debug)]
pub struct PropertyAtom {
    /// The property's name in the particle container.
    pub name: String,
    /// `true` for style `vector` (`f_ID[i]`), `false` for `scalar` (`f_ID`).
    pub vector: bool,
    /// Values given to existing and new particles.
    pub defaults: Vec<f64>,
    /// Ghost values refreshed every step (the `comm_ghost_value` flag).
    pub forward: bool,
    /// Values taken back from a restart file (the `restart` flag): with `no`, particles
    /// read from a restart file get the defaults again.
    pub restart: bool,
}

impl ScriptFix for PropertyAtom {
    fn install(&mut self, sim: &mut Sim, a: &Args, head: &FixHead) -> CmdResult<()> {
        let restored = sim.defs.restored.props.remove(&self.name);
        let from_liggghts = sim.defs.restored.peratom.remove(&head.id);
        let p = &mut sim.world_mut(a)?.particles;
        let id = p
            .add_property(&self.name, self.defaults.len(), &self.defaults)
            .map_err(|e| a.error_at(4, e.to_string(), None))?;
        if restored && !self.restart {
            let prop = &mut p.props[id.0];
            for c in prop.data.chunks_exact_mut(self.defaults.len()) {
                c.copy_from_slice(&self.defaults);
            }
        }
        if let Some(v) = from_liggghts.filter(|_| self.restart) {
            // A LIGGGHTS restart file's values for the fix of this ID, by tag (as
            // LIGGGHTS gives a fix defined again with its ID its per-atom state).
            let width = self.defaults.len();
            if v.width != width {
                return Err(a.error_at(
                    4,
                    format!(
                        "the LIGGGHTS restart file holds {} value(s) per particle for fix {}, this definition {width}",
                        v.width, head.id
                    ),
                    None,
                ));
            }
            for i in 0..p.nlocal() {
                if let Some(vals) = v.of(p.tag[i]) {
                    p.props[id.0].get_mut(i).copy_from_slice(vals);
                }
            }
        }
        if self.forward {
            p.set_forward(id);
        }
        Ok(())
    }

    /// One column (`f_ID`) or one per default (`f_ID[i]`), valid at every step.
    fn peratom_shape(&self) -> Option<(usize, u64)> {
        Some((if self.vector { self.defaults.len() } else { 0 }, 1))
    }

    fn peratom(&self, sim: &Sim, _head: &FixHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or("no simulation box")?;
        let p = &w.particles;
        let id = p
            .property(&self.name)
            .ok_or_else(|| format!("per-atom property '{}' is gone", self.name))?;
        let prop = &p.props[id.0];
        let k = col.map_or(0, |c| c - 1);
        Ok((0..p.nlocal()).map(|i| prop.get(i)[k]).collect())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&self.name);
        }
    }
}

/// Adds the per-particle property `name` (`width` values, 0 for every particle) in which
/// a fix keeps its own values (tracer markers, residence times, stored states), or takes
/// it back as a restart file left it: true in that case.
pub(super) fn fix_values(sim: &mut Sim, a: &Args, name: &str, width: usize) -> CmdResult<bool> {
    let restored = sim.defs.restored.props.remove(name);
    sim.world_mut(a)?
        .particles
        .add_property(name, width, &vec![0.0; width])
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(restored)
}

/// Defines `imp` as the fix `NAME all property/atom NAME ...` (fix ID = property name)
/// that another command brings along: heat/gran's `Temp`, a wall's `force_ID`,
/// couple/cfd's `dragforce`. Its origin is that command's style word.
pub(super) fn define(sim: &mut Sim, a: &Args, mut imp: PropertyAtom) -> CmdResult<()> {
    let head = FixHead {
        id: imp.name.clone(),
        style: "property/atom",
        groupbit: 1,
    };
    imp.install(sim, a, &head)?;
    let origin = sim.origin(a, STYLE_WORD);
    sim.defs.fixes.push(FixEntry {
        head,
        stages: Stages::NONE,
        origin,
        energy: false,
        imp: Box::new(imp),
        seconds: 0.0,
    });
    Ok(())
}

/// [`define`], replacing a `fix property/atom` of that ID the script defined first (as
/// LIGGGHTS lets heat/gran and couple/cfd take over the user's definition).
pub(super) fn redefine(sim: &mut Sim, a: &Args, imp: PropertyAtom) -> CmdResult<()> {
    let name = imp.name.as_str();
    if sim
        .fix_index(name)
        .is_some_and(|k| sim.defs.fixes[k].downcast::<PropertyAtom>().is_some())
    {
        super::unfix_id(sim, name);
    }
    define(sim, a, imp)
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    let name = a.word("property name")?.to_string();
    // A name another definition holds (a different fix, or a property of the engine's
    // own) is an error; the fix being redefined gives its name up first.
    let mine = sim.fix_index(&head.id).is_some_and(|k| {
        sim.defs.fixes[k]
            .downcast::<PropertyAtom>()
            .is_some_and(|f| f.name == name)
    });
    let restored = sim.defs.restored.props.contains(&name);
    if !mine && !restored && w.particles.property(&name).is_some() {
        let owner = sim
            .defs
            .fixes
            .iter()
            .find(|f| f.downcast::<PropertyAtom>().is_some_and(|p| p.name == name))
            .map(|f| format!("fix {}", f.id()));
        return Err(a.error_prev(
            format!(
                "per-atom property '{name}' already exists ({})",
                owner.unwrap_or_else(|| "used by rdem itself".into())
            ),
            Some("pick another name".into()),
        ));
    }
    let vector = a.keyword("property/atom style", &["scalar", "vector"])? == "vector";
    let restart = a.yes_no("restart value (yes or no)")?;
    let forward = a.yes_no("communicate ghost value (yes or no)")?;
    a.yes_no("communicate reverse ghost value (yes or no)")?;
    let start = a.pos();
    let mut defaults = Vec::new();
    while !a.is_done() {
        defaults.push(a.f64(&format!("{name} default value"))?);
    }
    if defaults.is_empty() {
        return Err(a.error_at(
            a.pos(),
            format!("fix property/atom: missing the default value(s) of '{name}'"),
            Some("scalar takes one default value, vector one per component".into()),
        ));
    }
    if !vector && defaults.len() != 1 {
        return Err(count_error(
            a,
            start,
            1,
            defaults.len(),
            format!(
                "{name} scalar takes one default value, got {}",
                defaults.len()
            ),
            "use 'vector' for several values per particle".into(),
        ));
    }
    Ok(Box::new(PropertyAtom {
        name,
        vector,
        defaults,
        forward,
        restart,
    }))
}
