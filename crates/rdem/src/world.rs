//! The simulation state: particles, box, materials, pair style, neighbor list, fixes and
//! the communicator, and what the front end does to it between steps (adding and removing
//! particles and fixes, new radii). [`crate::step`] holds the order of a timestep, of the
//! set-up before a run and of the full re-neighboring.

use glam::DVec3;

use crate::comm::Comm;
use crate::contact::Materials;
use crate::domain::Domain;
use crate::error::{Error, Result};
use crate::fix::Fix;
use crate::neighbor::{Neighbor, NeighborSettings};
use crate::pair::PairGran;
use crate::particles::{NewParticle, Particles, Tag};
use crate::timers::Timers;

/// What to do when particles leave a fixed boundary (`thermo_modify lost`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LostPolicy {
    /// Stop the run, with a report of the first lost particle.
    Error,
    /// Drop them and go on; the first loss (only the first, as in LIGGGHTS) gives a
    /// warning with the report. The default: LIGGGHTS' default is `ignore` (its manual,
    /// and measured on 3.8: a sphere shot through a fixed face is dropped and the run
    /// goes on), so the run goes on as there, and the warning says what LIGGGHTS does not.
    #[default]
    Warn,
    /// Drop them silently.
    Ignore,
}

/// `atom_modify sort Nfreq binsize`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SortSettings {
    /// Sort every this many steps (0 = never). LIGGGHTS default 1000.
    pub every: u64,
    /// Bin size; 0 means half the neighbor cutoff.
    pub binsize: f64,
}

impl Default for SortSettings {
    fn default() -> Self {
        Self {
            every: 1000,
            binsize: 0.0,
        }
    }
}

/// Per-particle flag of [`World::remove_at_reneighbor`].
const REMOVAL_PROP: &str = "remove_at_reneighbor";

/// The timestep before any `timestep` command: LIGGGHTS' default for `units si` and
/// `cgs` (the one place it is written; `units micro` sets its own).
pub const DEFAULT_TIMESTEP: f64 = 1e-8;

/// The whole simulation state.
#[derive(Debug)]
pub struct World {
    /// Particles (owned, then ghosts).
    pub particles: Particles,
    /// Box and subdomain.
    pub domain: Domain,
    /// Material properties.
    pub materials: Materials,
    /// Particle–particle contact (`pair_style gran`), if any.
    pub pair: Option<PairGran>,
    /// The SPH pair style (`pair_style sph/artVisc/tensCorr`), if any ([`crate::sph`]).
    pub sph: Option<crate::sph::SphPair>,
    /// Neighbor list and its settings.
    pub neighbor: Neighbor,
    /// Fixes, in definition order.
    pub fixes: Vec<Fix>,
    /// Triangle meshes (`fix mesh/surface`), which mesh walls, mesh motions, insertion
    /// faces and mesh dumps refer to by index.
    pub meshes: Vec<crate::wall::MeshSurface>,
    /// Timestep size.
    pub dt: f64,
    /// Current timestep number.
    pub step: u64,
    /// Communicator.
    pub comm: Box<dyn Comm>,
    /// Lost-particle policy.
    pub lost_policy: LostPolicy,
    /// Spatial sort settings.
    pub sort: SortSettings,
    /// Time per stage.
    pub timers: Timers,
    /// Particles lost so far (all ranks).
    pub lost: u64,
    /// True once a lost-particle warning was given ([`LostPolicy::Warn`] warns once).
    pub lost_warned: bool,
    /// Warnings raised during runs (lost particles under `warn`, ...), oldest first.
    pub warnings: Vec<String>,
    /// Set by the caller before a step (or a set-up) whose pair contact virial it needs:
    /// the force pass then also fills [`World::virial`]. Off, the force pass is the plain
    /// one and costs nothing more.
    pub want_virial: bool,
    /// Per-particle contact virial of the owned particles, xx yy zz xy xz yz: ½ r_ij ⊗ F_ij
    /// summed over the particle's pair contacts (r_ij = x_i − x_j, F_ij the force on i),
    /// ghost contributions added to their owners. Wall contacts do not contribute: LIGGGHTS
    /// 3.8's `compute stress/atom` reports none for a particle pressed on a `wall/gran`
    /// primitive. Valid when [`World::virial_step`] is the current step.
    pub virial: Vec<[f64; 6]>,
    /// Step at which [`World::virial`] was computed (`None`: never, or stale since
    /// particles were added).
    pub virial_step: Option<u64>,
    /// Heat conduction through contacts (`fix heat/gran/conduction`), if any.
    pub heat: Option<crate::heat::HeatConduction>,
    /// Heat radiation between particles (`fix heat/gran/radiation`), if any; the
    /// temperatures it changes are held and integrated by [`World::heat`], which exists
    /// whenever it does.
    pub radiation: Option<crate::heat_radiation::HeatRadiation>,
    /// Rigid clumps (`fix multisphere`), if any.
    pub multisphere: Option<crate::multisphere::Multisphere>,
    /// `fix multicontact/halfspace`, if any: the store that the pair style and the walls
    /// with `surface multicontact` share ([`crate::multicontact`]).
    pub multicontact: Option<std::sync::Arc<crate::multicontact::MultiContact>>,
    /// Bonds between spheres (`bond_style gran`), if the atom style has them.
    pub bonds: Option<crate::bond_gran::GranBonds>,
    pub(crate) next_sort: u64,
    /// Contact histories read from a restart file, for the next set-up.
    pub(crate) restored_history: Option<crate::restart::HistoryState>,
    pub(crate) needs_reneighbor: bool,
    /// `modify_timing on`: each fix's time is counted ([`crate::Fix::seconds`]), the
    /// post-force fixes then acting one at a time (the same forces, a little slower).
    pub fix_timing: bool,
    /// Particles were removed: the next step re-neighbors (no set-up needed).
    pub(crate) rebuild_next: bool,
}

