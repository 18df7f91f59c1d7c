//! LIGGGHTS-PFM's `fix ID group remove nevery N massrate R|massratevariable NAME style
//! delete|shrink delete_below D seed S [keywords]`: particles of the group (of one type,
//! in a region) removed at a mass rate, every N steps, as the fork's manual and code do
//! (ParticulateFlow/LIGGGHTS-PFM d075b97, run here):
//!
//! - the removal steps are the definition step plus N, 2N, ...; each happens after the
//!   step's initial integration (the fork's `pre_exchange`, which it makes a re-neighboring
//!   step), on the particles' new positions;
//! - the mass due is the rate times the time since the last removal step; with
//!   `integrated_error yes` (the default) the shortfall or excess of earlier removals is
//!   carried over: the mass due is the integrated rate less what was removed. Nothing is
//!   done while it is at most `minmass` (1e-6 by default);
//! - when the eligible mass is at most the mass due, every eligible particle goes;
//! - `delete`: particles drawn at random (Park–Miller, seeded `seed`) from the eligible
//!   ones are deleted whole until the mass due is at most `minmass`, so a removal step
//!   may take more than is due;
//! - `shrink`: the eligible particles below `delete_below` are deleted, then the others
//!   all lose the same fraction of their mass (radius by its cube root, density kept) to
//!   make up the rest;
//! - `compress yes` (the default) numbers the particles 1..N again after a deletion
//!   (kept in the order of their IDs; the contact history follows them); not under
//!   `atom_style bond/gran`, as the fork does not for molecular systems.
//!
//! `f_ID[1]`: the mass removed so far; `f_ID[2]` with `monitor_heat yes`: the heat removed
//! (m c T of each particle or part taken, with `fix heat/gran`'s capacities).
//!
//! Where rdem differs from the fork: the fork draws from each rank's own list in its
//! storage order, rdem from one list of all ranks' eligible particles in ID order, with
//! the fork's generator and rule: one rank with unsorted particles draws as the fork
//! does, and a run does not depend on the number of ranks or threads. The fork's
//! `restart_read`/`restart_write` choose whether its state is kept: rdem keeps it unless
//! `restart_write no`, and takes it back unless `restart_read no`. Clumps (`fix
//! multisphere`) are not supported yet: the fork removes whole bodies.

use super::{style, FixHead, FixRow, Notes, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::park_miller::ParkMiller;
use crate::sim::Sim;
use rdem::region::Region;
use rdem::World;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "remove",
    parse,
    Stages::PRE_STEP
        .and(Stages::PRE_EXCHANGE)
        .and(Stages::VALUES),
    "`nevery N massrate R\\|massratevariable NAME style delete\\|shrink delete_below D seed S` (LIGGGHTS-PFM), then `region ID`, `atomtype T`, `integrated_error yes\\|no`, `minmass M`, `verbose yes\\|no`, `compress yes\\|no`, `monitor_heat yes\\|no`, `restart_read yes\\|no`, `restart_write yes\\|no`",
)
.notes("removal steps every N steps from the definition, after the initial integration; `delete` deletes particles drawn at random until the mass due is taken (the integrated rate less what was removed), `shrink` deletes those below `delete_below` and shrinks the others by one mass fraction; `f_ID[1]` the mass removed, `f_ID[2]` the heat (`monitor_heat`). rdem draws from all ranks' eligible particles in ID order (the fork from each rank's list): the same run on any number of ranks and threads. Clumps are not supported yet");

/// The mass rate: a number, or an equal-style variable read at each removal step.
#[derive(Debug, Clone)]
enum Rate {
    Value(f64),
    Variable(String),
}

/// What the fix keeps in restart files.
#[derive(serde::Serialize, serde::Deserialize)]
struct RemoveState {
    rng: ParkMiller,
    next: u64,
    last: u64,
    removed: f64,
    integrated: f64,
    heat: f64,
    rate: f64,
}

