//! The bodies of the stages of a timestep, the set-up and the re-neighboring, each named
//! for what it does. [`crate::step`] says when each runs (and is the only caller).

use glam::DVec3;

use crate::error::{Error, Result};
use crate::fix::{integrate, FixKind};
use crate::particles::Tag;
use crate::sort::sort_particles;
use crate::sph::SphFix;
use crate::world::{LostPolicy, World};

/// Set-up stages.
impl World {
    /// Set-up 1: the timestep and the neighbor settings are valid.
    pub(crate) fn check_settings(&self) -> Result<()> {
        crate::error::check("timestep", self.dt, self.dt > 0.0, "must be > 0")?;
        if self.domain.shear.is_some() {
            self.check_shear()?;
        }
        self.neighbor.settings.validate()
    }

    /// What Lees–Edwards shear (`fix lebc`) needs: a box periodic along every axis, one
    /// brick along x with MPI (ghosts across a y face are shifted along x, and rdem
    /// sends them to the brick above or below only), no rigid clumps.
    fn check_shear(&self) -> Result<()> {
        let invalid = |reason: &str| Error::Invalid {
            what: "fix lebc",
            reason: reason.to_string(),
        };
        if !(0..3).all(|a| self.domain.periodic(a)) {
            return Err(invalid(
                "Lees-Edwards shear needs a box periodic along x, y and z (boundary p p p)",
            ));
        }
        if self.domain.procgrid[0] > 1 {
            return Err(invalid(&format!(
                "with MPI, Lees-Edwards shear needs one brick along x (this run has a {}x{}x{} grid); \
                 write 'processors 1 * *'",
                self.domain.procgrid[0], self.domain.procgrid[1], self.domain.procgrid[2]
            )));
        }
        Ok(())
    }

    /// The pair style's coefficients mixed again from [`World::materials`] (after a fix
    /// changed a material property during a run).
    pub fn refresh_pair_table(&mut self) -> Result<()> {
        if let Some(pair) = &mut self.pair {
            pair.setup(&self.materials)?;
        }
        Ok(())
    }

    /// Set-up 1: every owned particle's type is in the material table, when a pair style
    /// or a wall uses the table.
    pub(crate) fn check_types(&self) -> Result<()> {
        let ntypes = self.materials.ntypes as u32;
        let uses_materials =
            self.pair.is_some() || self.fixes.iter().any(|f| f.kind.as_wall().is_some());
        if uses_materials {
            if let Some(&ty) = self.particles.ty[..self.particles.nlocal()]
                .iter()
                .find(|&&t| t > ntypes)
            {
                return Err(Error::TypeOutOfRange { ty, ntypes });
            }
        }
        Ok(())
    }

    /// Set-up 2: the pair style's coefficient and bond tables, the contact history layout
    /// and the neighbor reach, the bond reach check and the `tsCreateBond` warning.
    pub(crate) fn setup_pair(&mut self) -> Result<()> {
        let Some(pair) = &mut self.pair else {
            self.neighbor.set_history_layout(0, 0);
            self.neighbor.reach = 0.0;
            self.neighbor.neck = 0.0;
            self.neighbor.contact_factor = self.neighbor.settings.contact_distance_factor;
            return Ok(());
        };
        pair.setup(&self.materials)?;
        pair.freeze = self
            .fixes
            .iter()
            .filter(|f| matches!(f.kind, crate::fix::FixKind::Freeze))
            .fold(0, |bits, f| bits | f.groupbit);
        // The largest of liquid bridges' reach, the user's `contact_distance_factor` and
        // `surface multicontact`'s 2: LIGGGHTS 3.8 lists multicontact pairs up to
        // 2 (r_i + r_j) + skin, since the corrections can close a gap (measured: the
        // hydrogel tutorial's 9680 pairs; docs/parity.md).
        let mut factor = self.neighbor.settings.contact_distance_factor;
        if pair.model.surface == crate::SurfaceKind::Multicontact {
            factor = factor.max(2.0);
        }
        self.neighbor.contact_factor = pair
            .setup_liquid(&mut self.particles, &self.materials)?
            .max(factor);
        let (w, odd) = (pair.model.history_width(), pair.model.history_odd());
        self.neighbor.set_history_layout(w, odd);
        self.neighbor.reach = pair.reach();
        self.neighbor.neck = pair.table().neck_reach(1.0);
        if pair.reach() > 0.0 {
            // As LIGGGHTS-INL: a bond longer than 10 diameters of the smallest particle
            // would make the neighbor lists explode.
            let n = self.particles.nlocal();
            let rmin = self.comm.min(
                self.particles.radius[..n]
                    .iter()
                    .copied()
                    .fold(f64::INFINITY, f64::min),
            );
            if rmin.is_finite() && pair.reach() > 20.0 * rmin {
                return Err(Error::Invalid {
                    what: "cohesion bond",
                    reason: format!(
                        "the longest bond ({:.4e}, from maxDistanceBond, or createDistanceBond and maxSigmaBond/normalBondStiffnessPerUnitArea) exceeds 10 diameters of the smallest particle ({:.4e}); reduce maxDistanceBond or maxSigmaBond",
                        pair.reach(),
                        2.0 * rmin
                    ),
                });
            }
        }
        if let Some(ts) = pair.bond_table().and_then(|b| b.ts_create) {
            let none = ts <= self.step
                && !pair.ts_warned
                && self.comm.sum_count(pair.count_bonds(&self.neighbor.list)) == 0;
            if none {
                pair.ts_warned = true;
                self.warnings.push(format!(
                    "tsCreateBond {ts} is not after the current step {}: no bond exists and none will be created (bonds are made in the force evaluation of step tsCreateBond, never at a run's set-up)",
                    self.step
                ));
            }
        }
        Ok(())
    }

