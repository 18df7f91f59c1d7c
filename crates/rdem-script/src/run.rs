//! `run N [upto]`: set-up, the steps (`rdem::step::step`, which writes down the order of
//! a step, with the script's fixes as its front-end stages: [`Front`]), thermo and dump
//! output, and LIGGGHTS' end-of-run report (`Loop time of T on P procs for N steps with M atoms` and the stage breakdown).

use std::time::Instant;

use rdem::timers::Stage;
use rdem::{HookMask, NoHooks, StepHooks, StepHost, World};

use crate::args::{Args, CmdResult};
use crate::diagnostic::{RunError, ScriptError};
use crate::fixes::{self, FixEntry, Notes, StageCtx, Stages};
use crate::sim::{ModifyTiming, Sim};
use crate::thermo;

/// What a `run` line asks for: `run N [upto] [start N1] [stop N2] [pre yes|no]
/// [post yes|no] [every M c1 c2 ...]`, checked against the current step as LIGGGHTS 3.8
/// checks it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RunPlan {
    /// Steps to run (after `upto`: up to N).
    pub nsteps: u64,
    /// `start N1`: the step the series of runs started at (`elaplong` counts from it).
    pub start: Option<u64>,
    /// `stop N2`: the step the series of runs ends at (checked; no style of rdem reads
    /// it: LIGGGHTS' `ramp()` and the fixes that ramp over a run are not in rdem).
    pub stop: Option<u64>,
    /// `pre`: the full set-up before the run (`no` skips it except for the thermo output,
    /// unless nothing ran yet).
    pub pre: bool,
    /// `post`: the full timing summary after the run (`no`: the loop-time line only).
    pub post: bool,
    /// `every M c1 c2 ...`: the run in chunks of M steps with the commands (the indices
    /// of their words; empty for none or `NULL`) after each chunk.
    pub every: Option<(u64, std::ops::Range<usize>)>,
}

/// One stretch of steps with its set-up and summary choices (a whole `run`, or one chunk
/// of `run every`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Chunk {
    /// Steps in it.
    pub nsteps: u64,
    /// The full set-up first (LAMMPS' `init` and `setup`); without it only the thermo
    /// header and row and the due dumps, as LAMMPS' `output->setup`.
    pub setup: bool,
    /// The full timing summary after it (else the loop-time line only).
    pub summary: bool,
    /// LAMMPS' `beginstep` (`elaplong` counts from it).
    pub begin: u64,
}

/// Reads a `run` line (after the command name).
pub fn parse(sim: &Sim, a: &mut Args) -> CmdResult<RunPlan> {
    let n = a.u64("number of steps")?;
    let (mut upto, mut start, mut stop, mut pre, mut post) = (false, None, None, true, true);
    let mut every = None;
    while !a.is_done() {
        match a.keyword(
            "run keyword",
            &["upto", "start", "stop", "pre", "post", "every"],
        )? {
            "upto" => upto = true,
            "start" => start = Some((a.pos(), a.u64("start step")?)),
            "stop" => stop = Some((a.pos(), a.u64("stop step")?)),
            "pre" => pre = a.yes_no("pre")?,
            "post" => post = a.yes_no("post")?,
            _ => {
                // Every word after M is a command (so `every` comes last, as the manual
                // says); a single NULL means none.
                let m = a.count("every (steps per chunk)")?;
                let first = a.pos();
                let last = a.words().len();
                let cmds = if last == first + 1 && a.words()[first].text == "NULL" {
                    first..first
                } else {
                    first..last
                };
                a.seek(last);
                every = Some((m, cmds));
            }
        }
    }
    let step = sim.world_ref(a)?.step;
    let nsteps = if upto {
        if n < step {
            return Err(a.error_at(
                1,
                format!("run {n} upto: the current step {step} is already beyond it"),
                None,
            ));
        }
        n - step
    } else {
        n
    };
    if let Some((k, s)) = start {
        if s > step {
            return Err(a.error_at(
                k,
                format!("run start {s} is after the start of the run (step {step})"),
                Some("start must be at or before the current step".into()),
            ));
        }
    }
    if let Some((k, s)) = stop {
        if s < step + nsteps {
            return Err(a.error_at(
                k,
                format!(
                    "run stop {s} is before the end of the run (step {})",
                    step + nsteps
                ),
                Some("stop must be at or after the run's last step".into()),
            ));
        }
    }
    Ok(RunPlan {
        nsteps,
        start: start.map(|s| s.1),
        stop: stop.map(|s| s.1),
        pre,
        post,
        every,
    })
}

