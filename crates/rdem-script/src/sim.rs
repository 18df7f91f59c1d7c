//! The state a script builds up: the engine's [`World`] once a box exists, and everything
//! only the front end knows — groups, regions, the lattice, material properties,
//! insertion templates, computes, variables, thermo and dump settings, and every fix in
//! definition order (engine fixes live in `World::fixes` under the same ID).

use crate::error::Error;
use std::collections::BTreeMap;
use std::time::Instant;

use rdem::insert::{Distribution, ParticleTemplate};
use rdem::region::Region;
use rdem::{Boundary, NeighborSettings, World};

use crate::args::{suggest, Args, CmdResult};
use crate::computes::Compute;
use crate::dumps::Dump;
use crate::fixes::FixEntry;
use crate::lattice::Lattice;
use crate::output::Output;
use crate::thermo::Thermo;
use crate::variables::Variables;

/// Group names by bit (bit 0 is `all`); at most 32 groups as in LIGGGHTS.
#[derive(Debug, Clone)]
pub struct Groups {
    names: Vec<Option<String>>,
}

impl Default for Groups {
    fn default() -> Self {
        let mut names = vec![None; 32];
        names[0] = Some("all".to_string());
        Self { names }
    }
}

impl Groups {
    /// Bit index of group `name`.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n.as_deref() == Some(name))
    }

    /// Bit index of `name`, creating the group if needed.
    pub fn find_or_create(&mut self, name: &str) -> Result<usize, Error> {
        if let Some(k) = self.find(name) {
            return Ok(k);
        }
        match self.names.iter().position(|n| n.is_none()) {
            Some(k) => {
                self.names[k] = Some(name.to_string());
                Ok(k)
            }
            None => Err("too many groups (32 at most, as in LIGGGHTS)".into()),
        }
    }

    /// Forgets group `k` (not `all`).
    pub fn delete(&mut self, k: usize) {
        if k > 0 {
            self.names[k] = None;
        }
    }

    /// The names by bit (restart files).
    pub fn table(&self) -> Vec<Option<String>> {
        self.names.clone()
    }

    /// Sets the names by bit (from a restart file): 32 bits, bit 0 `all`.
    pub fn set_table(&mut self, names: Vec<Option<String>>) -> Result<(), Error> {
        if names.len() != 32 || names[0].as_deref() != Some("all") {
            return Err("its group table is damaged".into());
        }
        self.names = names;
        Ok(())
    }

    /// The name of the group of bit mask `bit` (one bit set).
    pub fn name_of_bit(&self, bit: u32) -> Option<&str> {
        self.names.get(bit.trailing_zeros() as usize)?.as_deref()
    }

    /// Names of all groups.
    pub fn names(&self) -> Vec<&str> {
        self.names.iter().flatten().map(|s| s.as_str()).collect()
    }
}

/// A `fix property/global` value table.
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// `scalar`, `vector`, `peratomtype`, `peratomtypepair`, `matrix`.
    pub style: String,
    /// The numbers (for `peratomtypepair` the leading type count is not included).
    pub values: Vec<f64>,
    /// Fix ID that defined it.
    pub fix_id: String,
}