    /// Set-up 3b: the bonds of `bond_style gran`: their per-particle property, their
    /// coefficients, and the creators' cutoffs within the ghost cutoff (a pair across two
    /// ranks closer than a creator's cutoff must be seen by both).
    pub(crate) fn setup_bonds(&mut self) -> Result<()> {
        let Some(bonds) = &mut self.bonds else {
            return Ok(());
        };
        bonds.attach(&mut self.particles)?;
        self.neighbor.exclude.molecule = bonds.molecule_id();
        if let Some(pair) = &mut self.pair {
            let molecule = bonds.molecule_id().filter(|_| bonds.fibers_form());
            pair.bond_rules = match bonds.prop_id() {
                Some(b) if bonds.disable_contact || molecule.is_some() => {
                    Some(crate::pair::BondRules {
                        bonds: b,
                        disable_contact: bonds.disable_contact,
                        molecule,
                    })
                }
                _ => None,
            };
        }
        let n = self.particles.nlocal();
        if let Some(id) = bonds.molecule_id() {
            let local = self.particles.props[id.0].data[..n]
                .iter()
                .copied()
                .fold(0.0, f64::max);
            bonds.seen_molecules(self.comm.max(local));
        }
        let rmax = self.comm.max(
            self.particles.radius[..n]
                .iter()
                .copied()
                .fold(0.0, f64::max),
        );
        bonds.check(self.neighbor.cutoff_for(rmax), rmax)
    }

    /// Bond creation of the creators due at this step (`fix bond/create/gran`). New bonds
    /// re-neighbor at once, before this step's forces, as the fork's creation does (which
    /// also drops the bonds broken since the last re-neighboring).
    pub(crate) fn create_bonds(&mut self) -> Result<()> {
        let Some(bonds) = &mut self.bonds else {
            return Ok(());
        };
        let made = bonds.create(&mut self.particles, self.step, &self.neighbor.exclude)?;
        let due = bonds.creators.iter().any(|c| c.due(self.step));
        let renew = due && self.comm.sum_count(made) > 0;
        if renew {
            self.reneighbor()?;
        }
        Ok(())
    }

    /// The bonds of the bonded templates inserted since the last call, once their
    /// particles have tags.
    pub(crate) fn make_pending_bonds(&mut self) -> Result<()> {
        if let Some(bonds) = &mut self.bonds {
            bonds.make_pending(&mut self.particles)?;
        }
        Ok(())
    }

    /// The bond forces (`bond_style gran`), after the pair forces.
    pub(crate) fn bond_forces(&mut self) {
        if let Some(bonds) = &mut self.bonds {
            let skin = self.neighbor.settings.skin;
            bonds.forces(&mut self.particles, self.dt, &self.domain, skin);
        }
    }

    /// Set-up 3: each wall's coefficient table and history property, in definition order.
    pub(crate) fn setup_walls(&mut self) -> Result<()> {
        for fix in &mut self.fixes {
            if let Some(wall) = fix.kind.as_wall_mut() {
                self.neighbor.save_history(&self.particles);
                self.particles.clear_ghosts();
                wall.setup(&self.materials, &self.meshes, &mut self.particles)?;
            }
        }
        // Where each particle last touched a wall, for the lost-particle report.
        let reports = self.lost_policy != LostPolicy::Ignore && self.domain.has_fixed_face();
        if reports && self.fixes.iter().any(|fix| fix.kind.as_wall().is_some()) {
            let none = [-1.0; crate::wall::TOUCH_WIDTH];
            self.particles
                .add_property(crate::wall::TOUCH_PROPERTY, none.len(), &none)?;
        }
        if self.heat.is_none() {
            // A wall at a fixed temperature conducts into the particles' temperatures.
            for fix in &self.fixes {
                let hot = fix.kind.as_wall().is_some_and(|w| w.heats(&self.meshes));
                if hot {
                    return Err(Error::Invalid {
                        what: "wall temperature",
                        reason: format!(
                            "wall {} has a temperature but the particles have none: define fix heat/gran first",
                            fix.id
                        ),
                    });
                }
            }
        }
        Ok(())
    }
}

