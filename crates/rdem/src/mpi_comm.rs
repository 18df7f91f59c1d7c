//! [`Comm`] over MPI (feature `mpi`, the `mpi` crate over the system's OpenMPI): a brick
//! decomposition of the box into a Px×Py×Pz grid, one brick per rank.
//!
//! - **Ownership** is seed 000's half-open rule ([`Domain::is_in_subdomain`]).
//! - **Migration** ([`Comm::exchange`]) sends every particle that left its brick straight
//!   to the rank whose brick holds it (one all-to-all, so a particle may move any distance:
//!   created on one rank, read from a data file, or wrapped through a periodic face), with
//!   every per-particle array, its named properties and the data of [`Carried`] (contact
//!   history), all keyed by tag.
//! - **Ghosts** ([`Comm::borders`]) are made as in LAMMPS: axis by axis, each brick sends
//!   the particles (locals and the ghosts received along earlier axes, so edges and
//!   corners are covered) within the cutoff of its lower face to its lower neighbour and
//!   those near its upper face to its upper neighbour, shifted by the box length across a
//!   periodic face. With one brick along a periodic axis the "neighbour" is the brick
//!   itself and the images are made locally. The cutoff must not exceed a brick's extent.
//! - **Forward** communication repeats the ghost swaps in order with positions and
//!   velocities; **reverse** runs them backwards, adding ghost forces onto the particles
//!   they were copied from, so sums arrive at the owner in a fixed order.

use glam::DVec3;
use mpi::collective::SystemOperation;
use mpi::datatype::{Partition, PartitionMut};
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

use crate::comm::{Carried, Comm};
use crate::domain::{least_surface_grid, Domain};
use crate::error::{Error, Result};
use crate::particles::{Particles, Tag};

/// One ghost swap: particles `send` go to rank `send_to` (or are copied here when
/// `here`), and `nrecv` ghosts arrive from rank `recv_from` as indices `first..`.
#[derive(Debug, Clone, Default)]
struct Swap {
    send_to: Option<usize>,
    recv_from: Option<usize>,
    here: bool,
    send: Vec<usize>,
    shift: DVec3,
    first: usize,
    nrecv: usize,
    /// Under Lees–Edwards shear, how many box lengths up along y the received ghosts lie
    /// from the particles they copy (0 otherwise): they are shifted along x on arrival
    /// ([`crate::shear::shift_ghosts`]).
    ny: i32,
}

/// The MPI communicator of a run.
pub struct MpiComm {
    comm: SimpleCommunicator,
    rank: usize,
    size: usize,
    swaps: Vec<Swap>,
    buf: Vec<f64>,
    rbuf: Vec<f64>,
}

// SAFETY: the communicator is an MPI handle that rdem only uses from the thread that
// owns the `World` (rayon workers never touch it); OpenMPI is initialized with the
// default thread level and calls are never made concurrently.
unsafe impl Send for MpiComm {}

impl std::fmt::Debug for MpiComm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MpiComm {{ rank: {}, size: {} }}", self.rank, self.size)
    }
}

impl MpiComm {
    /// A communicator over all ranks of `comm` (usually `universe.world()`).
    pub fn new(comm: SimpleCommunicator) -> Self {
        let rank = comm.rank() as usize;
        let size = comm.size() as usize;
        Self {
            comm,
            rank,
            size,
            swaps: Vec::new(),
            buf: Vec::new(),
            rbuf: Vec::new(),
        }
    }

    /// Sends `data` to `to` and receives `n` values (or, with `n == None`, a message of
    /// any length, preceded by its length) from `from` into `self.rbuf`. Either side may
    /// be absent (a non-periodic edge of the grid).
    fn send_recv(
        &mut self,
        to: Option<usize>,
        data: &[f64],
        from: Option<usize>,
        n: Option<usize>,
    ) {
        let n = match n {
            Some(n) => n,
            None => {
                let len = [data.len() as u64];
                let mut got = [0u64];
                self.raw(to, &len, from, &mut got);
                got[0] as usize
            }
        };
        let mut rbuf = std::mem::take(&mut self.rbuf);
        rbuf.clear();
        rbuf.resize(if from.is_some() { n } else { 0 }, 0.0);
        self.raw(to, data, from, &mut rbuf);
        self.rbuf = rbuf;
    }

