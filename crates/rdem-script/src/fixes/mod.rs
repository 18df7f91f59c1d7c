//! The `fix` command and every fix style of the front end, one file per style (or small
//! family) in this folder, all listed in one registry ([`REGISTRY`]).
//!
//! A style's file holds its parser (script words → a typed value that implements
//! [`ScriptFix`]), and its registry row: the name, the parser, the [`Stages`] it takes part
//! in (as LAMMPS' `setmask`), one line of help and the notes of docs/commands.md. Adding a style is
//! that file and one row in [`REGISTRY`]; the unknown-style error, the "did you mean", the
//! list of valid styles, `rdem -check` and the command table of docs/commands.md read the registry.
//!
//! Fixes the engine runs every step (integration, walls, forces) are parsed here and
//! handed to `World::fixes` (stage [`Stages::ENGINE`]); the script keeps their ID, style
//! and group so that `unfix`, `f_ID` and redefinitions find them.

mod adapt;
mod addforce;
mod ave_atom;
pub mod ave_euler;
mod ave_histo;
mod ave_spatial;
mod ave_time;
mod balance;
mod bond_create_gran;
mod buoyancy;
mod check_timestep_bond;
mod check_timestep_gran;
mod couple_cfd;
mod engine;
mod gravity;
mod heat_gran;
mod heat_radiation;
pub mod insert;
mod insert_dense;
mod insert_fragments;
mod insert_stream;
mod lebc;
mod line_plane_force;
pub(crate) mod liquid;
mod massflow_mesh;
mod mcg;
mod mesh_servo;
mod mesh_surface;
mod modify;
mod momentum;
mod move_mesh;
mod move_particles;
mod multicontact;
pub(crate) mod multisphere;
mod nve_nonspherical;
mod particledistribution_discrete;
mod particletemplate_multisphere;
mod particletemplate_sphere;
mod peratom_ref;
mod pour;
mod print;
mod property_atom;
mod property_global;
mod remove;
mod sampling;
mod slowinit;
mod speedcontrol;
mod sph;
mod stage_ctx;
mod store_state;
pub mod tracer;
mod wall_gran;
mod wall_gran_old;

use crate::error::Error;
use std::any::Any;
use std::time::Instant;

use rdem::World;

use crate::args::{suggest, Args, CmdResult};
use crate::registry::{Registry, Row, Support};
use crate::sim::Sim;

pub use check_timestep_gran::timestep_limits;
pub use insert::insertion_report;
pub use modify::fix_modify;
pub use particletemplate_multisphere::{parse_spheres, parse_typed_spheres};
pub use stage_ctx::StageCtx;

/// The stages a fix takes part in (LAMMPS' `setmask`): the run loop calls each stage only
/// on the fixes that declare it, so a stage nobody uses costs nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Stages(u8);

impl Stages {
    /// No stage: a definition other fixes read (`property/global`, templates).
    pub const NONE: Self = Self(0);
    /// The engine runs it every step (`World::fixes`: integration, post-force, walls).
    pub const ENGINE: Self = Self(1);
    /// Before each step and before a run's set-up forces ([`ScriptFix::pre_step`]).
    pub const PRE_STEP: Self = Self(2);
    /// Inside the step after the initial integration ([`ScriptFix::pre_exchange`]).
    pub const PRE_EXCHANGE: Self = Self(4);
    /// After the final integration, and at a run's set-up ([`ScriptFix::end_of_step`]).
    pub const END_OF_STEP: Self = Self(8);
    /// When a run ends ([`ScriptFix::end_of_run`]).
    pub const END_OF_RUN: Self = Self(16);
    /// Global values for `f_ID`, `f_ID[i]` ([`ScriptFix::values`]).
    pub const VALUES: Self = Self(32);
    /// Every step after the initial integration, before the pre-exchange fixes
    /// ([`ScriptFix::post_integrate`]: LIGGGHTS' `post_integrate`, which sees the
    /// step's new positions and the half-step velocities).
    pub const POST_INTEGRATE: Self = Self(64);

    /// Both sets.
    pub const fn and(self, other: Self) -> Self {
        Self(self.0 | other.0)
    }

    /// True if every stage of `other` is in `self`.
    pub const fn has(self, other: Self) -> bool {
        self.0 & other.0 == other.0 && other.0 != 0
    }
}