/// `surface multicontact` (a set-up stage).
impl World {
    /// Set-up 3b: hands the `fix multicontact/halfspace` store, with the types' elastic
    /// constants, to the pair style and the walls whose model has `surface multicontact`;
    /// a model with it but no such fix, or the fix with no such model, is an error, as in
    /// LIGGGHTS.
    pub(crate) fn setup_multicontact(&mut self) -> Result<()> {
        let wants = |m: &crate::ContactModel| m.surface == crate::SurfaceKind::Multicontact;
        let neck = |m: &crate::ContactModel| wants(m) && m.holds_apart();
        let pair_neck = self.pair.as_ref().is_some_and(|p| neck(&p.model));
        let wall_neck = self
            .fixes
            .iter()
            .any(|f| f.kind.as_wall().is_some_and(|w| neck(w.model())));
        if pair_neck || wall_neck {
            // The shaping of a pair apart (a JKR neck) is not defined by either model.
            return Err(Error::Invalid {
                what: "surface multicontact",
                reason: "cannot be combined with model jkr (neither the fork nor LIGGGHTS 3.8 defines a neck between corrected radii)".into(),
            });
        }
        let Some(mc) = &self.multicontact else {
            let user = self
                .pair
                .as_ref()
                .filter(|p| wants(&p.model))
                .map(|_| "pair_style gran".to_string())
                .or_else(|| {
                    self.fixes.iter().find_map(|f| {
                        let w = f.kind.as_wall()?;
                        wants(w.model()).then(|| format!("fix {}", f.id))
                    })
                });
            return match user {
                Some(u) => Err(Error::Invalid {
                    what: "surface multicontact",
                    reason: format!("{u} uses it, which needs a fix multicontact/halfspace"),
                }),
                None => Ok(()),
            };
        };
        if self.comm.size() > 1 {
            return Err(Error::Invalid {
                what: "surface multicontact",
                reason: "runs on one MPI rank only (a ghost particle's other contacts are on another rank); run with threads instead".into(),
            });
        }
        mc.set_materials(
            &self.materials.youngs_modulus,
            &self.materials.poissons_ratio,
        );
        let mut any = false;
        if let Some(pair) = &mut self.pair {
            if wants(&pair.model) {
                pair.multicontact = Some(mc.clone());
                any = true;
            }
        }
        for fix in &mut self.fixes {
            let Some(w) = fix.kind.as_wall_mut().filter(|w| wants(w.model())) else {
                continue;
            };
            let slot = w.multicontact_slot();
            any = true;
            // A wall keeps its number from run to run, so that its records stay its own.
            let number = slot
                .as_ref()
                .map_or_else(|| mc.register_wall(), |(_, n)| *n);
            *slot = Some((mc.clone(), number));
        }
        if !any {
            return Err(Error::Invalid {
                what: "fix multicontact/halfspace",
                reason: "needs 'surface multicontact' in pair_style gran or a fix wall/gran".into(),
            });
        }
        Ok(())
    }
}

/// Re-neighboring stages.
impl World {
    /// Re-neighboring 1: the contact history saved by tag; with several ranks the mirror
    /// entries of contacts with other ranks' ghosts go to the ghosts' owners, so that
    /// whichever rank lists the pair next finds its history.
    pub(crate) fn save_history(&mut self) {
        self.neighbor.save_history(&self.particles);
        if self.comm.size() > 1 {
            let out = self.neighbor.take_remote(self.comm.size());
            let got = self.comm.all_to_all(out);
            self.neighbor.append_history(&got);
        }
    }

    /// Step 1: the Lees–Edwards offset advanced by one step; when it wraps by k box
    /// lengths, every owned particle's n_x grows by k n_y, so that its unwrapped
    /// position stays where it was ([`crate::shear`]).
    pub(crate) fn advance_shear(&mut self) {
        let k = self.domain.advance_shear(self.dt);
        if k == 0 {
            return;
        }
        let p = &mut self.particles;
        for i in 0..p.nlocal() {
            let mut im = p.image[i].get();
            im[0] += k * im[1];
            p.image[i] = im.into();
        }
    }

    /// Re-neighboring 3: owned particles beyond a periodic face wrapped back in.
    pub(crate) fn remap_periodic(&mut self) {
        let nlocal = self.particles.nlocal();
        let p = &mut self.particles;
        for i in 0..nlocal {
            let mut im = p.image[i].get();
            if let Some(s) = &self.domain.shear {
                let (lo, prd) = (self.domain.boxlo, self.domain.prd());
                crate::shear::wrap_y(s, lo, prd, &mut p.x[i], &mut p.v[i]);
            }
            self.domain.remap(&mut p.x[i], &mut im);
            p.image[i] = im.into();
        }
    }