/// A defined `fix remove`.
struct Remove {
    every: u64,
    rate: Rate,
    /// The rate of the next removal step (a variable's value is read before the step).
    rate_now: f64,
    /// `style shrink delete_below D`: Some(D); `delete`: None.
    shrink_below: Option<f64>,
    rng: ParkMiller,
    region: Option<Region>,
    /// The region's ID when it moves (read again before each removal step).
    moving: Option<String>,
    atom_type: Option<u32>,
    integrated_error: bool,
    min_mass: f64,
    restart_read: bool,
    restart_write: bool,
    verbose: bool,
    compress: bool,
    monitor_heat: bool,
    groupbit: u32,
    /// The next removal step and the last one (the definition step at first).
    next: u64,
    last: u64,
    /// Mass removed so far, the integrated rate, heat removed so far.
    removed: f64,
    integrated: f64,
    heat: f64,
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let step = sim.world_ref(a)?.step;
    if sim.world.as_ref().is_some_and(|w| w.multisphere.is_some()) {
        return Err(a.error_at(
            super::STYLE_WORD,
            "fix remove with clumps (fix multisphere) is not supported yet",
            Some("LIGGGHTS-PFM removes whole bodies; rdem does not yet".into()),
        ));
    }
    a.keyword("fix remove", &["nevery"])?;
    let every = a.count("nevery")?;
    let rate = match a.keyword("fix remove", &["massrate", "massratevariable"])? {
        "massrate" => {
            let r = a.positive("mass rate")?;
            Rate::Value(r)
        }
        _ => {
            let name = a.word("variable name")?;
            let name = name.strip_prefix("v_").unwrap_or(name).to_string();
            if sim.script.vars.get(&name).is_none() {
                return Err(a.error_prev(
                    format!("no variable '{name}'"),
                    Some("define an equal-style variable for the mass rate first".into()),
                ));
            }
            Rate::Variable(name)
        }
    };
    a.keyword("fix remove", &["style"])?;
    let shrink_below = match a.keyword("remove style", &["delete", "shrink"])? {
        "delete" => None,
        _ => {
            a.keyword("style shrink", &["delete_below"])?;
            Some(a.non_negative("delete_below radius")?)
        }
    };
    a.keyword("fix remove", &["seed"])?;
    let seed = a.count("seed")?;
    let seed = i32::try_from(seed).map_err(|_| {
        a.error_prev(
            format!("seed {seed} is too large"),
            Some("a seed is a positive 32-bit integer".into()),
        )
    })?;
    let mut fix = Remove {
        every,
        rate_now: match &rate {
            Rate::Value(r) => *r,
            Rate::Variable(_) => 0.0,
        },
        rate,
        shrink_below,
        rng: ParkMiller(seed),
        region: None,
        moving: None,
        atom_type: None,
        integrated_error: true,
        min_mass: 1e-6,
        restart_read: true,
        restart_write: true,
        verbose: false,
        compress: true,
        monitor_heat: false,
        groupbit: head.groupbit,
        next: step + every,
        last: step,
        removed: 0.0,
        integrated: 0.0,
        heat: 0.0,
    };
    while !a.is_done() {
        match a.keyword(
            "fix remove keyword",
            &[
                "region",
                "atomtype",
                "integrated_error",
                "minmass",
                "restart_read",
                "restart_write",
                "verbose",
                "compress",
                "monitor_heat",
            ],
        )? {
            "region" => {
                let (r, moving) = crate::regions::fix_region(sim, a)?;
                (fix.region, fix.moving) = (Some(r), moving);
            }
            "atomtype" => {
                let t = a.count("atom type")?;
                if t as usize > sim.ntypes() {
                    return Err(a.error_prev(
                        format!("atom type {t} > the box's {} type(s)", sim.ntypes()),
                        None,
                    ));
                }
                fix.atom_type = Some(t as u32);
            }
            "integrated_error" => fix.integrated_error = a.yes_no("integrated_error")?,
            "minmass" => fix.min_mass = a.f64("minmass")?,
            "restart_read" => fix.restart_read = a.yes_no("restart_read")?,
            "restart_write" => fix.restart_write = a.yes_no("restart_write")?,
            "verbose" => fix.verbose = a.yes_no("verbose")?,
            "compress" => fix.compress = a.yes_no("compress")?,
            _ => fix.monitor_heat = a.yes_no("monitor_heat")?,
        }
    }
    // The fork never renumbers molecular systems.
    fix.compress &= sim.setup.bond_gran.is_none();
    Ok(Box::new(fix))
}

/// An eligible particle: its tag, mass and radius.
struct Eligible {
    tag: f64,
    mass: f64,
    radius: f64,
}

