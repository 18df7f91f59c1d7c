//! The `fix` command: every style of SPEC §2 that is not a mesh or a bond. Engine fixes
//! (integration, forces, walls) go to `World::fixes`; the others live here with the hooks
//! the run loop calls: insertion and `adapt` before a step, `check/timestep/gran` and
//! `ave/time` after it.

use glam::DVec3;
use rdem::insert::{
    Distribution, InsertPack, PackTarget, ParticleTemplate, RadiusDist, VelocityLaw, Weighting,
};
use rdem::{Fix, FixKind, PrimitiveWall, WallShape};

use crate::args::{suggest, Args, CmdResult};
use crate::diagnostic::one_of;
use crate::models;
use crate::sim::{FixEntry, Property, Sim};
use crate::variables::format_g;

/// Fix styles rdem runs.
pub const STYLES: [&str; 25] = [
    "property/global",
    "mesh/surface",
    "mesh/surface/stress",
    "mesh/surface/planar",
    "particletemplate/sphere",
    "particledistribution/discrete",
    "particledistribution/discrete/massbased",
    "particledistribution/discrete/numberbased",
    "insert/pack",
    "insert/rate/region",
    "insert/stream",
    "massflow/mesh",
    "move/mesh",
    "nve/sphere",
    "gravity",
    "freeze",
    "viscous",
    "addforce",
    "setforce",
    "wall/gran",
    "adapt",
    "check/timestep/gran",
    "ave/time",
    "property/atom",
    "ave/euler",
];

/// LIGGGHTS fix styles that are part of rdem's scope but not of this release.
const LATER: [(&str, &str); 3] = [
    ("bond/gran", "bonds"),
    ("wall/gran/hooke/history", "old-style wall models"),
    ("particletemplate/multisphere", "multisphere particles"),
];

/// Index of the style word in `fix ID group style ...` (errors about the whole fix point
/// at it).
const STYLE_WORD: usize = 3;

/// The engine part of an insertion fix.
pub enum InsertEngine {
    /// `insert/pack`, `insert/rate/region`.
    Pack(InsertPack),
    /// `insert/stream`.
    Stream(rdem::insert::InsertStream),
}

impl InsertEngine {
    /// True if an insertion is due at `step`.
    pub fn due(&self, step: u64) -> bool {
        match self {
            Self::Pack(p) => p.due(step),
            Self::Stream(s) => s.due(step),
        }
    }
}

/// Insertion bookkeeping shared by the insertion fixes.
pub struct Inserter {
    /// Engine insertion (placement rules, generator, state).
    pub pack: InsertEngine,
    /// Particles inserted so far.
    pub total: u64,
    /// Their mass.
    pub total_mass: f64,
    /// `insert/rate/region`: particles per insertion (fractional, accumulated).
    pub rate: Option<RateState>,
    /// `verbose yes`.
    pub verbose: bool,
}

/// State of `insert/rate/region`.
pub struct RateState {
    /// Particles to insert in all (`None`: no limit).
    pub limit: Option<u64>,
    /// Particles per insertion (may be fractional).
    pub per_insertion: f64,
    /// Fractional carry.
    pub carry: f64,
}

/// `fix adapt N atom diameter v_name`.
pub struct Adapt {
    /// Every this many steps.
    pub every: u64,
    /// Atom-style variable giving the new diameter.
    pub var: String,
    /// `reset yes`: radii restored when the run ends.
    pub reset: bool,
    /// Radii at the start of the run (for reset).
    pub saved: Option<Vec<(u64, f64)>>,
}

/// `fix check/timestep/gran`.
pub struct CheckTimestep {
    /// Every this many steps.
    pub every: u64,
    /// Warn above this fraction of the Rayleigh time.
    pub fraction_r: f64,
    /// Warn above this fraction of the Hertz time.
    pub fraction_h: f64,
    /// `warn yes`.
    pub warn: bool,
    /// `error yes`.
    pub error: bool,
    /// `vmax`: least velocity for the Hertz estimate.
    pub vmax: f64,
    /// Last values: dt / Rayleigh time, dt / Hertz time.
    pub values: [f64; 2],
}

/// `fix ave/time` (scalar mode).
pub struct AveTime {
    /// Sample every.
    pub nevery: u64,
    /// Samples per average.
    pub nrepeat: u64,
    /// Output every.
    pub nfreq: u64,
    /// Inputs (`c_ID`, `c_ID[i]`, `f_ID[i]`, `v_name`).
    pub inputs: Vec<String>,
    /// `ave running`.
    pub running: bool,
    /// Output file.
    pub file: Option<std::io::BufWriter<std::fs::File>>,
    /// Sums of the current window.
    pub sum: Vec<f64>,
    /// Samples in the window.
    pub count: u64,
    /// Last finished averages.
    pub values: Vec<f64>,
    /// Running totals (for `ave running`).
    pub running_sum: Vec<f64>,
    /// Number of finished windows.
    pub windows: u64,
}

/// `fix ave/euler nevery N cell_size_relative c parallel yes|no [basevolume_region R]`:
/// cell averages on a regular grid ([`rdem::euler`]), computed at the end of every
/// `nevery`-th step (and at a run's set-up) for `dump euler/vtk`.
pub struct AveEuler {
    /// Compute every this many steps.
    pub nevery: u64,
    /// Cell size in multiples of the largest particle diameter.
    pub cell_size_relative: f64,
    /// `parallel yes|no` (with one process both give the same grid over the whole box).
    pub parallel: bool,
    /// `basevolume_region`: the cells' volumes are their parts inside this region.
    pub base_region: Option<(String, rdem::region::Region)>,
    /// Base volumes cached for a grid.
    pub base_volumes: Option<(rdem::euler::EulerGrid, Vec<f64>)>,
    /// The last result (`None` until the first evaluation).
    pub cells: Option<rdem::euler::EulerCells>,
    /// Step of the last result.
    pub step: u64,
}

/// `fix massflow/mesh`: the engine's counter and the output rates.
pub struct MassFlowFix {
    /// Totals and settings.
    pub flow: rdem::massflow::MassFlow,
    /// (step, mass, count) when the rates were last evaluated (`None`: the run start).
    pub last: std::cell::Cell<Option<(u64, f64, u64)>>,
    /// (step, mass rate, number rate) of the last evaluation.
    pub rates: std::cell::Cell<(u64, f64, f64)>,
}

impl MassFlowFix {
    /// `f_ID[1..6]`: mass, count, mass rate and number rate since the last evaluation
    /// at an earlier step (the previous thermo output), deleted mass and count.
    fn values(&self, step: u64, dt: f64) -> [f64; 6] {
        let f = &self.flow;
        let (s, mr, nr) = self.rates.get();
        let (mr, nr) = if s == step {
            (mr, nr)
        } else {
            let (s0, m0, c0) = self.last.get().unwrap_or((0, 0.0, 0));
            let t = step.saturating_sub(s0) as f64 * dt;
            let r = if t > 0.0 {
                ((f.mass - m0) / t, (f.count - c0) as f64 / t)
            } else {
                (0.0, 0.0)
            };
            self.last.set(Some((step, f.mass, f.count)));
            self.rates.set((step, r.0, r.1));
            r
        };
        [
            f.mass,
            f.count as f64,
            mr,
            nr,
            f.deleted_mass,
            f.deleted as f64,
        ]
    }
}

/// Front-end part of a fix.
pub enum FrontFix {
    /// `move/mesh` on the world's mesh of this index (the motion lives in the mesh).
    MeshMove(usize),
    /// `massflow/mesh`.
    MassFlow(Box<MassFlowFix>),
    /// `mesh/surface`: a mesh (in `World::meshes` under the fix ID) that `wall/gran ...
    /// mesh` walls, mesh motions, insertion faces and mesh dumps use.
    Mesh,
    /// The fix lives in `World::fixes` under the same ID.
    Engine,
    /// `property/global` (the values are in `Sim::properties`).
    Property(String),
    /// `particletemplate/sphere` (in `Sim::templates`).
    Template,
    /// `particledistribution/discrete` (in `Sim::distributions`).
    Distribution,
    /// `insert/pack`, `insert/rate/region`.
    Insert(Box<Inserter>),
    /// `adapt`.
    Adapt(Adapt),
    /// `check/timestep/gran`.
    CheckTimestep(CheckTimestep),
    /// `ave/time`.
    AveTime(Box<AveTime>),
    /// `ave/euler`.
    AveEuler(Box<AveEuler>),
}