    /// Re-neighboring 4: the shrink-wrapped faces of the box moved to the extent of the
    /// particles over all ranks and of every `fix mesh/surface` mesh where it is now. As
    /// in LIGGGHTS 3.8, a mesh counts whether a wall uses it or not: with `boundary m m m`
    /// a box mesh on the faces of the box widens it by the margin (the tutorial conveyor:
    /// volume 0.2201100176 instead of 0.22 from step 0), a mesh reaching outside the box
    /// takes the box with it, and a moving mesh drags the face along (measured: a mesh
    /// moving at 1 m/s in x put xhi at 0.6001, then 0.6101 after 0.01 s).
    pub(crate) fn shrink_wrap(&mut self) {
        if !self.domain.has_shrink() {
            return;
        }
        let nlocal = self.particles.nlocal();
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for &x in &self.particles.x[..nlocal] {
            lo = lo.min(x);
            hi = hi.max(x);
        }
        for m in &self.meshes {
            let (a, b) = m.mesh.bounds();
            lo = lo.min(a);
            hi = hi.max(b);
        }
        let lo = DVec3::new(
            self.comm.min(lo.x),
            self.comm.min(lo.y),
            self.comm.min(lo.z),
        );
        let hi = DVec3::new(
            self.comm.max(hi.x),
            self.comm.max(hi.y),
            self.comm.max(hi.z),
        );
        self.domain.shrink_wrap(lo, hi);
    }

    /// Re-neighboring 5: the particles beyond a fixed face, handled by the lost-particle
    /// policy (stop, or remove them with or without a warning).
    pub(crate) fn remove_lost(&mut self) -> Result<()> {
        let nlocal = self.particles.nlocal();
        let x = &self.particles.x[..nlocal];
        let nlost_local = x.iter().filter(|&&x| self.domain.is_lost(x)).count();
        let nlost = self.comm.sum_count(nlost_local as u64);
        if nlost == 0 {
            return Ok(());
        }
        let lost: Vec<bool> = x.iter().map(|&x| self.domain.is_lost(x)).collect();
        // The lowest of the ranks' first lost tags, the same on every rank.
        let first = lost.iter().position(|&l| l);
        let first_tag = self
            .comm
            .min(first.map_or(f64::INFINITY, |i| self.particles.tag[i] as f64))
            as Tag;
        let owned = first.filter(|&i| self.particles.tag[i] == first_tag);
        let detail = self.lost_detail(owned);
        if self.lost_policy == LostPolicy::Error {
            return Err(Error::LostParticles {
                count: nlost as usize,
                first_tag,
                detail,
                step: self.step,
            });
        }
        let mut lost = lost;
        self.remove_whole_bodies(&mut lost);
        self.particles.remove_locals(&lost);
        self.lost += nlost;
        if self.lost_policy == LostPolicy::Warn && !self.lost_warned {
            self.lost_warned = true;
            self.warnings.push(format!(
                "{nlost} particle(s) lost at step {} (left a fixed boundary); first lost tag {first_tag} {detail}. The run goes on without them, as in LIGGGHTS; this warning is given once (thermo_modify lost ignore: none; lost error: stop)",
                self.step
            ));
        }
        Ok(())
    }

    /// Where the first lost particle (owned particle `owned` on the rank that has it, the
    /// same text on every rank) was found, its velocity, the wall surface that its path
    /// traced back crosses first ([`crate::lost::crossing`]), and the wall it last
    /// touched ([`crate::wall::touch`]).
    fn lost_detail(&self, owned: Option<usize>) -> String {
        // The owner's values; the other ranks give +inf, so a minimum over the ranks
        // hands the owner's to all (-1 stands for "no crossing" and "no touch").
        let mut vals = [f64::INFINITY; 13];
        if let Some(i) = owned {
            let (x, v) = (self.particles.x[i], self.particles.v[i]);
            vals[..3].copy_from_slice(&x.to_array());
            vals[3..6].copy_from_slice(&v.to_array());
            match crate::lost::crossing(&self.fixes, &self.meshes, x, v) {
                Some(c) => {
                    let (m, t) = c.mesh.map_or((-1.0, -1.0), |(m, t)| (m as f64, t as f64));
                    vals[6..10].copy_from_slice(&[c.fix as f64, m, t, c.back]);
                }
                None => vals[6..10].fill(-1.0),
            }
            match self.particles.property(crate::wall::TOUCH_PROPERTY) {
                Some(id) => {
                    let w = crate::wall::TOUCH_WIDTH;
                    vals[10..]
                        .copy_from_slice(&self.particles.props[id.0].data[i * w..(i + 1) * w]);
                }
                // No record kept: neither "touched" nor "touched none".
                None => vals[10..].fill(-2.0),
            }
        }
        for v in &mut vals {
            *v = self.comm.min(*v);
        }
        let [x, y, z, vx, vy, vz, fix, mesh, tri, back, touch_fix, touch_tri, touch_step] = vals;
        let (xs, vs) = (DVec3::new(x, y, z), DVec3::new(vx, vy, vz));
        let mut s = format!(
            "at {} with velocity {}",
            crate::lost::show(xs),
            crate::lost::show(vs)
        );
        if touch_fix >= 0.0 && touch_fix.is_finite() {
            let surface = if touch_tri >= 0.0 {
                let (m, t) = crate::wall::touch::unpack_triangle(touch_tri);
                Some((m, t))
            } else {
                None
            };
            s.push_str(&format!(
                "; it last touched {} at step {} ({} steps before)",
                self.surface_name(touch_fix as usize, surface),
                touch_step as u64,
                self.step.saturating_sub(touch_step as u64)
            ));
        } else if touch_fix == crate::wall::touch::REMOVED {
            s.push_str(&format!(
                "; it last touched a wall at step {}, whose fix was removed since",
                touch_step as u64
            ));
        } else if touch_fix == -1.0 {
            s.push_str("; it has touched no wall");
        }
        if fix < 0.0 || !fix.is_finite() {
            s.push_str("; traced back along its velocity, its path crosses no wall");
            return s;
        }
        // The crossing point, on the path back from the particle.
        let p = xs - back * vs / vs.length();
        let surface = (mesh >= 0.0).then_some((mesh as usize, tri as u32));
        s.push_str(&format!(
            "; traced back along its velocity, its path crosses {} at {}, {} back",
            self.surface_name(fix as usize, surface),
            crate::lost::show(p),
            crate::lost::g6(back)
        ));
        s
    }