/// Settings given before the box exists, applied when it is created.
#[derive(Debug, Clone)]
pub struct Setup {
    /// `boundary`, per axis and face.
    pub boundary: [[Boundary; 2]; 3],
    /// `neighbor` / `neigh_modify` before the box exists; from then on the world holds
    /// them (read with [`Sim::neighbor_settings`], set with [`Sim::set_neighbor`]).
    pub neighbor: NeighborSettings,
    /// `neigh_modify exclude` before the box exists (pairs that never interact; then
    /// the world's, as [`Setup::neighbor`]).
    pub exclude: rdem::Exclusions,
    /// `timestep` before the box exists (then the world's [`World::dt`] is the one
    /// value: read it with [`Sim::dt`], set it with [`Sim::set_timestep`]).
    pub dt: f64,
    /// `atom_modify sort` before the box exists (then the world's: [`Sim::set_sort`]).
    pub sort: rdem::SortSettings,
    /// `thermo_modify lost` before the box exists (then the world's: [`Sim::set_lost`]).
    pub lost: rdem::LostPolicy,
    /// `processors Px Py Pz` (0 = `*`, free).
    pub procs: [usize; 3],
    /// `units` (SI unless the script says otherwise).
    pub units: crate::units::Units,
    /// `dimension` (3, or 2 for a plane in x and y: the temperature counts 2 degrees of
    /// freedom per particle and `fix enforce2d` keeps the particles in their plane).
    pub dimension: u8,
    /// `atom_style sph`: per-type masses (`mass`), density and pressure per particle.
    pub sph: bool,
    /// `atom_style ... bond/gran n_bondtypes N bonds_per_atom M [disableNormalContact
    /// 0|1]`: (N, M, disableNormalContact).
    pub bond_gran: Option<(usize, usize, bool)>,
    /// The columns of data files (`read_data`, `write_data`) under the atom style;
    /// `None` for plain `atom_style bond/gran`, whose lines have no diameter.
    pub data_layout: Option<rdem_io::AtomLayout>,
    /// `pair_style gran ...` given before the box (LIGGGHTS 3.8 takes it there): the box
    /// gets it.
    pub pair: Option<rdem::ContactModel>,
    /// `coarsegraining` (LIGGGHTS-PFM): the factor and its model check.
    pub coarse_graining: crate::coarse_graining::CoarseGraining,
    /// Whether `neighbor` gave the skin (`coarsegraining` must come before it).
    pub skin_given: bool,
}

impl Default for Setup {
    fn default() -> Self {
        Self {
            boundary: [[Boundary::Periodic; 2]; 3],
            neighbor: NeighborSettings::default(),
            exclude: rdem::Exclusions::default(),
            // LIGGGHTS' default for SI units.
            dt: rdem::world::DEFAULT_TIMESTEP,
            sort: rdem::SortSettings::default(),
            lost: rdem::LostPolicy::default(),
            procs: [0; 3],
            units: crate::units::Units::Si,
            dimension: 3,
            sph: false,
            bond_gran: None,
            data_layout: Some(rdem_io::AtomLayout::Granular),
            pair: None,
            coarse_graining: Default::default(),
            skin_given: false,
        }
    }
}

/// What the script defined by name that the engine does not hold: groups, regions, the
/// lattice, property tables, templates and distributions, every fix (in definition
/// order; an engine fix's state is in `World::fixes`, see [`crate::fixes`]) and compute.
#[derive(Default)]
pub struct Definitions {
    /// Groups.
    pub groups: Groups,
    /// Regions by ID.
    pub regions: BTreeMap<String, crate::regions::RegionDef>,
    /// The lattice (`lattice` command).
    pub lattice: Option<Lattice>,
    /// `fix property/global` tables by property name.
    pub properties: BTreeMap<String, Property>,
    /// Particle templates by fix ID.
    pub templates: BTreeMap<String, ParticleTemplate>,
    /// Particle distributions by fix ID.
    pub distributions: BTreeMap<String, Distribution>,
    /// Fixes in definition order.
    pub fixes: Vec<FixEntry>,
    /// Computes in definition order, starting with `thermo_temp`, which every script
    /// has (see [`crate::computes::temp`]).
    pub computes: Vec<Compute>,
    /// Whether a pair style was defined with `pair_coeff` given.
    pub pair_coeff_set: bool,
    /// Per-type masses of the `mass` command (index = type; `atom_style sph`).
    pub type_mass: Vec<Option<f64>>,
    /// What `read_restart` brought that later definitions take back.
    pub restored: crate::restart_state::Restored,
}

/// See [`Outputs::step_hook`].
pub type StepHook = Box<dyn FnMut(&Sim, u64) -> Result<bool, Error>>;

/// Where results go: thermo, dumps, the screen and log, the progress display.
pub struct Outputs {
    /// Thermo output settings.
    pub thermo: Thermo,
    /// Dumps in definition order.
    pub dumps: Vec<Dump>,
    /// Screen and log.
    pub out: Output,
    /// Called during long runs with (steps done, steps total) for a progress display.
    pub progress: Option<Box<dyn FnMut(u64, u64)>>,
    /// Called after every step of a run by a host program (the Python module's
    /// callbacks and interrupts), with the state after the step's output: `Ok(true)`
    /// goes on, `Ok(false)` ends the run after this step (as if it had been asked for
    /// that many steps; a `run every` does not go on either), `Err` ends it the same way
    /// and then fails the `run` command with that message (the script stops).
    pub step_hook: Option<StepHook>,
    /// Warnings already printed (see [`Outputs::warn_once`]).
    pub warned: std::collections::BTreeSet<String>,
    /// `restart N ...`: periodic restart files (none by default; at most one schedule
    /// with one name and one with two).
    pub restart: Vec<crate::commands::restart::RestartSchedule>,
}