/// Value `f_ID` / `f_ID[i]` (1-based).
pub fn fix_value(sim: &Sim, id: &str, idx: Option<usize>) -> Result<f64, String> {
    let f = sim
        .fixes
        .iter()
        .find(|f| f.id == id)
        .ok_or_else(|| format!("no fix '{id}'"))?;
    let pick = |v: &[f64]| -> Result<f64, String> {
        match idx {
            Some(k) if k >= 1 && k <= v.len() => Ok(v[k - 1]),
            None if v.len() == 1 => Ok(v[0]),
            _ => Err(format!(
                "fix {id} gives {} value(s): use f_{id}[1..{}]",
                v.len(),
                v.len()
            )),
        }
    };
    match &f.kind {
        FrontFix::CheckTimestep(c) => pick(&c.values),
        FrontFix::AveTime(a) => pick(&a.values),
        FrontFix::Insert(ins) => pick(&[ins.total as f64, ins.total_mass]),
        FrontFix::Mesh => {
            let w = sim.world.as_ref().ok_or("no simulation box")?;
            let st = w
                .mesh_index(id)
                .and_then(|k| w.meshes[k].stress.as_ref())
                .ok_or_else(|| format!("fix {id} ({}) computes no global values", f.style))?;
            let (fo, to, r) = (st.total_force, st.total_torque, st.reference_point);
            pick(&[fo.x, fo.y, fo.z, to.x, to.y, to.z, r.x, r.y, r.z])
        }
        FrontFix::MassFlow(mf) => {
            let w = sim.world.as_ref().ok_or("no simulation box")?;
            pick(&mf.values(w.step, w.dt))
        }
        FrontFix::Property(name) => {
            let p = &sim.properties[name];
            pick(&p.values)
        }
        _ => Err(format!("fix {id} ({}) computes no global values", f.style)),
    }
}