/// The words every fix starts with: `fix ID group style`.
#[derive(Debug, Clone, Default)]
pub struct FixHead {
    /// Fix ID.
    pub id: String,
    /// Style, as in the registry.
    pub style: &'static str,
    /// Group bit mask.
    pub groupbit: u32,
}

/// Lines a fix prints later (insertion reports while the engine holds the world, a
/// definition's report when it is installed), in order:
/// `(true, text)` for a warning, `(false, text)` for a plain line.
#[derive(Debug, Default)]
pub struct Notes(pub Vec<(bool, String)>);

impl Notes {
    /// A line for the screen and log.
    pub fn line(&mut self, text: String) {
        self.0.push((false, text));
    }

    /// A warning.
    pub fn warning(&mut self, text: String) {
        self.0.push((true, text));
    }

    /// Prints the lines and warnings in order.
    pub fn print(self, out: &mut crate::output::Output) {
        for (warning, text) in self.0 {
            if warning {
                out.warning(&text);
            } else {
                out.line(&text);
            }
        }
    }
}

/// `Any` for every fix, so that the few readers of one style's state (dumps of
/// `ave/euler`, tests) can reach it.
pub trait AsAny: Any {
    /// `self` as `Any`.
    fn as_any(&self) -> &dyn Any;
    /// `self` as mutable `Any`.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<T: Any> AsAny for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// A fix as the script defined it. Each method is one stage; a fix implements those its
/// registry row declares (the others are never called). The run-time stages see the
/// simulation through a [`StageCtx`]; methods that take the whole [`Sim`] (definition
/// and `fix_modify`) are called with the fix itself out of `Sim::fixes` (see [`with_fix`]).
///
/// A definition has three steps, as LAMMPS' constructor, `init` and destructor: the
/// style's parser reads the words with the script state read-only (a definition that
/// fails changes nothing), [`ScriptFix::install`] puts into the rest of the state what
/// the fix adds there, and [`ScriptFix::unfix`] takes it out again.
pub trait ScriptFix: AsAny {
    /// Adds to the rest of the script state what the definition brings (an engine fix, a
    /// mesh, a property table, a template), once the parser has read every word; errors
    /// point into `a`, the definition's words.
    fn install(&mut self, _sim: &mut Sim, _a: &Args, _head: &FixHead) -> CmdResult<()> {
        Ok(())
    }

    /// [`Stages::VALUES`]: the global values `f_ID[1..]` at the current step.
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Err("computes no global values".into())
    }

    /// Per-atom values: `Some((columns, every))` (0 columns: a vector) if the fix gives
    /// them, valid on multiples of `every` steps.
    fn peratom_shape(&self) -> Option<(usize, u64)> {
        None
    }

    /// Per-atom values (column `col`, 1-based, of an array) for the owned particles.
    fn peratom(&self, _sim: &Sim, head: &FixHead, _col: Option<usize>) -> Result<Vec<f64>, Error> {
        Err(format!("fix {} computes no per-atom values", head.id).into())
    }

    /// True if `thermo_modify norm yes` divides this fix's values by the atom count.
    fn extensive(&self) -> bool {
        false
    }

    /// [`Stages::PRE_STEP`]: before step `ctx.step` (with `ctx.setup`, before a run's
    /// set-up).
    fn pre_step(&mut self, _ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        Ok(())
    }

    /// [`Stages::POST_INTEGRATE`]: acts on the world inside every step, after the initial
    /// integration and before the [`Stages::PRE_EXCHANGE`] fixes.
    fn post_integrate(&mut self, _head: &FixHead, _world: &mut World) -> rdem::Result<()> {
        Ok(())
    }

    /// [`Stages::PRE_EXCHANGE`]: whether the fix acts in step `step`.
    fn due(&self, _step: u64) -> bool {
        false
    }

    /// [`Stages::PRE_EXCHANGE`]: acts on the world inside the step, after the initial
    /// integration (new particles are not moved this step).
    fn pre_exchange(
        &mut self,
        _head: &FixHead,
        _world: &mut World,
        _notes: &mut Notes,
    ) -> rdem::Result<()> {
        Ok(())
    }

    /// [`Stages::END_OF_STEP`]: after step `step` (with `setup`, after a run's set-up
    /// forces): whether the force pass of that step must compute the contact virial.
    fn wants_virial(&self, _step: u64, _setup: bool) -> bool {
        false
    }