    /// "wall 'ID'", or "mesh 'M' triangle T of wall 'ID'" for a mesh (`surface`: its
    /// index in the world's meshes and the triangle), for reports.
    fn surface_name(&self, fix: usize, surface: Option<(usize, u32)>) -> String {
        let id = &self.fixes[fix].id;
        match surface {
            Some((m, t)) => format!("mesh '{}' triangle {t} of wall '{id}'", self.meshes[m].id),
            None => format!("wall '{id}'"),
        }
    }

    /// Re-neighboring 7: the owned particles sorted by spatial bin when a sort is due.
    pub(crate) fn sort_if_due(&mut self) {
        if self.sort.every == 0 || self.step < self.next_sort {
            return;
        }
        let rmax = self
            .comm
            .max(self.particles.radius.iter().copied().fold(0.0, f64::max));
        let mut h = if self.sort.binsize > 0.0 {
            self.sort.binsize
        } else {
            0.5 * self.neighbor.cutoff_for(rmax)
        };
        // Bins over the subdomain (seed 002). A sparse system in a large box would ask
        // for far more bins than particles (LAMMPS stops with "too many atom sorting
        // bins"); instead the bin size doubles until there are at most 8 N + 64 bins.
        let (lo, hi) = (self.domain.sublo, self.domain.subhi);
        let limit = 8.0 * self.particles.nlocal() as f64 + 64.0;
        let nbins = |h: f64| -> f64 {
            (0..3)
                .map(|a| ((hi[a] - lo[a]) / h).floor().max(1.0))
                .product()
        };
        while nbins(h) > limit {
            h *= 2.0;
        }
        sort_particles(&mut self.particles, lo, hi, h);
        self.next_sort = (self.step / self.sort.every) * self.sort.every + self.sort.every;
    }

    /// Re-neighboring 8: the ghost cutoff for the largest particle (further when radiation
    /// rays reach further: [`crate::heat_radiation::HeatRadiation::ghost_reach`]), checked
    /// against the periodic box (at least twice the contact distance) and the subdomain; notes a
    /// periodic length below twice the cutoff for the build
    /// ([`crate::neighbor::Neighbor::short_periodic`]).
    pub(crate) fn checked_cutoff(&mut self) -> Result<f64> {
        let rmax = self.comm.max(
            self.particles.radius[..self.particles.nlocal()]
                .iter()
                .copied()
                .fold(0.0, f64::max),
        );
        let cutoff = self.neighbor.cutoff_for(rmax);
        self.domain
            .check_periodic_contact(self.neighbor.contact_for(rmax))?;
        // Radiation's rays reach further than contacts: ghosts out to their reach.
        let ghosts = self
            .radiation
            .as_ref()
            .map_or(cutoff, |r| cutoff.max(r.ghost_reach(rmax)));
        self.domain.check_subdomain_cutoff(ghosts)?;
        self.neighbor.short_periodic = self.domain.short_periodic_half(cutoff);
        Ok(ghosts)
    }

    /// Re-neighboring 11: the moving meshes' positions at this build (for the drift
    /// test of step 5) and each wall's candidate particles (those within the skin).
    pub(crate) fn build_wall_candidates(&mut self) {
        let skin = self.neighbor.settings.skin;
        for m in &mut self.meshes {
            if m.is_moving() {
                m.motion.built.clone_from(&m.mesh.verts);
            }
        }
        for fix in &mut self.fixes {
            if let Some(wall) = fix.kind.as_wall_mut() {
                wall.build_candidates(&self.meshes, &mut self.particles, fix.groupbit, skin);
            }
        }
        // `mode auto` servos: whether any particle (on any rank) is a candidate.
        for k in 0..self.meshes.len() {
            if self.meshes[k].servo.is_none() {
                continue;
            }
            let local = self.fixes.iter().any(|f| match &f.kind {
                FixKind::MeshWall(w) => w.has_candidates_on(k),
                _ => false,
            });
            let any = self.comm.any(local);
            if let Some(servo) = &mut self.meshes[k].servo {
                servo.contacts = any;
            }
        }
    }

    /// The run-start set-up of the servo meshes (LIGGGHTS' `init`): the smallest particle
    /// radius over all ranks for `mode auto` ([`crate::mesh_servo::Servo::start_run`]).
    pub fn start_servos(&mut self) {
        if self.meshes.iter().all(|m| m.servo.is_none()) {
            return;
        }
        let n = self.particles.nlocal();
        let local = self.particles.radius[..n]
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let rmin = self.comm.min(local);
        let rmin = rmin.is_finite().then_some(rmin);
        let dt = self.dt;
        for m in &mut self.meshes {
            if let Some(servo) = &mut m.servo {
                servo.start_run(rmin, dt);
            }
        }
    }
}

