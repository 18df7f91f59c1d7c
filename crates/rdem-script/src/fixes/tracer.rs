//! Residence-time tracers of LIGGGHTS 3.8, for residence time distributions:
//!
//! - `fix ID group property/atom/tracer region_mark REGION mark_step S [marker_style
//!   dirac|heaviside] [check_mark_every N]`: a per-particle marker (1 marked, 0 not). At
//!   the end of every step that is a multiple of N (default 10) and not before S, the
//!   group's particles inside the region are marked: with `dirac` (the default) at the
//!   first such step only, with `heaviside` at every such step from then on. The global
//!   scalar `f_ID` is the number of particles marked since it was last read (reading it
//!   starts the count again, as in LIGGGHTS). `compute nparticles/tracer/region` counts
//!   marked particles in a region and unmarks them.
//! - `fix ID group property/atom/tracer/stream mark_step S n_tracer N insert_stream INS
//!   every E|once`: marks, among the particles the `fix insert/stream` INS inserts, the
//!   first N (in the order of their release step, the step they pass the insertion face)
//!   released at or after S; with `every E` again the first N released at or after
//!   S + E, S + 2E, ... ([`StreamMarking`] gives the rules, measured on LIGGGHTS 3.8).
//! - `fix ID group property/atom/regiontracer/time [add_region REGION]...
//!   [check_region_every N]`: per particle of the group, the time it has spent in the
//!   simulation (dt added at the end of every step) and in each region. Whether a
//!   particle is in a region is looked up at the end of steps that are multiples of N
//!   (default 10), and dt is added at the end of every step while the last look-up found
//!   it inside. Per-atom: a vector (no region) or an array (domain time, then one column
//!   per region in their order); global vector: the mean of each column over the group.
//!
//! These rules were measured on LIGGGHTS 3.8 (the Debian package): with particles moving
//! at constant speed through the regions, the step each is marked and each accumulated
//! time agree with them (see `tests/tracer.rs` of rdem-cli). Both markers and times are
//! per-particle properties, so they move with their particles between ranks and come back
//! from restart files.

use std::collections::HashSet;
use std::sync::{Arc, Mutex};

use crate::error::Error;
use rdem::Tag;

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row of `property/atom/tracer`.
pub(super) const ROW: FixRow = style(
    "property/atom/tracer",
    parse_tracer,
    Stages::PRE_STEP
        .and(Stages::END_OF_STEP)
        .and(Stages::END_OF_RUN)
        .and(Stages::VALUES),
    "`region_mark REGION mark_step S [marker_style dirac|heaviside] [check_mark_every N]`: marks the group's particles in the region (once at the first check from step S on, or at every check with heaviside); `f_ID` per atom the marker, global the number marked since last read",
);

/// The registry row of `property/atom/tracer/stream`.
pub(super) const ROW_STREAM: FixRow = style(
    "property/atom/tracer/stream",
    parse_stream,
    Stages::PRE_STEP
        .and(Stages::END_OF_STEP)
        .and(Stages::END_OF_RUN)
        .and(Stages::VALUES),
    "`mark_step S n_tracer N insert_stream INS every E\\|once`: marks the first N particles of the group the insert/stream INS releases at or after step S (and S + E, S + 2E, ...); `f_ID` per atom the marker, global the number marked since last read",
)
.notes("the windows and the skipped ones are LIGGGHTS 3.8's (measured): a window S + kE is taken up by the packet inserted before it only when it starts after that packet's step and before the next packet's; particles released at the same step are taken in the order of their IDs (LIGGGHTS sorts them with an unstable sort)");

/// The registry row of `property/atom/regiontracer/time`.
pub(super) const ROW_TIME: FixRow = style(
    "property/atom/regiontracer/time",
    parse_time,
    Stages::END_OF_STEP.and(Stages::VALUES),
    "`[add_region REGION]... [check_region_every N]`: per particle, the time spent in the simulation and in each region (looked up every N steps); global: the mean of each over the group",
);

/// Particles whose marker `compute nparticles/tracer/region` has cleared, by tag, until
/// the tracer fix writes the zeros into its property (before the next step). Until then
/// the fix reports them as unmarked.
#[derive(Debug, Default)]
pub struct Unmarked(Mutex<Vec<Tag>>);

impl Unmarked {
    /// Queues `tags` to be unmarked.
    pub fn push(&self, tags: &[Tag]) {
        self.0.lock().expect("unmark queue").extend_from_slice(tags);
    }

