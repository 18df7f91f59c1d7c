//! One timestep, in the LAMMPS/LIGGGHTS order so that scripts behave the same. This is the
//! one place where the order is written down:
//!
//! 1. `step += 1`
//! 2. initial integrate (`nve/sphere`: half kick, drift); then the `pre_exchange` hook of
//!    [`World::advance_with`] (insertion), whose new particles force step 3's rebuild
//! 3. neighbor decision: if a rebuild is due (delay/every/check), full re-neighboring
//!    (periodic remap, shrink-wrap, lost particles, exchange, sort, borders, list build);
//!    otherwise forward communication of ghost positions and velocities
//! 4. force clear
//! 5. pair forces (particle–particle contacts)
//! 6. reverse communication (ghost forces onto their owners)
//! 7. post-force fixes in definition order: walls (`wall/gran`), gravity, addforce,
//!    setforce, viscous, freeze
//! 8. final integrate (half kick)
//! 9. finiteness checks, after 7 (forces, torques) and 8 (positions, velocities): a NaN or
//!    infinite value stops the run with the particle's tag and the step (the pair pass
//!    treats a NaN distance as no contact, so a broken particle does not spread NaN to
//!    its neighbours first)
//!
//! Set-up before a run ([`World::setup`]) does 3 (a full re-neighboring), 4–7.

use std::time::Instant;

use glam::DVec3;

use crate::error::{Error, Result};
use crate::fix::integrate;
use crate::timers::Stage;
use crate::world::World;

impl World {
    /// Runs `n` timesteps after a set-up.
    pub fn run(&mut self, n: u64) -> Result<()> {
        self.setup()?;
        for _ in 0..n {
            self.advance()?;
        }
        Ok(())
    }

    /// One timestep (the set-up must have been done; a particle added since forces a
    /// full set-up first).
    pub fn advance(&mut self) -> Result<()> {
        self.advance_with(|_| Ok(()))
    }

    /// One timestep with a hook between the initial integration and the neighbor
    /// decision, where LIGGGHTS' insertion fixes act (`pre_exchange`): particles the hook
    /// adds are not moved this step, get their forces and the final half kick, and force
    /// a re-neighboring of this step.
    pub fn advance_with(
        &mut self,
        mut pre_exchange: impl FnMut(&mut World) -> Result<()>,
    ) -> Result<()> {
        if self.needs_reneighbor {
            self.setup()?;
        }
        let t0 = Instant::now();
        self.step += 1;
        let dt = self.dt;
        for fix in &self.fixes {
            if fix.integrates() {
                integrate::initial_integrate(&mut self.particles, fix.groupbit, dt);
            }
        }
        self.move_meshes();
        pre_exchange(self)?;
        let t1 = self.timers.lap(Stage::Modify, t0);
        let nlocal = self.particles.nlocal();
        let removed = std::mem::take(&mut self.rebuild_next);
        let added = std::mem::take(&mut self.needs_reneighbor);
        // Every rank takes the same decision: particles added on any rank, or moved too
        // far on any rank.
        let comm = &self.comm;
        let added = comm.any(added);
        let removed = comm.any(removed);
        // A mesh that moved half a skin since the candidate lists were built needs new
        // ones (every rank moves every mesh alike: no communication).
        let skin = self.neighbor.settings.skin;
        let mesh_far = self
            .meshes
            .iter()
            .any(|m| m.motion.is_moving() && m.motion.max_drift(&m.mesh.verts) > 0.5 * skin);
        if added
            || removed
            || self
                .neighbor
                .decide(self.step, &self.particles.x[..nlocal], |b| comm.any(b))
            || mesh_far
        {
            self.timers.lap(Stage::Neigh, t1);
            if added {
                self.extend_tags();
            }
            self.reneighbor()?;
        } else {
            self.comm.forward(&mut self.particles);
            self.timers.lap(Stage::Comm, t1);
        }
        self.compute_forces(true)?;
        let t2 = Instant::now();
        for fix in &self.fixes {
            if fix.integrates() {
                integrate::final_integrate(&mut self.particles, fix.groupbit, dt);
            }
        }
        let t3 = self.timers.lap(Stage::Modify, t2);
        let p = &self.particles;
        self.check_finite(["position", "velocity"], &p.x, &p.v, None)?;
        self.timers.lap(Stage::Other, t3);
        Ok(())
    }

    /// Steps 4–7: force clear, pair, reverse communication, post-force fixes. `update`
    /// false evaluates the forces without advancing contact history (run set-up).
    pub(crate) fn compute_forces(&mut self, update: bool) -> Result<()> {
        let t0 = Instant::now();
        let p = &mut self.particles;
        crate::par::zero(&mut p.f, &mut p.torque);
        // Bonds are created at a given step.
        for fix in &mut self.fixes {
            match &mut fix.kind {
                crate::fix::FixKind::WallGran(wall) => wall.step = self.step,
                crate::fix::FixKind::MeshWall(wall) => wall.step = self.step,
                _ => {}
            }
        }
        let t1 = self.timers.lap(Stage::Other, t0);
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
        let t2 = self.timers.lap(Stage::Pair, t1);
        self.comm.reverse(&mut self.particles);
        if self.want_virial {
            self.comm.reverse_virial(&self.particles, &mut self.virial);
            self.virial.truncate(self.particles.nlocal());
            self.virial_step = Some(self.step);
        }
        let t3 = self.timers.lap(Stage::Comm, t2);
        let finite = crate::fix::post_force(
            &self.fixes,
            &self.meshes,
            &mut self.particles,
            self.dt,
            update,
        );
        self.hold_streamed();
        if self.meshes.iter().any(|m| m.stress.is_some()) {
            crate::wall::mesh_stress::accumulate(
                &self.fixes,
                &mut self.meshes,
                &self.particles,
                update,
            );
        }
        let t4 = self.timers.lap(Stage::Modify, t3);
        if !finite || self.comm.size() > 1 {
            let p = &self.particles;
            self.check_finite(["force", "torque"], &p.f, &p.torque, Some(!finite))?;
        }
        self.timers.lap(Stage::Other, t4);
        Ok(())
    }

    /// Moves the meshes with `fix move/mesh` motions to the current time.
    pub(crate) fn move_meshes(&mut self) {
        let t = self.step as f64 * self.dt;
        for m in &mut self.meshes {
            m.move_to(t);
        }
    }

    /// Zeroes the force and torque of particles an `insert/stream` still holds (they fly
    /// at their insertion velocity until they reach the insertion face).
    fn hold_streamed(&mut self) {
        let p = &mut self.particles;
        let Some(id) = p.property(crate::insert::stream::HOLD_PROPERTY) else {
            return;
        };
        let step = self.step as f64;
        let n = p.nlocal();
        let held = &p.props[id.0].data[..n];
        for (i, &release) in held.iter().enumerate() {
            if release > step {
                p.f[i] = DVec3::ZERO;
                p.torque[i] = DVec3::ZERO;
            }
        }
    }

    /// Stops with the first particle whose `a` or `b` (named `names`) is not finite. One
    /// pass over both arrays first ([`crate::par::all_finite_par`]), in parallel.
    /// `known_bad`: this rank's answer when already known (the fused post-force pass).
    /// With several ranks every rank must call this (it agrees on the answer).
    fn check_finite(
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
                tag: (first / 2.0).floor() as crate::particles::Tag,
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
