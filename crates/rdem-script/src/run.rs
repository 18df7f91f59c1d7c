//! `run N [upto]`: set-up, the steps with the front-end hooks around and inside the
//! engine's [`World::advance_with`] (`rdem::step` writes down the order of a step and where
//! these front-end stages sit in it), thermo and dump output, and LIGGGHTS' end-of-run
//! report (`Loop time of T on P procs for N steps with M atoms` and the stage breakdown).

use std::time::Instant;

use rdem::timers::Stage;
use rdem::{HookMask, StepHooks, World};

use crate::args::{Args, CmdResult};
use crate::context;
use crate::fixes::{self, FrontFix, InsertEngine};
use crate::sim::Sim;
use crate::thermo;

/// `run N [upto]`.
pub fn run(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let n = a.u64("number of steps")?;
    let mut upto = false;
    while !a.is_done() {
        match a.keyword(
            "run keyword",
            &["upto", "start", "stop", "pre", "post", "every"],
        )? {
            "upto" => upto = true,
            k => {
                return Err(a.error_prev(
                    format!("run {k} is not supported yet"),
                    Some("supported: 'run N' and 'run N upto'".into()),
                ))
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
    steps(sim, nsteps).map_err(|m| {
        let help = m.contains("lost").then(|| {
            "particles that leave through a fixed face stop the run by default; \
             'thermo_modify lost ignore' (or warn) drops them instead"
                .to_string()
        });
        a.error_cmd(m, help)
    })
}

/// Runs `nsteps` steps with set-up, output and the end-of-run report.
pub fn steps(sim: &mut Sim, nsteps: u64) -> Result<(), String> {
    let m = crate::materials::materials(sim)?;
    {
        let w = sim
            .world
            .as_mut()
            .ok_or("run before the simulation box is defined")?;
        if w.pair.is_some() && !sim.pair_coeff_set {
            return Err("all pair coefficients are not set: add 'pair_coeff * *'".into());
        }
        w.materials = m;
        // k_finnie for the meshes that wear.
        let ntypes = sim.ntypes;
        for mesh in &mut w.meshes {
            let Some(st) = &mut mesh.stress else { continue };
            if !st.finnie {
                continue;
            }
            let p = sim.properties.get("k_finnie").ok_or_else(|| {
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
                ));
            }
            st.k_finnie = p.values.clone();
            st.ntypes = ntypes;
        }
        w.neighbor.settings = sim.pending.neighbor;
        w.sort = sim.pending.sort;
        w.lost_policy = sim.pending.lost;
        w.set_timestep(sim.pending.dt).map_err(|e| e.to_string())?;
        w.timers.reset();
    }
    let start_step = sim.world.as_ref().map(|w| w.step).unwrap_or(0);
    sim.run_first = start_step;
    sim.run_last = start_step + nsteps;
    sim.run_started = Instant::now();
    sim.thermo.last_printed = None;
    let builds0 = sim
        .world
        .as_ref()
        .map(|w| (w.neighbor.nbuilds, w.neighbor.ndangerous))
        .unwrap_or((0, 0));
    // Set-up: adapt acts before the set-up forces as in LIGGGHTS (setup_pre_force).
    adapt_all(sim, start_step, true)?;
    // As LIGGGHTS: only when there is no fix at all.
    if sim.fixes.is_empty() {
        sim.warn_once("No fixes defined, atoms won't move");
    }
    sim.out.line("Setting up run ...");
    let want = crate::euler::wants_virial(sim, start_step, true);
    let w = sim.world.as_mut().expect("checked");
    w.want_virial = want;
    w.setup().map_err(|e| e.to_string())?;
    crate::euler::end_of_step(sim, start_step, true)?;
    flush_world_warnings(sim);
    let mem = sim.world.as_ref().map(|w| w.memory_bytes()).unwrap_or(0) as f64 / 1048576.0;
    sim.out.line(&format!(
        "Memory usage per processor = {} Mbytes",
        crate::variables::format_g(mem, 4)
    ));
    sim.out.line(&thermo::header(sim));
    thermo_row(sim)?;
    crate::dump::write_due(sim, start_step, true)?;
    if let Some(w) = &mut sim.world {
        // The breakdown covers the loop only, as "Loop time" does.
        w.timers.reset();
    }
    let t0 = Instant::now();
    sim.run_started = t0;
    let mut last_progress = Instant::now();
    for k in 0..nsteps {
        let step = start_step + k + 1;
        adapt_all(sim, step, false)?;
        let want = crate::euler::wants_virial(sim, step, false);
        if let Some(w) = &mut sim.world {
            w.want_virial = want;
        }
        advance(sim, step)?;
        flush_world_warnings(sim);
        end_of_step(sim, step)?;
        let t_out = Instant::now();
        let every = sim.thermo.every;
        if (every > 0 && step % every == 0) || step == sim.run_last {
            thermo_row(sim)?;
        }
        crate::dump::write_due(sim, step, false)?;
        if let Some(w) = &mut sim.world {
            w.timers.lap(Stage::Output, t_out);
        }
        if last_progress.elapsed().as_secs_f64() > 0.5 {
            last_progress = Instant::now();
            if let Some(p) = &mut sim.progress {
                p(k + 1, nsteps);
            }
        }
    }
    if let Some(p) = &mut sim.progress {
        p(nsteps, nsteps);
    }
    let loop_time = t0.elapsed().as_secs_f64();
    report(sim, loop_time, nsteps, builds0);
    reset_adapt(sim)?;
    Ok(())
}

fn flush_world_warnings(sim: &mut Sim) {
    if let Some(w) = &mut sim.world {
        let ws = std::mem::take(&mut w.warnings);
        for m in ws {
            sim.out.warning(&m);
        }
    }
}

fn thermo_row(sim: &mut Sim) -> Result<(), String> {
    let step = sim.world.as_ref().map(|w| w.step);
    if step.is_some() && sim.thermo.last_printed == step {
        return Ok(());
    }
    let r = thermo::row(sim)?;
    sim.out.line(&r);
    sim.thermo.last_printed = step;
    Ok(())
}

/// One step of the engine, with the insertion fixes due at `step` acting inside it as in
/// LIGGGHTS (after the initial integration: new particles are not moved in the step they
/// appear, get their forces and the final half kick).
fn advance(sim: &mut Sim, step: u64) -> Result<(), String> {
    let due: Vec<usize> = (0..sim.fixes.len())
        .filter(|&k| matches!(&sim.fixes[k].kind, FrontFix::Insert(ins) if ins.pack.due(step)))
        .collect();
    let w = sim.world.as_mut().expect("a run has a world");
    if due.is_empty() {
        return w.advance().map_err(|e| e.to_string());
    }
    let mut taken: Vec<(usize, FrontFix)> = due
        .iter()
        .map(|&k| {
            (
                k,
                std::mem::replace(&mut sim.fixes[k].kind, FrontFix::Engine),
            )
        })
        .collect();
    let mut hooks = Insertions {
        taken: &mut taken,
        reports: Vec::new(),
    };
    let result = w.advance_with(&mut hooks);
    let reports = hooks.reports;
    for (k, f) in taken {
        sim.fixes[k].kind = f;
    }
    result.map_err(|e| e.to_string())?;
    for (k, rep, total, total_mass, verbose) in reports {
        let id = &sim.fixes[k].id;
        // An event that had nothing to insert prints nothing (as LIGGGHTS).
        if verbose && rep.wanted > 0 {
            let line = fixes::insertion_report(id, rep.inserted, rep.mass, step, total, total_mass);
            sim.out.line(&line);
        }
        if rep.inserted < rep.wanted {
            let msg = format!(
                "Particle insertion {id}: less insertions than requested ({} of {}): the region is too full or maxattempt too small",
                rep.inserted, rep.wanted
            );
            sim.out.warning(&msg);
        }
    }
    Ok(())
}

/// The insertion fixes due at a step, in the engine's pre-exchange stage; what each
/// inserted: (fix index, report, total count, total mass, verbose).
struct Insertions<'a> {
    taken: &'a mut [(usize, FrontFix)],
    reports: Vec<(usize, rdem::insert::InsertReport, u64, f64, bool)>,
}

impl StepHooks for Insertions<'_> {
    fn mask(&self) -> HookMask {
        HookMask {
            pre_exchange: true,
            ..HookMask::NONE
        }
    }

    fn pre_exchange(&mut self, w: &mut World) -> rdem::Result<()> {
        for (k, f) in self.taken.iter_mut() {
            let FrontFix::Insert(ins) = f else { continue };
            let rep = match (&mut ins.pack, &mut ins.rate) {
                (InsertEngine::Stream(st), _) => st.insert(w)?,
                (InsertEngine::Pack(pack), None) => pack.insert(w)?,
                (InsertEngine::Pack(pack), Some(r)) => {
                    let want = r.per_insertion + r.carry;
                    let mut n = want.floor() as u64;
                    r.carry = want - n as f64;
                    if let Some(lim) = r.limit {
                        n = n.min(lim.saturating_sub(ins.total));
                    }
                    pack.insert_n(w, n)?
                }
            };
            ins.total += rep.inserted;
            ins.total_mass += rep.mass;
            self.reports
                .push((*k, rep, ins.total, ins.total_mass, ins.verbose));
        }
        Ok(())
    }
}

