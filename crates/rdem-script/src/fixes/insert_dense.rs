//! `fix insert/pack/dense` (LIGGGHTS-PFM; not in LIGGGHTS 3.8): the region filled once
//! with a dense random packing of a distribution's particles to a volume fraction (see
//! `rdem::insert::dense` for the algorithm). It acts in the step's pre-exchange stage, as
//! the other insertion fixes.

use crate::error::Error;
use glam::DVec3;
use rdem::insert::dense::MAX_VOLUME_FRACTION;
use rdem::insert::{DensePack, VelocityLaw};
use rdem::World;

use super::{style, FixHead, FixRow, Notes, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;
use crate::variables::format_g;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "insert/pack/dense",
    parse,
    Stages::PRE_EXCHANGE.and(Stages::VALUES),
    "`seed S` (first), `distributiontemplate`, `region` (bounded), `volumefraction_region φ` (default and at most 0.57); `insert_every once\\|N`, `verbose`, `vel constant\\|uniform\\|gaussian`, `omega constant`, `overlapcheck yes`, `all_in yes`: a dense random packing (advancing front) filling the region once; `f_ID[1..2]` particles and mass inserted",
)
.notes("LIGGGHTS-PFM's fix; LIGGGHTS 3.8 does not have it. The region is packed with radii enlarged by f = ∛(0.57/φ) and the particles inserted with their own radii, so new particles never touch (gaps ≥ (f − 1)(rᵢ + rⱼ)). Where the front packs looser than 0.57 (near walls, narrow regions) rdem packs again with f corrected by the cube root of the count's ratio (at least 1), landing within about 1 % of φ V / v̄ (measured: 0.5017 for 0.5 in a 40 mm cube of 1 mm spheres); LIGGGHTS-PFM inserts its first packing (0.464 there). Near φ = 0.57 the front's own limit caps it (0.535 for 0.55 in a cylinder). The packing is the same on any number of MPI ranks (LIGGGHTS-PFM packs each subdomain on its own, leaving gaps at their faces) and ignores `neigh_modify exclude` (LIGGGHTS-PFM lets excluded type pairs overlap); rdem's own random generator. `start`, `maxattempt`, `ntry_mc`, `random_distribute`, `compress_tags`, `particles_in_region`, `mass_in_region`, `target_variable`, `set_property`, `orientation`, `overlapcheck no`, `all_in no`: not supported yet (errors)")
.atoi();

/// `fix ID group insert/pack/dense seed S ...`.
pub struct InsertDense {
    pack: DensePack,
    total: u64,
    total_mass: f64,
    verbose: bool,
}