/// `fix ID group style args...`.
pub fn fix(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("fix ID")?.to_string();
    if let Some(k) = sim.fix_index(&id) {
        // LIGGGHTS replaces a fix of the same ID and style; a different style is an error.
        let style = a.words().get(3).map(|w| w.text.as_str()).unwrap_or("");
        if sim.fixes[k].style != style {
            return Err(a.error_prev(
                format!(
                    "fix ID '{id}' is already used by a {} fix",
                    sim.fixes[k].style
                ),
                Some("unfix it first or pick another ID".into()),
            ));
        }
        unfix_id(sim, &id);
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let style_word = a.word("fix style")?;
    let Some(style) = STYLES.iter().copied().find(|s| *s == style_word) else {
        if let Some((_, what)) = LATER.iter().find(|(s, _)| *s == style_word) {
            return Err(a.error_prev(
                format!("fix {style_word} ({what}) is not supported by this rdem release yet"),
                Some(format!("supported fix styles: {}", STYLES.join(", "))),
            ));
        }
        return Err(a.error_prev(
            format!("unknown fix style '{style_word}'"),
            Some(suggest(style_word, &STYLES)),
        ));
    };
    let kind = match style {
        "property/global" => property_global(sim, a, &id)?,
        "property/atom" => {
            return Err(a.error_prev(
                "fix property/atom is not supported by this rdem release yet",
                None,
            ))
        }
        "particletemplate/sphere" => template(sim, a, &id)?,
        s if s.starts_with("particledistribution/discrete") => distribution(sim, a, &id, s)?,
        "insert/pack" | "insert/rate/region" | "insert/stream" => {
            insert(sim, a, &id, groupbit, style)?
        }
        "massflow/mesh" => massflow(sim, a, &id, groupbit)?,
        "move/mesh" => move_mesh(sim, a, &id)?,
        "mesh/surface" | "mesh/surface/stress" | "mesh/surface/planar" => {
            let mesh = mesh_surface(sim, a, &id, style)?;
            sim.world_mut(a)?.add_mesh(mesh);
            FrontFix::Mesh
        }
        "wall/gran" => match wall_gran(sim, a, &id)? {
            Wall::Primitive(wall) => {
                engine_fix(sim, a, &id, groupbit, FixKind::WallGran(Box::new(wall)))?
            }
            Wall::Mesh(wall) => {
                engine_fix(sim, a, &id, groupbit, FixKind::MeshWall(Box::new(wall)))?
            }
        },
        "nve/sphere" => {
            if !a.is_done() {
                let w = a.word("")?;
                return Err(a.error_prev(
                    format!("nve/sphere: unexpected argument '{w}'"),
                    Some("rdem's nve/sphere takes no options".into()),
                ));
            }
            engine_fix(sim, a, &id, groupbit, FixKind::NveSphere)?
        }
        "gravity" => {
            let g = a.f64("gravity magnitude")?;
            let how = a.keyword("gravity direction style", &["vector"])?;
            debug_assert_eq!(how, "vector");
            let d = a.vec3("gravity vector")?;
            a.done()?;
            let fix =
                Fix::gravity(&id, groupbit, g, d).map_err(|e| a.error_cmd(e.to_string(), None))?;
            add_engine(sim, a, fix)?
        }
        "freeze" => {
            a.done()?;
            engine_fix(sim, a, &id, groupbit, FixKind::Freeze)?
        }
        "viscous" => {
            let gamma = a.non_negative("damping coefficient gamma")?;
            a.done()?;
            engine_fix(sim, a, &id, groupbit, FixKind::Viscous { gamma })?
        }
        "addforce" => {
            let mut v = [0.0; 3];
            for (k, c) in v.iter_mut().enumerate() {
                let w = a.word(["fx", "fy", "fz"][k])?;
                if w.starts_with("v_") {
                    return Err(a.error_prev(
                        "addforce with variables is not supported yet; give numbers",
                        None,
                    ));
                }
                a.seek(a.pos() - 1);
                *c = a.f64(["fx", "fy", "fz"][k])?;
            }
            a.done()?;
            let force = DVec3::from_array(v);
            engine_fix(sim, a, &id, groupbit, FixKind::AddForce { force })?
        }
        "setforce" => {
            let mut v = [None; 3];
            for (k, c) in v.iter_mut().enumerate() {
                let what = ["fx", "fy", "fz"][k];
                if a.peek() == Some("NULL") {
                    a.seek(a.pos() + 1);
                } else {
                    *c = Some(a.f64(&format!("{what} (a number or NULL)"))?);
                }
            }
            a.done()?;
            engine_fix(sim, a, &id, groupbit, FixKind::SetForce { force: v })?
        }
        "adapt" => adapt(sim, a)?,
        "check/timestep/gran" => check_timestep(a)?,
        "ave/time" => ave_time(sim, a)?,
        "ave/euler" => ave_euler(sim, a, &id)?,
        _ => unreachable!("every style in STYLES is handled"),
    };
    sim.fixes.push(FixEntry {
        id,
        style: style.to_string(),
        groupbit,
        kind,
    });
    Ok(())
}

/// Refuses to remove a `move/mesh` fix that is not the last one of its mesh (LIGGGHTS'
/// rule: superposed motions go in reverse order).
pub fn check_unfix(sim: &Sim, id: &str) -> Result<(), String> {
    let Some(k) = sim.fix_index(id) else {
        return Ok(());
    };
    if let (FrontFix::MeshMove(m), Some(w)) = (&sim.fixes[k].kind, &sim.world) {
        let movers = &w.meshes[*m].motion.movers;
        if let Some(last) = movers.last() {
            if last.0 != id && movers.iter().any(|x| x.0 == id) {
                return Err(format!(
                    "move/mesh fixes of mesh {} must be removed in reverse order: unfix {} first",
                    w.meshes[*m].id, last.0
                ));
            }
        }
    }
    Ok(())
}

/// Removes fix `id` (front end and engine); false if there was none.
pub fn unfix_id(sim: &mut Sim, id: &str) -> bool {
    let Some(k) = sim.fix_index(id) else {
        return false;
    };
    let f = sim.fixes.remove(k);
    match f.kind {
        FrontFix::MeshMove(m) => {
            if let Some(w) = &mut sim.world {
                let t = w.step as f64 * w.dt;
                // The order was checked (check_unfix); a redefinition removes the last.
                let _ = w.meshes[m].motion.remove(id, t);
            }
        }
        FrontFix::Engine => {
            if let Some(w) = &mut sim.world {
                w.remove_fix(id);
            }
        }
        FrontFix::Property(name) => {
            sim.properties.remove(&name);
        }
        FrontFix::Template => {
            sim.templates.remove(id);
        }
        FrontFix::Distribution => {
            sim.distributions.remove(id);
        }
        _ => {}
    }
    true
}

fn engine_fix(
    sim: &mut Sim,
    a: &Args,
    id: &str,
    groupbit: u32,
    kind: FixKind,
) -> CmdResult<FrontFix> {
    let fix = Fix::new(id, groupbit, kind).map_err(|e| a.error_cmd(e.to_string(), None))?;
    add_engine(sim, a, fix)
}

fn add_engine(sim: &mut Sim, a: &Args, fix: Fix) -> CmdResult<FrontFix> {
    let w = sim.world_mut(a)?;
    w.add_fix(fix)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    Ok(FrontFix::Engine)
}

fn property_global(sim: &mut Sim, a: &mut Args, id: &str) -> CmdResult<FrontFix> {
    let name = a.word("property name")?.to_string();
    let style = a.keyword(
        "property style",
        &[
            "scalar",
            "vector",
            "peratomtype",
            "peratomtypepair",
            "matrix",
            "atomtype",
            "atomtypepair",
        ],
    )?;
    let style = match style {
        "atomtype" => "peratomtype",
        "atomtypepair" => "peratomtypepair",
        s => s,
    };
    let mut values = Vec::new();
    if style == "peratomtypepair" || style == "matrix" {
        let n = a.count("number of atom types")? as usize;
        if style == "peratomtypepair" && sim.ntypes > 0 && n != sim.ntypes {
            return Err(a.error_prev(
                format!("{name}: {n} types given but the box has {}", sim.ntypes),
                None,
            ));
        }
        let start = a.pos();
        while !a.is_done() {
            values.push(a.f64(&format!("{name} value"))?);
        }
        if style == "peratomtypepair" && values.len() != n * n {
            return Err(count_error(
                a,
                start,
                n * n,
                values.len(),
                format!(
                    "{name} peratomtypepair {n} needs {}, got {}",
                    plural(n * n, "value"),
                    values.len()
                ),
                format!(
                    "peratomtypepair N takes N*N values, one per pair of atom types ({}*{} = {})",
                    n,
                    n,
                    n * n
                ),
            ));
        }
    } else {
        let start = a.pos();
        while !a.is_done() {
            values.push(a.f64(&format!("{name} value"))?);
        }
        if values.is_empty() {
            return Err(a.error_at(a.pos(), format!("{name}: no values given"), None));
        }
        if style == "scalar" && values.len() != 1 {
            return Err(count_error(
                a,
                start,
                1,
                values.len(),
                format!("{name} scalar takes one value, got {}", values.len()),
                "use 'vector' for several values".into(),
            ));
        }
        if style == "peratomtype" && sim.ntypes > 0 && values.len() != sim.ntypes {
            return Err(count_error(
                a,
                start,
                sim.ntypes,
                values.len(),
                format!(
                    "{name}: {} given but the box has {}",
                    plural(values.len(), "value"),
                    plural(sim.ntypes, "atom type")
                ),
                "peratomtype takes one value per atom type".into(),
            ));
        }
    }
    sim.properties.insert(
        name.clone(),
        Property {
            style: style.to_string(),
            values,
            fix_id: id.to_string(),
        },
    );
    Ok(FrontFix::Property(name))
}

/// "1 value", "2 values".
fn plural(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}

/// A wrong number of values starting at word `start`: the error points at the first
/// value too many, or just past the last word when values are missing.
fn count_error(
    a: &Args,
    start: usize,
    want: usize,
    got: usize,
    message: String,
    help: String,
) -> crate::diagnostic::ScriptError {
    let at = if got > want {
        start + want
    } else {
        a.words().len()
    };
    a.error_at(at, message, Some(help))
}

fn template(sim: &mut Sim, a: &mut Args, id: &str) -> CmdResult<FrontFix> {
    let seed = a.u64("seed")?;
    let (mut ty, mut density, mut radius) = (1u32, None, None);
    while !a.is_done() {
        match a.keyword(
            "particletemplate/sphere keyword",
            &["atom_type", "density", "radius", "volume_limit", "relative"],
        )? {
            "atom_type" => {
                let t = a.count("atom type")?;
                if sim.ntypes > 0 && t as usize > sim.ntypes {
                    return Err(a.error_prev(
                        format!(
                            "atom type {t} is larger than the box's {} type(s)",
                            sim.ntypes
                        ),
                        None,
                    ));
                }
                ty = t as u32;
            }
            "density" => {
                a.keyword("density distribution", &["constant"])?;
                density = Some(a.positive("density")?);
            }
            "radius" => {
                radius = Some(
                    match a.keyword("radius distribution", &["constant", "uniform", "gaussian"])? {
                        "constant" => RadiusDist::Constant(a.positive("radius")?),
                        "uniform" => RadiusDist::Uniform(
                            a.positive("smallest radius")?,
                            a.positive("largest radius")?,
                        ),
                        _ => RadiusDist::Gaussian(
                            a.positive("mean radius")?,
                            a.non_negative("radius standard deviation")?,
                        ),
                    },
                );
            }
            "volume_limit" => {
                a.positive("volume limit")?;
            }
            _ => {
                if a.yes_no("relative")? {
                    return Err(a.error_prev("relative radii are not supported", None));
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
    let radius = radius.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "particletemplate/sphere needs a radius",
            Some("add 'radius constant R' (m), or 'radius uniform RMIN RMAX'".into()),
        )
    })?;
    let t = ParticleTemplate::new(id, seed, ty, density, radius)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    sim.templates.insert(id.to_string(), t);
    Ok(FrontFix::Template)
}

fn distribution(sim: &mut Sim, a: &mut Args, id: &str, style: &str) -> CmdResult<FrontFix> {
    let seed = a.u64("seed")?;
    let n = a.count("number of templates")?;
    let mut parts = Vec::new();
    for _ in 0..n {
        let tid = a.word("template ID")?;
        let t = sim.templates.get(tid).cloned().ok_or_else(|| {
            let names: Vec<&str> = sim.templates.keys().map(|s| s.as_str()).collect();
            a.error_prev(
                format!("no particle template '{tid}'"),
                Some(suggest(tid, &names)),
            )
        })?;
        let w = a.positive("template weight")?;
        parts.push((t, w));
    }
    a.done()?;
    let weighting = if style.ends_with("numberbased") {
        Weighting::Number
    } else {
        Weighting::Mass
    };
    let d = Distribution::new(id, seed, weighting, parts)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    if let Some(wm) = &d.warning {
        sim.out.warning(wm);
    }
    sim.distributions.insert(id.to_string(), d);
    Ok(FrontFix::Distribution)
}

fn insert(
    sim: &mut Sim,
    a: &mut Args,
    id: &str,
    groupbit: u32,
    style: &str,
) -> CmdResult<FrontFix> {
    let stream = style == "insert/stream";
    let rate = style == "insert/rate/region" || stream;
    // Keywords of every style, then each style's own (in LIGGGHTS' manual order).
    const COMMON: [&str; 10] = [
        "seed",
        "distributiontemplate",
        "verbose",
        "maxattempt",
        "insert_every",
        "overlapcheck",
        "all_in",
        "random_distribute",
        "vel",
        "omega",
    ];
    let own: &[&'static str] = if stream {
        &[
            "nparticles",
            "mass",
            "particlerate",
            "massrate",
            "start",
            "compress_tags",
            "insertion_face",
            "extrude_length",
            "duration",
            "parallel",
        ]
    } else if rate {
        &[
            "nparticles",
            "mass",
            "particlerate",
            "massrate",
            "ntry_mc",
            "start",
            "compress_tags",
            "region",
        ]
    } else {
        &[
            "region",
            "volumefraction_region",
            "particles_in_region",
            "mass_in_region",
            "ntry_mc",
            "start",
        ]
    };
    let valid: Vec<&'static str> = COMMON.iter().chain(own).copied().collect();
    let valid = valid.as_slice();
    match a.peek() {
        Some("seed") => a.seek(a.pos() + 1),
        Some(w) => {
            return Err(a.error_at(
                a.pos(),
                format!("{style}: the first keyword must be 'seed', not '{w}'"),
                Some(format!(
                    "LIGGGHTS requires the seed first: 'fix ID group {style} seed 32452867 {w} ...'"
                )),
            ))
        }
        None => {
            return Err(a.error_at(
                a.pos(),
                format!("{style}: missing 'seed N'"),
                Some(format!(
                    "e.g. 'fix ID group {style} seed 32452867 distributiontemplate ID ...'"
                )),
            ))
        }
    }
    let seed = a.u64("seed")?;
    let mut dist = None;
    let (mut region, mut target, mut every, mut start) = (None, None, None, None);
    let (mut overlap, mut all_in, mut maxattempt, mut verbose) = (true, false, 50usize, true);
    let mut vel = VelocityLaw::Constant(DVec3::ZERO);
    let mut omega = DVec3::ZERO;
    let (mut nparticles, mut massmax, mut prate, mut mrate) = (None, None, None, None);
    let mut every_once = false;
    let (mut face, mut extrude, mut duration) = (None, None, None);
    while !a.is_done() {
        let k = a.keyword(&format!("{style} keyword"), valid)?;
        match k {
            "insertion_face" => {
                let at = a.pos();
                face = Some((
                    at,
                    mesh_ref(sim, a, "insertion face (a fix mesh/surface ID)")?,
                ));
            }
            "extrude_length" => extrude = Some(a.positive("extrude_length")?),
            "duration" => duration = Some((a.pos(), a.count("duration (steps)")?)),
            "parallel" => {
                a.yes_no("parallel")?;
            }
            "distributiontemplate" => {
                let d = a.word("distribution template ID")?;
                dist = Some(sim.distributions.get(d).cloned().ok_or_else(|| {
                    let names: Vec<&str> = sim.distributions.keys().map(|s| s.as_str()).collect();
                    a.error_prev(
                        format!("no particle distribution '{d}'"),
                        Some(suggest(d, &names)),
                    )
                })?);
            }
            "verbose" => verbose = a.yes_no("verbose")?,
            "maxattempt" => maxattempt = a.count("maxattempt")? as usize,
            "insert_every" => {
                if a.peek() == Some("once") && !rate {
                    a.seek(a.pos() + 1);
                    every = None;
                    every_once = true;
                } else {
                    every = Some(a.count("insert_every (steps, or 'once')")?);
                }
            }
            "overlapcheck" => overlap = a.yes_no("overlapcheck")?,
            "all_in" => all_in = a.yes_no("all_in")?,
            "random_distribute" => {
                a.keyword("random_distribute", &["exact", "uncorrelated"])?;
            }
            "compress_tags" => {
                a.yes_no("compress_tags")?;
            }
            "vel" => {
                vel = match a.keyword(
                    "velocity distribution",
                    &["constant", "uniform", "gaussian"],
                )? {
                    "constant" => VelocityLaw::Constant(a.vec3("velocity")?),
                    "uniform" => {
                        VelocityLaw::Uniform(a.vec3("mean velocity")?, a.vec3("velocity spread")?)
                    }
                    _ => VelocityLaw::Gaussian(a.vec3("mean velocity")?, a.vec3("velocity sigma")?),
                }
            }
            "omega" => {
                a.keyword("omega distribution", &["constant"])?;
                omega = a.vec3("omega")?;
            }
            "region" => region = Some(sim.region(a)?),
            "volumefraction_region" => {
                let f = a.f64("volume fraction")?;
                if !(f > 0.0 && f < 1.0) {
                    return Err(
                        a.error_prev(format!("volume fraction must be in (0, 1), got {f}"), None)
                    );
                }
                target = Some(PackTarget::VolumeFraction(f));
            }
            "particles_in_region" => target = Some(PackTarget::Count(a.u64("particle count")?)),
            "mass_in_region" => target = Some(PackTarget::Mass(a.positive("mass")?)),
            "ntry_mc" => {
                a.count("ntry_mc")?;
            }
            "start" => start = Some(a.u64("start step")?),
            "nparticles" => {
                if a.peek() == Some("INF") {
                    a.seek(a.pos() + 1);
                    nparticles = Some(None);
                } else {
                    nparticles = Some(Some(a.count("nparticles")?));
                }
            }
            "mass" => massmax = Some(a.positive("mass to insert")?),
            "particlerate" => prate = Some(a.positive("particle rate")?),
            "massrate" => mrate = Some(a.positive("mass rate")?),
            _ => unreachable!(),
        }
    }
    let dist = dist.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            format!("{style} needs 'distributiontemplate ID'"),
            None,
        )
    })?;
    sim.world_ref(a)?;
    let dt = sim.pending.dt;
    if stream {
        return insert_stream(
            sim,
            a,
            StreamArgs {
                id,
                seed,
                groupbit,
                dist,
                face,
                extrude,
                every,
                duration,
                nparticles,
                massmax,
                prate,
                mrate,
                dt,
            },
            |s| {
                s.overlap_check = overlap;
                s.all_in = all_in;
                s.max_attempt = maxattempt;
                s.omega = omega;
                s.start = start;
            },
            vel,
            verbose,
        );
    }
    let region =
        region.ok_or_else(|| a.error_at(STYLE_WORD, format!("{style} needs 'region ID'"), None))?;
    let (target, rate_state) = if rate {
        let every = every.ok_or_else(|| {
            a.error_at(
                STYLE_WORD,
                "insert/rate/region needs 'insert_every N'",
                None,
            )
        })?;
        let limit = match (nparticles, massmax) {
            (Some(n), None) => n,
            (None, Some(m)) => Some((m / dist.mean_particle_mass()).round() as u64),
            (None, None) => {
                return Err(a.error_at(
                    STYLE_WORD,
                    "insert/rate/region needs 'nparticles N' (or INF) or 'mass M'",
                    None,
                ))
            }
            (Some(_), Some(_)) => {
                return Err(a.error_at(
                    STYLE_WORD,
                    "give either nparticles or mass, not both",
                    None,
                ))
            }
        };
        let per_step = match (prate, mrate) {
            (Some(r), None) => r * dt,
            (None, Some(m)) => m * dt / dist.mean_particle_mass(),
            _ => {
                return Err(a.error_at(
                    STYLE_WORD,
                    "insert/rate/region needs exactly one of 'particlerate' or 'massrate'",
                    None,
                ))
            }
        };
        (
            PackTarget::Count(0),
            Some(RateState {
                limit,
                per_insertion: per_step * every as f64,
                carry: 0.0,
            }),
        )
    } else {
        let t = target.ok_or_else(|| {
            a.error_at(
                STYLE_WORD,
                "insert/pack needs a target",
                Some(format!(
                    "add {}",
                    one_of(&[
                        "volumefraction_region f",
                        "particles_in_region N",
                        "mass_in_region m"
                    ])
                )),
            )
        })?;
        if every.is_none() && !every_once {
            return Err(a.error_at(
                STYLE_WORD,
                "insert/pack needs 'insert_every once' or 'insert_every N'",
                None,
            ));
        }
        (t, None)
    };
    let mut pack = InsertPack::new(id, seed, groupbit, region, dist, target, every)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    pack.overlap_check = overlap;
    pack.all_in = all_in;
    pack.max_attempt = maxattempt;
    pack.velocity = vel;
    pack.omega = omega;
    pack.start = start;
    Ok(FrontFix::Insert(Box::new(Inserter {
        pack: InsertEngine::Pack(pack),
        total: 0,
        total_mass: 0.0,
        rate: rate_state,
        verbose,
    })))
}