    /// The queued tags.
    pub fn tags(&self) -> HashSet<Tag> {
        self.0
            .lock()
            .expect("unmark queue")
            .iter()
            .copied()
            .collect()
    }
}

/// `fix property/atom/tracer` and `fix property/atom/tracer/stream`.
pub struct Tracer {
    /// The particle property holding the marker.
    pub prop: String,
    /// How particles get marked.
    mode: Mode,
    /// Particles marked on this rank since the global scalar was last read.
    marked: Arc<Mutex<u64>>,
    /// Markers cleared by computes, not yet written.
    pub unmarked: Arc<Unmarked>,
}

/// How a tracer marks.
enum Mode {
    /// `property/atom/tracer`: in a region, at the end of checked steps.
    Region {
        region: String,
        mark_step: u64,
        heaviside: bool,
        every: u64,
        /// The dirac impulse was given.
        done: bool,
    },
    /// `property/atom/tracer/stream`: among the packets of an insert/stream, which marks
    /// them as it inserts them (through the shared [`StreamMarking`]).
    Stream {
        /// The insert/stream's fix ID.
        insert: String,
        marking: Arc<StreamMarking>,
    },
}

/// The marking of `fix property/atom/tracer/stream`, shared with the `fix insert/stream`
/// it follows, which calls [`StreamMarking::mark`] on each packet right after inserting
/// it (as LIGGGHTS' insert/stream calls its tracers).
///
/// The rules, as LIGGGHTS 3.8 marks (measured on a stream of 500-particle packets every
/// 500 steps with mark steps and periods chosen to probe them):
/// - the pending windows start with one at `mark_step` wanting N particles;
/// - at a packet inserted at step t (packets every P steps): `every once` drops the window
///   once it has its N; otherwise windows are dropped from the front while they have
///   their N or started before t − P (with a warning if some were not marked), and the
///   windows S + kE (k ≥ 1) with t < S + kE < t + P are added;
/// - the packet's particles of the group released at or after the first window's start
///   are taken in the order of their release steps (ties by ID); each marks one for the
///   current window if its release is at or after the window's start, and a window that
///   has its N passes on to the next one.
pub struct StreamMarking {
    prop: String,
    groupbit: u32,
    mark_step: u64,
    n_tracer: u64,
    /// 0: `once`.
    every: u64,
    /// The pending windows: (start step, particles still wanted).
    windows: Mutex<std::collections::VecDeque<(u64, u64)>>,
    /// The tracer fix's count of marked particles.
    marked: Arc<Mutex<u64>>,
}

impl StreamMarking {
    /// Marks among the particles `first..` of this rank, a packet just inserted at `w`'s
    /// step by a stream with a packet every `period` steps. Every rank calls it (the
    /// packet's release steps are gathered).
    pub fn mark(&self, w: &mut rdem::World, first: usize, period: u64) -> rdem::Result<()> {
        let t = w.step;
        let mut windows = self.windows.lock().expect("tracer windows");
        if self.every == 0 {
            if windows.front().is_some_and(|&(_, left)| left == 0) {
                windows.pop_front();
            }
        } else {
            let mut unmarked = false;
            while let Some(&(start, left)) = windows.front() {
                if left == 0 || start + period < t {
                    unmarked |= left > 0;
                    windows.pop_front();
                } else {
                    break;
                }
            }
            if unmarked {
                w.warnings.push(format!(
                    "fix property/atom/tracer/stream ({}): not all requested tracers could be marked",
                    self.prop.trim_start_matches("tracer:")
                ));
            }
            // The windows S + jE (j ≥ 1) with t < S + jE < t + P, from the first past t.
            let j = if t < self.mark_step + self.every {
                1
            } else {
                (t - self.mark_step) / self.every + 1
            };
            let mut k = self.mark_step + j * self.every;
            while k < t + period {
                windows.push_back((k, self.n_tracer));
                k += self.every;
            }
        }
        let Some(&(first_start, _)) = windows.front() else {
            return Ok(());
        };
        let p = &w.particles;
        let release = p
            .property(rdem::insert::stream::RELEASE_STEP_PROPERTY)
            .ok_or_else(|| rdem::Error::Invalid {
                what: "fix property/atom/tracer/stream",
                reason: "the insert/stream records no release steps".into(),
            })?;
        if let Some(body) = p.property(rdem::multisphere::bodies::BODY_PROP) {
            if (first..p.nlocal()).any(|i| p.props[body.0].data[i] != 0.0) {
                return Err(rdem::Error::Invalid {
                    what: "fix property/atom/tracer/stream",
                    reason: "it does not mark multi-sphere particles (clumps), as in LIGGGHTS"
                        .into(),
                });
            }
        }
        let mut here = Vec::new();
        for i in first..p.nlocal() {
            let r = p.props[release.0].data[i];
            if p.mask[i] & self.groupbit != 0 && r >= first_start as f64 {
                here.extend_from_slice(&[r, p.tag[i] as f64]);
            }
        }
        let all = w.comm.all_gather(&here);
        let mut eligible: Vec<(u64, Tag)> = all
            .chunks_exact(2)
            .map(|c| (c[0] as u64, c[1] as Tag))
            .collect();
        eligible.sort_unstable();
        let mut chosen = Vec::new();
        let mut k = 0;
        for (r, tag) in eligible {
            let Some(win) = windows.get_mut(k) else { break };
            if r >= win.0 && win.1 > 0 {
                win.1 -= 1;
                chosen.push(tag);
            }
            if win.1 == 0 {
                k += 1;
            }
        }
        let Some(id) = w.particles.property(&self.prop) else {
            return Ok(());
        };
        let p = &mut w.particles;
        let mut n = 0;
        for tag in chosen {
            if let Some(i) = p.find_tag(tag).filter(|&i| i < p.nlocal()) {
                p.props[id.0].get_mut(i)[0] = 1.0;
                n += 1;
            }
        }
        *self.marked.lock().expect("tracer count") += n;
        Ok(())
    }
}