/// Timestep stages.
impl World {
    /// Step 2: the first half of velocity Verlet for each integrating fix; the heat
    /// flows of the heat conduction group zeroed.
    pub(crate) fn initial_integrate(&mut self) {
        if let Some(heat) = &self.heat {
            heat.reset_flux(&mut self.particles);
        }
        let timing = self.fix_timing;
        for fix in &mut self.fixes {
            let t0 = timing.then(std::time::Instant::now);
            match &mut fix.kind {
                FixKind::NveSphere => {
                    integrate::initial_integrate(&mut self.particles, fix.groupbit, self.dt)
                }
                FixKind::NveLimit(l) => {
                    l.integrate(&mut self.particles, fix.groupbit, self.dt, true)
                }
                FixKind::NveNoforce => {
                    let (p, dt) = (&mut self.particles, self.dt);
                    for i in 0..p.nlocal() {
                        if p.mask[i] & fix.groupbit != 0 {
                            p.x[i] += dt * p.v[i];
                        }
                    }
                }
                FixKind::Sph(s @ (SphFix::Nve | SphFix::NveStationary)) => {
                    if let Some(props) = crate::sph::SphProps::find(&self.particles) {
                        crate::sph::initial_integrate(
                            &mut self.particles,
                            props,
                            fix.groupbit,
                            self.dt,
                            *s == SphFix::Nve,
                        );
                    }
                }
                FixKind::Move(m) => m.initial_integrate(
                    &mut self.particles,
                    &self.domain,
                    fix.groupbit,
                    self.step,
                    self.dt,
                ),
                _ => {}
            }
            if let Some(t0) = t0 {
                fix.seconds += t0.elapsed().as_secs_f64();
            }
        }
        self.initial_integrate_bodies();
    }

    /// Step 3: the meshes with `fix move/mesh` motions moved to the current time.
    pub(crate) fn move_meshes(&mut self) {
        let t = self.step as f64 * self.dt;
        for m in &mut self.meshes {
            m.move_to(t);
        }
    }

    /// Set-up: the meshes moved to the current time, as in step 3, but a mesh that no
    /// step has moved yet keeps zero velocity for the set-up's contacts: LIGGGHTS 3.8
    /// sets a mesh's vertex velocities in the steps of its `fix move/mesh`, so a run's
    /// set-up sees the motion's velocity only once a step has moved the mesh (measured: a
    /// sphere pressed on a mesh that a new `move/mesh` drives at 0.1 m/s gets the set-up
    /// force without damping, and with it at the set-up of every later run).
    pub(crate) fn move_meshes_at_setup(&mut self) {
        let t = self.step as f64 * self.dt;
        for m in &mut self.meshes {
            let fresh = m.motion.vel.is_empty();
            m.move_to(t);
            if fresh {
                m.motion.vel.clear();
            }
        }
    }

    /// Step 3b: the servo meshes (`mesh/surface/stress/servo`) translated by the velocity
    /// (or, `ctrlPV torque`, turned about the axis through their centre of mass by the
    /// angular velocity) their controller set at the end of the previous step (LIGGGHTS'
    /// `initial_integrate`), with their centre of mass and stress reference point; their
    /// vertices carry that velocity for the wall contacts, even while the servo is stopped.
    pub(crate) fn move_servo_meshes(&mut self) {
        let dt = self.dt;
        for m in &mut self.meshes {
            let Some(servo) = &mut m.servo else { continue };
            if servo.torque {
                let angle = servo.turn(dt);
                if angle != 0.0 {
                    let (c, q) = (servo.com, glam::DQuat::from_axis_angle(servo.axis, angle));
                    m.mesh.transform(|p| c + q * (p - c));
                }
                // The vertex velocities stay those of the controller update (LIGGGHTS
                // 3.8 computes them there, from the positions before this turn).
                if m.motion.vel.len() != m.mesh.verts.len() {
                    m.motion.vel.clear();
                    m.motion.vel.resize(m.mesh.verts.len(), DVec3::ZERO);
                }
                continue;
            }
            let d = servo.displacement(dt);
            // A stopped servo does not move, but its vertices keep the last velocity
            // for the contacts, as in LIGGGHTS 3.8 (a lid stopped while rising pulls
            // on the particle it touches through the contact damping).
            let vel = servo.vel;
            servo.com += d;
            if d != DVec3::ZERO {
                m.mesh.transform(|p| p + d);
            }
            if let Some(st) = &mut m.stress {
                st.reference_point += d;
            }
            m.motion.vel.clear();
            m.motion.vel.resize(m.mesh.verts.len(), vel);
        }
    }