    fn raw<T: Equivalence>(
        &self,
        to: Option<usize>,
        data: &[T],
        from: Option<usize>,
        into: &mut [T],
    ) {
        match (to, from) {
            (Some(t), Some(f)) => {
                let (pt, pf) = (
                    self.comm.process_at_rank(t as i32),
                    self.comm.process_at_rank(f as i32),
                );
                mpi::point_to_point::send_receive_into(data, &pt, into, &pf);
            }
            (Some(t), None) => self.comm.process_at_rank(t as i32).send(data),
            (None, Some(f)) => {
                self.comm.process_at_rank(f as i32).receive_into(into);
            }
            (None, None) => {}
        }
    }

    /// Counts of `len` from every rank, on every rank.
    fn all_counts(&self, len: usize) -> Vec<i32> {
        let mut counts = vec![0i32; self.size];
        self.comm.all_gather_into(&(len as i32), &mut counts[..]);
        counts
    }

    /// Reverse communication of `width` values per particle of `data`, read by `get` and
    /// added by `add` (forces and torques, or virials).
    fn reverse_with<D: ?Sized>(
        &mut self,
        data: &mut D,
        width: usize,
        get: impl Fn(&D, usize, &mut Vec<f64>),
        add: impl Fn(&mut D, usize, &[f64]),
    ) {
        let swaps = std::mem::take(&mut self.swaps);
        let mut tmp = Vec::with_capacity(width);
        for s in swaps.iter().rev() {
            if s.here {
                // The ghosts were made here: add each back onto its source.
                for (k, &i) in s.send.iter().enumerate() {
                    tmp.clear();
                    get(data, s.first + k, &mut tmp);
                    add(data, i, &tmp);
                }
                continue;
            }
            let mut buf = std::mem::take(&mut self.buf);
            buf.clear();
            if s.recv_from.is_some() {
                for g in s.first..s.first + s.nrecv {
                    get(data, g, &mut buf);
                }
            }
            let n = if s.send_to.is_some() {
                s.send.len() * width
            } else {
                0
            };
            // Backwards: ghost values go to the rank they came from.
            self.send_recv(s.recv_from, &buf, s.send_to, Some(n));
            self.buf = buf;
            if s.send_to.is_some() {
                for (k, &i) in s.send.iter().enumerate() {
                    add(data, i, &self.rbuf[k * width..(k + 1) * width]);
                }
            }
        }
        self.swaps = swaps;
    }

    fn reduce(&self, x: f64, op: SystemOperation) -> f64 {
        let mut y = 0.0;
        self.comm.all_reduce_into(&x, &mut y, op);
        y
    }
}

impl Comm for MpiComm {
    fn rank(&self) -> usize {
        self.rank
    }
    fn size(&self) -> usize {
        self.size
    }

    fn decompose(&mut self, domain: &mut Domain, fixed: [usize; 3]) -> Result<()> {
        let grid =
            least_surface_grid(self.size, domain.prd(), fixed).ok_or_else(|| Error::Invalid {
                what: "processors",
                reason: format!(
                    "no {} x {} x {} grid has {} ranks (the number mpirun started)",
                    show(fixed[0]),
                    show(fixed[1]),
                    show(fixed[2]),
                    self.size
                ),
            })?;
        domain.set_grid(grid, self.rank);
        Ok(())
    }

