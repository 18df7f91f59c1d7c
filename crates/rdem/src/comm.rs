//! Communication seam. The engine talks to other subdomains only through [`Comm`]; the
//! serial case is the one-rank implementation [`Serial`], whose only ghosts are periodic
//! images. The MPI implementation (feature `mpi`, `mpi_comm`) implements the same
//! trait: the engine has one code path, and serial is its one-rank case.

use glam::DVec3;

use crate::domain::Domain;
use crate::error::Result;
use crate::particles::{Particles, Tag};

/// The communicator for a new simulation: over MPI when this process is one of several
/// MPI ranks (feature `mpi`, after `init_mpi`), else [`Serial`] (also for one rank, so
/// that a one-rank run is the serial run, bit for bit).
pub fn default_comm() -> Box<dyn Comm> {
    #[cfg(feature = "mpi")]
    if process_rank_size().1 > 1 {
        return Box::new(crate::mpi_comm::MpiComm::new(
            mpi::topology::SimpleCommunicator::world(),
        ));
    }
    Box::new(Serial::new())
}

/// Rank and number of processes of this run (`(0, 1)` without MPI). Known before any
/// simulation exists, for the screen and log (only rank 0 prints).
pub fn process_rank_size() -> (usize, usize) {
    #[cfg(feature = "mpi")]
    if mpi::environment::is_initialized() && !mpi::environment::is_finalized() {
        use mpi::traits::Communicator;
        let w = mpi::topology::SimpleCommunicator::world();
        return (w.rank() as usize, w.size() as usize);
    }
    (0, 1)
}

/// Starts MPI (feature `mpi`); MPI ends when the returned guard is dropped. Without the
/// feature this does nothing.
#[cfg(feature = "mpi")]
pub fn init_mpi() -> Option<mpi::environment::Universe> {
    mpi::initialize()
}

/// After a command that every rank ran: `None` when it succeeded on every rank, else the
/// lowest rank that failed and its message (the same answer on every rank), so that all
/// ranks stop together and one reports. Serially: this process's failure.
pub fn agree_on_failure(failed: Option<&str>) -> Option<(usize, String)> {
    #[cfg(feature = "mpi")]
    if process_rank_size().1 > 1 {
        use mpi::collective::{CommunicatorCollectives, Root, SystemOperation};
        use mpi::traits::Communicator;
        let w = mpi::topology::SimpleCommunicator::world();
        let me = if failed.is_some() {
            w.rank() as u64
        } else {
            w.size() as u64
        };
        let mut first = 0u64;
        w.all_reduce_into(&me, &mut first, SystemOperation::min());
        if first == w.size() as u64 {
            return None;
        }
        let root = w.process_at_rank(first as i32);
        let text = failed.unwrap_or("").as_bytes().to_vec();
        let mut len = text.len() as u64;
        root.broadcast_into(&mut len);
        let mut bytes = if first == w.rank() as u64 {
            text
        } else {
            vec![0u8; len as usize]
        };
        root.broadcast_into(&mut bytes[..]);
        return Some((first as usize, String::from_utf8_lossy(&bytes).into_owned()));
    }
    failed.map(|m| (0, m.to_string()))
}

/// Where failing ranks meet before they stop: a communicator of its own (a duplicate of
/// the world, made at start-up while every rank is there), so that meeting on it never
/// mixes with a collective call of the simulation that other ranks may be blocked in.
///
/// A failure that every rank agreed on (every command's and every file write's are)
/// brings every rank here, and the meeting ends at once. A failure on some ranks only
/// would leave the others waiting forever in their next collective call; the failing
/// ranks then stop the whole job with `MPI_Abort` after a grace time, so that no rank
/// waits forever. Serially (or without the feature) there is nobody to meet.
pub struct StopLine {
    #[cfg(feature = "mpi")]
    comm: Option<mpi::topology::SimpleCommunicator>,
}

impl StopLine {
    /// Makes the meeting place. Collective (call it on every rank, after `init_mpi`).
    pub fn new() -> Self {
        #[cfg(feature = "mpi")]
        {
            use mpi::traits::Communicator;
            let comm = (process_rank_size().1 > 1)
                .then(|| mpi::topology::SimpleCommunicator::world().duplicate());
            Self { comm }
        }
        #[cfg(not(feature = "mpi"))]
        Self {}
    }