impl World {
    /// An empty world in `domain`, serial.
    pub fn new(domain: Domain) -> Self {
        Self {
            particles: Particles::new(),
            domain,
            materials: Materials::default(),
            pair: None,
            sph: None,
            neighbor: Neighbor::new(NeighborSettings::default()),
            fixes: Vec::new(),
            meshes: Vec::new(),
            dt: DEFAULT_TIMESTEP,
            step: 0,
            comm: crate::comm::default_comm(),
            lost_policy: LostPolicy::default(),
            sort: SortSettings::default(),
            timers: Timers::default(),
            lost: 0,
            lost_warned: false,
            warnings: Vec::new(),
            want_virial: false,
            virial: Vec::new(),
            virial_step: None,
            heat: None,
            radiation: None,
            multisphere: None,
            multicontact: None,
            bonds: None,
            next_sort: 0,
            restored_history: None,
            needs_reneighbor: true,
            fix_timing: false,
            rebuild_next: false,
        }
    }

    /// Adds a mesh, or replaces the mesh of the same ID; returns its index.
    pub fn add_mesh(&mut self, mesh: crate::wall::MeshSurface) -> usize {
        if let Some(k) = self.mesh_index(&mesh.id) {
            self.meshes[k] = mesh;
            k
        } else {
            self.meshes.push(mesh);
            self.meshes.len() - 1
        }
    }

    /// The index of mesh `id` in [`World::meshes`].
    pub fn mesh_index(&self, id: &str) -> Option<usize> {
        self.meshes.iter().position(|m| m.id == id)
    }

    /// Sets the timestep (must be finite and > 0).
    pub fn set_timestep(&mut self, dt: f64) -> Result<()> {
        crate::error::check("timestep", dt, dt > 0.0, "must be > 0")?;
        self.dt = dt;
        Ok(())
    }

    /// Adds an owned particle after checking it lies inside the fixed faces of the box.
    /// Untagged particles get tags at the next set-up or re-neighboring.
    pub fn add_particle(&mut self, np: &NewParticle) -> Result<usize> {
        self.domain.check_inside_fixed(np.x)?;
        if self.particles.nghost() > 0 {
            self.neighbor.save_history(&self.particles);
            self.particles.clear_ghosts();
        }
        let i = self.particles.add_local(np)?;
        self.needs_reneighbor = true;
        self.virial_step = None;
        Ok(i)
    }

    /// Removes the owned particles whose `remove` entry is true (their contact history
    /// goes with them; a clump goes whole with any of its spheres); the next step re-neighbors (without a new set-up: the others
    /// carry on as if nothing happened).
    pub fn remove_particles(&mut self, remove: &[bool]) -> usize {
        // The contact histories go by tag before the indices shift (with or without
        // ghosts: a list without ghosts holds histories by index too).
        self.neighbor.save_history(&self.particles);
        self.particles.clear_ghosts();
        let mut remove = remove.to_vec();
        self.remove_whole_bodies(&mut remove);
        let n = self.particles.remove_locals(&remove);
        self.rebuild_next = true;
        self.virial_step = None;
        n
    }