fn parse_tracer(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (mut region, mut mark_step) = (None, None);
    let (mut heaviside, mut every) = (false, 10);
    while !a.is_done() {
        match a.keyword(
            "fix property/atom/tracer keyword",
            &[
                "region_mark",
                "mark_step",
                "marker_style",
                "check_mark_every",
            ],
        )? {
            "region_mark" => region = Some(sim.region_id(a)?),
            "mark_step" => mark_step = Some(a.u64("mark_step")?),
            "marker_style" => {
                heaviside = a.keyword("marker_style", &["dirac", "heaviside"])? == "heaviside"
            }
            _ => every = a.count("check_mark_every")?,
        }
    }
    let (Some(region), Some(mark_step)) = (region, mark_step) else {
        return Err(a.error_cmd(
            "fix property/atom/tracer needs 'region_mark REGION' and 'mark_step S'",
            None,
        ));
    };
    sim.world_ref(a)?;
    Ok(Box::new(Tracer {
        prop: format!("tracer:{}", head.id),
        mode: Mode::Region {
            region,
            mark_step,
            heaviside,
            every,
            done: false,
        },
        marked: Arc::default(),
        unmarked: Arc::default(),
    }))
}

/// The `fix insert/stream` `id`, as its own type.
fn stream_inserter<'s>(sim: &'s mut Sim, id: &str) -> Option<&'s mut super::insert::Inserter> {
    sim.defs
        .fixes
        .iter_mut()
        .find(|f| f.head.id == id)
        .and_then(|f| f.downcast_mut::<super::insert::Inserter>())
        .filter(|i| matches!(i.pack, super::insert::InsertEngine::Stream(_)))
}

fn parse_stream(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (mut mark_step, mut n_tracer, mut insert, mut every) = (None, None, None, None);
    while !a.is_done() {
        match a.keyword(
            "fix property/atom/tracer/stream keyword",
            &["mark_step", "n_tracer", "insert_stream", "every"],
        )? {
            "mark_step" => mark_step = Some(a.u64("mark_step")?),
            "n_tracer" => n_tracer = Some(a.u64("n_tracer")?),
            "insert_stream" => {
                let id = a.word("insert_stream fix ID")?;
                let is_stream = sim.defs.fixes.iter().any(|f| {
                    f.head.id == id
                        && f.downcast::<super::insert::Inserter>().is_some_and(|i| {
                            matches!(i.pack, super::insert::InsertEngine::Stream(_))
                        })
                });
                if !is_stream {
                    let ids: Vec<&str> = sim
                        .defs
                        .fixes
                        .iter()
                        .filter(|f| f.head.style == "insert/stream")
                        .map(|f| f.id())
                        .collect();
                    return Err(a.error_prev(
                        format!("no fix insert/stream '{id}'"),
                        Some(crate::args::id_help("fix insert/stream", id, &ids)),
                    ));
                }
                insert = Some(id.to_string());
            }
            _ => {
                every = Some(if a.peek() == Some("once") {
                    a.word("every")?;
                    0
                } else {
                    a.count("every (a number of steps > 0, or once)")?
                })
            }
        }
    }
    let (Some(mark_step), Some(n_tracer), Some(insert), Some(every)) =
        (mark_step, n_tracer, insert, every)
    else {
        return Err(a.error_cmd(
            "fix property/atom/tracer/stream needs 'mark_step S', 'n_tracer N', 'insert_stream ID' and 'every E|once'",
            None,
        ));
    };
    sim.world_ref(a)?;
    let prop = format!("tracer:{}", head.id);
    let marked: Arc<Mutex<u64>> = Arc::default();
    let marking = Arc::new(StreamMarking {
        prop: prop.clone(),
        groupbit: head.groupbit,
        mark_step,
        n_tracer,
        every,
        windows: Mutex::new([(mark_step, n_tracer)].into()),
        marked: marked.clone(),
    });
    Ok(Box::new(Tracer {
        prop,
        mode: Mode::Stream { insert, marking },
        marked,
        unmarked: Arc::default(),
    }))
}