/// What `fix insert/stream` was given (besides the settings every insertion has).
struct StreamArgs<'a> {
    id: &'a str,
    seed: u64,
    groupbit: u32,
    dist: Distribution,
    /// (word position, mesh index).
    face: Option<(usize, usize)>,
    extrude: Option<f64>,
    every: Option<u64>,
    /// (word position, steps).
    duration: Option<(usize, u64)>,
    nparticles: Option<Option<u64>>,
    massmax: Option<f64>,
    prate: Option<f64>,
    mrate: Option<f64>,
    dt: f64,
}

/// `fix insert/stream`: checks the keyword combinations LIGGGHTS requires and builds
/// the engine's stream.
fn insert_stream(
    sim: &mut Sim,
    a: &mut Args,
    s: StreamArgs,
    settings: impl FnOnce(&mut rdem::insert::InsertStream),
    vel: VelocityLaw,
    verbose: bool,
) -> CmdResult<FrontFix> {
    use rdem::insert::stream::Extrusion;
    let err = |a: &Args, msg: &str| a.error_at(STYLE_WORD, msg.to_string(), None);
    let Some((face_at, mesh)) = s.face else {
        return Err(err(a, "insert/stream needs 'insertion_face MESH-ID'"));
    };
    let extrusion = match (s.extrude, s.every) {
        (Some(_), _) if s.duration.is_some() => {
            return Err(a.error_at(
                s.duration.map(|d| d.0 - 1).unwrap_or(STYLE_WORD),
                "insert/stream: 'duration' goes with 'insert_every', not 'extrude_length'",
                None,
            ))
        }
        (Some(l), None) => Extrusion::Length(l),
        (None, Some(n)) => match s.duration {
            Some((at, d)) if d > n => {
                return Err(a.error_at(
                    at,
                    format!("duration {d} is longer than insert_every {n}"),
                    None,
                ))
            }
            Some((_, d)) => Extrusion::Pulsed {
                every: n,
                duration: d,
            },
            None => Extrusion::Every(n),
        },
        (Some(_), Some(_)) => {
            return Err(err(
                a,
                "insert/stream takes 'extrude_length' or 'insert_every', not both",
            ))
        }
        (None, None) => {
            return Err(err(
                a,
                "insert/stream needs 'extrude_length L' or 'insert_every N'",
            ))
        }
    };
    let limit = match (s.nparticles, s.massmax) {
        (Some(n), None) => n,
        (None, Some(m)) => Some((m / s.dist.mean_particle_mass()).round() as u64),
        (None, None) => {
            return Err(err(
                a,
                "insert/stream needs 'nparticles N' (or INF) or 'mass M'",
            ))
        }
        (Some(_), Some(_)) => return Err(err(a, "give either nparticles or mass, not both")),
    };
    let rate = match (s.prate, s.mrate) {
        (Some(r), None) => r,
        (None, Some(m)) => m / s.dist.mean_particle_mass(),
        _ => {
            return Err(err(
                a,
                "insert/stream needs exactly one of 'particlerate' or 'massrate'",
            ))
        }
    };
    let w = sim.world_ref(a)?;
    let face = &w.meshes[mesh].mesh;
    let mut st = rdem::insert::InsertStream::new(
        s.id, s.seed, s.groupbit, s.dist, mesh, face, vel, rate, extrusion, s.dt,
    )
    .map_err(|e| a.error_at(face_at, e.to_string(), None))?;
    st.limit = limit;
    settings(&mut st);
    if verbose {
        sim.out.line(&format!(
            "INFO: Particle insertion {}: {:.6} particles every {} steps - particle rate {:.6}  (mass rate {})",
            s.id,
            st.per_insertion,
            st.every,
            rate,
            format_e(rate * st.dist.mean_particle_mass())
        ));
    }
    Ok(FrontFix::Insert(Box::new(Inserter {
        pack: InsertEngine::Stream(st),
        total: 0,
        total_mass: 0.0,
        rate: None,
        verbose,
    })))
}