    fn exchange(&mut self, p: &mut Particles, domain: &Domain, carried: &mut dyn Carried) {
        if self.size == 1 {
            return;
        }
        let nlocal = p.nlocal();
        let mut out = vec![Vec::new(); self.size];
        let mut leave = vec![false; nlocal];
        for (i, gone) in leave.iter_mut().enumerate() {
            let x = p.x[i];
            if domain.is_in_subdomain(x) {
                continue;
            }
            let dest = domain.rank_of(domain.owner_loc(x));
            if dest == self.rank {
                continue;
            }
            p.pack(i, DVec3::ZERO, &mut out[dest]);
            carried.pack(p.tag[i], &mut out[dest]);
            *gone = true;
        }
        if leave.iter().any(|&l| l) {
            p.remove_locals(&leave);
        } else {
            p.clear_ghosts();
        }
        let got = self.all_to_all(out);
        let mut k = 0;
        while k < got.len() {
            let tag = got[k] as Tag;
            k += p.unpack(&got[k..], None);
            k += carried.unpack(tag, &got[k..]);
        }
    }

    fn borders(&mut self, p: &mut Particles, domain: &Domain, cutoff: f64) {
        p.clear_ghosts();
        self.swaps.clear();
        let prd = domain.prd();
        let shear = domain.shear;
        // Under shear one brick along x (see `World::check_settings`).
        let (offset, jump) = shear.map_or((0.0, 0.0), |s| (s.offset, s.jump(prd.y)));
        for a in domain.ghost_axes() {
            let np = domain.procgrid[a];
            let m = domain.myloc[a];
            let periodic = domain.periodic(a);
            if np == 1 && !periodic {
                continue;
            }
            let neighbour = |up: bool| -> Option<usize> {
                let mut loc = domain.myloc;
                if up {
                    if m + 1 == np && !periodic {
                        return None;
                    }
                    loc[a] = (m + 1) % np;
                } else {
                    if m == 0 && !periodic {
                        return None;
                    }
                    loc[a] = (m + np - 1) % np;
                }
                Some(domain.rank_of(loc))
            };
            // Particles present before this axis's swaps (locals and earlier ghosts).
            let n = p.len();
            for up in [false, true] {
                // Sent up (down) across the upper (lower) face; a wrap shifts by ∓L.
                let send_to = neighbour(up);
                let recv_from = neighbour(!up);
                let mut shift = DVec3::ZERO;
                if up && m + 1 == np {
                    shift[a] = -prd[a];
                } else if !up && m == 0 {
                    shift[a] = prd[a];
                }
                if np == 1 {
                    // Images of this rank's own particles: one swap per layer of images
                    // (several along a periodic axis shorter than the cutoff).
                    let mut k = 1.0;
                    loop {
                        let reach = cutoff - (k - 1.0) * prd[a];
                        let send: Vec<usize> = (0..n)
                            .filter(|&i| {
                                if up {
                                    p.x[i][a] >= domain.subhi[a] - reach
                                } else {
                                    p.x[i][a] < domain.sublo[a] + reach
                                }
                            })
                            .collect();
                        if k > 1.0 && send.is_empty() {
                            break;
                        }
                        let first = p.len();
                        for &i in &send {
                            p.push_ghost(i, k * shift);
                        }
                        let nrecv = send.len();
                        let ny = if shear.is_some() && a == 1 {
                            (k * shift[1] / prd[1]).round() as i32
                        } else {
                            0
                        };
                        crate::shear::shift_ghosts(p, first..first + nrecv, ny, offset, jump);
                        self.swaps.push(Swap {
                            send_to,
                            recv_from,
                            here: true,
                            send,
                            shift: k * shift,
                            first,
                            nrecv,
                            ny,
                        });
                        k += 1.0;
                    }
                    continue;
                }
                let send: Vec<usize> = if send_to.is_some() {
                    (0..n)
                        .filter(|&i| {
                            if up {
                                p.x[i][a] >= domain.subhi[a] - cutoff
                            } else {
                                p.x[i][a] < domain.sublo[a] + cutoff
                            }
                        })
                        .collect()
                } else {
                    Vec::new()
                };
                let first = p.len();
                let mut buf = std::mem::take(&mut self.buf);
                buf.clear();
                for &i in &send {
                    p.pack(i, shift, &mut buf);
                    let owner = p.remote_owner(i).unwrap_or(self.rank);
                    buf.push(owner as f64);
                }
                self.send_recv(send_to, &buf, recv_from, None);
                self.buf = buf;
                let rbuf = std::mem::take(&mut self.rbuf);
                let mut k = 0;
                let mut nrecv = 0;
                while k < rbuf.len() {
                    let len = p.packed_len();
                    let owner = rbuf[k + len] as usize;
                    k += p.unpack(&rbuf[k..k + len], Some(owner)) + 1;
                    nrecv += 1;
                }
                self.rbuf = rbuf;
                // What arrived crossed the periodic y face when it came from the brick at
                // the other end: from below into the lowest brick (shifted down), from
                // above into the highest (shifted up).
                let ny = match (shear.is_some() && a == 1 && periodic, up) {
                    (true, true) if m == 0 => -1,
                    (true, false) if m + 1 == np => 1,
                    _ => 0,
                };
                crate::shear::shift_ghosts(p, first..first + nrecv, ny, offset, jump);
                self.swaps.push(Swap {
                    send_to,
                    recv_from,
                    here: false,
                    send,
                    shift,
                    first,
                    nrecv,
                    ny,
                });
            }
        }
    }