#[derive(serde::Serialize, serde::Deserialize)]
enum TracerState {
    Region { done: bool },
    Stream { windows: Vec<(u64, u64)> },
}

impl Tracer {
    /// Writes the queued unmarks into the markers of the particles this rank owns.
    fn apply_unmarks(&self, w: &mut rdem::World) {
        let tags = std::mem::take(&mut *self.unmarked.0.lock().expect("unmark queue"));
        let Some(id) = w
            .particles
            .property(&self.prop)
            .filter(|_| !tags.is_empty())
        else {
            return;
        };
        let tags: HashSet<Tag> = tags.into_iter().collect();
        let p = &mut w.particles;
        for i in 0..p.nlocal() {
            if tags.contains(&p.tag[i]) {
                p.props[id.0].get_mut(i)[0] = 0.0;
            }
        }
    }
}

impl ScriptFix for Tracer {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        super::property_atom::fix_values(sim, a, &self.prop, 1)?;
        if let Mode::Stream { insert, marking } = &self.mode {
            if let Some(ins) = stream_inserter(sim, insert) {
                ins.stream_tracers.push(marking.clone());
            }
        }
        Ok(())
    }

    fn values(&self, sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let here = std::mem::take(&mut *self.marked.lock().expect("tracer count"));
        Ok(vec![w.comm.sum_count(here) as f64])
    }

    fn peratom_shape(&self) -> Option<(usize, u64)> {
        Some((0, 1))
    }

    fn peratom(&self, sim: &Sim, head: &FixHead, _col: Option<usize>) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let p = &w.particles;
        let id = p
            .property(&self.prop)
            .ok_or_else(|| format!("fix {}: its markers are gone", head.id))?;
        let mut v: Vec<f64> = (0..p.nlocal()).map(|i| p.props[id.0].get(i)[0]).collect();
        let queue = self.unmarked.0.lock().expect("unmark queue");
        if !queue.is_empty() {
            let tags: HashSet<Tag> = queue.iter().copied().collect();
            for (i, v) in v.iter_mut().enumerate() {
                if tags.contains(&p.tag[i]) {
                    *v = 0.0;
                }
            }
        }
        Ok(v)
    }

    fn pre_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        self.apply_unmarks(ctx.world());
        Ok(())
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        self.apply_unmarks(ctx.world());
        let step = ctx.step;
        let Mode::Region {
            region,
            mark_step,
            heaviside,
            every,
            done,
        } = &mut self.mode
        else {
            return Ok(());
        };
        if ctx.setup || step % *every != 0 || step < *mark_step || *done {
            return Ok(());
        }
        let region = crate::regions::region_now(ctx.view(), region)?;
        let w = ctx.world();
        let id = w
            .particles
            .property(&self.prop)
            .ok_or_else(|| format!("fix {}: its markers are gone", head.id))?;
        let p = &mut w.particles;
        let mut n = 0;
        for i in 0..p.nlocal() {
            if p.mask[i] & head.groupbit != 0
                && p.props[id.0].get(i)[0] == 0.0
                && region.contains(p.x[i])
            {
                p.props[id.0].get_mut(i)[0] = 1.0;
                n += 1;
            }
        }
        *self.marked.lock().expect("tracer count") += n;
        *done = !*heaviside;
        Ok(())
    }

    fn end_of_run(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        self.apply_unmarks(ctx.world());
        Ok(())
    }

    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let st = match &self.mode {
            Mode::Region { done, .. } => TracerState::Region { done: *done },
            Mode::Stream { marking, .. } => TracerState::Stream {
                windows: marking
                    .windows
                    .lock()
                    .expect("tracer windows")
                    .iter()
                    .copied()
                    .collect(),
            },
        };
        postcard::to_stdvec(&st).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        match (super::decode_state(state)?, &mut self.mode) {
            (TracerState::Region { done: d }, Mode::Region { done, .. }) => *done = d,
            (TracerState::Stream { windows }, Mode::Stream { marking, .. }) => {
                *marking.windows.lock().expect("tracer windows") = windows.into();
            }
            _ => return Err("it was written by another tracer style".into()),
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Mode::Stream { insert, marking } = &self.mode {
            if let Some(ins) = stream_inserter(sim, insert) {
                ins.stream_tracers.retain(|m| !Arc::ptr_eq(m, marking));
            }
        }
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&self.prop);
        }
    }
}