/// Reads a mesh ID (a `fix mesh/surface`) and returns its index in the world's meshes.
fn mesh_ref(sim: &Sim, a: &mut Args, what: &str) -> CmdResult<usize> {
    let at = a.pos();
    let mid = a.word(what)?;
    let found = sim.world.as_ref().and_then(|w| w.mesh_index(mid));
    found.ok_or_else(|| {
        let ids: Vec<&str> = sim
            .world
            .iter()
            .flat_map(|w| w.meshes.iter().map(|m| m.id.as_str()))
            .collect();
        a.error_at(
            at,
            format!("no mesh '{mid}' (define it with fix mesh/surface first)"),
            Some(suggest(mid, &ids)),
        )
    })
}

/// `fix ID group massflow/mesh mesh MESH vec_side x y z [count once|multiple]
/// [delete_atoms yes|no] [screen yes|no]`.
fn massflow(sim: &mut Sim, a: &mut Args, id: &str, groupbit: u32) -> CmdResult<FrontFix> {
    a.keyword("massflow/mesh keyword", &["mesh"])?;
    let mesh_at = a.pos();
    let mesh = mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?;
    const KEYS: [&str; 5] = ["vec_side", "count", "delete_atoms", "screen", "writeTime"];
    const LATER_KEYS: [&str; 5] = ["point_at_outlet", "inside_out", "file", "append", "lambda"];
    let (mut side, mut once, mut delete) = (None, false, false);
    while let Some(w) = a.peek() {
        if LATER_KEYS.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("massflow/mesh keyword '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", KEYS.join(", "))),
            ));
        }
        match a.keyword("massflow/mesh keyword", &KEYS)? {
            "vec_side" => side = Some(a.vec3("vec_side")?),
            "count" => once = a.keyword("count", &["once", "multiple"])? == "once",
            "delete_atoms" => delete = a.yes_no("delete_atoms")?,
            "screen" => {
                a.yes_no("screen")?;
            }
            _ => {}
        }
    }
    let Some(side) = side else {
        return Err(a.error_at(
            STYLE_WORD,
            "massflow/mesh needs 'vec_side vx vy vz' (the outer side of the face)",
            None,
        ));
    };
    let w = sim.world_ref(a)?;
    let mut mf = rdem::massflow::MassFlow::new(id, mesh, &w.meshes[mesh].mesh, groupbit, side)
        .map_err(|e| a.error_at(mesh_at, e.to_string(), None))?;
    mf.once = once;
    mf.delete = delete;
    Ok(FrontFix::MassFlow(Box::new(MassFlowFix {
        flow: mf,
        last: std::cell::Cell::new(None),
        rates: std::cell::Cell::new((u64::MAX, 0.0, 0.0)),
    })))
}