    fn forward(&mut self, p: &mut Particles, domain: &Domain) {
        let swaps = std::mem::take(&mut self.swaps);
        let len = p.forward_len();
        let prd = domain.prd();
        let (offset, jump) = domain
            .shear
            .map_or((0.0, 0.0), |s| (s.current(prd.x), s.jump(prd.y)));
        for s in &swaps {
            if s.here {
                for (k, &i) in s.send.iter().enumerate() {
                    p.copy_forward(s.first + k, i, s.shift);
                }
                crate::shear::shift_ghosts(p, s.first..s.first + s.nrecv, s.ny, offset, jump);
                continue;
            }
            let mut buf = std::mem::take(&mut self.buf);
            buf.clear();
            if s.send_to.is_some() {
                for &i in &s.send {
                    p.pack_forward(i, s.shift, &mut buf);
                }
            }
            let n = if s.recv_from.is_some() {
                s.nrecv * len
            } else {
                0
            };
            self.send_recv(s.send_to, &buf, s.recv_from, Some(n));
            self.buf = buf;
            for (k, c) in self.rbuf.chunks_exact(len).enumerate() {
                p.unpack_forward(s.first + k, c);
            }
            crate::shear::shift_ghosts(p, s.first..s.first + s.nrecv, s.ny, offset, jump);
        }
        self.swaps = swaps;
    }

    fn reverse(&mut self, p: &mut Particles) {
        self.reverse_with(
            p,
            6,
            |p, g, buf| {
                let (f, t) = (p.f[g], p.torque[g]);
                buf.extend_from_slice(&[f.x, f.y, f.z, t.x, t.y, t.z]);
            },
            |p, i, v| {
                p.f[i] += DVec3::new(v[0], v[1], v[2]);
                p.torque[i] += DVec3::new(v[3], v[4], v[5]);
            },
        );
    }

    fn reverse_virial(&mut self, _p: &Particles, virial: &mut [[f64; 6]]) {
        self.reverse_with(
            virial,
            6,
            |v, g, buf| buf.extend_from_slice(&v[g]),
            |v, i, w| {
                for (a, b) in v[i].iter_mut().zip(w) {
                    *a += b;
                }
            },
        );
    }