/// Whether `tag` is in `tags` (tags as numbers, sorted).
fn listed(tags: &[f64], tag: rdem::Tag) -> bool {
    tags.binary_search_by(|t| t.total_cmp(&(tag as f64)))
        .is_ok()
}

impl Remove {
    /// The mass due at removal step `now` (and the bookkeeping of the rate).
    fn mass_due(&mut self, now: u64, dt: f64) -> f64 {
        let span = (now - self.last) as f64 * dt * self.rate_now;
        self.last = now;
        if self.integrated_error {
            self.integrated += span;
            self.integrated - self.removed
        } else {
            span
        }
    }

    /// This rank's eligible particles (group, type, region).
    fn local_eligible(&self, w: &World) -> Vec<usize> {
        let p = &w.particles;
        (0..p.nlocal())
            .filter(|&i| {
                p.mask[i] & self.groupbit != 0
                    && self.atom_type.is_none_or(|t| p.ty[i] == t)
                    && self.region.as_ref().is_none_or(|r| r.contains(p.x[i]))
            })
            .collect()
    }

    /// The heat a particle of mass `m` carries (m c T), with `monitor_heat`.
    fn heat_of(&self, w: &World, i: usize, m: f64) -> rdem::Result<f64> {
        if !self.monitor_heat {
            return Ok(0.0);
        }
        let (Some(heat), Some(id)) = (&w.heat, w.particles.property(rdem::heat::TEMP)) else {
            return Err(rdem::Error::Invalid {
                what: "fix remove monitor_heat",
                reason: "needs fix heat/gran (the temperatures and thermalCapacity)".into(),
            });
        };
        let ty = w.particles.ty[i] as usize;
        let c = heat
            .capacity
            .get(ty.wrapping_sub(1))
            .copied()
            .unwrap_or(0.0);
        Ok(m * c * w.particles.props[id.0].data[i])
    }

    /// One removal step.
    fn act(&mut self, head: &FixHead, w: &mut World, notes: &mut Notes) -> rdem::Result<()> {
        if w.multisphere.is_some() {
            // A `fix multisphere` defined after this fix.
            return Err(rdem::Error::Invalid {
                what: "fix remove",
                reason: format!(
                    "fix {}: removing clumps (fix multisphere) is not supported yet",
                    head.id
                ),
            });
        }
        let now = w.step;
        self.next = now + self.every;
        let due = self.mass_due(now, w.dt);
        if self.verbose {
            notes.line(format!(
                "Timestep {now}, removing material, mass to remove this step {due:.6}"
            ));
        }
        if due <= self.min_mass {
            return Ok(());
        }
        // Every rank's eligible particles, in ID order.
        let mine = self.local_eligible(w);
        let p = &w.particles;
        let rows: Vec<f64> = mine
            .iter()
            .flat_map(|&i| [p.tag[i] as f64, p.rmass[i], p.radius[i]])
            .collect();
        let mut all: Vec<Eligible> = w
            .comm
            .all_gather(&rows)
            .chunks_exact(3)
            .map(|r| Eligible {
                tag: r[0],
                mass: r[1],
                radius: r[2],
            })
            .collect();
        all.sort_by(|a, b| a.tag.total_cmp(&b.tag));
        let eligible: f64 = all.iter().map(|e| e.mass).sum();
        if eligible == 0.0 {
            if self.verbose {
                notes.warning(format!(
                    "fix {}: mass to remove, but no eligible particle",
                    head.id
                ));
            }
            return Ok(());
        }
        // Tags to delete, and (tag, mass fraction kept) to shrink.
        let mut delete: Vec<f64> = Vec::new();
        let mut keep_fraction = None;
        let mut removed = 0.0;
        let mut left = due;
        if eligible <= due {
            delete.extend(all.iter().map(|e| e.tag));
            removed = eligible;
            if self.verbose {
                notes.warning(format!("fix {}: removed less mass than requested", head.id));
            }
        } else if let Some(below) = self.shrink_below {
            let mut shrinkable = Vec::new();
            for e in &all {
                if e.radius < below {
                    delete.push(e.tag);
                    removed += e.mass;
                    left -= e.mass;
                } else {
                    shrinkable.push(e);
                }
            }
            let mass: f64 = shrinkable.iter().map(|e| e.mass).sum();
            if mass > 0.0 && left > 0.0 {
                let ratio = 1.0 - left / mass;
                let mut shrunk = Vec::new();
                for e in shrinkable {
                    if left <= 0.0 {
                        break;
                    }
                    removed += (1.0 - ratio) * e.mass;
                    left -= (1.0 - ratio) * e.mass;
                    shrunk.push(e.tag);
                }
                keep_fraction = Some((ratio, shrunk));
            }
        } else {
            let mut pool: Vec<&Eligible> = all.iter().collect();
            while !pool.is_empty() && left > self.min_mass {
                let n = pool.len();
                let k = ((self.rng.uniform() * n as f64) as usize).min(n - 1);
                let e = pool.remove(k);
                delete.push(e.tag);
                removed += e.mass;
                left -= e.mass;
            }
        }
        // Apply to this rank's particles.
        let mut heat = 0.0;
        let nlocal = w.particles.nlocal();
        if let Some((ratio, tags)) = &keep_fraction {
            let r_ratio = ratio.cbrt();
            for &i in &mine {
                if listed(tags, w.particles.tag[i]) {
                    let m = w.particles.rmass[i];
                    heat += self.heat_of(w, i, (1.0 - ratio) * m)?;
                    let p = &mut w.particles;
                    p.rmass[i] *= ratio;
                    p.radius[i] *= r_ratio;
                }
            }
        }
        let mut gone = vec![false; nlocal];
        let mut any = false;
        delete.sort_by(f64::total_cmp);
        for &i in &mine {
            if listed(&delete, w.particles.tag[i]) {
                heat += self.heat_of(w, i, w.particles.rmass[i])?;
                gone[i] = true;
                any = true;
            }
        }
        let heat = w.comm.sum(heat);
        let deleted = delete.len();
        if w.comm.any(any) {
            w.remove_particles(&gone);
            if self.compress {
                w.renumber_tags();
            }
        }
        self.removed += removed;
        self.heat += heat;
        if self.verbose {
            notes.line(format!(
                "    fix {}: this step: mass removed {removed:.6} (of {eligible:.6} eligible), #particles removed {deleted}; accumulated: mass removed: {:.6}",
                head.id, self.removed
            ));
        }
        Ok(())
    }
}