impl RunPlan {
    /// The chunk of `nsteps` steps from `step`: `first` (the first chunk of `every`, which
    /// always sets up) and `last` (the last one, which always prints the full summary),
    /// as LAMMPS' `run` does.
    pub fn chunk(&self, step: u64, nsteps: u64, first: bool, last: bool) -> Chunk {
        Chunk {
            nsteps,
            setup: self.pre || first,
            summary: self.post || last,
            begin: self.start.unwrap_or(step),
        }
    }
}

/// `run` without `every` (the interpreter runs `every`'s chunks and commands).
pub fn run_plan(sim: &mut Sim, a: &Args, plan: &RunPlan) -> CmdResult {
    let step = sim.world_ref(a)?.step;
    let chunk = plan.chunk(step, plan.nsteps, false, false);
    run_chunk(sim, a, chunk)
}

/// Runs one chunk; errors point at `a`'s words.
pub fn run_chunk(sim: &mut Sim, a: &Args, chunk: Chunk) -> CmdResult {
    run_steps(sim, chunk).map_err(|e| run_error(a, e))
}

/// A run's error: at the word that introduced what failed when it is known (with the
/// `run` command's line in the help), else at the `run` command.
fn run_error(a: &Args, e: RunError) -> ScriptError {
    let help = e.message.contains("lost").then(|| {
        "'thermo_modify lost error' stops the run when particles leave through a fixed face; \
         'lost warn' (the default) drops them with one warning, 'lost ignore' silently"
            .to_string()
    });
    let mut err = match &e.origin {
        Some(o) => {
            let line = a.command().line;
            ScriptError::at_origin(
                o,
                e.message,
                Some(format!("found during the run of line {line}")),
            )
        }
        None => a.error_cmd(e.message, help),
    };
    err.code = Some(e.code);
    err
}

/// Runs `nsteps` steps with set-up, output and the end-of-run report.
pub fn steps(sim: &mut Sim, nsteps: u64) -> Result<(), RunError> {
    let step = sim.world.as_ref().map(|w| w.step).unwrap_or(0);
    run_steps(
        sim,
        Chunk {
            nsteps,
            setup: true,
            summary: true,
            begin: step,
        },
    )
}

