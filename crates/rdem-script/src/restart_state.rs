//! What an rdem restart file holds, and the writer and reader that `write_restart`,
//! `restart N ...` and `read_restart` share.
//!
//! The payload (framed by [`rdem_io::restart_file`]: magic, format version, length,
//! CRC-32) is a [`RestartHead`] followed by one block per writing rank, each a
//! [`rdem::restart::RankState`] (that rank's owned particles in storage order, with every
//! named property, and its contact histories), all serialized with `postcard`:
//!
//! ```text
//! u64 length, RestartHead | u64 number of blocks | (u64 length, RankState) × blocks
//! ```
//!
//! As in LIGGGHTS, a restart file continues a study in a new script: `read_restart`
//! takes the place of `create_box` and restores the box, units, particles, groups, the
//! step, the time and the timestep; the script then defines its pair style, walls and
//! fixes again. A fix defined with the ID and style of a fix of the writing run takes
//! back that fix's state (insertion counts, random generators, accumulators,
//! controllers: [`crate::fixes::ScriptFix::save_state`]); per-particle values
//! (`fix property/atom`, wall histories, temperatures) come back with the particles and
//! are kept when the fix that holds them is defined again.

use crate::error::Error;
use std::collections::BTreeSet;
use std::path::Path;

use rdem::restart::{BodyCore, HistoryState, ParticleState, RankState, WorldValues};
use rdem::{Boundary, Domain, World};
use serde::{Deserialize, Serialize};

use crate::sim::Sim;

/// One fix's state in a restart file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FixState {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// The style's own serialization of its state.
    pub state: Vec<u8>,
}

/// The world-wide part of a restart file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RestartHead {
    /// The program that wrote it (`rdem VERSION`).
    pub program: String,
    /// `units` style.
    pub units: String,
    /// `dimension`.
    pub dimension: u8,
    /// Boundary letters, lower and upper face per axis (`p`, `f`, `s`, `m`).
    pub boundary: [[char; 2]; 3],
    /// Box corners.
    pub boxlo: [f64; 3],
    /// Box corners.
    pub boxhi: [f64; 3],
    /// Number of particle types.
    pub ntypes: u32,
    /// Group names by bit.
    pub groups: Vec<Option<String>>,
    /// Step, timestep, sort schedule.
    pub world: WorldValues,
    /// (step, time) at the last change of the timestep.
    pub time_origin: (u64, f64),
    /// Ranks that wrote the file.
    pub nranks: u32,
    /// Particles in the file.
    pub natoms: u64,
    /// Fix states, in definition order.
    pub fixes: Vec<FixState>,
}

/// What `read_restart` brought that later definitions take back.
#[derive(Debug, Clone, Default)]
pub struct Restored {
    /// Fix states not yet taken by a fix of the same ID.
    pub fixes: Vec<FixState>,
    /// Per-particle properties of the file that no fix holds yet.
    pub props: BTreeSet<String>,
    /// Per-particle values of the `fix property/atom` fixes of a LIGGGHTS restart file,
    /// by fix ID, for the fix defined again with that ID (as LIGGGHTS matches them).
    pub peratom: std::collections::BTreeMap<String, PeratomValues>,
    /// The pair style of a LIGGGHTS restart file, until the first run: LIGGGHTS takes it
    /// from the file, rdem needs it defined again (the run says so when it is not).
    pub liggghts_pair: Option<String>,
}

/// The values one fix of a LIGGGHTS restart file stores with each particle.
#[derive(Debug, Clone, Default)]
pub struct PeratomValues {
    /// Values per particle.
    pub width: usize,
    /// Particle tags, increasing.
    pub tags: Vec<u64>,
    /// `width` values per tag.
    pub values: Vec<f64>,
}

impl PeratomValues {
    /// The values of the particle tagged `tag`.
    pub fn of(&self, tag: u64) -> Option<&[f64]> {
        let k = self.tags.binary_search(&tag).ok()?;
        Some(&self.values[k * self.width..(k + 1) * self.width])
    }
}

/// The boundary letter of a face (`p`, `f`, `s`, `m`).
pub(crate) fn letter(b: Boundary) -> char {
    match b {
        Boundary::Periodic => 'p',
        Boundary::Fixed => 'f',
        Boundary::Shrink => 's',
        Boundary::ShrinkMin => 'm',
    }
}

fn push_block(out: &mut Vec<u8>, bytes: &[u8]) {
    out.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
    out.extend_from_slice(bytes);
}

/// Encodes `v` (the types here always serialize).
fn encode<T: Serialize>(v: &T) -> Vec<u8> {
    postcard::to_stdvec(v).expect("restart state serializes")
}