impl ScriptFix for Remove {
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(if self.monitor_heat {
            vec![self.removed, self.heat]
        } else {
            vec![self.removed]
        })
    }

    /// Before a removal step: the rate variable and a moving region, read at that step.
    fn pre_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if ctx.setup || ctx.step != self.next {
            return Ok(());
        }
        let rate = self.rate.clone();
        let moving = self.moving.clone();
        let (rate, region) = ctx.at_step("fix remove", |sim| -> Result<_, Error> {
            let rate = match &rate {
                Rate::Value(r) => *r,
                Rate::Variable(name) => {
                    crate::context::eval_name_equal(sim, &crate::expr::Name::Variable(name.clone()))
                        .map_err(|e| e.within(format!("fix remove: variable {name}")))?
                }
            };
            let region = match &moving {
                Some(id) => Some(crate::regions::region_now(sim, id)?),
                None => None,
            };
            Ok((rate, region))
        })??;
        if !rate.is_finite() {
            return Err(format!("fix remove: the mass rate is {rate}, not a finite number").into());
        }
        self.rate_now = rate;
        if region.is_some() {
            self.region = region;
        }
        Ok(())
    }

    fn due(&self, step: u64) -> bool {
        step == self.next
    }

    fn pre_exchange(
        &mut self,
        head: &FixHead,
        w: &mut World,
        notes: &mut Notes,
    ) -> rdem::Result<()> {
        self.act(head, w, notes)
    }

    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        if !self.restart_write {
            return None;
        }
        postcard::to_stdvec(&RemoveState {
            rng: self.rng,
            next: self.next,
            last: self.last,
            removed: self.removed,
            integrated: self.integrated,
            heat: self.heat,
            rate: self.rate_now,
        })
        .ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        if !self.restart_read {
            return Ok(());
        }
        let st: RemoveState = super::decode_state(state)?;
        if let Rate::Value(r) = self.rate {
            if r != st.rate {
                return Err(format!(
                    "the restart file's mass rate is {}, this definition's {r}: LIGGGHTS-PFM refuses to continue with another rate too",
                    st.rate
                )
                .into());
            }
        }
        self.rng = st.rng;
        (self.next, self.last) = (st.next, st.last);
        (self.removed, self.integrated, self.heat) = (st.removed, st.integrated, st.heat);
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