    fn reverse_scalar(&self, p: &Particles, c: &mut [f64]) {
        // Only when every rank still has the ghosts of the last swaps (particles added
        // since drop them until the next re-neighboring).
        let end = self.swaps.iter().map(|s| s.first + s.nrecv).max();
        let current = end.is_none_or(|e| e == p.len()) && c.len() == p.len();
        if self.any(!current) {
            return;
        }
        for s in self.swaps.iter().rev() {
            if s.here {
                for (k, &i) in s.send.iter().enumerate() {
                    c[i] += c[s.first + k];
                }
                continue;
            }
            let out: Vec<f64> = if s.recv_from.is_some() {
                c[s.first..s.first + s.nrecv].to_vec()
            } else {
                Vec::new()
            };
            let mut got = vec![0.0; if s.send_to.is_some() { s.send.len() } else { 0 }];
            self.raw(s.recv_from, &out, s.send_to, &mut got);
            for (&i, v) in s.send.iter().zip(&got) {
                c[i] += v;
            }
        }
    }

    fn sum(&self, x: f64) -> f64 {
        self.reduce(x, SystemOperation::sum())
    }
    fn sum_count(&self, x: u64) -> u64 {
        let mut y = 0u64;
        self.comm
            .all_reduce_into(&x, &mut y, SystemOperation::sum());
        y
    }
    fn min(&self, x: f64) -> f64 {
        self.reduce(x, SystemOperation::min())
    }
    fn max(&self, x: f64) -> f64 {
        self.reduce(x, SystemOperation::max())
    }
    fn max_count(&self, x: u64) -> u64 {
        let mut y = 0u64;
        self.comm
            .all_reduce_into(&x, &mut y, SystemOperation::max());
        y
    }
    fn exclusive_prefix_count(&self, x: u64) -> u64 {
        let mut y = 0u64;
        self.comm
            .exclusive_scan_into(&x, &mut y, SystemOperation::sum());
        if self.rank == 0 {
            0
        } else {
            y
        }
    }
    fn sum_slice(&self, x: &mut [f64]) {
        if self.size == 1 || x.is_empty() {
            return;
        }
        let src = x.to_vec();
        self.comm
            .all_reduce_into(&src[..], x, SystemOperation::sum());
    }

    fn all_to_all(&self, out: Vec<Vec<f64>>) -> Vec<f64> {
        let send_counts: Vec<i32> = out.iter().map(|v| v.len() as i32).collect();
        let mut recv_counts = vec![0i32; self.size];
        self.comm
            .all_to_all_into(&send_counts[..], &mut recv_counts[..]);
        let (sdispls, _) = offsets(&send_counts);
        let (rdispls, total) = offsets(&recv_counts);
        let flat: Vec<f64> = out.concat();
        let mut got = vec![0.0; total];
        {
            let sp = Partition::new(&flat[..], &send_counts[..], &sdispls[..]);
            let mut rp = PartitionMut::new(&mut got[..], &recv_counts[..], &rdispls[..]);
            self.comm.all_to_all_varcount_into(&sp, &mut rp);
        }
        got
    }

    fn gather(&self, data: &[f64]) -> Option<Vec<f64>> {
        let root = self.comm.process_at_rank(0);
        let n = data.len() as i32;
        if self.rank == 0 {
            let mut counts = vec![0i32; self.size];
            root.gather_into_root(&n, &mut counts[..]);
            let (displs, total) = offsets(&counts);
            let mut all = vec![0.0; total];
            {
                let mut rp = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
                root.gather_varcount_into_root(data, &mut rp);
            }
            Some(all)
        } else {
            root.gather_into(&n);
            root.gather_varcount_into(data);
            None
        }
    }

    fn all_gather(&self, data: &[f64]) -> Vec<f64> {
        let counts = self.all_counts(data.len());
        let (displs, total) = offsets(&counts);
        let mut all = vec![0.0; total];
        {
            let mut rp = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
            self.comm.all_gather_varcount_into(data, &mut rp);
        }
        all
    }
}

/// Start offsets of consecutive blocks of `counts` values, and their total.
fn offsets(counts: &[i32]) -> (Vec<i32>, usize) {
    let mut at = 0;
    let displs = counts
        .iter()
        .map(|&c| {
            let d = at;
            at += c;
            d
        })
        .collect();
    (displs, at as usize)
}

fn show(n: usize) -> String {
    if n == 0 {
        "*".into()
    } else {
        n.to_string()
    }
}