    /// Step 13b: each active servo's controller fed with the total force (or torque
    /// about the centre of mass) on its mesh (summed over the ranks, so that every rank
    /// moves the mesh alike; LIGGGHTS' `final_integrate`).
    pub(crate) fn control_servos(&mut self) {
        let dt = self.dt;
        for m in &mut self.meshes {
            let (Some(servo), Some(st)) = (&mut m.servo, &m.stress) else {
                continue;
            };
            if !servo.active {
                continue;
            }
            let f = if servo.torque {
                st.total_torque
            } else {
                st.total_force
            };
            let f = if self.comm.size() > 1 {
                let mut s = [f.x, f.y, f.z];
                self.comm.sum_slice(&mut s);
                DVec3::from_array(s)
            } else {
                f
            };
            servo.control(f, dt);
            // The vertices take the new velocity at once (LIGGGHTS 3.8: the next run's
            // set-up forces already see it).
            let vel = servo.vel;
            m.motion.vel.clear();
            if servo.torque {
                let c = servo.com;
                let verts = &m.mesh.verts;
                m.motion.vel.extend(verts.iter().map(|&p| vel.cross(p - c)));
            } else {
                m.motion.vel.resize(m.mesh.verts.len(), vel);
            }
        }
    }

    /// Whether this step will re-neighbor (asked after the initial integration, before
    /// step 5 decides; every rank must ask): particles added or removed, the list's
    /// delay/every/check, or a moving mesh's drift. A fix that acts only where LIGGGHTS'
    /// `pre_exchange` runs (on re-neighboring steps) asks this.
    pub fn rebuild_pending(&self) -> bool {
        let nlocal = self.particles.nlocal();
        let comm = &self.comm;
        comm.any(self.needs_reneighbor || self.rebuild_next)
            || self
                .neighbor
                .due(self.step, &self.particles.x[..nlocal], |b| comm.any(b))
                .0
            || self.mesh_drifted()
    }

    /// Step 5: whether particles were added (on any rank), and whether the neighbor
    /// lists must be rebuilt: particles added or removed, the list's own decision, or a
    /// moving mesh that drifted half a skin since the wall candidates were built. Every
    /// rank takes the same decision. Clears the added and removed flags.
    pub(crate) fn rebuild_due(&mut self) -> (bool, bool) {
        let nlocal = self.particles.nlocal();
        let removed = std::mem::take(&mut self.rebuild_next);
        let added = std::mem::take(&mut self.needs_reneighbor);
        let comm = &self.comm;
        self.neighbor.shear_drift = self
            .domain
            .shear
            .map_or(0.0, |s| s.drift(self.domain.prd().x));
        let added = comm.any(added);
        let removed = comm.any(removed);
        let rebuild = added
            || removed
            || self
                .neighbor
                .decide(self.step, &self.particles.x[..nlocal], |b| comm.any(b))
            || self.mesh_drifted();
        (added, rebuild)
    }

    /// Whether a moving mesh drifted half a skin since its wall candidates were built
    /// (every rank moves every mesh alike: no communication).
    fn mesh_drifted(&self) -> bool {
        let skin = self.neighbor.settings.skin;
        self.meshes
            .iter()
            .any(|m| m.is_moving() && m.motion.max_drift(&m.mesh.verts) > 0.5 * skin)
    }

    /// Step 6: forces and torques zeroed; the walls told the step (bonds are created at
    /// a given step).
    pub(crate) fn clear_forces(&mut self) {
        self.refresh_contact_mass();
        let p = &mut self.particles;
        crate::par::zero(&mut p.f, &mut p.torque);
        for fix in &mut self.fixes {
            if let Some(wall) = fix.kind.as_wall_mut() {
                wall.set_step(self.step);
            }
        }
    }

    /// Step 7: the pair style's forces (the near list refreshed when stale, the virial
    /// filled when wanted; without a pair style, a zero virial when wanted).
    pub(crate) fn pair_forces(&mut self, update: bool) {
        if let Some(sph) = &self.sph {
            // Also at a run's set-up, from the current P, ρ and v̂ (as LIGGGHTS).
            if let Some(props) = crate::sph::SphProps::find(&self.particles) {
                sph.compute(&mut self.particles, props, &self.neighbor.list);
            }
        }
        if let Some(pair) = &mut self.pair {
            pair.step = self.step;
            // A local decision: the check covers this rank's ghosts too.
            if pair.near_list_stale(&self.particles.x, &self.neighbor) {
                pair.build_near_list(&self.particles, &self.neighbor);
            }
            if self.want_virial {
                self.virial.clear();
                self.virial.resize(self.particles.len(), [0.0; 6]);
                pair.compute_with_virial(
                    &mut self.particles,
                    &mut self.neighbor.list,
                    self.dt,
                    update,
                    &mut self.virial,
                );
            } else {
                pair.compute(
                    &mut self.particles,
                    &mut self.neighbor.list,
                    self.dt,
                    update,
                );
            }
        } else if self.want_virial {
            self.virial.clear();
            self.virial.resize(self.particles.len(), [0.0; 6]);
        }
    }