    /// Renumbers the particles 1..N keeping the order of their tags (LIGGGHTS'
    /// `compress yes` after removing particles; call with the contact history saved, as
    /// [`World::remove_particles`] leaves it): the saved history follows the new tags.
    /// Returns whether any tag changed (on any rank). The bond and clump stores are not
    /// renamed.
    pub fn renumber_tags(&mut self) -> bool {
        let p = &mut self.particles;
        let nlocal = p.nlocal();
        let mine: Vec<f64> = p.tag[..nlocal].iter().map(|&t| t as f64).collect();
        let mut all: Vec<Tag> = self
            .comm
            .all_gather(&mine)
            .iter()
            .map(|&t| t as Tag)
            .collect();
        all.sort_unstable();
        let new = |t: Tag| match all.binary_search(&t) {
            Ok(k) => k as Tag + 1,
            Err(_) => 0,
        };
        let mut changed = false;
        for t in &mut p.tag[..nlocal] {
            let n = new(*t);
            changed |= n != *t;
            *t = n;
        }
        let changed = self.comm.any(changed);
        if changed {
            self.neighbor.renumber_saved(&new);
        }
        changed
    }

    /// Marks owned particle `i` for removal at the next re-neighboring (as LIGGGHTS
    /// deletes particles in its pre-exchange stage): it keeps acting until then, and no
    /// re-neighboring is forced.
    pub fn remove_at_reneighbor(&mut self, i: usize) -> Result<()> {
        let id = match self.particles.property(REMOVAL_PROP) {
            Some(id) => id,
            None => self.particles.add_property(REMOVAL_PROP, 1, &[0.0])?,
        };
        self.particles.props[id.0].data[i] = 1.0;
        Ok(())
    }

    /// Removes the owned particles marked by [`World::remove_at_reneighbor`] (call with
    /// the ghosts cleared and the history saved).
    pub(crate) fn remove_marked(&mut self) {
        let nlocal = self.particles.nlocal();
        let flags = self
            .particles
            .property(REMOVAL_PROP)
            .map(|id| &self.particles.props[id.0].data[..nlocal]);
        let any = flags.is_some_and(|f| f.iter().any(|&v| v != 0.0));
        // Clumps on several ranks: every rank takes part in dropping whole bodies.
        let collective = self.multisphere.is_some() && self.comm.size() > 1;
        if !any && !collective {
            return;
        }
        let mut marked: Vec<bool> = match flags {
            Some(f) => f.iter().map(|&v| v != 0.0).collect(),
            None => vec![false; nlocal],
        };
        self.remove_whole_bodies(&mut marked);
        if marked.iter().any(|&m| m) {
            self.particles.remove_locals(&marked);
            self.virial_step = None;
        }
    }

    /// Adds a fix (its ID must be new).
    pub fn add_fix(&mut self, fix: Fix) -> Result<()> {
        if self.fixes.iter().any(|f| f.id == fix.id) {
            return Err(Error::Invalid {
                what: "fix ID",
                reason: format!("'{}' is already used", fix.id),
            });
        }
        self.fixes.push(fix);
        Ok(())
    }

    /// The engine fix `id`, to change its parameters.
    pub fn fix_mut(&mut self, id: &str) -> Option<&mut Fix> {
        self.fixes.iter_mut().find(|f| f.id == id)
    }

    /// Removes the fix `id`; returns false if there was none.
    pub fn remove_fix(&mut self, id: &str) -> bool {
        let Some(k) = self.fixes.iter().position(|f| f.id == id) else {
            return false;
        };
        self.fixes.remove(k);
        if let Some(pid) = self.particles.property(crate::wall::TOUCH_PROPERTY) {
            crate::wall::touch::forget_fix(&mut self.particles.props[pid.0].data, k);
        }
        true
    }

    /// Gives untagged owned particles new tags: max+1, max+2, ... over all ranks, each rank
    /// starting after the untagged particles of the ranks below it (seed 002 eq. 2).
    pub fn extend_tags(&mut self) {
        let (_, max) = self.particles.tag_extent();
        let gmax = self.comm.max_count(max);
        let mine = self.particles.untagged() as u64;
        let before = self.comm.exclusive_prefix_count(mine);
        self.particles.assign_tags_from(gmax + 1 + before);
    }

