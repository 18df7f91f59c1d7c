//! `fix ID group insert/fragments seed S distributiontemplate D every N [region R]
//! [type_replace T] [check_bound_sphere yes|no] [start STEP] [verbose yes|no]`
//! (LIGGGHTS-INL; not in LIGGGHTS 3.8): replaces particles by fragments.
//!
//! Every step, each particle of the group (and of type T, with `type_replace`) is marked
//! for replacement when it is in region R (a clump's sphere: when its clump's centre of
//! mass is), or always without a region. A mark stays with its particle. Every N steps
//! from the step after the definition (or from `start`), in the step's pre-exchange
//! stage, every marked clump and every marked single sphere is removed and the one
//! template of distribution D put in its place:
//!
//! - the template must be a `particletemplate/multiplespheres` with `relative yes`: its
//!   positions and radii are in units of the radius of the replaced particle's bounding
//!   sphere (a clump: its template's, [`rdem::multisphere::ClumpTemplate::enclosing`];
//!   a sphere: its radius); that radius scales them;
//! - the template's bounding sphere is centred on the replaced clump's centre of mass
//!   (a sphere's centre), and turned as the clump is turned: the template is laid out in
//!   the frame the clump's own template was given in;
//! - every fragment takes the replaced particle's velocity (a clump's centre-of-mass
//!   velocity) and no spin, the template's type and density, and joins the fix's, the
//!   template's and the distribution's groups;
//! - there is no overlap check (the replaced particle leaves the room);
//! - with `bonded yes` in the template the fragments of one replacement share a
//!   [`rdem::bond::RANDOM_ID`], so `cohesion bond` bonds those closer than
//!   `createDistanceBond` at the step they appear.
//!
//! The fix prints a line for each replacement event, as LIGGGHTS-INL does; `f_ID[1]` and
//! `f_ID[2]` are the count and mass of the particles replaced so far.
//!
//! Where rdem differs from LIGGGHTS-INL: the fork turns the fragments by the clump's
//! principal-axes orientation, rdem by the orientation of the frame its template was
//! given in (the same when the template is given along its principal axes, as symmetric
//! ones are). The bond IDs are rdem's own numbers (the fork draws them at
//! random): only which spheres share one matters.

use glam::{DQuat, DVec3};
use rdem::particles::NewParticle;
use rdem::World;

use super::{style, FixHead, FixRow, Notes, ScriptFix, StageCtx, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "insert/fragments",
    parse,
    Stages::END_OF_STEP
        .and(Stages::PRE_EXCHANGE)
        .and(Stages::VALUES),
    "`seed S` (first), `distributiontemplate D` (one `particletemplate/multiplespheres` with `relative yes`), `every\\|insert_every N`, `region R`, `type_replace T`, `check_bound_sphere yes\\|no`, `start STEP`, `verbose`: clumps (centre of mass in R) and single spheres (in R) of the group are replaced every N steps by the template scaled by their bounding radius, at their centre, with their velocity; `f_ID[1..2]` count and mass replaced",
)
.notes("LIGGGHTS-INL turns fragments by the clump's principal axes, rdem by the frame its template was given in (the same for templates given along their axes)");

/// One fragment of the template: its offset from the template's bounding-sphere centre
/// (in the frame the template was given in) and its radius, both in bounding radii.
#[derive(Debug, Clone, Copy)]
struct Piece {
    offset: DVec3,
    radius: f64,
    /// Atom type (the template's, or the sphere's own with `spheres_different_types`).
    ty: u32,
}

/// The fix.
struct InsertFragments {
    pieces: Vec<Piece>,
    density: f64,
    /// Groups of the fragments: the fix's, the template's and the distribution's.
    mask: u32,
    /// Fragments of one replacement share a bond ID.
    random_bond_id: bool,
    region: Option<rdem::region::Region>,
    type_replace: Option<u32>,
    first: u64,
    every: u64,
    /// Name of the per-particle mark.
    mark: String,
    /// Count and mass replaced so far.
    total: u64,
    total_mass: f64,
}

/// What a restart file keeps.
#[derive(serde::Serialize, serde::Deserialize)]
struct State {
    first: u64,
    total: u64,
    total_mass: f64,
}

/// A particle to replace: where, how it moves, how big, how turned, and a key for its
/// fragments' bond ID.
struct Replaced {
    x: DVec3,
    v: DVec3,
    scale: f64,
    q: DQuat,
    mass: f64,
    key: u64,
    /// Whether this rank adds its fragments.
    here: bool,
}