/// Writes the whole state to `path` as a restart file: every rank sends its block, rank
/// 0 writes the file under a temporary name and renames it. Under `rdem -check`
/// nothing is written.
pub(crate) fn write(sim: &Sim, path: &str) -> Result<(), Error> {
    if sim.script.check {
        return Ok(());
    }
    let w = sim.world.as_ref().ok_or("no simulation box")?;
    let mine = encode(&w.rank_state());
    let natoms = w.comm.sum_count(w.particles.nlocal() as u64);
    let fixes: Vec<FixState> = sim
        .defs
        .fixes
        .iter()
        .filter_map(|f| {
            f.imp.save_state(sim, &f.head).map(|state| FixState {
                id: f.head.id.clone(),
                style: f.head.style.to_string(),
                state,
            })
        })
        .collect();
    // One rank: its block as it is (no round trip through the gather's words).
    let blocks = if w.comm.size() == 1 {
        Some(vec![mine])
    } else {
        w.comm.gather_bytes(&mine)
    };
    let written = match blocks {
        Some(blocks) => write_file(sim, w, path, natoms, fixes, &blocks),
        None => Ok(()),
    };
    // Only rank 0 writes: a failure there stops every rank (none waits for the others).
    crate::dumps::agree(&*w.comm, "write_restart", written)
}

/// Rank 0's part of [`write`]: the file from every rank's block.
fn write_file(
    sim: &Sim,
    w: &World,
    path: &str,
    natoms: u64,
    fixes: Vec<FixState>,
    blocks: &[Vec<u8>],
) -> Result<(), Error> {
    let d = &w.domain;
    let head = RestartHead {
        program: format!("rdem {}", env!("CARGO_PKG_VERSION")),
        units: sim.setup.units.name().to_string(),
        dimension: sim.setup.dimension,
        boundary: d.boundary.map(|f| f.map(letter)),
        boxlo: d.boxlo.to_array(),
        boxhi: d.boxhi.to_array(),
        ntypes: sim.ntypes() as u32,
        groups: sim.defs.groups.table(),
        world: w.world_values(),
        time_origin: sim.script.time_origin,
        nranks: w.comm.size() as u32,
        natoms,
        fixes,
    };
    // The payload goes straight after room for the header (filled in last), so the
    // blocks are copied once.
    let total: usize = blocks.iter().map(|b| b.len() + 8).sum();
    let mut payload = Vec::with_capacity(rdem_io::restart_file::HEADER_LEN + total + 1024);
    payload.resize(rdem_io::restart_file::HEADER_LEN, 0);
    push_block(&mut payload, &encode(&head));
    payload.extend_from_slice(&(blocks.len() as u64).to_le_bytes());
    for b in blocks {
        push_block(&mut payload, b);
    }
    rdem_io::restart_file::fill_header(&mut payload);
    rdem_io::write_atomic(Path::new(path), &payload).map_err(Error::from)
}

/// A restart file's contents, decoded.
pub struct RestartContents {
    /// The world-wide part.
    pub head: RestartHead,
    /// One block per writing rank.
    pub ranks: Vec<RankState>,
}

/// Reads and decodes the restart file at `path`; the message names the file.
pub fn read(path: &str) -> Result<RestartContents, Error> {
    let (_version, payload) = rdem_io::restart_file::read_restart_file(Path::new(path))?;
    decode(&payload).map_err(|m| Error::invalid(format!("'{path}' cannot be decoded ({m}); its checksum is right, so it was written by an rdem whose format differs from this one's")))
}

/// Reads the blocks of a payload in order.
struct Cursor<'a> {
    buf: &'a [u8],
    at: usize,
}

impl<'a> Cursor<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], Error> {
        let s = self
            .buf
            .get(self.at..self.at.saturating_add(n))
            .ok_or_else(|| format!("{n} bytes expected at byte {}", self.at))?;
        self.at += n;
        Ok(s)
    }
    fn len(&mut self) -> Result<usize, Error> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")) as usize)
    }
    fn block<T: serde::de::DeserializeOwned>(&mut self) -> Result<T, Error> {
        let n = self.len()?;
        postcard::from_bytes(self.take(n)?).map_err(|e| Error::Decode(e.to_string()))
    }
}

/// Decodes the payload of an rdem restart file (after its framing is checked,
/// [`rdem_io::restart_file::unframe`]); any bytes give the contents or an error.
pub fn decode(payload: &[u8]) -> Result<RestartContents, Error> {
    let mut c = Cursor {
        buf: payload,
        at: 0,
    };
    let head: RestartHead = c.block()?;
    let nb = c.len()?;
    let mut ranks = Vec::with_capacity(nb.min(1 << 16));
    for _ in 0..nb {
        let n = c.len()?;
        let bytes = c.take(n)?;
        let rank = decode_rank(bytes)?;
        ranks.push(rank);
    }
    Ok(RestartContents { head, ranks })
}