    /// Waits up to `grace` for every rank to arrive; true when they all did (or there is
    /// one rank). Call it only on the way out after a failure.
    pub fn all_stopping(&self, grace: std::time::Duration) -> bool {
        #[cfg(feature = "mpi")]
        if let Some(c) = &self.comm {
            use mpi::collective::CommunicatorCollectives;
            let start = std::time::Instant::now();
            let mut req = c.immediate_barrier();
            loop {
                match req.test() {
                    Ok(_) => return true,
                    Err(r) if start.elapsed() < grace => {
                        req = r;
                        std::thread::sleep(std::time::Duration::from_millis(5));
                    }
                    Err(r) => {
                        // The barrier stays posted: the job is aborted next.
                        std::mem::forget(r);
                        return false;
                    }
                }
            }
        }
        let _ = grace;
        true
    }

    /// Stops every rank of the job with exit code `code` (`MPI_Abort`); serially, this
    /// process.
    pub fn abort(&self, code: u8) -> ! {
        #[cfg(feature = "mpi")]
        if let Some(c) = &self.comm {
            use mpi::traits::Communicator;
            c.abort(i32::from(code));
        }
        std::process::exit(i32::from(code))
    }
}

impl Default for StopLine {
    fn default() -> Self {
        Self::new()
    }
}

/// Per-particle data kept outside [`Particles`] that travels with a migrating particle
/// (the contact history rows of the neighbor list).
pub trait Carried {
    /// Appends the data of the particle with tag `tag` to `buf`.
    fn pack(&mut self, tag: Tag, buf: &mut Vec<f64>);
    /// Reads the data of the arriving particle `tag` from the start of `buf`; returns the
    /// number of values read.
    fn unpack(&mut self, tag: Tag, buf: &[f64]) -> usize;
}