    /// Sets the radius of every owned particle to `radius[i]` keeping its density (the
    /// mass follows), as `fix adapt ... atom diameter` does. The largest growth counts
    /// against the neighbor skin until the next build, so no contact is missed.
    pub fn set_radii(&mut self, radius: &[f64]) -> Result<()> {
        let nlocal = self.particles.nlocal();
        let mut grow: f64 = 0.0;
        for (i, &r) in radius.iter().enumerate().take(nlocal) {
            grow = grow.max(r - self.particles.radius[i]);
            self.particles.set_radius(i, r)?;
        }
        let grow = self.comm.max(grow);
        self.neighbor.growth += grow.max(0.0);
        Ok(())
    }

    /// The contact virial of the owned particles if it is current (computed at this step
    /// for these particles; see [`World::want_virial`]).
    pub fn current_virial(&self) -> Option<&[[f64; 6]]> {
        (self.virial_step == Some(self.step) && self.virial.len() == self.particles.nlocal())
            .then_some(&self.virial[..])
    }

    /// Chooses the processor grid (`processors`; 0 = free) and this rank's subdomain.
    /// Call once the box exists and before particles are created.
    pub fn decompose(&mut self, fixed: [usize; 3]) -> Result<()> {
        self.comm.decompose(&mut self.domain, fixed)
    }

    /// True when a particle created at `x` by a command that every rank runs (create_atoms,
    /// read_data) belongs to this rank: seed 000's half-open subdomain rule.
    pub fn owns_point(&self, x: DVec3) -> bool {
        self.comm.size() == 1 || self.domain.is_in_subdomain(x)
    }

    /// True when a particle that insertion places at `x` belongs to this rank: seed 000's
    /// extended subdomain rule (edge ranks also take what lies beyond their outer faces).
    pub fn owns_inserted(&self, x: DVec3) -> bool {
        self.comm.size() == 1 || self.domain.is_in_extended_subdomain(x)
    }

    /// Total number of owned particles over all ranks.
    pub fn natoms(&self) -> u64 {
        self.comm.sum_count(self.particles.nlocal() as u64)
    }

    /// This rank's bond tallies (`cohesion bond`): pair bonds created and broken so far,
    /// intact pair bonds now (each pair once: the rank and row that list it), then the
    /// same three for wall bonds (all walls together).
    pub fn bond_tallies(&self) -> [u64; 6] {
        let mut t = [0u64; 6];
        if let Some(pair) = &self.pair {
            let (c, b) = pair.bond_events.totals();
            t[0] = c;
            t[1] = b;
            t[2] = pair.count_bonds(&self.neighbor.list);
        }
        for fix in &self.fixes {
            let Some(wall) = fix.kind.as_wall() else {
                continue;
            };
            let (events, intact) = (wall.bond_events(), wall.count_bonds(&self.particles));
            let (c, b) = events.totals();
            t[3] += c;
            t[4] += b;
            t[5] += intact;
        }
        t
    }

    /// Intact bonds of each owned particle (pair bonds, counted for both particles, and
    /// wall bonds), as f64 for the per-atom computes.
    pub fn bonds_per_particle(&self) -> Vec<f64> {
        let p = &self.particles;
        let nlocal = p.nlocal();
        let mut c = vec![0.0; p.len()];
        let list = &self.neighbor.list;
        let layout = self.pair.as_ref().and_then(|pair| pair.model.bond_layout());
        // A list older than the particles (after an insertion) counts nothing.
        if let Some(layout) = layout.filter(|_| list.width > 0 && list.first.len() == nlocal + 1) {
            let flag = list.width - layout.pair_tail;
            for i in 0..nlocal {
                for k in list.first[i] as usize..list.first[i + 1] as usize {
                    let j = list.partner[k] as usize;
                    let h = &list.hist[k * list.width..(k + 1) * list.width];
                    if j < p.len() && crate::bond::is_bonded(&h[flag..]) {
                        c[i] += 1.0;
                        c[j] += 1.0;
                    }
                }
            }
        }
        self.comm.reverse_scalar(p, &mut c);
        c.truncate(nlocal);
        for fix in &self.fixes {
            let Some(wall) = fix.kind.as_wall() else {
                continue;
            };
            let (id, flag) = (wall.history_prop(), wall.bond_flag_at());
            for (ci, b) in c.iter_mut().zip(crate::wall::bonded(p, id, flag)) {
                if b {
                    *ci += 1.0;
                }
            }
        }
        c
    }

    /// Seed 002 eq. (13) for this process: bytes held by particles and the neighbor list.
    pub fn memory_bytes(&self) -> usize {
        let l = &self.neighbor.list;
        self.particles.memory_bytes()
            + l.first.capacity() * 4
            + l.partner.capacity() * 4
            + l.hist.capacity() * 8
    }
}
