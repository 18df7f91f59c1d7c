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

/// `fix property/atom/tracer`.
pub struct Tracer {
    /// The particle property holding the marker.
    pub prop: String,
    region: String,
    mark_step: u64,
    heaviside: bool,
    every: u64,
    /// The dirac impulse was given.
    done: bool,
    /// Particles marked on this rank since the global scalar was last read.
    marked: Mutex<u64>,
    /// Markers cleared by computes, not yet written.
    pub unmarked: Arc<Unmarked>,
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
        region,
        mark_step,
        heaviside,
        every,
        done: false,
        marked: Mutex::new(0),
        unmarked: Arc::default(),
    }))
}

#[derive(serde::Serialize, serde::Deserialize)]
struct TracerState {
    done: bool,
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
        if ctx.setup || step % self.every != 0 || step < self.mark_step || self.done {
            return Ok(());
        }
        let region = crate::regions::region_now(ctx.view(), &self.region)?;
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
        self.done = !self.heaviside;
        Ok(())
    }

    fn end_of_run(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        self.apply_unmarks(ctx.world());
        Ok(())
    }

    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        postcard::to_stdvec(&TracerState { done: self.done }).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let st: TracerState = super::decode_state(state)?;
        self.done = st.done;
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
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
