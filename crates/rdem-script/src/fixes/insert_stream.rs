//! `fix insert/stream`: packets of particles poured through a planar mesh face
//! (`insertion_face`), held at the insertion velocity until they have crossed it. Its
//! keywords are read with the other insertion styles' ([`super::insert`]); this file checks
//! the combinations LIGGGHTS requires and builds the engine's stream.

use rdem::insert::{Distribution, VelocityLaw};

use super::insert::{InsertEngine, Inserter};
use super::{style, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;
use crate::variables::format_e;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "insert/stream",
    super::insert::parse,
    Stages::PRE_EXCHANGE.and(Stages::VALUES).and(Stages::PRE_STEP),
    "`insertion_face MESH` (a planar mesh), `extrude_length L` or `insert_every N`, `nparticles N\\|INF` or `mass M\\|INF`, `particlerate` or `massrate`, `vel`, `omega`, `overlapcheck`, `all_in`, `maxattempt`, `start`, `set_property NAME value`; `parallel`, `random_distribute`, `compress_tags`, `verbose` accepted",
)
.notes("a packet every `round(L / (v·n dt))` steps (dt: the run's time step, as LIGGGHTS 3.8), each particle flying at its insertion velocity (no force) until it reaches the face, as in LIGGGHTS; the per-template split of a packet is LIGGGHTS' expected split, not its random one; `duration` with `insert_every` pours each packet in that many steps; `f_release_fix_insert_stream[5]` is each particle's release step, as LIGGGHTS records it (its other columns are not kept)")
.atoi();

/// What `fix insert/stream` was given (besides the settings every insertion has).
pub(super) struct StreamArgs<'a> {
    pub(super) id: &'a str,
    pub(super) seed: u64,
    pub(super) groupbit: u32,
    pub(super) dist: Distribution,
    /// (word position, mesh index).
    pub(super) face: Option<(usize, usize)>,
    pub(super) extrude: Option<f64>,
    pub(super) every: Option<u64>,
    /// (word position, steps).
    pub(super) duration: Option<(usize, u64)>,
    pub(super) nparticles: Option<Option<u64>>,
    /// `mass M` (`Some(None)`: `mass INF`).
    pub(super) massmax: Option<Option<f64>>,
    pub(super) prate: Option<f64>,
    pub(super) mrate: Option<f64>,
    pub(super) dt: f64,
    pub(super) set_property: Vec<(String, f64)>,
}

/// `fix insert/stream`: checks the keyword combinations LIGGGHTS requires and builds
/// the engine's stream.
pub(super) fn build(
    sim: &Sim,
    a: &mut Args,
    s: StreamArgs,
    settings: impl FnOnce(&mut rdem::insert::InsertStream),
    vel: VelocityLaw,
    verbose: bool,
) -> CmdResult<Box<dyn ScriptFix>> {
    use rdem::insert::stream::Extrusion;
    let err = |a: &Args, msg: &str| a.error_at(STYLE_WORD, msg.to_string(), None);
    let Some((face_at, mesh)) = s.face else {
        return Err(err(a, "insert/stream needs 'insertion_face MESH-ID'"));
    };
    let extrusion = match (s.extrude, s.every) {
        (Some(_), _) if s.duration.is_some() => {
            return Err(a.error_at(
                s.duration.map(|d| d.0 - 1).unwrap_or(STYLE_WORD),
                "insert/stream: 'duration' goes with 'insert_every', not 'extrude_length'",
                None,
            ))
        }
        (Some(l), None) => Extrusion::Length(l),
        (None, Some(n)) => match s.duration {
            Some((at, d)) if d > n => {
                return Err(a.error_at(
                    at,
                    format!("duration {d} is longer than insert_every {n}"),
                    None,
                ))
            }
            Some((_, d)) => Extrusion::Pulsed {
                every: n,
                duration: d,
            },
            None => Extrusion::Every(n),
        },
        (Some(_), Some(_)) => {
            return Err(err(
                a,
                "insert/stream takes 'extrude_length' or 'insert_every', not both",
            ))
        }
        (None, None) => {
            return Err(err(
                a,
                "insert/stream needs 'extrude_length L' or 'insert_every N'",
            ))
        }
    };
    let limit = match (s.nparticles, s.massmax) {
        (Some(n), None) => n,
        (None, Some(m)) => m.map(|m| super::insert::count_for_mass(m, s.dist.mean_particle_mass())),
        (None, None) => {
            return Err(err(
                a,
                "insert/stream needs 'nparticles N' or 'mass M' (or INF)",
            ))
        }
        (Some(_), Some(_)) => return Err(err(a, "give either nparticles or mass, not both")),
    };
    let rate = match (s.prate, s.mrate) {
        (Some(r), None) => r,
        (None, Some(m)) => m / s.dist.mean_particle_mass(),
        _ => {
            return Err(err(
                a,
                "insert/stream needs exactly one of 'particlerate' or 'massrate'",
            ))
        }
    };
    let w = sim.world_ref(a)?;
    let face = &w.meshes[mesh].mesh;
    let mut st = rdem::insert::InsertStream::new(
        s.id, s.seed, s.groupbit, s.dist, mesh, face, vel, rate, extrusion, s.dt,
    )
    .map_err(|e| a.error_at(face_at, e.to_string(), None))?;
    st.limit = limit;
    settings(&mut st);
    Ok(Box::new(Inserter {
        pack: InsertEngine::Stream(st),
        total: 0,
        total_mass: 0.0,
        rate: None,
        verbose,
        announce: None,
        rate_line_due: true,
        set_property: s.set_property,
        stream_tracers: Vec::new(),
    }))
}

/// The lines an insertion at a rate prints at the first run's set-up (with `verbose`
/// yes or no, as LIGGGHTS 3.8): the packet size, its period and the rates, and with a
/// limit of `limit` particles, their mass and the steps they take
/// (whole packets × period, as LIGGGHTS: 5000 particles in packets of 300 every 30000
/// steps "within 480000 steps").
pub(super) fn rate_lines(
    id: &str,
    per_insertion: f64,
    every: u64,
    rate: f64,
    mean_mass: f64,
    limit: Option<u64>,
) -> String {
    let mut s = format!(
        "INFO: Particle insertion {id}: {per_insertion:.6} particles every {every} steps - particle rate {rate:.6}  (mass rate {})",
        format_e(rate * mean_mass)
    );
    if let Some(n) = limit {
        let packets = if per_insertion > 0.0 {
            (n as f64 / per_insertion).floor() as u64
        } else {
            0
        };
        s.push_str(&format!(
            "\n      {n} particles (mass {}) within {} steps",
            format_e(n as f64 * mean_mass),
            packets * every
        ));
    }
    s
}

/// [`rate_lines`] of an `insert/stream`.
pub(super) fn rate_line(id: &str, st: &rdem::insert::InsertStream) -> String {
    rate_lines(
        id,
        st.per_insertion,
        st.every,
        st.rate(),
        st.dist.mean_particle_mass(),
        st.limit,
    )
}