/// `fix ID group move/mesh mesh MESH style args`: linear, wiggle, rotate, riggle,
/// viblin, vibrot ([`rdem::mesh_motion::Motion`]), from the current time on.
fn move_mesh(sim: &mut Sim, a: &mut Args, id: &str) -> CmdResult<FrontFix> {
    use rdem::mesh_motion::Motion;
    a.keyword("move/mesh keyword", &["mesh"])?;
    let mesh = mesh_ref(sim, a, "mesh ID (a fix mesh/surface)")?;
    const STYLES: [&str; 6] = ["linear", "wiggle", "rotate", "riggle", "viblin", "vibrot"];
    const LATER_STYLES: [&str; 3] = ["linear/variable", "rotate/variable", "file"];
    if let Some(w) = a.peek() {
        if LATER_STYLES.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("move/mesh style '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", STYLES.join(", "))),
            ));
        }
    }
    let style_at = a.pos();
    let style = a.keyword("move/mesh style", &STYLES)?;
    let axis = |a: &mut Args| -> CmdResult<rdem::DVec3> {
        a.keyword(&format!("{style} keyword"), &["axis"])?;
        let at = a.pos();
        let v = a.vec3("axis")?;
        if !v.is_finite() || v.length() <= 0.0 {
            return Err(a.error_at(at, "the axis has no direction", None));
        }
        Ok(v.normalize())
    };
    let origin = |a: &mut Args| -> CmdResult<rdem::DVec3> {
        a.keyword(&format!("{style} keyword"), &["origin"])?;
        a.vec3("origin")
    };
    let period = |a: &mut Args| -> CmdResult<f64> {
        a.keyword(&format!("{style} keyword"), &["period"])?;
        a.positive("period")
    };
    // order n amplitude C1..Cn phase p1..pn period T1..Tn
    let series = |a: &mut Args| -> CmdResult<Vec<[f64; 3]>> {
        a.keyword(&format!("{style} keyword"), &["order"])?;
        let n = a.count("order (1 to 30)")? as usize;
        if n > 30 {
            return Err(a.error_prev("order must be 1 to 30", None));
        }
        let mut terms = vec![[0.0; 3]; n];
        for (k, what) in ["amplitude", "phase", "period"].iter().enumerate() {
            a.keyword(&format!("{style} keyword"), &[what])?;
            for t in terms.iter_mut() {
                t[k] = if k == 2 {
                    a.positive("period")?
                } else {
                    a.f64(what)?
                };
            }
        }
        Ok(terms)
    };
    let motion = match style {
        "linear" => Motion::Linear(a.vec3("velocity")?),
        "wiggle" => {
            a.keyword("wiggle keyword", &["amplitude"])?;
            let amplitude = a.vec3("amplitude")?;
            Motion::Wiggle {
                amplitude,
                period: period(a)?,
            }
        }
        "rotate" => Motion::Rotate {
            origin: origin(a)?,
            axis: axis(a)?,
            period: period(a)?,
        },
        "riggle" => {
            let (origin, axis, period) = (origin(a)?, axis(a)?, period(a)?);
            a.keyword("riggle keyword", &["amplitude"])?;
            let deg = a.f64("amplitude (degrees)")?;
            Motion::Riggle {
                origin,
                axis,
                period,
                amplitude: deg.to_radians(),
            }
        }
        "viblin" => {
            let axis = axis(a)?;
            Motion::Viblin {
                axis,
                terms: series(a)?,
            }
        }
        _ => {
            let (origin, axis) = (origin(a)?, axis(a)?);
            Motion::Vibrot {
                origin,
                axis,
                terms: series(a)?,
            }
        }
    };
    a.done()?;
    let w = sim.world_mut(a)?;
    let t = w.step as f64 * w.dt;
    let m = &mut w.meshes[mesh];
    let verts = m.mesh.verts.clone();
    m.motion
        .add(id, motion, t, &verts)
        .map_err(|e| a.error_at(style_at, e.to_string(), None))?;
    Ok(FrontFix::MeshMove(mesh))
}

/// A `wall/gran` wall.
enum Wall {
    Primitive(PrimitiveWall),
    Mesh(rdem::wall::MeshWall),
}

/// `fix ID group mesh/surface file F type T [keywords]`: the STL file's triangles with
/// `scale`, `move` and `rotate` applied in the order given, vertices closer than
/// `precision` merged, `heal auto_remove_duplicates` dropping degenerate and repeated
/// triangles, and `surface_vel` for a conveyor belt.
fn mesh_surface(
    sim: &mut Sim,
    a: &mut Args,
    id: &str,
    style: &str,
) -> CmdResult<rdem::wall::MeshSurface> {
    let stress_style = style == "mesh/surface/stress";
    let (mut stress_on, mut finnie, mut reference_point) = (true, false, rdem::DVec3::ZERO);
    a.keyword("mesh/surface keyword", &["file"])?;
    let file_at = a.pos();
    let file = a.word("STL file name")?.to_string();
    let mut soup = rdem_io::stl::read_stl(std::path::Path::new(&file))
        .map_err(|e| a.error_at(file_at, e.to_string(), None))?;
    let mut wall_type = None;
    let mut precision = 1e-8;
    let mut heal = false;
    let mut surface_vel = rdem::DVec3::ZERO;
    let mut surface_ang_vel = None;
    let mut coplanar_cos = rdem::wall::mesh::COPLANAR_COS;
    const KEYS: [&str; 11] = [
        "surface_ang_vel",
        "type",
        "precision",
        "heal",
        "verbose",
        "scale",
        "move",
        "rotate",
        "surface_vel",
        "curvature",
        "curvature_tolerant",
    ];
    const LATER_KEYS: [&str; 5] = [
        "element_exclusion_list",
        "min_feature_length",
        "temperature",
        "mass_temperature",
        "extrude_planar",
    ];
    const STRESS_KEYS: [&str; 3] = ["stress", "wear", "reference_point"];
    while let Some(w) = a.peek() {
        if LATER_KEYS.contains(&w) {
            a.seek(a.pos() + 1);
            return Err(a.error_prev(
                format!("mesh/surface keyword '{w}' is not supported by this rdem release yet"),
                Some(format!("supported: {}", KEYS.join(", "))),
            ));
        }
        if STRESS_KEYS.contains(&w) {
            if !stress_style {
                return Err(a.error_at(
                    a.pos(),
                    format!("'{w}' is a keyword of fix mesh/surface/stress"),
                    Some(format!("use fix {id} all mesh/surface/stress ... {w} ...")),
                ));
            }
            a.seek(a.pos() + 1);
            match w {
                "stress" => stress_on = a.keyword("stress", &["on", "off"])? == "on",
                "wear" => finnie = a.keyword("wear", &["finnie", "off", "none"])? == "finnie",
                _ => reference_point = a.vec3("reference point")?,
            }
            continue;
        }
        match a.keyword("mesh/surface keyword", &KEYS)? {
            "type" => wall_type = Some(a.count("wall atom type")? as u32),
            "surface_ang_vel" => {
                a.keyword("surface_ang_vel keyword", &["origin"])?;
                let o = a.vec3("origin")?;
                a.keyword("surface_ang_vel keyword", &["axis"])?;
                let at = a.pos();
                let ax = a.vec3("axis")?;
                if !ax.is_finite() || ax.length() <= 0.0 {
                    return Err(a.error_at(at, "the axis has no direction", None));
                }
                a.keyword("surface_ang_vel keyword", &["omega"])?;
                let w = a.f64("omega (rad per time unit)")?;
                surface_ang_vel = Some((o, ax.normalize() * w));
            }
            "precision" => precision = a.positive("precision")?,
            "heal" => {
                heal = a.keyword("heal", &["auto_remove_duplicates", "no"])? != "no";
            }
            "verbose" => {
                a.yes_no("verbose")?;
            }
            "curvature" => {
                let at = a.pos();
                let deg = a.positive("curvature (degrees)")?;
                if deg >= 90.0 {
                    return Err(a.error_at(
                        at,
                        "curvature is the largest angle (degrees) between two triangles of one flat surface: below 90",
                        None,
                    ));
                }
                coplanar_cos = deg.to_radians().cos();
            }
            "curvature_tolerant" => {
                a.yes_no("curvature_tolerant")?;
            }
            "scale" => {
                let f = a.positive("scale factor")?;
                for t in &mut soup {
                    *t = t.map(|p| p * f);
                }
            }
            "move" => {
                let d = rdem::DVec3::new(a.f64("mx")?, a.f64("my")?, a.f64("mz")?);
                for t in &mut soup {
                    *t = t.map(|p| p + d);
                }
            }
            "rotate" => {
                a.keyword("rotate keyword", &["axis"])?;
                let axis_at = a.pos();
                let axis = rdem::DVec3::new(a.f64("ax")?, a.f64("ay")?, a.f64("az")?);
                a.keyword("rotate keyword", &["angle"])?;
                let deg = a.f64("angle (degrees)")?;
                if axis.length().is_nan() || axis.length() <= 0.0 || !axis.is_finite() {
                    return Err(a.error_at(axis_at, "the rotation axis has no direction", None));
                }
                let q = glam::DQuat::from_axis_angle(axis.normalize(), deg.to_radians());
                for t in &mut soup {
                    *t = t.map(|p| q * p);
                }
            }
            _ => {
                surface_vel = rdem::DVec3::new(a.f64("vx")?, a.f64("vy")?, a.f64("vz")?);
            }
        }
    }
    let Some(wall_type) = wall_type else {
        return Err(a.error_at(
            STYLE_WORD,
            "mesh/surface needs 'type T' (the wall's material type)",
            None,
        ));
    };
    let (mesh, report) = rdem::mesh::TriMesh::from_triangles(&soup, precision, heal)
        .map_err(|e| a.error_at(file_at, format!("{file}: {e}"), None))?;
    if !report.degenerate.is_empty() || !report.duplicates.is_empty() {
        sim.out.warning(&format!(
            "mesh/surface {id}: dropped {} degenerate and {} repeated triangle(s) of {file}",
            report.degenerate.len(),
            report.duplicates.len()
        ));
    }
    sim.out.line(&format!(
        "  mesh {id}: {} triangles, {} vertices",
        mesh.tris.len(),
        mesh.verts.len()
    ));
    if style == "mesh/surface/planar" {
        let n = mesh.normals.first().copied().unwrap_or(rdem::DVec3::Z);
        let p0 = mesh.verts.first().copied().unwrap_or_default();
        let (lo, hi) = mesh.bounds();
        let tol = 1e-6 * (hi - lo).length();
        if mesh.verts.iter().any(|&v| (v - p0).dot(n).abs() > tol) {
            return Err(a.error_at(
                file_at,
                format!("{file}: mesh/surface/planar needs a planar mesh, and this one is not"),
                Some("use fix mesh/surface".into()),
            ));
        }
    }
    let ntri = mesh.tris.len();
    let mut surface = rdem::wall::MeshSurface::new(id, mesh, wall_type);
    if stress_style && (stress_on || finnie) {
        let mut st = rdem::wall::mesh_stress::MeshStress::new(ntri, finnie);
        st.reference_point = reference_point;
        surface.stress = Some(st);
    }
    surface.surface_vel = surface_vel;
    surface.surface_ang_vel = surface_ang_vel;
    surface.coplanar_cos = coplanar_cos;
    Ok(surface)
}