/// Runs a chunk of steps: set-up (or, after `pre no`, the thermo output alone), the
/// steps with their output, and the end-of-run report.
fn run_steps(sim: &mut Sim, chunk: Chunk) -> Result<(), RunError> {
    let nsteps = chunk.nsteps;
    sim.script.halted = false;
    sim.script.stop_requested = false;
    // `pre no` is overridden before anything ran (LAMMPS' `first_update`).
    let setup = chunk.setup || !sim.script.set_up;
    let m = crate::materials::materials(sim)?;
    crate::sph::tables(sim)?;
    {
        let w = sim
            .world
            .as_mut()
            .ok_or("run before the simulation box is defined")?;
        if (w.pair.is_some() || w.sph.is_some()) && !sim.defs.pair_coeff_set {
            return Err("all pair coefficients are not set: add 'pair_coeff * *'".into());
        }
        // LIGGGHTS 3.8 runs on with the pair style of its restart file when the script
        // does not define one (measured); rdem does not decode it.
        if let Some(pair) = sim.defs.restored.liggghts_pair.take() {
            if w.pair.is_none() {
                return Err(format!(
                    "the LIGGGHTS restart file read holds {pair}, which LIGGGHTS would take from \
                     the file; rdem does not: define pair_style and pair_coeff again after read_restart"
                )
                .into());
            }
        }
        w.materials = m;
        // k_finnie for the meshes that wear.
        let ntypes = w.materials.ntypes;
        for mesh in &mut w.meshes {
            let Some(st) = &mut mesh.stress else { continue };
            if !st.finnie {
                continue;
            }
            let p = sim.defs.properties.get("k_finnie").ok_or_else(|| {
                format!(
                    "mesh {} wears (wear finnie): define fix ID all property/global k_finnie peratomtypepair {ntypes} ...",
                    mesh.id
                )
            })?;
            if p.style != "peratomtypepair" || p.values.len() != ntypes * ntypes {
                return Err(format!(
                    "property k_finnie (fix {}) must be peratomtypepair with {} value(s)",
                    p.fix_id,
                    ntypes * ntypes
                )
                .into());
            }
            st.k_finnie = p.values.clone();
            st.ntypes = ntypes;
        }
        w.timers.reset();
        w.fix_timing = sim.script.modify_timing != crate::sim::ModifyTiming::Off;
    }
    // LAMMPS' init: computes count what they keep through the run (skipped with the
    // set-up after `pre no`, as LAMMPS skips `init`).
    if let Some(w) = sim.world.as_ref().filter(|_| setup) {
        for c in &mut sim.defs.computes {
            c.imp.init(w, &c.head);
        }
    }
    let start_step = sim.world.as_ref().map(|w| w.step).unwrap_or(0);
    sim.script.run_first = start_step;
    sim.script.run_last = start_step + nsteps;
    sim.script.run_begin = chunk.begin;
    sim.script.run_started = Instant::now();
    sim.outputs.thermo.last_printed = None;
    let builds0 = sim
        .world
        .as_ref()
        .map(|w| (w.neighbor.nbuilds, w.neighbor.ndangerous))
        .unwrap_or((0, 0));
    let stages = RunStages::of(sim);
    if setup {
        // Set-up: adapt acts before the set-up forces as in LIGGGHTS (setup_pre_force).
        rdem::step::set_up(&mut Front::new(sim, &stages))?;
        let mem = peak_resident_bytes()
            .unwrap_or_else(|| sim.world.as_ref().map_or(0, |w| w.memory_bytes()))
            as f64
            / 1048576.0;
        sim.outputs.out.line(&format!(
            "Memory usage per processor = {} Mbytes",
            crate::variables::format_g(mem, 4)
        ));
    }
    if let Some(h) = thermo::header(sim) {
        sim.outputs.out.thermo_line(&h);
    }
    sim.outputs.thermo.table = thermo::ThermoTable {
        columns: sim.outputs.thermo.columns.clone(),
        rows: Vec::new(),
    };
    // Dumps before thermo, as LIGGGHTS: a compute with an effect (nparticles/tracer/
    // region unmarks what it counts) changes the dumped values after them.
    if !sim.script.check {
        crate::dumps::write_due(sim, start_step, true)?;
    }
    thermo_row(sim)?;
    if sim.script.check {
        crate::check::after_setup(sim, nsteps)?;
        // What a run's end undoes (fix adapt's `reset yes`) is undone here too.
        return stages.end_of_run(sim);
    }
    if let Some(w) = &mut sim.world {
        // The breakdown covers the loop only, as "Loop time" does.
        w.timers.reset();
        w.fixes.iter_mut().for_each(|f| f.seconds = 0.0);
    }
    sim.defs.fixes.iter_mut().for_each(|f| f.seconds = 0.0);
    let t0 = Instant::now();
    sim.script.run_started = t0;
    // The pool's other threads wait for the steps' parallel loops awake (see
    // `rdem::par::with_busy_pool`).
    let (done, stopped) =
        rdem::par::with_busy_pool(|| step_loop(sim, &stages, start_step, nsteps))?;
    if let Some(p) = &mut sim.outputs.progress {
        p(done, done);
    }
    let nsteps = done;
    let loop_time = t0.elapsed().as_secs_f64();
    // The set-up's build is not counted (as in LIGGGHTS).
    let builds0 = (builds0.0 + u64::from(setup), builds0.1);
    report(sim, loop_time, nsteps, builds0, chunk.summary);
    stages.end_of_run(sim)?;
    match stopped {
        Some(m) => Err(m.into()),
        None => Ok(()),
    }
}