/// Exchange of particles and ghost data between subdomains, and global reductions.
pub trait Comm: std::fmt::Debug + Send {
    /// This process's rank.
    fn rank(&self) -> usize;
    /// Number of ranks.
    fn size(&self) -> usize;
    /// Chooses the processor grid (`fixed`: the user's `processors` counts, 0 = free) and
    /// sets this rank's subdomain in `domain`.
    fn decompose(&mut self, domain: &mut Domain, fixed: [usize; 3]) -> Result<()>;
    /// Moves owned particles that left this subdomain to their new owners, with the data
    /// `carried` holds for them. Ghosts must have been cleared.
    fn exchange(&mut self, p: &mut Particles, domain: &Domain, carried: &mut dyn Carried);
    /// Creates ghosts of every particle within `cutoff` of a subdomain face (including
    /// periodic images), after the locals.
    fn borders(&mut self, p: &mut Particles, domain: &Domain, cutoff: f64);
    /// Refreshes ghost positions, velocities, angular velocities, radii and masses from
    /// their owners (radii and masses change between re-neighborings under `fix adapt`);
    /// ghosts across a Lees–Edwards y face follow the offset of `domain`'s shear.
    fn forward(&mut self, p: &mut Particles, domain: &Domain);
    /// Adds ghost forces and torques onto their owners.
    fn reverse(&mut self, p: &mut Particles);
    /// Adds the per-particle virial of ghosts (`virial[g]`, 6 components) onto their
    /// owners, as [`Comm::reverse`] does for forces.
    fn reverse_virial(&mut self, p: &Particles, virial: &mut [[f64; 6]]);
    /// Adds one value per ghost (`c[g]`) onto the particle it copies, as
    /// [`Comm::reverse`] does for forces (for per-particle tallies outside a step).
    fn reverse_scalar(&self, p: &Particles, c: &mut [f64]);
    /// Global sum.
    fn sum(&self, x: f64) -> f64;
    /// Global sum of a count.
    fn sum_count(&self, x: u64) -> u64;
    /// Global minimum.
    fn min(&self, x: f64) -> f64;
    /// Global maximum.
    fn max(&self, x: f64) -> f64;
    /// True on every rank when `b` is true on any rank.
    fn any(&self, b: bool) -> bool {
        self.max(b as u8 as f64) > 0.0
    }
    /// Global maximum of a count or tag.
    fn max_count(&self, x: u64) -> u64;
    /// Sum of `x` over the ranks below this one (exclusive prefix sum), for tag extension.
    fn exclusive_prefix_count(&self, x: u64) -> u64;
    /// Element-wise global sum, in place.
    fn sum_slice(&self, x: &mut [f64]);
    /// Sends `out[r]` to rank `r` (one buffer per rank); returns what every rank sent to
    /// this one, concatenated in rank order.
    fn all_to_all(&self, out: Vec<Vec<f64>>) -> Vec<f64>;
    /// Concatenation of every rank's `data` in rank order, on rank 0 (`None` elsewhere).
    fn gather(&self, data: &[f64]) -> Option<Vec<f64>>;
    /// Concatenation of every rank's `data` in rank order, on every rank.
    fn all_gather(&self, data: &[f64]) -> Vec<f64>;
    /// True on the rank that prints and writes files (rank 0).
    fn is_root(&self) -> bool {
        self.rank() == 0
    }
    /// Every rank's `data`, one buffer per rank in rank order, on rank 0 (`None`
    /// elsewhere). The bytes travel as f64 words (a length, then the bytes eight to a
    /// word) through [`Comm::gather`].
    fn gather_bytes(&self, data: &[u8]) -> Option<Vec<Vec<u8>>> {
        let mut words = Vec::with_capacity(data.len() / 8 + 2);
        words.push(f64::from_bits(data.len() as u64));
        for c in data.chunks(8) {
            let mut b = [0u8; 8];
            b[..c.len()].copy_from_slice(c);
            words.push(f64::from_bits(u64::from_le_bytes(b)));
        }
        let all = self.gather(&words)?;
        let mut out = Vec::with_capacity(self.size());
        let mut k = 0;
        while k < all.len() {
            let n = all[k].to_bits() as usize;
            let nw = n.div_ceil(8);
            let mut bytes = Vec::with_capacity(nw * 8);
            for w in &all[k + 1..k + 1 + nw] {
                bytes.extend_from_slice(&w.to_bits().to_le_bytes());
            }
            bytes.truncate(n);
            out.push(bytes);
            k += 1 + nw;
        }
        Some(out)
    }
}

/// One process owning the whole box. Ghosts are the periodic images within the cutoff,
/// made axis by axis so that edge and corner images exist too; a particle has images
/// through both faces of an axis shorter than twice the cutoff, and several layers of
/// them along an axis shorter than the cutoff.
#[derive(Debug, Clone, Default)]
pub struct Serial {
    /// Shift of each ghost relative to its owner (index `g - nlocal`).
    shift: Vec<DVec3>,
    /// Under Lees–Edwards shear, how many box lengths each ghost lies above its owner
    /// along y (index `g - nlocal`; empty without shear).
    ny: Vec<i32>,
}