impl Outputs {
    /// Prints a warning once per distinct text.
    pub fn warn_once(&mut self, text: &str) {
        if self.warned.insert(text.to_string()) {
            self.out.warning(text);
        }
    }
}

/// The state of the script itself: variables, where it is being read, the clocks and
/// the current run's bounds (labels and loops are the interpreter's).
pub struct ScriptState {
    /// Variables.
    pub vars: Variables,
    /// The generator of `random()` in equal-style formulas: one for the whole script,
    /// seeded by the first call's seed (later seeds are not used), as LIGGGHTS does.
    pub random_equal: std::sync::Mutex<Option<crate::ranmars::RanMars>>,
    /// The file of the command being run (see [`Sim::origin`]).
    pub here: Option<crate::diagnostic::SourceFile>,
    /// `rdem -check`: runs no step and writes no file (see `crate::check`).
    pub check: bool,
    /// Number of threads asked for (`--threads`); the force pass runs on a rayon pool of
    /// that size, which the caller sets up.
    pub threads: usize,
    /// Time the script started (for `elapsed`, `cpu`).
    pub started: Instant,
    /// First step of the current run (for `elapsed`).
    pub run_first: u64,
    /// Last step of the current run.
    pub run_last: u64,
    /// LAMMPS' `beginstep`: `run ... start N1`, else the run's first step (`elaplong`).
    pub run_begin: u64,
    /// A run has set up (LAMMPS' `first_update`): `run ... pre no` skips the set-up only
    /// after one.
    pub set_up: bool,
    /// Wall-clock start of the current run.
    pub run_started: Instant,
    /// (step, simulated time) when the timestep last changed: `time` is
    /// t0 + (step − step0)·dt, continuous across `timestep` changes as in LIGGGHTS.
    pub time_origin: (u64, f64),
    /// The last run was ended early by [`Outputs::step_hook`] or a fix.
    pub halted: bool,
    /// A fix asked the current run to end after this step ([`crate::fixes::StageCtx::end_run`]).
    pub stop_requested: bool,
    /// `modify_timing`: each fix's time is counted and printed after a run.
    pub modify_timing: ModifyTiming,
}

/// `modify_timing off|on|verbose`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ModifyTiming {
    /// No per-fix times (the default).
    #[default]
    Off,
    /// Each fix's time after a run.
    On,
    /// Each fix's time on each rank too.
    Verbose,
}

/// Everything a script defines, each fact in one place: the set-up before the box
/// exists, the engine's [`World`] once it does, the script's definitions, the outputs
/// and the script state.
pub struct Sim {
    /// The engine state, once `create_box` or `read_data` made a box.
    pub world: Option<World>,
    /// Settings that wait for the box.
    pub setup: Setup,
    /// Groups, regions, fixes, computes and the tables they read.
    pub defs: Definitions,
    /// Thermo, dumps, screen and log.
    pub outputs: Outputs,
    /// Variables, clocks, the file being read.
    pub script: ScriptState,
}

impl Sim {
    /// A fresh script state writing to `out`.
    pub fn new(out: Output) -> Self {
        Self {
            world: None,
            setup: Setup::default(),
            defs: Definitions {
                computes: vec![crate::computes::temp::thermo_temp()],
                ..Definitions::default()
            },
            outputs: Outputs {
                thermo: Thermo::default(),
                dumps: Vec::new(),
                out,
                progress: None,
                step_hook: None,
                warned: Default::default(),
                restart: Vec::new(),
            },
            script: ScriptState {
                vars: Variables::new(),
                random_equal: std::sync::Mutex::new(None),
                here: None,
                check: false,
                threads: 1,
                started: Instant::now(),
                run_first: 0,
                run_last: 0,
                run_begin: 0,
                set_up: false,
                run_started: Instant::now(),
                time_origin: (0, 0.0),
                halted: false,
                stop_requested: false,
                modify_timing: ModifyTiming::Off,
            },
        }
    }