fn wall_gran(sim: &Sim, a: &mut Args, id: &str) -> CmdResult<Wall> {
    let mut model = models::parse_types(a)?;
    models::parse_leading_switches(a, &mut model)?;
    let style_at = a.pos();
    match a.peek() {
        Some("primitive") => a.seek(a.pos() + 1),
        Some("mesh") => {
            a.seek(a.pos() + 1);
            a.keyword("mesh keyword", &["n_meshes"])?;
            let n = a.count("n_meshes")?;
            a.keyword("mesh keyword", &["meshes"])?;
            let mut meshes = Vec::with_capacity(n as usize);
            for _ in 0..n {
                let at = a.pos();
                let mid = a.word("mesh ID (a fix mesh/surface)")?;
                let found = sim.world.as_ref().and_then(|w| w.mesh_index(mid));
                let Some(m) = found else {
                    let ids: Vec<&str> = sim
                        .world
                        .iter()
                        .flat_map(|w| w.meshes.iter().map(|m| m.id.as_str()))
                        .collect();
                    return Err(a.error_at(
                        at,
                        format!("no fix mesh/surface '{mid}'"),
                        Some(crate::commands::id_help("fix mesh/surface", mid, &ids)),
                    ));
                };
                meshes.push(m);
            }
            if models::at_switch(a) {
                models::parse_switches(a, &mut model)?;
            } else if !a.is_done() {
                return Err(models::unknown(a, a.pos(), &[]));
            }
            let wall = rdem::wall::MeshWall::new(id, model, meshes)
                .map_err(|e| a.error_cmd(e.to_string(), None))?;
            return Ok(Wall::Mesh(wall));
        }
        Some(
            w @ ("type" | "xplane" | "yplane" | "zplane" | "xcylinder" | "ycylinder" | "zcylinder"),
        ) => {
            return Err(a.error_at(
                style_at,
                format!("wall/gran: missing 'primitive' before '{w}'"),
                Some("write 'primitive type T zplane POS' (or another primitive)".into()),
            ))
        }
        Some(_) => return Err(models::unknown(a, style_at, &["primitive", "mesh"])),
        None => {
            return Err(a.error_at(
                a.pos(),
                "wall/gran: missing wall style",
                Some("add 'primitive type T zplane POS' (or another primitive)".into()),
            ))
        }
    }
    a.keyword("primitive keyword", &["type"])?;
    let wall_type = a.count("wall atom type")? as u32;
    let shape = match a.keyword(
        "primitive wall",
        &[
            "xplane",
            "yplane",
            "zplane",
            "xcylinder",
            "ycylinder",
            "zcylinder",
        ],
    )? {
        p @ ("xplane" | "yplane" | "zplane") => WallShape::Plane {
            axis: (p.as_bytes()[0] - b'x') as usize,
            pos: a.f64("plane position")?,
        },
        c => WallShape::Cylinder {
            axis: (c.as_bytes()[0] - b'x') as usize,
            radius: a.positive("cylinder radius")?,
            c1: a.f64("axis coordinate c1")?,
            c2: a.f64("axis coordinate c2")?,
        },
    };
    let mut velocity = DVec3::ZERO;
    while let Some(w) = a.peek() {
        if models::at_switch(a) {
            models::parse_switches(a, &mut model)?;
            break;
        }
        match w {
            "shear" => {
                a.seek(a.pos() + 1);
                let d = a.keyword("shear direction", &["x", "y", "z"])?;
                let v = a.f64("shear velocity")?;
                velocity[(d.as_bytes()[0] - b'x') as usize] = v;
            }
            "store_force" | "store_force_contact" => {
                a.seek(a.pos() + 1);
                if a.yes_no(w)? {
                    return Err(a.error_prev(format!("{w} yes is not supported yet"), None));
                }
            }
            _ => return Err(models::unknown(a, a.pos(), &["shear", "store_force"])),
        }
    }
    let mut wall = PrimitiveWall::new(id, model, wall_type, shape)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    wall.velocity = velocity;
    Ok(Wall::Primitive(wall))
}

fn adapt(sim: &Sim, a: &mut Args) -> CmdResult<FrontFix> {
    let every = a.count("N (adapt every N steps)")?;
    match a.keyword("adapt attribute", &["atom", "pair"])? {
        "atom" => {}
        _ => return Err(a.error_prev(
            "fix adapt pair is not supported (granular pair styles have no per-pair parameters)",
            Some("use 'atom diameter v_name'".into()),
        )),
    }
    a.keyword("atom attribute", &["diameter"])?;
    let v = a.word("variable (v_name)")?;
    let Some(var) = v.strip_prefix("v_") else {
        return Err(a.error_prev(
            format!("expected v_name, got '{v}'"),
            Some("give an atom-style variable: 'variable d atom ...' then 'v_d'".into()),
        ));
    };
    // A variable defined later is checked when the run starts, as LIGGGHTS does.
    match sim.vars.get(var) {
        Some(crate::variables::Variable::Atom(_)) | None => {}
        Some(_) => {
            return Err(a.error_prev(
                format!("fix adapt: variable '{var}' is not atom-style"),
                Some(format!(
                    "the new diameters come per particle: define 'variable {var} atom FORMULA'"
                )),
            ))
        }
    }
    let var = var.to_string();
    let mut reset = false;
    while !a.is_done() {
        match a.keyword("adapt keyword", &["reset", "scale"])? {
            "reset" => reset = a.yes_no("reset")?,
            _ => {
                if a.yes_no("scale")? {
                    return Err(a.error_prev("scale yes applies to pair parameters only", None));
                }
            }
        }
    }
    Ok(FrontFix::Adapt(Adapt {
        every,
        var,
        reset,
        saved: None,
    }))
}