fn adapt_all(sim: &mut Sim, step: u64, setup: bool) -> Result<(), String> {
    for k in 0..sim.fixes.len() {
        let (every, var) = match &sim.fixes[k].kind {
            FrontFix::Adapt(ad) => (ad.every, ad.var.clone()),
            _ => continue,
        };
        if !setup && step % every != 0 {
            continue;
        }
        let groupbit = sim.fixes[k].groupbit;
        let formula = match sim.vars.get(&var) {
            Some(crate::variables::Variable::Atom(f)) => f.clone(),
            Some(_) => return Err(format!("fix adapt: variable '{var}' is not atom-style")),
            None => return Err(format!("fix adapt: no variable '{var}'")),
        };
        let d = context::eval_atom(sim, &formula)?;
        let w = sim.world.as_mut().expect("run has a world");
        if let FrontFix::Adapt(ad) = &mut sim.fixes[k].kind {
            if ad.reset && ad.saved.is_none() {
                let p = &w.particles;
                ad.saved = Some((0..p.nlocal()).map(|i| (p.tag[i], p.radius[i])).collect());
            }
        }
        let p = &w.particles;
        let radii: Vec<f64> = (0..p.nlocal())
            .map(|i| {
                if p.mask[i] & groupbit != 0 {
                    0.5 * d[i]
                } else {
                    p.radius[i]
                }
            })
            .collect();
        w.set_radii(&radii)
            .map_err(|e| format!("fix {}: {e}", sim.fixes[k].id))?;
    }
    Ok(())
}