    /// The world, or an error at the command saying a box is needed first.
    pub fn world_mut(&mut self, a: &Args) -> CmdResult<&mut World> {
        let name = a.name().to_string();
        self.world.as_mut().ok_or_else(|| {
            a.error_cmd(
                format!("{name} before the simulation box is defined"),
                Some("use create_box or read_data first".into()),
            )
        })
    }

    /// Where word `k` of the command being run stands, for errors found later (during a
    /// run) about what it introduced.
    pub fn origin(&self, a: &Args, k: usize) -> Option<crate::diagnostic::Origin> {
        let file = self.script.here.clone()?;
        let span = a.words().get(k)?.span.clone();
        Some(crate::diagnostic::Origin { file, span })
    }

    /// The world (read-only), or the same error.
    pub fn world_ref(&self, a: &Args) -> CmdResult<&World> {
        self.world.as_ref().ok_or_else(|| {
            a.error_cmd(
                format!("{} before the simulation box is defined", a.name()),
                Some("use create_box or read_data first".into()),
            )
        })
    }

    /// Reads a group ID word and returns its bit mask.
    pub fn group_bit(&self, a: &mut Args, what: &str) -> CmdResult<u32> {
        let g = a.word(what)?;
        match self.defs.groups.find(g) {
            Some(k) => Ok(1u32 << k),
            None => Err(a.error_prev(
                format!("no group '{g}'"),
                Some(format!(
                    "{}; define one with 'group {g} region|type|id ...'",
                    suggest(g, &self.defs.groups.names())
                )),
            )),
        }
    }

    /// Reads a region ID word and returns the region where it is now (a moving region's
    /// variables evaluated at the current step).
    pub fn region(&self, a: &mut Args) -> CmdResult<Region> {
        let r = self.region_id(a)?;
        crate::regions::region_now(self, &r).map_err(|e| a.error_prev(e, None))
    }

    /// Reads a region ID word for a use that needs a region that stays put (`who`:
    /// e.g. "fix insert/pack"; LIGGGHTS refuses dynamic regions there too).
    pub fn fixed_region(&self, a: &mut Args, who: &str) -> CmdResult<Region> {
        let r = self.region_id(a)?;
        if crate::regions::is_dynamic(self, &r) {
            return Err(a.error_prev(
                format!(
                    "{who}: region '{r}' moves (move/rotate): dynamic regions are not allowed here"
                ),
                None,
            ));
        }
        Ok(self.defs.regions[&r].region.clone())
    }

    /// Reads a region ID word and checks that the region exists.
    pub fn region_id(&self, a: &mut Args) -> CmdResult<String> {
        let r = a.word("region ID")?;
        if self.defs.regions.contains_key(r) {
            return Ok(r.to_string());
        }
        let names: Vec<&str> = self.defs.regions.keys().map(|s| s.as_str()).collect();
        Err(a.error_prev(
            format!("no region '{r}'"),
            Some(if names.is_empty() {
                "no region is defined yet".into()
            } else {
                suggest(r, &names)
            }),
        ))
    }

    /// Index of fix `id`.
    pub fn fix_index(&self, id: &str) -> Option<usize> {
        self.defs.fixes.iter().position(|f| f.id() == id)
    }

    /// Index of compute `id`.
    pub fn compute_index(&self, id: &str) -> Option<usize> {
        self.defs.computes.iter().position(|c| c.id() == id)
    }

    /// Makes `w` the simulation's world (a new box: `create_box`, `read_data`,
    /// `read_restart`), with the neighbor, exclusion, sort and lost-particle settings the
    /// script gave before it; from here on the world is their one owner.
    pub fn install_world(&mut self, mut w: World) {
        w.neighbor.settings = self.setup.neighbor;
        w.neighbor.exclude.clone_from(&self.setup.exclude);
        w.sort = self.setup.sort;
        w.lost_policy = self.setup.lost;
        if let Some((ntypes, per_atom, disable)) = self.setup.bond_gran {
            if w.bonds.is_none() {
                // Checked by the atom style.
                let mut b = rdem::bond_gran::GranBonds::new(ntypes, per_atom)
                    .expect("bond/gran settings checked by atom_style");
                b.disable_contact = disable;
                // A restart file's property of another width fails here and again,
                // with its message, at the run's set-up.
                let _ = b.attach(&mut w.particles);
                w.bonds = Some(b);
            }
        }
        let pair = self.setup.pair.take();
        if let Some(m) = pair {
            w.pair = Some(rdem::pair::PairGran::new(m));
            w.sph = None;
        }
        self.world = Some(w);
        if pair.is_some_and(|m| m.cohesion == rdem::CohesionKind::Easo) {
            crate::fixes::liquid::define(self);
        }
    }

