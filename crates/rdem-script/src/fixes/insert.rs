//! `fix insert/pack` and `fix insert/rate/region` (and the keyword parsing that
//! `insert/stream` shares): particles from a distribution placed in a region, once, every
//! N steps or at a rate. They act in the step's pre-exchange stage, after the initial
//! integration, as LIGGGHTS' insertion fixes do.

use crate::error::Error;
use rdem::insert::{InsertPack, Orientation, PackTarget, VelocityLaw};
use rdem::World;

use glam::DVec3;

use super::{mesh_ref, style, FixHead, FixRow, Notes, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{suggest, Args, CmdResult};
use crate::diagnostic::one_of;
use crate::sim::Sim;
use crate::variables::format_e;

/// `orientation random|template|constant q0 q1 q2 q3` (the words after the keyword): how
/// inserted clumps are turned; a constant quaternion (normalised) turns the template as
/// its spheres were given.
pub(super) fn orientation_law(a: &mut Args) -> CmdResult<Orientation> {
    Ok(
        match a.keyword("orientation", &["random", "template", "constant"])? {
            "random" => Orientation::Random,
            "template" => Orientation::Template,
            _ => {
                let at = a.pos();
                let mut q = [0.0; 4];
                for (k, c) in ["q0", "q1", "q2", "q3"].iter().enumerate() {
                    q[k] = a.f64(&format!("quaternion {c}"))?;
                }
                let quat = glam::DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
                if quat.length() == 0.0 || !quat.is_finite() {
                    return Err(a.error_at(at, "the quaternion must not be zero", None));
                }
                Orientation::Constant(quat.normalize())
            }
        },
    )
}

/// Reads the keyword `seed` that every insertion fix takes first (LIGGGHTS' and the
/// forks'); the caller reads the number, by its own rule. A located error otherwise; a
/// missing one shows `example`, a whole command of the style.
pub(super) fn seed_keyword(a: &mut Args, style: &str, example: &str) -> CmdResult<()> {
    match a.peek() {
        Some("seed") => {
            a.seek(a.pos() + 1);
            Ok(())
        }
        Some(w) => Err(a.error_at(
            a.pos(),
            format!("{style}: the first keyword must be 'seed', not '{w}'"),
            Some(format!(
                "LIGGGHTS requires the seed first: 'fix ID group {style} seed 32452867 {w} ...'"
            )),
        )),
        None => Err(a.error_at(
            a.pos(),
            format!("{style}: missing 'seed N'"),
            Some(format!("e.g. {example}")),
        )),
    }
}

/// The distribution named by the next word (after `distributiontemplate`). Its templates
/// must be relative ones (`relative yes`) if `relative`, else none may be.
pub(super) fn distribution(
    sim: &Sim,
    a: &mut Args,
    relative: bool,
) -> CmdResult<rdem::insert::Distribution> {
    let d = a.word("distribution template ID")?;
    let dist = sim.defs.distributions.get(d).cloned().ok_or_else(|| {
        let names: Vec<&str> = sim.defs.distributions.keys().map(|s| s.as_str()).collect();
        a.error_prev(
            format!("no particle distribution '{d}'"),
            Some(suggest(d, &names)),
        )
    })?;
    let is_relative =
        |t: &rdem::insert::ParticleTemplate| t.clump.as_ref().is_some_and(|c| c.relative);
    if let Some(t) = dist.templates.iter().find(|t| is_relative(t) != relative) {
        return Err(if relative {
            a.error_prev(
                format!("template {} of distribution {d} is not relative", t.id),
                Some("fix insert/fragments takes a particletemplate/multiplespheres with 'relative yes'".into()),
            )
        } else {
            a.error_prev(
                format!("template {} of distribution {d} is relative ('relative yes')", t.id),
                Some("relative templates are the fragments of fix insert/fragments; other insertions take absolute sizes".into()),
            )
        });
    }
    Ok(dist)
}

/// The registry row of `insert/pack`.
pub(super) const ROW_PACK: FixRow = style(
    "insert/pack",
    parse,
    Stages::PRE_EXCHANGE.and(Stages::VALUES),
    "`volumefraction_region`, `particles_in_region`, `mass_in_region`; `insert_every once\\|N`; `overlapcheck`; `all_in`; `maxattempt`; `vel constant\\|uniform\\|gaussian`; `omega constant`; `orientation random\\|template\\|constant q0 q1 q2 q3` (clumps); `start`; `set_property NAME value` (a scalar `fix property/atom` of each new particle); `ntry_mc`, `verbose`; `check_dist_from_subdomain_border` (read; rdem's placement never overlaps across ranks); LIGGGHTS-PFM's `pos x y z` (every try at that point: one particle or template)",
)
.notes("rdem's own random generator: positions differ from LIGGGHTS', counts and statistics do not")
.atoi();

/// The registry row of `insert/rate/region`.
pub(super) const ROW_RATE: FixRow = style(
    "insert/rate/region",
    parse,
    Stages::PRE_EXCHANGE.and(Stages::VALUES).and(Stages::PRE_STEP),
    "`nparticles N\\|INF` or `mass M\\|INF`, `particlerate` or `massrate`, `insert_every`, the placement keywords of insert/pack",
)
.atoi();

/// The engine part of an insertion fix.
pub enum InsertEngine {
    /// `insert/pack`, `insert/rate/region`.
    Pack(InsertPack),
    /// `insert/stream`.
    Stream(rdem::insert::InsertStream),
}

/// What an insertion fix keeps in restart files.
#[derive(serde::Serialize, serde::Deserialize)]
struct InserterState {
    progress: rdem::insert::InsertProgress,
    total: u64,
    total_mass: f64,
    carry: f64,
}

impl InsertEngine {
    fn progress(&self) -> rdem::insert::InsertProgress {
        match self {
            Self::Pack(p) => p.progress(),
            Self::Stream(s) => s.progress(),
        }
    }

    fn set_progress(&mut self, p: &rdem::insert::InsertProgress) -> bool {
        match self {
            Self::Pack(x) => x.set_progress(p),
            Self::Stream(x) => x.set_progress(p),
        }
    }

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
    /// What the definition reports, printed when it is installed.
    pub announce: Option<Notes>,
    /// `insert/stream` with `verbose yes`: its rate line is still to be printed, at the
    /// first run's set-up with that run's time step (as LIGGGHTS 3.8 prints it).
    pub rate_line_due: bool,
    /// `set_property NAME value`: the per-particle property NAME (a scalar `fix
    /// property/atom`) of each inserted particle set to value.
    pub set_property: Vec<(String, f64)>,
    /// `insert/stream`: the `fix property/atom/tracer/stream` markings that follow it,
    /// called on each packet right after it is inserted.
    pub stream_tracers: Vec<std::sync::Arc<super::tracer::StreamMarking>>,
}

/// State of `insert/rate/region` (and `fix pour`).
pub struct RateState {
    /// Particles to insert in all (`None`: no limit).
    pub limit: Option<u64>,
    /// Particles per insertion.
    pub per: PerInsertion,
    /// Fractional carry.
    pub carry: f64,
}

/// How many particles one insertion asks for (may be fractional).
pub enum PerInsertion {
    /// A fixed count (`fix pour`'s batch).
    Fixed(f64),
    /// `insert/rate/region`: particles per unit time, and the steps between insertions.
    /// The count follows the time step at each insertion (a `timestep` after the fix
    /// counts, as in LIGGGHTS).
    Rate {
        /// Particles per unit time.
        per_time: f64,
        /// Steps between insertions.
        every: u64,
    },
}

impl PerInsertion {
    /// The count for time step `dt`.
    fn count(&self, dt: f64) -> f64 {
        match *self {
            Self::Fixed(n) => n,
            Self::Rate { per_time, every } => per_time * dt * every as f64,
        }
    }
}

/// The parser of all three insertion styles (their keywords overlap).
pub(super) fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let (id, groupbit, style) = (head.id.as_str(), head.groupbit, head.style);
    let stream = style == "insert/stream";
    let rate = style == "insert/rate/region" || stream;
    // Keywords of every style, then each style's own (in LIGGGHTS' manual order).
    const COMMON: [&str; 12] = [
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
        "orientation",
        "set_property",
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
            "check_dist_from_subdomain_border",
        ]
    } else {
        &[
            "region",
            "volumefraction_region",
            "particles_in_region",
            "mass_in_region",
            "ntry_mc",
            "start",
            "check_dist_from_subdomain_border",
            "pos",
        ]
    };
    let valid: Vec<&'static str> = COMMON.iter().chain(own).copied().collect();
    let valid = valid.as_slice();
    seed_keyword(
        a,
        style,
        &format!("'fix ID group {style} seed 32452867 distributiontemplate ID ...'"),
    )?;
    let seed = a.seed()?;
    let mut dist = None;
    let (mut region, mut target, mut every, mut start) = (None, None, None, None);
    let (mut overlap, mut all_in, mut maxattempt, mut verbose) = (true, false, 50usize, true);
    let mut vel = VelocityLaw::Constant(DVec3::ZERO);
    let mut omega = DVec3::ZERO;
    // LIGGGHTS 3.8's default (measured; see `Orientation::Template`).
    let mut orientation = Orientation::Template;
    let (mut nparticles, mut massmax, mut prate, mut mrate) = (None, None, None, None);
    let mut every_once = false;
    let mut position = None;
    let (mut face, mut extrude, mut duration) = (None, None, None);
    let mut set_property = Vec::new();
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
                dist = Some(distribution(sim, a, false)?);
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
            "vel" => vel = velocity_law(a)?,
            "omega" => {
                a.keyword("omega distribution", &["constant"])?;
                omega = a.vec3("omega")?;
            }
            "orientation" => orientation = orientation_law(a)?,
            "set_property" => {
                let name = a
                    .word("property name (of a fix property/atom)")?
                    .to_string();
                set_property.push((name, a.f64("property value")?));
            }
            "region" => region = Some(sim.fixed_region(a, &format!("fix {style}"))?),
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
            // LIGGGHTS keeps particles a bounding radius away from subdomain borders so
            // that two ranks cannot insert overlapping particles. rdem places every
            // particle on every rank, each checked against all the others and against the
            // particles of every rank, and each rank keeps those in its subdomain: no
            // overlap across a border either way.
            "check_dist_from_subdomain_border" => {
                a.yes_no("check_dist_from_subdomain_border")?;
            }
            // LIGGGHTS-PFM: insert at this position (see `InsertPack::position`).
            "pos" => position = Some(a.vec3("insertion position")?),
            "start" => start = Some(a.u64("start step")?),
            "nparticles" => {
                if a.peek() == Some("INF") {
                    a.seek(a.pos() + 1);
                    nparticles = Some(None);
                } else {
                    nparticles = Some(Some(a.count("nparticles")?));
                }
            }
            // `INF`: no limit (the LIGGGHTS 3.8 manual's "as many as possible").
            "mass" => {
                if a.peek() == Some("INF") {
                    a.seek(a.pos() + 1);
                    massmax = Some(None);
                } else {
                    massmax = Some(Some(a.positive("mass to insert")?));
                }
            }
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
    let dt = sim.dt();
    if stream {
        return super::insert_stream::build(
            sim,
            a,
            super::insert_stream::StreamArgs {
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
                set_property,
            },
            |s| {
                s.overlap_check = overlap;
                s.all_in = all_in;
                s.max_attempt = maxattempt;
                s.omega = omega;
                s.orientation = orientation;
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
            (None, Some(m)) => m.map(|m| count_for_mass(m, dist.mean_particle_mass())),
            (None, None) => {
                return Err(a.error_at(
                    STYLE_WORD,
                    "insert/rate/region needs 'nparticles N' or 'mass M' (or INF)",
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
        let per_time = match (prate, mrate) {
            (Some(r), None) => r,
            (None, Some(m)) => m / dist.mean_particle_mass(),
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
                per: PerInsertion::Rate { per_time, every },
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
    pack.orientation = orientation;
    pack.start = start;
    pack.position = position;
    Ok(Box::new(Inserter {
        pack: InsertEngine::Pack(pack),
        total: 0,
        total_mass: 0.0,
        rate: rate_state,
        verbose,
        announce: None,
        rate_line_due: rate,
        set_property,
        stream_tracers: Vec::new(),
    }))
}

/// `vel constant|uniform|gaussian ...`: the velocity law of inserted particles (after
/// the keyword `vel`), as the insertion fixes read it.
pub(super) fn velocity_law(a: &mut Args) -> CmdResult<VelocityLaw> {
    Ok(
        match a.keyword(
            "velocity distribution",
            &["constant", "uniform", "gaussian"],
        )? {
            "constant" => VelocityLaw::Constant(a.vec3("velocity")?),
            "uniform" => VelocityLaw::Uniform(a.vec3("mean velocity")?, a.vec3("velocity spread")?),
            _ => VelocityLaw::Gaussian(a.vec3("mean velocity")?, a.vec3("velocity sigma")?),
        },
    )
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

impl ScriptFix for Inserter {
    /// Prints what the definition reports (`insert/stream`'s rate).
    fn install(&mut self, sim: &mut Sim, _a: &Args, _head: &FixHead) -> CmdResult<()> {
        if let Some(notes) = self.announce.take() {
            notes.print(&mut sim.outputs.out);
        }
        Ok(())
    }

    /// `f_ID[1]`, `f_ID[2]`: particles inserted so far and their mass.
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(vec![self.total as f64, self.total_mass])
    }

    /// `insert/stream`: at each run's set-up, the packets follow the run's time step (a
    /// `timestep` after the fix counts, as in LIGGGHTS 3.8). `insert/stream` and
    /// `insert/rate/region` print their rate lines at the first run's set-up.
    fn pre_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if !ctx.setup {
            return Ok(());
        }
        let w = ctx.world_ref();
        let due = std::mem::take(&mut self.rate_line_due);
        let line = match (&mut self.pack, &self.rate) {
            (InsertEngine::Stream(st), _) => {
                st.set_timestep(w.dt)
                    .map_err(|e| format!("fix {} (insert/stream): {e}", head.id))?;
                due.then(|| super::insert_stream::rate_line(&head.id, st))
            }
            (
                InsertEngine::Pack(p),
                Some(RateState {
                    limit,
                    per: per @ PerInsertion::Rate { per_time, every },
                    ..
                }),
            ) => due.then(|| {
                super::insert_stream::rate_lines(
                    &head.id,
                    per.count(w.dt),
                    *every,
                    *per_time,
                    p.dist.mean_particle_mass(),
                    *limit,
                )
            }),
            _ => None,
        };
        if let Some(line) = line {
            ctx.line(&line);
        }
        Ok(())
    }

    fn due(&self, step: u64) -> bool {
        self.pack.due(step)
    }

    /// The generators, the schedule and the counts.
    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let st = InserterState {
            progress: self.pack.progress(),
            total: self.total,
            total_mass: self.total_mass,
            carry: self.rate.as_ref().map_or(0.0, |r| r.carry),
        };
        postcard::to_stdvec(&st).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let st: InserterState = super::decode_state(state)?;
        if !self.pack.set_progress(&st.progress) {
            return Err(
                "it was written for a distribution with another number of templates".into(),
            );
        }
        self.total = st.total;
        self.total_mass = st.total_mass;
        if let Some(r) = &mut self.rate {
            r.carry = st.carry;
        }
        Ok(())
    }

    fn pre_exchange(
        &mut self,
        head: &FixHead,
        w: &mut World,
        notes: &mut Notes,
    ) -> rdem::Result<()> {
        let first = w.particles.nlocal();
        let rep = match (&mut self.pack, &mut self.rate) {
            (InsertEngine::Stream(st), _) => st.insert(w)?,
            (InsertEngine::Pack(pack), None) => pack.insert(w)?,
            (InsertEngine::Pack(pack), Some(r)) => {
                let want = r.per.count(w.dt) + r.carry;
                let mut n = want.floor() as u64;
                r.carry = want - n as f64;
                if let Some(lim) = r.limit {
                    n = n.min(lim.saturating_sub(self.total));
                }
                pack.insert_n(w, n)?
            }
        };
        if let InsertEngine::Stream(st) = &self.pack {
            for t in &self.stream_tracers {
                t.mark(w, first, st.packet_every())?;
            }
        }
        for (name, value) in &self.set_property {
            let p = &mut w.particles;
            let Some(id) = p.property(name).filter(|id| p.props[id.0].width == 1) else {
                return Err(rdem::Error::Invalid {
                    what: "set_property",
                    reason: format!(
                        "fix {}: no scalar per-particle property '{name}' (define it with 'fix ID all property/atom {name} scalar ...')",
                        head.id
                    ),
                });
            };
            for i in first..p.nlocal() {
                p.props[id.0].get_mut(i)[0] = *value;
            }
        }
        self.total += rep.inserted;
        self.total_mass += rep.mass;
        let id = &head.id;
        // An event that had nothing to insert prints nothing (as LIGGGHTS).
        if self.verbose && rep.wanted > 0 {
            notes.line(insertion_report(
                id,
                rep.inserted,
                rep.mass,
                w.step,
                self.total,
                self.total_mass,
            ));
        }
        if rep.inserted < rep.wanted {
            notes.warning(format!(
                "Particle insertion {id}: less insertions than requested ({} of {}): the region is too full or maxattempt too small",
                rep.inserted, rep.wanted
            ));
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

/// The particle count a `mass M` limit of `insert/rate/region` or `insert/stream` stands
/// for: M over the expected particle mass, rounded down, as LIGGGHTS 3.8 does (measured:
/// 10.8 expected particles' mass gave 10, 382.99 gave 382; "382 particles (mass
/// 2.992242e+01)"). A count within 1e-9 below a whole number is that number, so a mass
/// of exactly N particles gives N whatever the last bit of the division.
pub(super) fn count_for_mass(mass: f64, mean_mass: f64) -> u64 {
    (mass / mean_mass + 1e-9).floor().max(0.0) as u64
}