/// The steps of a run after its set-up, with their output: the number of steps done
/// (fewer than `nsteps` when the step hook ended the run) and the hook's error, if any.
fn step_loop(
    sim: &mut Sim,
    stages: &RunStages,
    start_step: u64,
    nsteps: u64,
) -> Result<(u64, Option<String>), RunError> {
    let mut last_progress = Instant::now();
    let mut done = nsteps;
    let mut stopped = None;
    for k in 0..nsteps {
        let step = start_step + k + 1;
        rdem::step::step(&mut Front::new(sim, stages))?;
        let t_out = Instant::now();
        let every = sim.outputs.thermo.every;
        crate::dumps::write_due(sim, step, false)?;
        crate::commands::restart::write_due(sim, step)?;
        if (every > 0 && step % every == 0) || step == sim.script.run_last {
            thermo_row(sim)?;
        }
        if let Some(w) = &mut sim.world {
            w.timers.lap(Stage::Output, t_out);
        }
        if last_progress.elapsed().as_secs_f64() > 0.5 {
            last_progress = Instant::now();
            if let Some(p) = &mut sim.outputs.progress {
                p(k + 1, nsteps);
            }
        }
        if std::mem::take(&mut sim.script.stop_requested) {
            // A fix ended the run (its output of this step is written).
            done = k + 1;
            sim.script.run_last = step;
            sim.script.halted = true;
            if !(every > 0 && step % every == 0) {
                thermo_row(sim)?;
            }
            break;
        }
        if let Some(mut hook) = sim.outputs.step_hook.take() {
            let asked = hook(sim, step);
            sim.outputs.step_hook = Some(hook);
            if let Err(m) = &asked {
                stopped = Some(m.to_string());
            }
            if !matches!(asked, Ok(true)) {
                // The run ends here, as if it had been asked for this many steps.
                done = k + 1;
                sim.script.run_last = step;
                sim.script.halted = true;
                thermo_row(sim)?;
                break;
            }
        }
    }
    Ok((done, stopped))
}

/// The script's fixes as the front-end stages of a step ([`StepHost`]): the pre-step
/// and end-of-step fixes around the engine's part, the insertions inside it.
struct Front<'a> {
    sim: &'a mut Sim,
    stages: &'a RunStages,
}

impl<'a> Front<'a> {
    fn new(sim: &'a mut Sim, stages: &'a RunStages) -> Self {
        Self { sim, stages }
    }
}

impl StepHost for Front<'_> {
    type Error = RunError;

    fn world(&mut self) -> &mut World {
        self.sim.world.as_mut().expect(WORLD)
    }

    /// The fixes due in the step's pre-exchange stage (insertion) act on the world while
    /// the engine holds it; their lines are printed once the engine is done.
    fn with_hooks(
        &mut self,
        f: impl FnOnce(&mut World, &mut dyn StepHooks) -> rdem::Result<()>,
    ) -> Result<(), RunError> {
        let Sim { world, defs, .. } = &mut *self.sim;
        let w = world.as_mut().expect(WORLD);
        let step = w.step + 1;
        let fixes = &mut defs.fixes;
        if self.stages.post_integrate.is_empty()
            && !self
                .stages
                .pre_exchange
                .iter()
                .any(|&k| fixes[k].imp.due(step))
        {
            return Ok(f(w, &mut NoHooks)?);
        }
        let mut hooks = Insertions {
            fixes,
            post_integrate: &self.stages.post_integrate,
            candidates: &self.stages.pre_exchange,
            step,
            notes: Notes::default(),
        };
        let result = f(w, &mut hooks);
        hooks.notes.print(&mut self.sim.outputs.out);
        Ok(result?)
    }

    fn pre_step(&mut self, step: u64, setup: bool) -> Result<(), RunError> {
        let (sim, stages) = (&mut *self.sim, self.stages);
        stages.pre_step(sim, step, setup)?;
        if setup {
            // As LIGGGHTS: only when there is no fix at all.
            if sim.defs.fixes.is_empty() {
                sim.warn_once("No fixes defined, atoms won't move");
            }
            sim.outputs.out.line("Setting up run ...");
        }
        let want = stages.wants_virial(sim, step, setup);
        self.world().want_virial = want;
        Ok(())
    }

    fn end_of_step(&mut self, step: u64, setup: bool) -> Result<(), RunError> {
        let sim = &mut *self.sim;
        if setup {
            sim.script.set_up = true;
        }
        flush_world_warnings(sim);
        self.stages.end_of_step(sim, step, setup)
    }
}