/// Keywords LIGGGHTS-PFM's manual names for the insertion fixes that this style does not
/// run, with why.
const NOT_YET: [(&str, &str); 10] = [
    (
        "start",
        "the packing is inserted at the first step of the next run (or every insert_every steps)",
    ),
    (
        "maxattempt",
        "the packing draws no random positions to retry",
    ),
    (
        "ntry_mc",
        "the region's volume is exact for a block and sampled with 10^6 points otherwise",
    ),
    ("random_distribute", "every rank packs the same particles"),
    ("compress_tags", "tags are always consecutive"),
    (
        "particles_in_region",
        "give the target as volumefraction_region",
    ),
    ("mass_in_region", "give the target as volumefraction_region"),
    (
        "target_variable",
        "insertion is once or every insert_every steps",
    ),
    (
        "set_property",
        "set the property after the insertion with 'set'",
    ),
    ("orientation", "rdem's particles are spheres"),
];

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    const VALID: [&str; 9] = [
        "distributiontemplate",
        "region",
        "volumefraction_region",
        "insert_every",
        "verbose",
        "vel",
        "omega",
        "overlapcheck",
        "all_in",
    ];
    // Any positive integer, as LIGGGHTS-PFM's manual says (not the prime > 10000 that
    // LIGGGHTS 3.8's other insertion fixes ask for).
    super::insert::seed_keyword(
        a,
        "insert/pack/dense",
        "'fix ID group insert/pack/dense seed 123 region R distributiontemplate D volumefraction_region 0.5'",
    )?;
    let seed = a.u64("seed")?;
    if seed == 0 {
        return Err(a.error_prev("seed must be a positive integer, not 0", None));
    }
    let (mut dist, mut region, mut every) = (None, None, None);
    let mut fraction = (None, MAX_VOLUME_FRACTION);
    let mut verbose = true;
    let mut vel = VelocityLaw::Constant(DVec3::ZERO);
    let mut omega = DVec3::ZERO;
    let all: Vec<&'static str> = VALID
        .iter()
        .copied()
        .chain(NOT_YET.iter().map(|n| n.0))
        .collect();
    while !a.is_done() {
        let k = a.keyword("insert/pack/dense keyword", &all)?;
        if let Some((_, why)) = NOT_YET.iter().find(|n| n.0 == k) {
            return Err(a.error_prev(
                format!("insert/pack/dense: '{k}' is not supported yet"),
                Some(format!("{why}; supported: {}", VALID.join(", "))),
            ));
        }
        match k {
            "distributiontemplate" => {
                dist = Some(super::insert::distribution(sim, a, false)?);
            }
            "region" => region = Some(sim.fixed_region(a, "fix insert/pack/dense")?),
            "volumefraction_region" => {
                let at = a.pos();
                let f = a.f64("volume fraction")?;
                if f <= 0.0 {
                    return Err(a.error_prev(
                        format!("volume fraction must be > 0, got {f}"),
                        Some(format!("at most {MAX_VOLUME_FRACTION}")),
                    ));
                }
                fraction = (Some(at), f);
            }
            "insert_every" => {
                if a.peek() == Some("once") {
                    a.seek(a.pos() + 1);
                    every = None;
                } else {
                    every = Some(a.count("insert_every (steps, or 'once')")?);
                }
            }
            "verbose" => verbose = a.yes_no("verbose")?,
            "vel" => vel = super::insert::velocity_law(a)?,
            "omega" => {
                a.keyword("omega distribution", &["constant"])?;
                omega = a.vec3("omega")?;
            }
            // What the packing always does: accepted as `yes` only.
            _ => {
                if !a.yes_no(k)? {
                    return Err(a.error_prev(
                        format!("insert/pack/dense: '{k} no' is not supported yet"),
                        Some("the dense packing never overlaps and keeps whole spheres in the region".into()),
                    ));
                }
            }
        }
    }
    let dist = dist.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "insert/pack/dense needs 'distributiontemplate ID'",
            None,
        )
    })?;
    let region = region.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "insert/pack/dense needs 'region ID'",
            Some("a bounded region to fill".into()),
        )
    })?;
    if let Some(t) = dist.templates.iter().find(|t| t.clump.is_some()) {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "insert/pack/dense packs spheres; template '{}' is a multisphere clump",
                t.id
            ),
            Some("insert clumps with insert/pack, insert/rate/region or insert/stream".into()),
        ));
    }
    sim.world_ref(a)?;
    let mut phi = fraction.1;
    if phi > MAX_VOLUME_FRACTION {
        // As LIGGGHTS-PFM: a warning, and the densest fraction the packing reaches.
        a.warn_at(
            fraction.0.unwrap_or(STYLE_WORD),
            &format!(
                "insert/pack/dense: volumefraction_region {} is more than the packing reaches; {MAX_VOLUME_FRACTION} is used",
                format_g(phi, 6)
            ),
        );
        phi = MAX_VOLUME_FRACTION;
    }
    let mut pack = DensePack::new(&head.id, seed, head.groupbit, region, dist, phi, every)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    pack.velocity = vel;
    pack.omega = omega;
    Ok(Box::new(InsertDense {
        pack,
        total: 0,
        total_mass: 0.0,
        verbose,
    }))
}

impl ScriptFix for InsertDense {
    /// `f_ID[1]`, `f_ID[2]`: particles inserted so far and their mass.
    fn values(&self, _sim: &Sim, _head: &FixHead) -> Result<Vec<f64>, Error> {
        Ok(vec![self.total as f64, self.total_mass])
    }

    fn due(&self, step: u64) -> bool {
        self.pack.due(step)
    }

    /// The generators, whether the packing is done and the totals: a continued run
    /// does not pack the region again, and an `insert_every N` packing goes on with the
    /// same random numbers.
    fn save_state(&self, _sim: &Sim, _head: &FixHead) -> Option<Vec<u8>> {
        let (progress, done) = self.pack.progress();
        postcard::to_stdvec(&(progress, done, self.total, self.total_mass)).ok()
    }

    fn restore_state(
        &mut self,
        _sim: &mut Sim,
        _head: &FixHead,
        state: &[u8],
    ) -> Result<(), Error> {
        let (progress, done, total, total_mass): (rdem::insert::InsertProgress, bool, u64, f64) =
            super::decode_state(state)?;
        if !self.pack.set_progress(&progress, done) {
            return Err(
                "it was written for a distribution with another number of templates".into(),
            );
        }
        self.total = total;
        self.total_mass = total_mass;
        Ok(())
    }

    fn pre_exchange(
        &mut self,
        head: &FixHead,
        w: &mut World,
        notes: &mut Notes,
    ) -> rdem::Result<()> {
        let rep = self.pack.insert(w)?;
        self.total += rep.inserted;
        self.total_mass += rep.mass;
        if self.verbose {
            // LIGGGHTS' insertion report, then one more ` - ` line (tools that read the
            // thermo table skip `INFO` and ` - ` lines).
            let g = |v: f64| format_g(v, 6);
            notes.line(super::insertion_report(
                &head.id,
                rep.inserted,
                rep.mass,
                w.step,
                self.total,
                self.total_mass,
            ));
            notes.line(format!(
                " - volume fraction {} reached, {} asked for (about {} particles; radii enlarged {} times for the packing)",
                g(rep.volume_fraction),
                g(self.pack.volume_fraction),
                rep.estimate,
                g(rep.radius_factor)
            ));
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