impl Serial {
    /// The serial communicator.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Comm for Serial {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn decompose(&mut self, domain: &mut Domain, fixed: [usize; 3]) -> Result<()> {
        if fixed.iter().any(|&n| n > 1) {
            return Err(crate::error::Error::Invalid {
                what: "processors",
                reason: format!(
                    "a {}x{}x{} grid needs {} MPI ranks; this run has 1 (start it with \
                     mpirun -np N on an rdem built with the 'mpi' feature)",
                    fixed[0].max(1),
                    fixed[1].max(1),
                    fixed[2].max(1),
                    fixed.iter().map(|&n| n.max(1)).product::<usize>()
                ),
            });
        }
        domain.set_grid([1, 1, 1], 0);
        Ok(())
    }

    fn exchange(&mut self, _p: &mut Particles, _domain: &Domain, _c: &mut dyn Carried) {}

    fn borders(&mut self, p: &mut Particles, domain: &Domain, cutoff: f64) {
        p.clear_ghosts();
        self.shift.clear();
        self.ny.clear();
        let prd = domain.prd();
        let nlocal = p.nlocal();
        let shear = domain.shear;
        for a in domain.ghost_axes() {
            if !domain.periodic(a) {
                continue;
            }
            let n = p.len();
            let mut l = DVec3::ZERO;
            l[a] = prd[a];
            // Under shear, the images across a y face slide along x.
            let sheared = shear.filter(|_| a == 1);
            for i in 0..n {
                let (base, base_ny) = if i < nlocal {
                    (DVec3::ZERO, 0)
                } else {
                    let g = i - nlocal;
                    (self.shift[g], self.ny.get(g).copied().unwrap_or(0))
                };
                let xa = p.x[i][a];
                // Image k (k = 1, 2, ...) lies within the cutoff beyond the upper face
                // (shifted up) or the lower face (shifted down). Along a box shorter than
                // the cutoff there are several layers.
                for dir in [1.0, -1.0] {
                    let mut k = 1.0;
                    while if dir > 0.0 {
                        xa < domain.boxlo[a] + cutoff - (k - 1.0) * prd[a]
                    } else {
                        xa >= domain.boxhi[a] - cutoff + (k - 1.0) * prd[a]
                    } {
                        let mut shift = dir * k * l;
                        let mut ny = base_ny;
                        if let Some(s) = sheared {
                            ny = (dir * k) as i32;
                            shift.x = ny as f64 * s.offset;
                        }
                        let g = p.push_ghost(i, shift);
                        if let Some(s) = sheared {
                            p.v[g].x += ny as f64 * s.jump(prd.y);
                        }
                        self.shift.push(base + shift);
                        if shear.is_some() {
                            self.ny.push(ny);
                        }
                        k += 1.0;
                    }
                }
            }
        }
    }

    fn forward(&mut self, p: &mut Particles, domain: &Domain) {
        let nlocal = p.nlocal();
        for (k, &s) in self.shift.iter().enumerate() {
            let g = nlocal + k;
            p.copy_forward(g, p.origin(g), s);
        }
        if let Some(s) = &domain.shear {
            let prd = domain.prd();
            let (slide, jump) = (s.current(prd.x) - s.built, s.jump(prd.y));
            for (k, &ny) in self.ny.iter().enumerate() {
                let g = nlocal + k;
                crate::shear::shift_ghosts(p, g..g + 1, ny, slide, jump);
            }
        }
    }

    fn reverse(&mut self, p: &mut Particles) {
        let nlocal = p.nlocal();
        for g in nlocal..p.len() {
            let o = p.origin(g);
            let (f, t) = (p.f[g], p.torque[g]);
            p.f[o] += f;
            p.torque[o] += t;
        }
    }

    fn reverse_virial(&mut self, p: &Particles, virial: &mut [[f64; 6]]) {
        let nlocal = p.nlocal();
        for g in nlocal..p.len() {
            let o = p.origin(g);
            let w = virial[g];
            for (a, b) in virial[o].iter_mut().zip(&w) {
                *a += b;
            }
        }
    }

    fn reverse_scalar(&self, p: &Particles, c: &mut [f64]) {
        for g in p.nlocal()..p.len() {
            c[p.origin(g)] += c[g];
        }
    }

    fn sum(&self, x: f64) -> f64 {
        x
    }
    fn sum_count(&self, x: u64) -> u64 {
        x
    }
    fn min(&self, x: f64) -> f64 {
        x
    }
    fn max(&self, x: f64) -> f64 {
        x
    }
    fn max_count(&self, x: u64) -> u64 {
        x
    }
    fn exclusive_prefix_count(&self, _x: u64) -> u64 {
        0
    }
    fn sum_slice(&self, _x: &mut [f64]) {}
    fn all_to_all(&self, out: Vec<Vec<f64>>) -> Vec<f64> {
        out.into_iter().next().unwrap_or_default()
    }
    fn gather(&self, data: &[f64]) -> Option<Vec<f64>> {
        Some(data.to_vec())
    }
    fn all_gather(&self, data: &[f64]) -> Vec<f64> {
        data.to_vec()
    }
}