    /// [`Stages::END_OF_STEP`]: after step `ctx.step`'s final integration, or after a
    /// run's set-up (`ctx.setup`).
    fn end_of_step(&mut self, _ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        Ok(())
    }

    /// [`Stages::END_OF_RUN`]: when a run ends.
    fn end_of_run(&mut self, _ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        Ok(())
    }

    /// `fix_modify ID keyword ...`: reads the value(s) of the style's own `keyword`
    /// (already read) and returns true; false leaves the keyword to the generic ones
    /// ([`fix_modify`]). The fix is out of `sim` while this runs (see [`with_fix`]).
    fn modify(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        _keyword: &str,
        _a: &mut Args,
    ) -> CmdResult<bool> {
        Ok(false)
    }

    /// Restart files: the fix's own state that a continued run needs to go on as the
    /// unbroken run would (insertion counts, random generators, accumulators,
    /// controllers), serialized; `None` (the default) for a fix with nothing to keep.
    /// Per-particle values are not here: they travel with the particles.
    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        None
    }

    /// Takes back what [`ScriptFix::save_state`] wrote, when a fix of the same ID and
    /// style is defined after `read_restart` (once installed).
    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        _state: &[u8],
    ) -> Result<(), Error> {
        Err("this fix style keeps no state in restart files".into())
    }

    /// Whether `unfix` may remove the fix now.
    fn check_unfix(&self, _sim: &Sim, _head: &FixHead) -> Result<(), Error> {
        Ok(())
    }

    /// Undoes what the fix's definition did outside itself (engine fixes, meshes,
    /// property tables).
    fn unfix(&mut self, sim: &mut Sim, head: &FixHead);
}

/// A fix's parser: reads the words after `fix ID group style` with the script state
/// read-only; [`ScriptFix::install`] then adds the fix's effects.
pub type Parse = fn(&Sim, &mut Args, &FixHead) -> CmdResult<Box<dyn ScriptFix>>;

/// What the registry knows of a fix style rdem runs.
#[derive(Clone, Copy)]
pub struct FixStyle {
    /// The parser.
    pub parse: Parse,
    /// The stages its fixes take part in.
    pub stages: Stages,
    /// LIGGGHTS 3.8 reads its integer arguments with C's `atoi`, so `seed 10037.` or
    /// `insert_every 5.` run there: rdem reads them so too, with a warning (checked on
    /// LIGGGHTS 3.8: the insertion fixes, templates, distributions and
    /// check/timestep/gran do; `fix ave/time 1. ...` stops with "Expected integer
    /// parameter").
    pub atoi: bool,
}

impl FixRow {
    /// The same row for a style whose integers LIGGGHTS reads with `atoi`.
    pub const fn atoi(self) -> Self {
        match self.support {
            Support::Runs(h) => Row {
                support: Support::Runs(FixStyle { atoi: true, ..h }),
                ..self
            },
            Support::Not(_) | Support::Alias(_) => self,
        }
    }
}

/// A row of the fix registry.
pub type FixRow = Row<FixStyle>;

/// A fix style rdem runs.
pub(crate) const fn style(
    name: &'static str,
    parse: Parse,
    stages: Stages,
    help: &'static str,
) -> FixRow {
    Row::runs(
        name,
        FixStyle {
            parse,
            stages,
            atoi: false,
        },
        help,
    )
}