    /// The `neighbor` / `neigh_modify` settings: the world's once the box exists, else
    /// those the box will get.
    pub fn neighbor_settings(&self) -> NeighborSettings {
        self.world
            .as_ref()
            .map_or(self.setup.neighbor, |w| w.neighbor.settings)
    }

    /// The `neigh_modify exclude` pairs (the world's once the box exists).
    pub fn exclusions(&self) -> &rdem::Exclusions {
        self.world
            .as_ref()
            .map_or(&self.setup.exclude, |w| &w.neighbor.exclude)
    }

    /// Sets the neighbor settings where they live now (see [`Sim::install_world`]).
    pub fn set_neighbor(&mut self, s: NeighborSettings) {
        match &mut self.world {
            Some(w) => w.neighbor.settings = s,
            None => self.setup.neighbor = s,
        }
    }

    /// Sets the `neigh_modify exclude` pairs where they live now.
    pub fn set_exclusions(&mut self, exclude: rdem::Exclusions) {
        match &mut self.world {
            Some(w) => w.neighbor.exclude = exclude,
            None => self.setup.exclude = exclude,
        }
    }

    /// Sets the `atom_modify sort` schedule where it lives now.
    pub fn set_sort(&mut self, s: rdem::SortSettings) {
        match &mut self.world {
            Some(w) => w.sort = s,
            None => self.setup.sort = s,
        }
    }

    /// Sets the `thermo_modify lost` policy where it lives now.
    pub fn set_lost(&mut self, p: rdem::LostPolicy) {
        match &mut self.world {
            Some(w) => w.lost_policy = p,
            None => self.setup.lost = p,
        }
    }

    /// The time step.
    pub fn dt(&self) -> f64 {
        self.world.as_ref().map_or(self.setup.dt, |w| w.dt)
    }

    /// Sets the time step (finite and > 0): the world's once a box exists, else the one
    /// the box will get. Simulated time stays continuous across a change (`time` is
    /// t0 + (step − step0)·dt from the step of the change on, as in LIGGGHTS). The same
    /// step again changes nothing: a script continued from a restart file, which gives
    /// its `timestep` again, counts time with the same formula (and so the same
    /// roundings) as the unbroken run.
    pub fn set_timestep(&mut self, dt: f64) -> Result<(), Error> {
        if self.world.is_some() && dt == self.dt() {
            return Ok(());
        }
        let now = (self.world.as_ref().map_or(0, |w| w.step), self.time());
        match &mut self.world {
            Some(w) => w.set_timestep(dt)?,
            None if dt.is_finite() && dt > 0.0 => self.setup.dt = dt,
            None => return Err(format!("timestep must be finite and > 0, not {dt}").into()),
        }
        self.script.time_origin = now;
        Ok(())
    }

    /// Number of atom types of the box (0 before it exists): the world's material
    /// table holds it.
    pub fn ntypes(&self) -> usize {
        self.world.as_ref().map_or(0, |w| w.materials.ntypes)
    }

    /// Simulated time at the current step.
    pub fn time(&self) -> f64 {
        let (s0, t0) = self.script.time_origin;
        let w = self.world.as_ref();
        let step = w.map(|w| w.step).unwrap_or(0);
        t0 + (step as f64 - s0 as f64) * self.dt()
    }

    /// Number of owned particles (0 without a box).
    pub fn natoms(&self) -> u64 {
        self.world.as_ref().map(|w| w.natoms()).unwrap_or(0)
    }

    /// Prints a warning once per distinct text.
    pub fn warn_once(&mut self, text: &str) {
        self.outputs.warn_once(text);
    }
}