const KEYS: [&str; 9] = [
    "distributiontemplate",
    "every",
    "insert_every",
    "region",
    "type_replace",
    "check_bound_sphere",
    "start",
    "verbose",
    // Refused with the fork's reason (listed so that the message says so).
    "nparticles",
];

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    let step = w.step;
    super::insert::seed_keyword(
        a,
        "insert/fragments",
        "'fix ID all insert/fragments seed 123 distributiontemplate D every 50 region R'",
    )?;
    a.u64("seed")?;
    let (mut dist, mut every, mut region, mut type_replace) = (None, None, None, None);
    let (mut check_bound, mut start) = (true, None);
    while !a.is_done() {
        let at = a.pos();
        match a.keyword("fix insert/fragments keyword", &KEYS)? {
            "distributiontemplate" => dist = Some(super::insert::distribution(sim, a, true)?),
            "every" | "insert_every" => every = Some(a.count("every (steps)")?),
            "region" => region = Some(sim.fixed_region(a, "fix insert/fragments")?),
            "type_replace" => {
                type_replace = Some(super::particletemplate_sphere::atom_type(sim, a)?)
            }
            "check_bound_sphere" => check_bound = a.yes_no("check_bound_sphere")?,
            "start" => {
                let s = a.u64("start step")?;
                if s <= step {
                    return Err(a.error_prev(
                        format!("start step {s} is not after the current step {step}"),
                        None,
                    ));
                }
                start = Some(s);
            }
            "verbose" => {
                a.yes_no("verbose")?;
            }
            _ => {
                return Err(a.error_at(
                    at,
                    "fix insert/fragments inserts what it replaces: 'nparticles', 'mass' and rates are not allowed",
                    Some("give 'every N' and a region".into()),
                ))
            }
        }
    }
    let dist = dist.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "fix insert/fragments needs 'distributiontemplate D'",
            Some("D: a particledistribution/discrete of one particletemplate/multiplespheres with 'relative yes'".into()),
        )
    })?;
    let every = every.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "fix insert/fragments needs 'every N' (steps between replacements)",
            None,
        )
    })?;
    let [t] = dist.templates.as_slice() else {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "distribution {} holds {} templates: fix insert/fragments takes exactly one",
                dist.id,
                dist.templates.len()
            ),
            None,
        ));
    };
    let Some(c) = t.clump.as_ref().filter(|c| !c.rigid) else {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "template {} is not a particletemplate/multiplespheres",
                t.id
            ),
            None,
        ));
    };
    let tpl = &c.template;
    let (centre, bound) = tpl.enclosing;
    let rmax = tpl.spheres.iter().map(|s| s.r).fold(0.0, f64::max);
    if rmax >= 1.0 {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "template {}'s largest radius is {rmax}: relative radii must be below 1",
                t.id
            ),
            None,
        ));
    }
    if check_bound && bound > 1.0 + 1e-12 {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "the bounding sphere of template {} has radius {bound}, more than 1",
                t.id
            ),
            Some("scale the template down, or give 'check_bound_sphere no'".into()),
        ));
    }
    let pieces = tpl
        .spheres
        .iter()
        .enumerate()
        .map(|(k, s)| Piece {
            offset: tpl.axes * (s.x - centre),
            radius: s.r,
            ty: c.sphere_type(k).unwrap_or(t.ty),
        })
        .collect();
    Ok(Box::new(InsertFragments {
        pieces,
        density: t.density,
        mask: 1 | head.groupbit | t.groupbit | dist.groupbit,
        random_bond_id: c.random_bond_id,
        region,
        type_replace,
        first: start.unwrap_or(step + 1),
        every,
        mark: format!("replace_{}", head.id),
        total: 0,
        total_mass: 0.0,
    }))
}

impl InsertFragments {
    /// Marks the particles to replace (group, type, and in the region); those marked
    /// already are skipped, so that the list is empty on most steps.
    fn mark(&self, w: &mut World, groupbit: u32) -> rdem::Result<()> {
        let id = self.mark_id(w)?;
        let p = &w.particles;
        let n = p.nlocal();
        let marks: Vec<usize> = {
            let clump_of = w.clump_of();
            let done = &p.props[id.0].data;
            (0..n)
                .filter(|&i| done[i] == 0.0 && p.mask[i] & groupbit != 0)
                .filter(|&i| self.type_replace.is_none_or(|t| p.ty[i] == t))
                .filter(|&i| {
                    let x = match (clump_of(i), &w.multisphere) {
                        (Some(k), Some(ms)) => ms.bodies[k].x,
                        _ => p.x[i],
                    };
                    self.region.as_ref().is_none_or(|r| r.contains(x))
                })
                .collect()
        };
        let data = &mut w.particles.props[id.0].data;
        for i in marks {
            data[i] = 1.0;
        }
        Ok(())
    }

    fn mark_id(&self, w: &mut World) -> rdem::Result<rdem::particles::PropId> {
        let p = &mut w.particles;
        match p.property(&self.mark) {
            Some(id) => Ok(id),
            None => p.add_property(&self.mark, 1, &[0.0]),
        }
    }