/// The fixes due in a step's pre-exchange stage (insertion), borrowed from the script's
/// fix list while the engine holds the world, and what they print.
struct Insertions<'a> {
    fixes: &'a mut [FixEntry],
    /// The fixes with a post-integrate stage: they act first, every step.
    post_integrate: &'a [usize],
    /// The fixes with a pre-exchange stage; those due at `step` act.
    candidates: &'a [usize],
    step: u64,
    notes: Notes,
}

impl StepHooks for Insertions<'_> {
    fn mask(&self) -> HookMask {
        HookMask { pre_exchange: true }
    }

    fn pre_exchange(&mut self, w: &mut World) -> rdem::Result<()> {
        // LIGGGHTS' post_integrate comes before its pre_exchange, in the same place of
        // the step (after the initial integration and the mesh motion).
        for &k in self.post_integrate {
            let f = &mut self.fixes[k];
            let t0 = w.fix_timing.then(Instant::now);
            f.imp.post_integrate(&f.head, w)?;
            if let Some(t0) = t0 {
                f.seconds += t0.elapsed().as_secs_f64();
            }
        }
        for &k in self.candidates {
            let f = &mut self.fixes[k];
            if f.imp.due(self.step) {
                let t0 = w.fix_timing.then(Instant::now);
                f.imp.pre_exchange(&f.head, w, &mut self.notes)?;
                if let Some(t0) = t0 {
                    f.seconds += t0.elapsed().as_secs_f64();
                }
            }
        }
        Ok(())
    }
}

/// An error of fix `k`'s stage, at the fix's style word.
fn fix_error(sim: &Sim, k: usize, message: String) -> RunError {
    RunError::at(sim.defs.fixes[k].origin.as_ref(), "rdem::run::fix", message)
}

/// The fixes of each stage, listed once when a run starts (no fix is added or removed
/// during a run): a stage no fix uses costs nothing.
struct RunStages {
    pre_step: Vec<usize>,
    post_integrate: Vec<usize>,
    pre_exchange: Vec<usize>,
    end_of_step: Vec<usize>,
    end_of_run: Vec<usize>,
    /// A `compute stress/atom` with a pair term wants the virial at every step.
    virial_always: bool,
}

impl RunStages {
    fn of(sim: &Sim) -> Self {
        Self {
            pre_step: fixes::with_stage(sim, Stages::PRE_STEP),
            post_integrate: fixes::with_stage(sim, Stages::POST_INTEGRATE),
            pre_exchange: fixes::with_stage(sim, Stages::PRE_EXCHANGE),
            end_of_step: fixes::with_stage(sim, Stages::END_OF_STEP),
            end_of_run: fixes::with_stage(sim, Stages::END_OF_RUN),
            virial_always: sim.defs.computes.iter().any(|c| c.imp.needs_virial()),
        }
    }

    /// Whether the force pass of `step` (or of the set-up at `step`) must compute the
    /// contact virial.
    fn wants_virial(&self, sim: &Sim, step: u64, setup: bool) -> bool {
        self.virial_always
            || self
                .end_of_step
                .iter()
                .any(|&k| sim.defs.fixes[k].imp.wants_virial(step, setup))
    }