/// Every fix style: those rdem runs, then LIGGGHTS styles it does not run yet.
pub static REGISTRY: Registry<FixStyle> = Registry {
    family: "fix style",
    readme_prefix: "fix ",
    rows: &[
        property_global::ROW,
        property_atom::ROW,
        tracer::ROW,
        tracer::ROW_STREAM,
        tracer::ROW_TIME,
        mesh_surface::ROW,
        mesh_surface::ROW_PLANAR,
        mesh_surface::ROW_STRESS,
        mesh_servo::ROW,
        move_mesh::ROW,
        move_particles::ROW,
        wall_gran::ROW,
        wall_gran_old::ROW_HERTZ,
        wall_gran_old::ROW_HOOKE_HISTORY,
        wall_gran_old::ROW_HOOKE,
        particletemplate_sphere::ROW,
        particletemplate_multisphere::ROW,
        particletemplate_multisphere::ROW_MULTIPLE,
        multisphere::ROW,
        nve_nonspherical::ROW,
        mcg::ROW,
        lebc::ROW,
        slowinit::ROW,
        insert_fragments::ROW,
        particledistribution_discrete::ROW,
        particledistribution_discrete::ROW_MASS,
        particledistribution_discrete::ROW_NUMBER,
        insert::ROW_PACK,
        insert::ROW_RATE,
        insert_dense::ROW,
        insert_stream::ROW,
        pour::ROW,
        massflow_mesh::ROW,
        remove::ROW,
        engine::ROW_NVE,
        engine::ROW_NVE_LIMIT,
        engine::ROW_NVE_NOFORCE,
        gravity::ROW,
        engine::ROW_FREEZE,
        engine::ROW_VISCOUS,
        addforce::ROW,
        engine::ROW_SETFORCE,
        engine::ROW_AVEFORCE,
        engine::ROW_ENFORCE2D,
        momentum::ROW,
        line_plane_force::ROW_LINE,
        line_plane_force::ROW_PLANE,
        speedcontrol::ROW,
        buoyancy::ROW,
        sph::ROW_CONTINUITY,
        sph::ROW_SUMMATION,
        sph::ROW_CORR,
        sph::ROW_PRESSURE,
        sph::ROW_NVE,
        sph::ROW_NVE_STATIONARY,
        sph::ROW_WALL,
        sph::ROW_WALL_REGION,
        adapt::ROW,
        check_timestep_gran::ROW,
        ave_time::ROW,
        print::ROW,
        ave_atom::ROW,
        ave_histo::ROW,
        ave_spatial::ROW,
        store_state::ROW,
        ave_euler::ROW,
        heat_gran::ROW,
        heat_gran::ROW_ALIAS,
        heat_radiation::ROW,
        Row::alias("gravity/omp", "gravity", OMP),
        Row::alias("nve/sphere/omp", "nve/sphere", OMP),
        Row::alias("mesh/surface/omp", "mesh/surface", OMP),
        Row::alias("mesh/surface/planar/omp", "mesh/surface/planar", OMP),
        Row::alias("wall/gran/omp", "wall/gran", OMP),
        multicontact::ROW,
        couple_cfd::ROW,
        couple_cfd::ROW_FORCE,
        couple_cfd::ROW_IMPLICIT,
        balance::ROW,
        bond_create_gran::ROW,
        check_timestep_bond::ROW,
        Row::not_yet("bond/gran", "bonds"),
    ],
};

/// The help of LIGGGHTS-PFM's OpenMP variants of fix styles.
const OMP: &str = "LIGGGHTS-PFM's OpenMP variant (its hybrid parallelization): runs as the style without `/omp`, on rdem's threads";

/// Index of the style word in `fix ID group style ...` (errors about the whole fix point
/// at it).
pub(crate) const STYLE_WORD: usize = 3;

/// One fix as the script defined it.
pub struct FixEntry {
    /// ID, style and group.
    pub head: FixHead,
    /// The stages it takes part in (from its registry row).
    pub stages: Stages,
    /// Where its style word stands, for errors of its stages during a run.
    pub origin: Option<crate::diagnostic::Origin>,
    /// `fix_modify ID energy yes|no` (default no).
    pub energy: bool,
    /// The fix.
    pub imp: Box<dyn ScriptFix>,
    /// Seconds its stages took since the run started, counted under `modify_timing`.
    pub seconds: f64,
}

impl FixEntry {
    /// Fix ID.
    pub fn id(&self) -> &str {
        &self.head.id
    }

    /// The fix as its own type, if it is one.
    pub fn downcast<T: ScriptFix>(&self) -> Option<&T> {
        // Through the trait object: `self.imp.as_any()` would give the Box itself.
        (*self.imp).as_any().downcast_ref::<T>()
    }

    /// The fix as its own type, mutably, if it is one.
    pub fn downcast_mut<T: ScriptFix>(&mut self) -> Option<&mut T> {
        (*self.imp).as_any_mut().downcast_mut::<T>()
    }
}

/// The placeholder of a fix that is out of `Sim::fixes` while one of its stages runs.
struct Vacant;