    /// Removes the marked particles and adds their fragments.
    fn replace(&mut self, w: &mut World, notes: &mut Notes) -> rdem::Result<()> {
        let mark = self.mark_id(w)?;
        let p = &w.particles;
        let n = p.nlocal();
        let marked = |i: usize| p.props[mark.0].data[i] != 0.0;
        let body_of = w.clump_of();
        // Clumps any rank marked, by tag (every rank holds every clump).
        let mine: Vec<f64> = (0..n)
            .filter(|&i| marked(i))
            .filter_map(|i| {
                body_of(i).map(|k| w.multisphere.as_ref().expect("a body").tags[k] as f64)
            })
            .collect();
        let mut tags: Vec<u64> = if w.comm.size() > 1 {
            w.comm.all_gather(&mine)
        } else {
            mine
        }
        .into_iter()
        .map(|t| t as u64)
        .collect();
        tags.sort_unstable();
        tags.dedup();
        let mut out = Vec::new();
        if let Some(ms) = w.multisphere.as_ref() {
            for &tag in &tags {
                let k = ms.body_of(tag as f64).expect("a marked clump");
                let (b, info) = (&ms.bodies[k], &ms.info[k]);
                if info.bound <= 0.0 {
                    return Err(rdem::Error::Invalid {
                        what: "fix insert/fragments",
                        reason: format!(
                            "clump {tag} came from a restart file of an older rdem, which did not keep its template's bounding sphere"
                        ),
                    });
                }
                out.push(Replaced {
                    x: b.x,
                    v: b.v,
                    scale: info.bound,
                    // Input frame to body frame, then to space.
                    q: b.q * info.frame,
                    mass: b.mass,
                    key: tag | 1 << 63,
                    here: w.owns_inserted(b.x),
                });
            }
        }
        let mut remove = vec![false; n];
        let mut singles = Vec::new();
        for i in (0..n).filter(|&i| marked(i)) {
            // A clump goes whole (on every rank) when any of its spheres is marked.
            remove[i] = true;
            if body_of(i).is_none() {
                singles.push(Replaced {
                    x: p.x[i],
                    v: p.v[i],
                    scale: p.radius[i],
                    q: DQuat::IDENTITY,
                    mass: p.rmass[i],
                    key: p.tag[i],
                    here: true,
                });
            }
        }
        singles.sort_by_key(|r| r.key);
        out.extend(singles);
        drop(body_of);
        // Every rank takes part: removing whole clumps is collective.
        w.remove_particles(&remove);
        let rid = if self.random_bond_id {
            w.particles.property(rdem::bond::RANDOM_ID)
        } else {
            None
        };
        let step = w.step;
        let (mut count, mut mass) = (0.0, 0.0);
        for r in out.iter().filter(|r| r.here) {
            count += 1.0;
            mass += r.mass;
            let bond_id = rdem::bond::random_id(step, r.key);
            for piece in &self.pieces {
                let i = w.add_particle(&NewParticle {
                    tag: 0,
                    ty: piece.ty,
                    mask: self.mask,
                    x: r.x + r.q * (piece.offset * r.scale),
                    v: r.v,
                    omega: DVec3::ZERO,
                    radius: piece.radius * r.scale,
                    density: self.density,
                })?;
                if let Some(rid) = rid {
                    w.particles.props[rid.0].data[i] = bond_id;
                }
            }
        }
        let (count, mass) = (w.comm.sum(count) as u64, w.comm.sum(mass));
        if count > 0 {
            self.total += count;
            self.total_mass += mass;
            // LIGGGHTS-INL's line (masses with 6 decimals, as it prints them).
            notes.line(format!(
                "Particle replacement: replaced {count} particle templates (mass {mass:.6}) at step {step}\n  - a total of {} particles (mass {:.6}) replaced so far.",
                self.total, self.total_mass
            ));
        }
        Ok(())
    }
}

impl ScriptFix for InsertFragments {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let w = sim.world_mut(a)?;
        self.mark_id(w)
            .map_err(|e| a.error_at(STYLE_WORD, e.to_string(), None))?;
        Ok(())
    }

    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(vec![self.total as f64, self.total_mass])
    }

    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        self.mark(ctx.world(), head.groupbit)?;
        Ok(())
    }

    fn due(&self, step: u64) -> bool {
        step >= self.first && (step - self.first) % self.every == 0
    }

    fn pre_exchange(
        &mut self,
        _head: &FixHead,
        world: &mut World,
        notes: &mut Notes,
    ) -> rdem::Result<()> {
        self.replace(world, notes)
    }

    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        postcard::to_stdvec(&State {
            first: self.first,
            total: self.total,
            total_mass: self.total_mass,
        })
        .ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let st: State = super::decode_state(state)?;
        self.first = st.first;
        self.total = st.total;
        self.total_mass = st.total_mass;
        Ok(())
    }

    fn unfix(&mut self, sim: &mut Sim, _head: &FixHead) {
        if let Some(w) = &mut sim.world {
            w.particles.retire_property(&self.mark);
        }
    }
}