    fn pre_step(&self, sim: &mut Sim, step: u64, setup: bool) -> Result<(), RunError> {
        for &k in &self.pre_step {
            fixes::with_fix(sim, k, |f, sim, head| {
                f.pre_step(&mut StageCtx::new(sim, step, setup).expect(WORLD), head)
            })
            .map_err(|m| fix_error(sim, k, m.to_string()))?;
        }
        Ok(())
    }

    fn end_of_step(&self, sim: &mut Sim, step: u64, setup: bool) -> Result<(), RunError> {
        for &k in &self.end_of_step {
            fixes::with_fix(sim, k, |f, sim, head| {
                f.end_of_step(&mut StageCtx::new(sim, step, setup).expect(WORLD), head)
            })
            .map_err(|m| fix_error(sim, k, m.to_string()))?;
        }
        Ok(())
    }

    fn end_of_run(&self, sim: &mut Sim) -> Result<(), RunError> {
        let step = sim.world.as_ref().expect(WORLD).step;
        for &k in &self.end_of_run {
            fixes::with_fix(sim, k, |f, sim, head| {
                f.end_of_run(&mut StageCtx::new(sim, step, false).expect(WORLD), head)
            })
            .map_err(|m| fix_error(sim, k, m.to_string()))?;
        }
        Ok(())
    }
}

/// A run has a world (`run_steps` checks it first).
const WORLD: &str = "a run has a world";

fn flush_world_warnings(sim: &mut Sim) {
    if let Some(w) = &mut sim.world {
        let ws = std::mem::take(&mut w.warnings);
        for m in ws {
            sim.outputs.out.warning(&m);
        }
    }
}

fn thermo_row(sim: &mut Sim) -> Result<(), RunError> {
    let step = sim.world.as_ref().map(|w| w.step);
    if step.is_some() && sim.outputs.thermo.last_printed == step {
        return Ok(());
    }
    let (r, values) = thermo::row_and_values(sim)?;
    sim.outputs.out.thermo_line(&r);
    sim.outputs.thermo.table.rows.push(values);
    sim.outputs.thermo.last_printed = step;
    Ok(())
}

/// LAMMPS' per-rank statistics of one count: `Label:    ave ave max max min min` and a
/// ten-bin histogram of the ranks' values between min and max.
fn spread(label: &str, vals: &[f64]) -> (String, String) {
    let g = |v: f64| crate::variables::format_g(v, 6);
    let n = vals.len().max(1) as f64;
    let ave = vals.iter().sum::<f64>() / n;
    let max = vals.iter().copied().fold(f64::MIN, f64::max).max(0.0);
    let min = vals.iter().copied().fold(f64::MAX, f64::min).min(max);
    let mut bins = [0usize; 10];
    for &v in vals {
        let b = if max > min {
            (((v - min) / (max - min) * 10.0) as usize).min(9)
        } else {
            0
        };
        bins[b] += 1;
    }
    let hist: Vec<String> = bins.iter().map(|b| b.to_string()).collect();
    (
        format!("{label}:    {} ave {} max {} min", g(ave), g(max), g(min)),
        format!("Histogram: {}", hist.join(" ")),
    )
}