/// `fix property/atom/regiontracer/time`.
struct RegionTime {
    /// The particle property: the times (domain, then each region), then the last
    /// look-up's in/out flags of the regions.
    prop: String,
    regions: Vec<String>,
    every: u64,
}

fn parse_time(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (mut regions, mut every) = (Vec::new(), 10);
    while !a.is_done() {
        match a.keyword(
            "fix property/atom/regiontracer/time keyword",
            &["add_region", "check_region_every"],
        )? {
            "add_region" => regions.push(sim.region_id(a)?),
            _ => every = a.count("check_region_every")?,
        }
    }
    sim.world_ref(a)?;
    Ok(Box::new(RegionTime {
        prop: format!("regiontracer/time:{}", head.id),
        regions,
        every,
    }))
}

impl RegionTime {
    fn width(&self) -> usize {
        1 + 2 * self.regions.len()
    }

    /// The time columns (domain, then each region) of the owned particles.
    fn columns(&self, w: &rdem::World, head: &FixHead) -> Result<Vec<Vec<f64>>, Error> {
        let p = &w.particles;
        let id = p
            .property(&self.prop)
            .ok_or_else(|| format!("fix {}: its times are gone", head.id))?;
        let n = 1 + self.regions.len();
        Ok((0..n)
            .map(|k| (0..p.nlocal()).map(|i| p.props[id.0].get(i)[k]).collect())
            .collect())
    }
}

impl ScriptFix for RegionTime {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        super::property_atom::fix_values(sim, a, &self.prop, self.width())?;
        Ok(())
    }

    /// The mean of each time over the group's particles.
    fn values(&self, sim: &Sim, head: &FixHead) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let cols = self.columns(w, head)?;
        let p = &w.particles;
        let members: Vec<usize> = (0..p.nlocal())
            .filter(|&i| p.mask[i] & head.groupbit != 0)
            .collect();
        let mut s: Vec<f64> = cols
            .iter()
            .map(|c| members.iter().map(|&i| c[i]).sum())
            .collect();
        w.comm.sum_slice(&mut s);
        let n = w.comm.sum_count(members.len() as u64);
        Ok(s.into_iter()
            .map(|x| if n > 0 { x / n as f64 } else { 0.0 })
            .collect())
    }

    fn peratom_shape(&self) -> Option<(usize, u64)> {
        let n = self.regions.len();
        Some((if n == 0 { 0 } else { n + 1 }, 1))
    }

    fn peratom(&self, sim: &Sim, head: &FixHead, col: Option<usize>) -> Result<Vec<f64>, Error> {
        let w = sim.world.as_ref().ok_or(Error::NoBox)?;
        let mut cols = self.columns(w, head)?;
        Ok(cols.swap_remove(col.map_or(0, |c| c - 1)))
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        let look = ctx.step % self.every == 0;
        let regions = if look {
            self.regions
                .iter()
                .map(|r| crate::regions::region_now(ctx.view(), r))
                .collect::<Result<Vec<_>, _>>()?
        } else {
            Vec::new()
        };
        let n = self.regions.len();
        let w = ctx.world();
        let dt = w.dt;
        let id = w
            .particles
            .property(&self.prop)
            .ok_or_else(|| format!("fix {}: its times are gone", head.id))?;
        let p = &mut w.particles;
        for i in (0..p.nlocal()).filter(|&i| p.mask[i] & head.groupbit != 0) {
            let x = p.x[i];
            let v = p.props[id.0].get_mut(i);
            v[0] += dt;
            for k in 0..n {
                if look {
                    v[1 + n + k] = f64::from(u8::from(regions[k].contains(x)));
                }
                if v[1 + n + k] != 0.0 {
                    v[1 + k] += dt;
                }
            }
        }
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&self.prop);
        }
    }
}