/// Decodes one rank's block. Files of rdem before clumps end it at the histories; files
/// of rdem before bodies kept their template's bounding sphere and frame hold bodies
/// without them ([`BodyCore`]s).
fn decode_rank(bytes: &[u8]) -> Result<RankState, String> {
    postcard::from_bytes::<RankState>(bytes).or_else(|e| {
        type V1 = (ParticleState, HistoryState, Option<Vec<BodyCore>>);
        if let Ok((particles, history, bodies)) = postcard::from_bytes::<V1>(bytes) {
            return Ok(RankState {
                particles,
                history,
                bodies: bodies.map(|b| b.into_iter().map(Into::into).collect()),
            });
        }
        postcard::from_bytes::<(ParticleState, HistoryState)>(bytes)
            .map(|(particles, history)| RankState {
                particles,
                history,
                bodies: None,
            })
            .map_err(|_| e.to_string())
    })
}

/// Builds the world a restart file describes (box, decomposition, particles this rank
/// owns, contact histories, step and timestep) and sets the script state it holds
/// (units, dimension, groups, time, the fix states and properties later definitions
/// take back). `decompose` splits the box between the ranks.
pub(crate) fn restore(
    sim: &mut Sim,
    c: RestartContents,
    decompose: impl FnOnce(&mut Sim, &mut World) -> Result<(), Error>,
) -> Result<(), Error> {
    let h = c.head;
    sim.setup.units = crate::units::Units::from_name(&h.units)
        .ok_or_else(|| format!("the file's units '{}' are not rdem's", h.units))?;
    sim.setup.dimension = h.dimension;
    let mut boundary = [[Boundary::Fixed; 2]; 3];
    for (faces, letters) in boundary.iter_mut().zip(&h.boundary) {
        for (b, &c) in faces.iter_mut().zip(letters) {
            *b = Boundary::from_letter(c).ok_or_else(|| format!("boundary letter '{c}'"))?;
        }
    }
    let domain = Domain::with_faces(h.boxlo.into(), h.boxhi.into(), boundary)?;
    let mut w = World::new(domain);
    decompose(sim, &mut w)?;
    w.set_world_values(&h.world)?;
    w.materials.ntypes = h.ntypes as usize;
    let mut history = HistoryState::default();
    let mut props = BTreeSet::new();
    for r in &c.ranks {
        w.restore_particles(&r.particles)?;
        if let Some(b) = &r.bodies {
            w.restore_bodies(b);
        }
        props.extend(r.particles.props.iter().map(|q| q.name.clone()));
        if !r.history.entries.is_empty() {
            history.width = r.history.width;
            history.odd = r.history.odd;
            history.entries.extend_from_slice(&r.history.entries);
        }
    }
    let placed = w.comm.sum_count(w.particles.nlocal() as u64);
    if placed != h.natoms {
        return Err(format!(
            "{} of its {} particles lie outside the box",
            h.natoms - placed,
            h.natoms
        )
        .into());
    }
    w.restore_history(history);
    sim.setup.dt = h.world.dt;
    sim.script.time_origin = h.time_origin;
    sim.defs.groups.set_table(h.groups)?;
    sim.defs.restored = Restored {
        fixes: h.fixes,
        props,
        ..Restored::default()
    };
    sim.install_world(w);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rdem::restart::BodyState;

    /// A rank's block in each layout rdem has written reads back: today's, bodies
    /// without their bounding sphere (their bound then 0, "unknown"), and no bodies.
    #[test]
    fn older_rank_blocks_still_read() {
        let core = |tag| BodyCore {
            tag,
            mass: 2.0,
            x: [1.0, 2.0, 3.0],
            q: [0.0, 0.0, 0.0, 1.0],
            fflag: [true; 3],
            tflag: [true, false, true],
            ..BodyCore::default()
        };
        let now = RankState {
            bodies: Some(vec![BodyState {
                core: core(1),
                bound: 0.009,
                frame: [0.0, 0.0, 0.0, 1.0],
            }]),
            ..RankState::default()
        };
        assert_eq!(decode_rank(&encode(&now)).unwrap(), now);
        let old = (
            ParticleState::default(),
            HistoryState::default(),
            Some(vec![core(1), core(2), core(7)]),
        );
        let got = decode_rank(&encode(&old)).unwrap();
        let bodies = got.bodies.unwrap();
        assert_eq!(bodies.len(), 3);
        assert!(bodies.iter().all(|b| b.bound == 0.0 && b.core.mass == 2.0));
        assert_eq!(
            bodies.iter().map(|b| b.core.tag).collect::<Vec<_>>(),
            [1, 2, 7]
        );
        let oldest = (ParticleState::default(), HistoryState::default());
        assert_eq!(decode_rank(&encode(&oldest)).unwrap().bodies, None);
    }
}