fn check_timestep(a: &mut Args) -> CmdResult<FrontFix> {
    let every = a.count("nevery")?;
    let fraction_r = a.positive("fraction of the Rayleigh time")?;
    let fraction_h = a.positive("fraction of the Hertz time")?;
    let (mut warn, mut error, mut vmax) = (true, false, 0.0);
    while !a.is_done() {
        match a.keyword("check/timestep/gran keyword", &["warn", "error", "vmax"])? {
            "warn" => warn = a.yes_no("warn")?,
            "error" => error = a.yes_no("error")?,
            _ => vmax = a.non_negative("vmax")?,
        }
    }
    Ok(FrontFix::CheckTimestep(CheckTimestep {
        every,
        fraction_r,
        fraction_h,
        warn,
        error,
        vmax,
        values: [0.0; 2],
    }))
}

fn ave_euler(sim: &Sim, a: &mut Args, id: &str) -> CmdResult<FrontFix> {
    // LIGGGHTS 3.8 stops a second ave/euler with "Reuse of compute ID" (each creates an
    // internal compute of the same name); say so plainly.
    if let Some(other) = sim
        .fixes
        .iter()
        .find(|f| f.style == "ave/euler" && f.id != id)
    {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "only one fix ave/euler can exist (fix {} is one already)",
                other.id
            ),
            Some(format!(
                "LIGGGHTS 3.8 stops on a second one too; 'unfix {}' first",
                other.id
            )),
        ));
    }
    a.keyword("ave/euler keyword", &["nevery"])?;
    let nevery = a.count("nevery")?;
    a.keyword("ave/euler keyword", &["cell_size_relative"])?;
    let cell_size_relative = a.positive("cell_size_relative")?;
    a.keyword("ave/euler keyword", &["parallel"])?;
    let parallel = a.yes_no("parallel")?;
    let mut base_region = None;
    while !a.is_done() {
        a.keyword("ave/euler keyword", &["basevolume_region"])?;
        let name = a.peek().unwrap_or("").to_string();
        let r = sim.region(a)?;
        base_region = Some((name, r));
    }
    Ok(FrontFix::AveEuler(Box::new(AveEuler {
        nevery,
        cell_size_relative,
        parallel,
        base_region,
        base_volumes: None,
        cells: None,
        step: 0,
    })))
}

fn ave_time(sim: &mut Sim, a: &mut Args) -> CmdResult<FrontFix> {
    let nevery = a.count("Nevery")?;
    let nrepeat = a.count("Nrepeat")?;
    let nfreq = a.count("Nfreq")?;
    if nfreq % nevery != 0 || (nrepeat - 1) * nevery >= nfreq + nevery {
        return Err(a.error_at(
            a.pos() - 1,
            format!("Nfreq must be a multiple of Nevery and Nrepeat*Nevery <= Nfreq (got {nevery} {nrepeat} {nfreq})"),
            None,
        ));
    }
    let mut inputs = Vec::new();
    while let Some(w) = a.peek() {
        if !(w.starts_with("c_") || w.starts_with("f_") || w.starts_with("v_")) {
            break;
        }
        let Some((kind, id, _)) = crate::thermo::split_reference(w) else {
            return Err(a.error_at(a.pos(), format!("bad value '{w}'"), None));
        };
        let known = match kind {
            'c' => sim.compute_index(id).is_some(),
            'f' => sim.fix_index(id).is_some(),
            _ => sim.vars.get(id).is_some(),
        };
        if !known {
            let (what, ids): (&str, Vec<&str>) = match kind {
                'c' => (
                    "compute",
                    sim.computes.iter().map(|c| c.id.as_str()).collect(),
                ),
                'f' => ("fix", sim.fixes.iter().map(|f| f.id.as_str()).collect()),
                _ => ("variable", sim.vars.names()),
            };
            return Err(a.error_at(
                a.pos(),
                format!("'{w}': no {what} '{id}'"),
                Some(crate::commands::id_help(what, id, &ids)),
            ));
        }
        inputs.push(w.to_string());
        a.seek(a.pos() + 1);
    }
    if inputs.is_empty() {
        return Err(a.error_at(
            a.pos(),
            "ave/time needs at least one value (c_ID, c_ID[i], f_ID[i], v_name)",
            None,
        ));
    }
    let (mut running, mut file) = (false, None);
    while !a.is_done() {
        match a.keyword("ave/time keyword", &["file", "ave", "mode"])? {
            "file" => {
                let f = a.word("file name")?;
                if sim.check {
                    continue; // rdem -check writes no file
                }
                rdem_io::atomic::create_parent_dir(std::path::Path::new(f))
                    .map_err(|e| a.error_prev(e.to_string(), None))?;
                file = Some(std::io::BufWriter::new(std::fs::File::create(f).map_err(
                    |e| a.error_prev(format!("cannot create '{f}': {e}"), None),
                )?));
            }
            "ave" => running = a.keyword("ave", &["one", "running"])? == "running",
            _ => {
                a.keyword("mode", &["scalar"])?;
            }
        }
    }
    let n = inputs.len();
    let mut ave = AveTime {
        nevery,
        nrepeat,
        nfreq,
        inputs,
        running,
        file,
        sum: vec![0.0; n],
        count: 0,
        values: vec![0.0; n],
        running_sum: vec![0.0; n],
        windows: 0,
    };
    if let Some(f) = &mut ave.file {
        use std::io::Write;
        let id = a.words()[1].text.clone();
        let _ = writeln!(f, "# Time-averaged data for fix {id}");
        let _ = writeln!(f, "# TimeStep {}", ave.inputs.join(" "));
    }
    Ok(FrontFix::AveTime(Box::new(ave)))
}

/// Rayleigh and Hertz times of the current state (LIGGGHTS' check/timestep/gran
/// estimates): the smallest Rayleigh time π r √(ρ/G)/(0.1631 ν + 0.8766) over particles,
/// and the Hertz time 2.87 (m²/(r E*² v))^(1/5) per particle, with E* = E/(2(1−ν²)), the
/// particle's own mass m and radius r, and v the largest particle speed (at least `vmax`)
/// — the value LIGGGHTS 3.8 reports (checked against it, tests/liggghts_parity.rs).
pub fn timestep_limits(sim: &Sim, vmax: f64) -> Option<(f64, f64)> {
    let w = sim.world.as_ref()?;
    let p = &w.particles;
    let e = sim.properties.get("youngsModulus")?;
    let nu = sim.properties.get("poissonsRatio")?;
    let (mut t_r, mut t_h) = (f64::MAX, f64::MAX);
    let mut v: f64 = 0.0;
    for i in 0..p.nlocal() {
        v = v.max(p.v[i].length());
    }
    let v = w.comm.max(v).max(vmax);
    for i in 0..p.nlocal() {
        let t = p.ty[i] as usize - 1;
        let (ei, ni) = (*e.values.get(t)?, *nu.values.get(t)?);
        let g = ei / (2.0 * (1.0 + ni));
        let r = p.radius[i];
        t_r =
            t_r.min(std::f64::consts::PI * r * (p.density[i] / g).sqrt() / (0.1631 * ni + 0.8766));
        if v > 0.0 {
            let e_star = ei / (2.0 * (1.0 - ni * ni));
            let m = p.rmass[i];
            t_h = t_h.min(2.87 * (m * m / (r * e_star * e_star * v)).powf(0.2));
        }
    }
    Some((w.comm.min(t_r), w.comm.min(t_h)))
}

/// The LIGGGHTS report line of an insertion.
pub fn insertion_report(
    id: &str,
    n: u64,
    mass: f64,
    step: u64,
    total: u64,
    total_mass: f64,
) -> String {
    format!(
        "INFO: Particle insertion {id}: inserted {n} particle templates (mass {}) at step {step}\n - a total of {total} particle templates (mass {}) inserted so far.",
        format_e(mass),
        format_e(total_mass)
    )
}

/// C's `%e`.
pub fn format_e(v: f64) -> String {
    let s = format!("{v:.6e}");
    // Rust writes 1.5e-1; C writes 1.500000e-01.
    match s.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

/// Helper for numbers in messages.
pub fn g(v: f64) -> String {
    format_g(v, 6)
}