    /// Step 8: ghost forces (and the virial, when wanted) added to their owners.
    pub(crate) fn reverse_comm(&mut self) {
        self.comm.reverse(&mut self.particles);
        if let Some(pair) = &self.pair {
            pair.reverse_liquid(&mut self.particles, &*self.comm);
        }
        if self.want_virial {
            self.comm.reverse_virial(&self.particles, &mut self.virial);
            self.virial.truncate(self.particles.nlocal());
            self.virial_step = Some(self.step);
        }
    }

    /// Step 9b: the heat flows of this step's contacts (pairs and walls at a fixed
    /// temperature) and of radiation, not at a run's set-up (`update` false), as in
    /// LIGGGHTS.
    pub(crate) fn conduct_heat(&mut self, update: bool) {
        if !update {
            return;
        }
        if let Some(heat) = &mut self.heat {
            heat.conduct(
                &mut self.particles,
                &self.neighbor.list,
                &self.fixes,
                &self.meshes,
                &*self.comm,
            );
        }
        // Radiation is only ever defined with the heat integration, which holds the
        // temperatures.
        if let (Some(rad), Some(heat)) = (&mut self.radiation, &self.heat) {
            rad.radiate(&mut self.particles, &heat.props, &*self.comm);
        }
    }

    /// Step 11: the wall contacts of this evaluation summed per triangle of the meshes
    /// that track stress ([`crate::wall::mesh_stress::accumulate`]).
    pub(crate) fn accumulate_mesh_stress(&mut self, update: bool) {
        if self.meshes.iter().any(|m| m.stress.is_some()) {
            crate::wall::mesh_stress::accumulate(
                &self.fixes,
                &mut self.meshes,
                &self.particles,
                update,
            );
        }
    }

    /// Step 13: the temperatures of heat conduction; the second half of velocity Verlet
    /// for each integrating fix; then the liquid transport of liquid bridges.
    pub(crate) fn final_integrate(&mut self) {
        if let Some(heat) = &self.heat {
            heat.integrate(&mut self.particles, self.dt);
        }
        let timing = self.fix_timing;
        for fix in &mut self.fixes {
            let t0 = timing.then(std::time::Instant::now);
            match &mut fix.kind {
                FixKind::NveSphere => {
                    integrate::final_integrate(&mut self.particles, fix.groupbit, self.dt)
                }
                FixKind::NveLimit(l) => {
                    l.integrate(&mut self.particles, fix.groupbit, self.dt, false)
                }
                FixKind::Sph(SphFix::Nve) => {
                    crate::sph::final_integrate(&mut self.particles, fix.groupbit, self.dt)
                }
                FixKind::Move(m) => m.final_integrate(&mut self.particles, fix.groupbit, self.dt),
                _ => {}
            }
            if let Some(t0) = t0 {
                fix.seconds += t0.elapsed().as_secs_f64();
            }
        }
        self.final_integrate_bodies();
        if let Some(pair) = &self.pair {
            pair.integrate_liquid(&mut self.particles, self.dt);
        }
    }

    /// Steps 12 and 14: stops with the first particle whose `a` or `b` (named `names`) is
    /// not finite. One pass over both arrays first ([`crate::par::all_finite_par`]), in
    /// parallel. `known_bad`: this rank's answer when already known (the fused post-force
    /// pass). With several ranks every rank must call this (it agrees on the answer).
    pub(crate) fn check_finite(
        &self,
        names: [&'static str; 2],
        a: &[DVec3],
        b: &[DVec3],
        known_bad: Option<bool>,
    ) -> Result<()> {
        let n = self.particles.nlocal();
        let bad_here = known_bad.unwrap_or_else(|| !crate::par::all_finite_par(a, b, n));
        if self.comm.size() > 1 {
            // Every rank stops with the same error: the lowest of each rank's first
            // offending particle, as 2·tag + (0 for `a`, 1 for `b`), in one reduction.
            let mine = if bad_here {
                self.first_nonfinite(names, a, b)
                    .map(|(i, q)| 2.0 * self.particles.tag[i] as f64 + (q != names[0]) as u8 as f64)
                    .unwrap_or(f64::INFINITY)
            } else {
                f64::INFINITY
            };
            let first = self.comm.min(mine);
            if first.is_infinite() {
                return Ok(());
            }
            return Err(Error::NonFinite {
                quantity: names[(first % 2.0) as usize],
                tag: (first / 2.0).floor() as Tag,
                step: self.step,
            });
        }
        if !bad_here {
            return Ok(());
        }
        match self.first_nonfinite(names, a, b) {
            Some((i, quantity)) => Err(Error::NonFinite {
                quantity,
                tag: self.particles.tag[i],
                step: self.step,
            }),
            None => Ok(()),
        }
    }

    /// The first owned particle whose `a` or `b` is not finite, with the quantity's name.
    fn first_nonfinite(
        &self,
        names: [&'static str; 2],
        a: &[DVec3],
        b: &[DVec3],
    ) -> Option<(usize, &'static str)> {
        let n = self.particles.nlocal().min(a.len());
        (0..n).find_map(|i| {
            if !a[i].is_finite() {
                Some((i, names[0]))
            } else if !b[i].is_finite() {
                Some((i, names[1]))
            } else {
                None
            }
        })
    }
}