/// The end-of-run report in LIGGGHTS' words.
/// With `summary` false (`run ... post no`), the loop-time line alone.
fn report(sim: &mut Sim, loop_time: f64, nsteps: u64, builds0: (u64, u64), summary: bool) {
    let Some(w) = &sim.world else { return };
    let natoms = w.natoms();
    let nprocs = w.comm.size();
    let timers = w.timers;
    // Builds during the steps.
    let nbuilds = w.neighbor.nbuilds.saturating_sub(builds0.0);
    let ndanger = w.neighbor.ndangerous - builds0.1;
    // Per-rank counts, gathered for the ave/max/min lines and histograms.
    let counts = w.comm.all_gather(&[
        w.particles.nlocal() as f64,
        w.particles.nghost() as f64,
        w.neighbor.list.partner.len() as f64,
    ]);
    let column = |k: usize| -> Vec<f64> { counts.iter().skip(k).step_by(3).copied().collect() };
    let pairs = column(2).iter().sum::<f64>() as usize;
    let g = |v: f64| crate::variables::format_g(v, 6);
    let mut lines = vec![format!(
        "Loop time of {} on {nprocs} procs for {nsteps} steps with {natoms} atoms",
        g(loop_time)
    )];
    lines.push(String::new());
    if !summary {
        for l in lines {
            sim.outputs.out.line(&l);
        }
        return;
    }
    let pct = |t: f64| {
        if loop_time > 0.0 {
            100.0 * t / loop_time
        } else {
            0.0
        }
    };
    // LIGGGHTS' labels; Modify (the fixes) is rdem's addition, which LIGGGHTS prints
    // as `Modfy` under `modify_timing`.
    let timing = sim.script.modify_timing;
    let stages = [
        ("Pair ", Stage::Pair),
        ("Neigh", Stage::Neigh),
        ("Comm ", Stage::Comm),
        ("Outpt", Stage::Output),
        (
            if timing == ModifyTiming::Off {
                "Modify"
            } else {
                "Modfy"
            },
            Stage::Modify,
        ),
    ];
    let mut accounted = 0.0;
    for (name, st) in stages {
        let t = timers.get(st).as_secs_f64();
        accounted += t;
        lines.push(format!("{name} time (%) = {} ({})", g(t), g(pct(t))));
        if st == Stage::Modify && timing == ModifyTiming::Verbose {
            for (r, t) in w.comm.all_gather(&[t]).into_iter().enumerate() {
                lines.push(format!(
                    "  Modify   time [{r}] (%) = {} ({})",
                    g(t),
                    g(pct(t))
                ));
            }
        }
    }
    let other = (loop_time - accounted).max(0.0);
    lines.push(format!("Other time (%) = {} ({})", g(other), g(pct(other))));
    if timing != ModifyTiming::Off {
        // Each fix's stages in the script and in the engine (an engine fix shares its
        // script fix's ID).
        let times: Vec<f64> = sim
            .defs
            .fixes
            .iter()
            .map(|e| {
                e.seconds
                    + w.fixes
                        .iter()
                        .filter(|f| f.id == e.head.id)
                        .map(|f| f.seconds)
                        .sum::<f64>()
            })
            .collect();
        let ranks = w.comm.all_gather(&times);
        for (k, e) in sim.defs.fixes.iter().enumerate() {
            let t = times[k];
            lines.push(format!(
                "Fix {} {} time (%) = {} ({})",
                e.head.id,
                e.head.style,
                g(t),
                g(pct(t))
            ));
            if timing == ModifyTiming::Verbose {
                for (r, row) in ranks.chunks(times.len().max(1)).enumerate() {
                    lines.push(format!(
                        "  [{r}] Fix {} {} time {}",
                        e.head.id,
                        e.head.style,
                        g(row[k])
                    ));
                }
            }
        }
    }
    lines.push(String::new());
    for (label, k) in [("Nlocal", 0), ("Nghost", 1), ("Neighs", 2)] {
        let (line, hist) = spread(label, &column(k));
        lines.push(line);
        lines.push(hist);
    }
    lines.push(String::new());
    lines.push(format!("Total # of neighbors = {pairs}"));
    if natoms > 0 {
        lines.push(format!(
            "Ave neighs/atom = {}",
            g(pairs as f64 / natoms as f64)
        ));
    }
    lines.push(format!("Neighbor list builds = {nbuilds}"));
    lines.push(format!("Dangerous builds = {ndanger}"));
    lines.push(String::new());
    for l in lines {
        sim.outputs.out.line(&l);
    }
}

/// This process's peak resident memory so far, in bytes: `VmHWM` of `/proc/self/status`
/// (Linux). "Memory usage per processor" prints it after the set-up, whose first neighbor
/// build and list allocations are where a run's memory peaks: the figure is what the
/// process really held, every buffer counted (the engine's own count of its particle
/// arrays and neighbor list, [`rdem::world::World::memory_bytes`], missed half of it at a
/// million particles, and is printed only where `/proc` is missing).
fn peak_resident_bytes() -> Option<usize> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}