impl ScriptFix for Vacant {
    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// Calls `f` with fix `k` taken out of `sim.defs.fixes` (a vacant entry stands in for it), so
/// that the fix can read and change the rest of the script state; puts it back after.
/// `f` must not add or remove fixes.
pub(crate) fn with_fix<R>(
    sim: &mut Sim,
    k: usize,
    f: impl FnOnce(&mut dyn ScriptFix, &mut Sim, &FixHead) -> R,
) -> R {
    let mut e = take(sim, k);
    let t0 = (sim.script.modify_timing != crate::sim::ModifyTiming::Off).then(Instant::now);
    let r = f(&mut *e.imp, sim, &e.head);
    if let Some(t0) = t0 {
        e.seconds += t0.elapsed().as_secs_f64();
    }
    sim.defs.fixes[k] = e;
    r
}

/// Takes fix `k` out of `sim.defs.fixes`, leaving a vacant entry (no allocation) that the
/// caller replaces with it again.
pub(crate) fn take(sim: &mut Sim, k: usize) -> FixEntry {
    std::mem::replace(
        &mut sim.defs.fixes[k],
        FixEntry {
            head: FixHead::default(),
            stages: Stages::NONE,
            origin: None,
            energy: false,
            imp: Box::new(Vacant),
            seconds: 0.0,
        },
    )
}

/// The outcome of a file write during a run that only MPI rank 0 does, made the same on
/// every rank (see [`crate::dumps::agree`]): a failed write stops every rank with rank
/// 0's report instead of leaving the others in the next collective call. Collective:
/// every rank calls it at the same point of the same step.
pub(crate) fn agree_write(sim: &Sim, what: &str, r: Result<(), Error>) -> Result<(), Error> {
    match &sim.world {
        Some(w) => crate::dumps::agree(&*w.comm, what, r),
        None => r,
    }
}

/// Indices of the fixes that take part in `stage`, in definition order.
pub fn with_stage(sim: &Sim, stage: Stages) -> Vec<usize> {
    (0..sim.defs.fixes.len())
        .filter(|&k| sim.defs.fixes[k].stages.has(stage))
        .collect()
}

/// Value `f_ID` / `f_ID[i]` (1-based).
pub fn fix_value(sim: &Sim, id: &str, idx: Option<usize>) -> Result<f64, Error> {
    let f = sim
        .defs
        .fixes
        .iter()
        .find(|f| f.head.id == id)
        .ok_or_else(|| Error::undefined("fix", id))?;
    if !f.stages.has(Stages::VALUES) {
        return Err(format!("fix {id} ({}) computes no global values", f.head.style).into());
    }
    let v = f
        .imp
        .values(sim, &f.head)
        .map_err(|m| format!("fix {id} ({}) {m}", f.head.style))?;
    match idx {
        Some(k) if k >= 1 && k <= v.len() => Ok(v[k - 1]),
        None if v.len() == 1 => Ok(v[0]),
        _ => Err(format!(
            "fix {id} gives {} value(s): use f_{id}[1..{}]",
            v.len(),
            v.len()
        )
        .into()),
    }
}

/// The ID of the per-particle array LIGGGHTS' `fix insert/stream` keeps (its release
/// data); rdem gives its column 5, the release step (see [`release_step_column`]).
pub const STREAM_RELEASE_ID: &str = "release_fix_insert_stream";

/// `f_release_fix_insert_stream[5]`, when no fix has that ID: LIGGGHTS 3.8's release step of
/// each streamed particle (0 for the others). Its other columns (insertion position and
/// step, velocities) are not kept by rdem: an error says so.
fn release_step_column(sim: &Sim, col: Option<usize>) -> Result<Vec<f64>, Error> {
    check_release_column(col)?;
    let w = sim.world.as_ref().ok_or(Error::NoBox)?;
    let p = &w.particles;
    Ok(
        match p.property(rdem::insert::stream::RELEASE_STEP_PROPERTY) {
            Some(id) => p.props[id.0].data[..p.nlocal()].to_vec(),
            None => vec![0.0; p.nlocal()],
        },
    )
}

/// Only column 5 of `f_release_fix_insert_stream` is kept.
fn check_release_column(col: Option<usize>) -> Result<(), Error> {
    if col == Some(5) {
        return Ok(());
    }
    Err(format!(
        "f_{STREAM_RELEASE_ID}: rdem keeps column 5 of it (the release step), not {}",
        col.map_or("the whole array".to_string(), |c| format!("column {c}"))
    )
    .into())
}

/// True if `id` names LIGGGHTS' release data of `fix insert/stream` (no fix has the ID
/// and an insert/stream is defined).
fn is_stream_release(sim: &Sim, id: &str) -> bool {
    id == STREAM_RELEASE_ID
        && sim.fix_index(id).is_none()
        && sim
            .defs
            .fixes
            .iter()
            .any(|f| f.head.style == "insert/stream")
}

/// The per-particle values `f_ID` / `f_ID[i]` (1-based) of every owned particle.
pub fn fix_peratom(sim: &Sim, id: &str, col: Option<usize>) -> Result<Vec<f64>, Error> {
    if is_stream_release(sim, id) {
        return release_step_column(sim, col);
    }
    check_fix_peratom(sim, id, col)?;
    let f = &sim.defs.fixes[sim.fix_index(id).expect("checked")];
    // `f_ID[0]` of a fix with one value per atom is `f_ID`, as in LIGGGHTS.
    f.imp.peratom(sim, &f.head, col.filter(|&c| c != 0))
}

/// Checks a reference `f_ID` / `f_ID[i]` to per-particle values of a fix.
pub fn check_fix_peratom(sim: &Sim, id: &str, col: Option<usize>) -> Result<(), Error> {
    if is_stream_release(sim, id) {
        return check_release_column(col);
    }
    let Some(f) = sim.defs.fixes.iter().find(|f| f.head.id == id) else {
        let ids: Vec<&str> = sim.defs.fixes.iter().map(|f| f.id()).collect();
        return Err(format!("no fix '{id}' ({})", crate::args::id_help("fix", id, &ids)).into());
    };
    match (f.imp.peratom_shape().map(|(n, _)| n), col) {
        (None, _) => Err(format!("fix {id} ({}) has no per-atom values", f.head.style).into()),
        // `f_ID[0]`: LIGGGHTS' old spelling of a per-atom vector (its manual's
        // `f_Temp[0]`), accepted by LIGGGHTS 3.8 as `f_ID`.
        (Some(0), None | Some(0)) => Ok(()),
        (Some(n), Some(k)) if n > 0 && k >= 1 && k <= n => Ok(()),
        (Some(0), Some(_)) => Err(format!("fix {id} has one value per atom: use f_{id}").into()),
        (Some(n), _) => Err(format!("fix {id} has {n} values per atom: use f_{id}[1..{n}]").into()),
    }
}

/// The number of per-particle columns of fix `id` (0: one value per particle), if it has
/// per-particle values.
pub fn peratom_cols(sim: &Sim, id: &str) -> Option<usize> {
    if is_stream_release(sim, id) {
        return Some(5);
    }
    sim.defs
        .fixes
        .iter()
        .find(|f| f.head.id == id)
        .and_then(|f| f.imp.peratom_shape().map(|(n, _)| n))
}

/// True if fix `id` has per-particle values.
pub fn is_peratom(sim: &Sim, id: &str) -> bool {
    peratom_cols(sim, id).is_some()
}

/// True if `f_ID[I]` (I ≠ 0) names atom I's value (LAMMPS' rule): a per-atom vector of a
/// fix with no global values. (`f_ID[0]` is LIGGGHTS' old spelling of the whole vector.)
pub fn indexes_atoms(sim: &Sim, id: &str, idx: Option<usize>) -> bool {
    matches!(idx, Some(k) if k != 0) && peratom_cols(sim, id) == Some(0) && !has_global(sim, id)
}

/// True if fix `id` gives global values (`f_ID`, `f_ID[i]`): in a formula these take
/// precedence over its per-atom values, as in LIGGGHTS (`fix property/atom/tracer`'s
/// `f_ID` is its count, `fix heat/gran`'s its energy); dumps and reductions read the
/// per-atom values.
pub fn has_global(sim: &Sim, id: &str) -> bool {
    sim.defs
        .fixes
        .iter()
        .any(|f| f.head.id == id && f.stages.has(Stages::VALUES))
}

/// True if `f_ID` is divided by the atom count under `thermo_modify norm yes`.
pub fn is_extensive(sim: &Sim, id: &str) -> bool {
    sim.defs
        .fixes
        .iter()
        .any(|f| f.head.id == id && f.imp.extensive())
}

/// `fix ID group style args...`: the style's parser reads the words (the state is
/// unchanged if they are wrong), a fix of the same ID is removed, and the new one is
/// installed.
pub fn fix(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("fix ID")?.to_string();
    let replaces = sim.fix_index(&id);
    if let Some(k) = replaces {
        // LIGGGHTS replaces a fix of the same ID and style; a different style is an error.
        let style = a.words().get(3).map(|w| w.text.as_str()).unwrap_or("");
        if sim.defs.fixes[k].head.style != style {
            return Err(a.error_prev(
                format!(
                    "fix ID '{id}' is already used by a {} fix",
                    sim.defs.fixes[k].head.style
                ),
                Some("unfix it first or pick another ID".into()),
            ));
        }
    }
    let groupbit = sim.group_bit(a, "group ID")?;
    let style_word = a.word("fix style")?;
    let (style, row) = REGISTRY.lookup(a, style_word)?;
    if row.atoi {
        a.read_integers_with_atoi();
    }
    if crate::coarse_graining::INCONSISTENT_FIXES.contains(&style) {
        crate::coarse_graining::check(sim, a, STYLE_WORD, &format!("fix {style}"))?;
    }
    let head = FixHead {
        id,
        style,
        groupbit,
    };
    let mut imp = (row.parse)(sim, a, &head)?;
    if replaces.is_some() {
        unfix_id(sim, &head.id);
    }
    imp.install(sim, a, &head)?;
    restore_state(sim, a, &head, &mut *imp)?;
    let origin = sim.origin(a, STYLE_WORD);
    sim.defs.fixes.push(FixEntry {
        head,
        stages: row.stages,
        origin,
        energy: false,
        imp,
        seconds: 0.0,
    });
    Ok(())
}

/// Decodes a state that a fix's [`ScriptFix::save_state`] wrote (the message for
/// [`ScriptFix::restore_state`]'s error).
pub(super) fn decode_state<T: serde::de::DeserializeOwned>(state: &[u8]) -> Result<T, Error> {
    postcard::from_bytes(state).map_err(|e| Error::Decode(format!("it does not decode ({e})")))
}

/// After `read_restart`: a fix defined with the ID of a fix of the writing run takes
/// back its state if the style is the same (as LIGGGHTS); with another style the state
/// is dropped with a warning.
fn restore_state(sim: &mut Sim, a: &Args, head: &FixHead, imp: &mut dyn ScriptFix) -> CmdResult {
    let restored = &mut sim.defs.restored.fixes;
    let Some(k) = restored.iter().position(|f| f.id == head.id) else {
        return Ok(());
    };
    let st = restored.remove(k);
    if st.style != head.style {
        sim.outputs.out.warning(&format!(
            "fix {}: the restart file holds the state of a {} fix of this ID, not of a {} fix: it starts afresh",
            head.id, st.style, head.style
        ));
        return Ok(());
    }
    imp.restore_state(sim, head, &st.state).map_err(|m| {
        a.error_at(
            STYLE_WORD,
            format!("the restart file's state of fix {}: {m}", head.id),
            None,
        )
    })?;
    sim.outputs.out.line(&format!(
        "fix {} ({}): state taken from the restart file",
        head.id, head.style
    ));
    Ok(())
}

/// `unfix ID`.
pub fn unfix(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let id = a.word("fix ID")?;
    a.done()?;
    let Some(k) = sim.fix_index(id) else {
        let names: Vec<&str> = sim.defs.fixes.iter().map(|f| f.id()).collect();
        return Err(a.error_prev(format!("no fix '{id}'"), Some(suggest(id, &names))));
    };
    let f = &sim.defs.fixes[k];
    f.imp
        .check_unfix(sim, &f.head)
        .map_err(|m| a.error_prev(m, None))?;
    unfix_id(sim, id);
    Ok(())
}

/// Removes fix `id` (front end and engine); false if there was none.
pub fn unfix_id(sim: &mut Sim, id: &str) -> bool {
    let Some(k) = sim.fix_index(id) else {
        return false;
    };
    let mut f = sim.defs.fixes.remove(k);
    f.imp.unfix(sim, &f.head);
    true
}

/// "1 value", "2 values".
pub(crate) fn plural(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
}

/// A wrong number of values starting at word `start`: the error points at the first
/// value too many, or just past the last word when values are missing.
pub(crate) fn count_error(
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

/// Reads a mesh ID (a `fix mesh/surface`) and returns its index in the world's meshes.
pub(crate) fn mesh_ref(sim: &Sim, a: &mut Args, what: &str) -> CmdResult<usize> {
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