fn reset_adapt(sim: &mut Sim) -> Result<(), String> {
    for f in &mut sim.fixes {
        if let FrontFix::Adapt(ad) = &mut f.kind {
            if let (Some(saved), Some(w)) = (ad.saved.take(), &mut sim.world) {
                let p = &w.particles;
                let mut r: Vec<f64> = p.radius[..p.nlocal()].to_vec();
                for (i, ri) in r.iter_mut().enumerate() {
                    if let Some(&(_, r0)) = saved.iter().find(|(t, _)| *t == p.tag[i]) {
                        *ri = r0;
                    }
                }
                w.set_radii(&r).map_err(|e| e.to_string())?;
            }
        }
    }
    Ok(())
}

fn end_of_step(sim: &mut Sim, step: u64) -> Result<(), String> {
    crate::euler::end_of_step(sim, step, false)?;
    for k in 0..sim.fixes.len() {
        if let FrontFix::MassFlow(mf) = &mut sim.fixes[k].kind {
            let w = sim.world.as_mut().expect("a run has a world");
            mf.flow.update(w).map_err(|e| e.to_string())?;
            continue;
        }
        match &sim.fixes[k].kind {
            FrontFix::CheckTimestep(c) if step % c.every == 0 => {
                let (fr, fh, vmax, warn, error) =
                    (c.fraction_r, c.fraction_h, c.vmax, c.warn, c.error);
                let Some((tr, th)) = fixes::timestep_limits(sim, vmax) else {
                    continue;
                };
                let dt = sim.world.as_ref().map(|w| w.dt).unwrap_or(0.0);
                let vals = [dt / tr, if th < f64::MAX { dt / th } else { 0.0 }];
                let id = sim.fixes[k].id.clone();
                if let FrontFix::CheckTimestep(c) = &mut sim.fixes[k].kind {
                    c.values = vals;
                }
                for (v, f, what) in [(vals[0], fr, "Rayleigh"), (vals[1], fh, "Hertz")] {
                    if v > f {
                        let msg = format!(
                            "time-step is {:.2} % of {what} time (fix {id}: limit {:.2} %)",
                            100.0 * v,
                            100.0 * f
                        );
                        if error {
                            return Err(msg);
                        }
                        if warn {
                            sim.warn_once(&msg);
                        }
                    }
                }
            }
            FrontFix::AveTime(ave) => {
                let in_window = {
                    let next = step.div_ceil(ave.nfreq) * ave.nfreq;
                    let first = next.saturating_sub((ave.nrepeat - 1) * ave.nevery);
                    step >= first && (next - step) % ave.nevery == 0
                };
                if !in_window {
                    continue;
                }
                let inputs = ave.inputs.clone();
                let mut vals = Vec::with_capacity(inputs.len());
                for i in &inputs {
                    vals.push(thermo::column_value(sim, i)?.0);
                }
                let FrontFix::AveTime(ave) = &mut sim.fixes[k].kind else {
                    unreachable!()
                };
                for (s, v) in ave.sum.iter_mut().zip(&vals) {
                    *s += v;
                }
                ave.count += 1;
                if step % ave.nfreq == 0 {
                    ave.windows += 1;
                    for j in 0..ave.values.len() {
                        let mean = ave.sum[j] / ave.count as f64;
                        ave.running_sum[j] += mean;
                        ave.values[j] = if ave.running {
                            ave.running_sum[j] / ave.windows as f64
                        } else {
                            mean
                        };
                    }
                    ave.sum.iter_mut().for_each(|s| *s = 0.0);
                    ave.count = 0;
                    if let Some(f) = &mut ave.file {
                        use std::io::Write;
                        let row: Vec<String> = ave
                            .values
                            .iter()
                            .map(|v| crate::variables::format_g(*v, 6))
                            .collect();
                        writeln!(f, "{step} {}", row.join(" ")).map_err(|e| e.to_string())?;
                        f.flush().map_err(|e| e.to_string())?;
                    }
                }
            }
            _ => {}
        }
    }
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
fn report(sim: &mut Sim, loop_time: f64, nsteps: u64, builds0: (u64, u64)) {
    let Some(w) = &sim.world else { return };
    let natoms = w.natoms();
    let nprocs = w.comm.size();
    let timers = w.timers;
    // Builds during the steps (the set-up build is not counted, as in LIGGGHTS).
    let nbuilds = w.neighbor.nbuilds.saturating_sub(builds0.0 + 1);
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
    let pct = |t: f64| {
        if loop_time > 0.0 {
            100.0 * t / loop_time
        } else {
            0.0
        }
    };
    // LIGGGHTS' labels; Modify (the fixes) is rdem's addition.
    let stages = [
        ("Pair ", Stage::Pair),
        ("Neigh", Stage::Neigh),
        ("Comm ", Stage::Comm),
        ("Outpt", Stage::Output),
        ("Modify", Stage::Modify),
    ];
    let mut accounted = 0.0;
    for (name, st) in stages {
        let t = timers.get(st).as_secs_f64();
        accounted += t;
        lines.push(format!("{name} time (%) = {} ({})", g(t), g(pct(t))));
    }
    let other = (loop_time - accounted).max(0.0);
    lines.push(format!("Other time (%) = {} ({})", g(other), g(pct(other))));
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
        sim.out.line(&l);
    }
}
