//! The order of everything a run does — one timestep, the set-up before a run and the full
//! re-neighboring — in the LAMMPS/LIGGGHTS order, so that scripts behave the same. This is
//! the one place where the order is written down: the functions below call the stages in
//! this order; the bodies of the larger stages live in `stages.rs` and in the
//! modules named for what they do (sorting, insertion, walls, mesh stress). The timer each
//! stage counts against ([`Stage`], printed in the end-of-run breakdown) is in brackets.
//!
//! # One timestep ([`step`])
//!
//! A front end that owns the world ([`StepHost`]: rdem-script's `run.rs`) runs each step
//! through [`step`]; without one, [`World::advance`] runs stages 0–14 alone.
//!
//! −1. the front end's pre-step stage ([`StepHost::pre_step`]): its pre-step fixes
//!     (rdem-script's `Stages::PRE_STEP`: `fix adapt`, new radii), and whether it wants
//!     the contact virial this step ([`World::want_virial`]) [Modify]
//! 0. a full set-up first if particles were added since the last one ([`World::setup`])
//! 1. `step += 1`
//! 2. initial integrate (`nve/sphere`: half kick, drift; `move`: the prescribed positions
//!    and velocities, velocity Verlet for its NULL components; heat conduction: the heat
//!    flows zeroed); then the rigid clumps (`rdem::multisphere`): each body's half kick,
//!    drift and rotation, its spheres placed and moving with it [Modify]
//! 3. mesh motion (`move/mesh`) to the step's time; servo meshes
//!    (`mesh/surface/stress/servo`) translated by the velocity their controller set at
//!    the end of the previous step (LIGGGHTS moves them in `initial_integrate`) [Modify]
//! 4. [`StepHooks::pre_exchange`]: first the front end's post-integrate fixes (LIGGGHTS'
//!    `post_integrate`: `massflow/mesh` counts the crossings with the new positions and
//!    the half-step velocities), then LIGGGHTS' `pre_exchange` (insertion); particles added
//!    here are not moved this step, get their forces and the final half kick, and force
//!    step 5's rebuild [Modify]
//! 5. neighbor decision: a rebuild is due when particles were added or removed (on any
//!    rank), when the list's delay/every/check says so (any rank), or when a moving mesh
//!    drifted half a skin since its wall candidates were built. Rebuild: tags for the
//!    added particles, then the full re-neighboring below [Neigh, Comm]; otherwise
//!    forward communication of ghost positions and velocities [Comm]
//! 6. force clear; walls told the step (bonds are created at a given step); the SPH
//!    pre-force fixes in definition order (density rate, Shepard filter, pressure; see
//!    [`crate::sph`]; not at a run's set-up) [Other]
//! 7. pair forces (SPH: [`crate::sph::SphPair`]; particle–particle contacts, bonds; the near list refreshed when
//!    stale; the per-particle virial when wanted) [Pair]
//! 8. reverse communication: ghost forces (and virial, liquid flux) onto their owners
//!    [Comm]
//! 9. post-force fixes in definition order, each particle seeing them in that order:
//!    walls (`wall/gran` primitive and mesh), gravity, addforce, setforce, viscous,
//!    freeze, the front end's force fixes ([`crate::fix::ForceFix`]: `speedcontrol`), aveforce (which needs the group's total force over all ranks, so the fixes
//!    around it run in separate passes) [Modify]
//!    9b. heat conduction (`heat/gran`): the heat flows of the step's pair and wall
//!    contacts (see [`crate::heat`]; not at a run's set-up) [Modify]
//! 10. held streamed particles: force and torque zeroed for the particles an
//!     `insert/stream` still holds (they fly at their insertion velocity) [Modify]
//! 11. mesh stress: the wall contacts summed per triangle (`mesh/surface/stress`, wear)
//!     [Modify]
//! 12. finiteness check of forces and torques [Other]
//! 13. final integrate (the temperatures of heat conduction: T += (Q + Q_source) dt / (m c);
//!     half kick; `move`: its NULL components only); the liquid transport of liquid
//!     bridges (content += (flux + source)·dt); then the servo
//!     controllers: each active servo
//!     reads its mesh's total force of step 11 (summed over ranks) and sets the wall
//!     velocity for the next step (LIGGGHTS' `final_integrate`, after the force pass)
//!     [Modify]; then the rigid clumps: each body's force and torque summed from its
//!     spheres (gravity at the centre of mass), its half kick, its spheres' velocities
//! 14. finiteness check of positions and velocities [Other]
//! 15. the front end's end-of-step stage ([`StepHost::end_of_step`], LIGGGHTS'
//!     `end_of_step`): the world's warnings of the step printed, then rdem-script's
//!     `Stages::END_OF_STEP` fixes (`ave/euler`, `ave/atom`, `ave/time`, `ave/histo`,
//!     `massflow/mesh`'s file lines, `check/timestep/gran`, `print`) in definition order, with the
//!     whole script state (variables, computes) in reach. This is the last stage of a
//!     step; the thermo output and the dumps that are due follow [Modify].
//!
//! The finiteness checks stop the run at the first NaN or infinite value with the
//! particle's tag and the step (the pair pass treats a NaN distance as no contact, so a
//! broken particle does not spread NaN to its neighbours first).
//!
//! # Set-up before a run ([`set_up`]: [`World::setup`], LAMMPS' `setup`)
//!
//! Before it, the front end's pre-step stage with `setup` (`fix adapt`, LIGGGHTS'
//! `setup_pre_force`); after it, its end-of-step stage with `setup` (`ave/euler`), then
//! the front end's thermo output and dumps.
//!
//! 1. checks: timestep, neighbor settings; tags for untagged particles; particle types
//!    within the material table when a pair style or a wall uses it
//! 2. pair style: coefficient mixing and bond table, contact history layout, bond reach
//!    (at most 10 diameters of the smallest particle), the `tsCreateBond` warning; SPH:
//!    kernels of the SPH fixes, radii = smoothing lengths, dρ/dt zeroed
//! 3. walls in definition order: coefficient tables, history properties; rigid clumps:
//!    one rank and no periodic boundary so far, a body's spheres excluded from each other
//! 4. mesh motion to the current time
//! 5. full re-neighboring (below)
//! 6. forces: steps 6–12 of a timestep, without advancing contact history (as LIGGGHTS);
//!    each rigid clump's force and torque summed from them
//!
//! # Full re-neighboring ([`World::reneighbor`])
//!
//! 1. contact history saved by tag (several ranks: the mirror entries of contacts with
//!    other ranks' ghosts go to the ghosts' owners) [Neigh]
//! 2. ghosts cleared; the particles marked for removal removed
//!    ([`World::remove_at_reneighbor`]: `massflow/mesh delete_atoms`) [Neigh]
//! 3. periodic remap [Neigh]
//! 4. shrink-wrap of the shrink-wrapped faces around the particles [Neigh]
//! 5. lost particles (beyond a fixed face): error, warning or silence as
//!    `thermo_modify lost` says [Neigh]
//! 6. exchange: particles migrate to the rank of their subdomain, with their carried
//!    history [Comm]
//! 7. spatial sort when due (`atom_modify sort`) [Neigh]
//! 8. cutoff checks (periodic box, subdomain) [Neigh]
//! 9. borders: ghosts [Comm]
//! 10. neighbor list build, contact history carried by tag [Neigh]
//! 11. moving meshes' reference positions; wall candidate lists [Neigh]

use std::time::Instant;

use crate::error::Result;
use crate::fix::FixKind;
use crate::timers::Stage;
use crate::world::World;
use crate::Particles;

/// The front end's stage inside the engine's step (LAMMPS' fix masks): a hook that the
/// front end leaves out costs nothing.
pub trait StepHooks {
    /// Which hooks act (LAMMPS' `setmask`); a stage left out is skipped, untimed.
    fn mask(&self) -> HookMask {
        HookMask::ALL
    }

    /// Step 4: after the initial integration and the mesh motion, before the neighbor
    /// decision (LIGGGHTS' `pre_exchange`: insertion). Particles added here force a
    /// re-neighboring of this step.
    fn pre_exchange(&mut self, world: &mut World) -> Result<()> {
        let _ = world;
        Ok(())
    }
}

/// The stages a [`StepHooks`] acts in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct HookMask {
    /// [`StepHooks::pre_exchange`] acts.
    pub pre_exchange: bool,
}

impl HookMask {
    /// No hook acts.
    pub const NONE: Self = Self {
        pre_exchange: false,
    };
    /// Every hook acts.
    pub const ALL: Self = Self { pre_exchange: true };
}

/// No front-end stage: the engine's step alone ([`World::advance`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoHooks;

impl StepHooks for NoHooks {
    fn mask(&self) -> HookMask {
        HookMask::NONE
    }
}

/// A front end that owns the world and has stages of its own before, inside and after
/// the engine's part of a step (rdem-script's run). [`step`] and [`set_up`] call them in
/// the order of this module's list.
pub trait StepHost {
    /// The front end's error; the engine's errors convert into it.
    type Error: From<crate::Error>;

    /// The world.
    fn world(&mut self) -> &mut World;

    /// Runs `f` on the world with the front end's in-step hooks ([`StepHooks`]), then
    /// whatever the front end does once they have acted (their printed lines).
    fn with_hooks(
        &mut self,
        f: impl FnOnce(&mut World, &mut dyn StepHooks) -> Result<()>,
    ) -> std::result::Result<(), Self::Error>;

    /// Step −1: before step `step` (with `setup`, before a run's set-up): the
    /// front end's pre-step fixes and [`World::want_virial`].
    fn pre_step(&mut self, step: u64, setup: bool) -> std::result::Result<(), Self::Error>;

    /// Step 15: after step `step` (with `setup`, after a run's set-up forces).
    fn end_of_step(&mut self, step: u64, setup: bool) -> std::result::Result<(), Self::Error>;
}

/// One whole timestep of a front end's run: its pre-step stage, the engine's stages 0–14
/// ([`World::advance_with`], its in-step hooks at their place) and its end-of-step stage.
pub fn step<H: StepHost>(host: &mut H) -> std::result::Result<(), H::Error> {
    let t0 = Instant::now();
    let step = host.world().step + 1;
    host.pre_step(step, false)?;
    host.world().timers.lap(Stage::Modify, t0);
    // Without an acting hook, the step monomorphized for NoHooks (no dynamic call).
    host.with_hooks(|w, hooks| {
        if hooks.mask() == HookMask::NONE {
            w.advance()
        } else {
            w.advance_with(hooks)
        }
    })?;
    let t1 = Instant::now();
    host.end_of_step(step, false)?;
    host.world().timers.lap(Stage::Modify, t1);
    Ok(())
}

/// A front end's set-up before a run: its pre-step stage with `setup`, the engine's
/// set-up ([`World::setup`], servo controllers started) and its end-of-step stage with
/// `setup`.
pub fn set_up<H: StepHost>(host: &mut H) -> std::result::Result<(), H::Error> {
    let step = host.world().step;
    host.pre_step(step, true)?;
    let w = host.world();
    w.start_servos();
    w.start_counts();
    w.setup()?;
    host.end_of_step(step, true)
}

impl World {
    /// Runs `n` timesteps after a set-up.
    pub fn run(&mut self, n: u64) -> Result<()> {
        self.start_servos();
        self.start_counts();
        self.setup()?;
        for _ in 0..n {
            self.advance()?;
        }
        Ok(())
    }

    /// One timestep without front-end stages (the set-up must have been done; a particle
    /// added since forces a full set-up first).
    pub fn advance(&mut self) -> Result<()> {
        self.advance_with(&mut NoHooks)
    }

    /// One timestep, stages 0–14 of [`crate::step`], with the front end's `hooks` at
    /// their places.
    pub fn advance_with(&mut self, hooks: &mut (impl StepHooks + ?Sized)) -> Result<()> {
        let mask = hooks.mask();
        if self.needs_reneighbor {
            self.setup()?;
        }
        let t0 = Instant::now();
        self.step += 1;
        // The offset first: a clump's spheres are placed with this step's.
        self.advance_shear();
        self.initial_integrate();
        self.move_meshes();
        self.move_servo_meshes();
        if mask.pre_exchange {
            hooks.pre_exchange(self)?;
        }
        let t1 = self.timers.lap(Stage::Modify, t0);
        let (added, rebuild) = self.rebuild_due();
        if rebuild {
            self.timers.lap(Stage::Neigh, t1);
            if added {
                self.extend_tags();
                self.make_pending_bonds()?;
            }
            self.reneighbor()?;
        } else {
            self.comm.forward(&mut self.particles, &self.domain);
            self.timers.lap(Stage::Comm, t1);
        }
        self.create_bonds()?;
        self.compute_forces(true)?;
        let t2 = Instant::now();
        self.final_integrate();
        self.control_servos();
        let t3 = self.timers.lap(Stage::Modify, t2);
        let p = &self.particles;
        self.check_finite(["position", "velocity"], &p.x, &p.v, None)?;
        self.timers.lap(Stage::Other, t3);
        Ok(())
    }

    /// Steps 6–12: force clear, pair, reverse communication, post-force fixes, held
    /// streamed particles, mesh stress, finiteness check. `update` false evaluates the
    /// forces without advancing contact history (run set-up).
    pub(crate) fn compute_forces(&mut self, update: bool) -> Result<()> {
        let t0 = Instant::now();
        self.clear_forces();
        if update {
            self.sph_pre_force();
            if let Some(mc) = &self.multicontact {
                mc.advance();
            }
        } else if let Some(mc) = &self.multicontact {
            mc.peek_latest();
        }
        let t1 = self.timers.lap(Stage::Other, t0);
        self.pair_forces(update);
        self.bond_forces();
        let t2 = self.timers.lap(Stage::Pair, t1);
        self.reverse_comm();
        let t3 = self.timers.lap(Stage::Comm, t2);
        let finite = crate::fix::post_force(
            &mut self.fixes,
            &self.meshes,
            &mut self.particles,
            &*self.comm,
            crate::fix::PostForce {
                dt: self.dt,
                update,
                step: self.step,
                timing: self.fix_timing,
            },
        );
        self.conduct_heat(update);
        crate::insert::stream::hold_streamed(&mut self.particles, self.step);
        self.accumulate_mesh_stress(update);
        let t4 = self.timers.lap(Stage::Modify, t3);
        if !finite || self.comm.size() > 1 {
            let p = &self.particles;
            self.check_finite(["force", "torque"], &p.f, &p.torque, Some(!finite))?;
        }
        self.timers.lap(Stage::Other, t4);
        Ok(())
    }

    /// A run's start: the counts the fixes keep per run (`fix nve/limit`'s resets) back
    /// to zero.
    pub fn start_counts(&mut self) {
        for f in &mut self.fixes {
            if let FixKind::NveLimit(l) = &mut f.kind {
                l.resets = 0;
            }
        }
    }

    /// Prepares a run (set-up 1–6 of [`crate::step`]): checks, coefficient tables,
    /// re-neighboring and the forces of the current state (LAMMPS `setup`).
    pub fn setup(&mut self) -> Result<()> {
        self.check_settings()?;
        self.extend_tags();
        self.make_pending_bonds()?;
        self.check_types()?;
        self.setup_pair()?;
        self.setup_sph()?;
        self.apply_restored_history();
        self.setup_walls()?;
        self.setup_multicontact()?;
        self.setup_multisphere()?;
        self.setup_bonds()?;
        self.move_meshes_at_setup();
        self.reneighbor_then(Particles::shrink_to_fit)?;
        // As in LIGGGHTS, the set-up force evaluation does not advance contact history.
        self.compute_forces(false)?;
        self.sum_body_forces();
        self.needs_reneighbor = false;
        self.rebuild_next = false;
        Ok(())
    }

    /// Full re-neighboring (1–11 of [`crate::step`]): history saved, removals, periodic
    /// remap, shrink-wrap, lost particles, migration, spatial sort when due, ghosts,
    /// neighbor list (history carried by tag), wall candidates.
    pub(crate) fn reneighbor(&mut self) -> Result<()> {
        self.reneighbor_then(|_| ())
    }

    /// [`World::reneighbor`], with `before_build` applied to the particles (ghosts
    /// included) just before the neighbor list is built. The set-up of a run gives back
    /// the arrays' spare capacity there, before the largest allocation of the run.
    fn reneighbor_then(&mut self, before_build: impl FnOnce(&mut Particles)) -> Result<()> {
        let t0 = Instant::now();
        self.save_history();
        if let Some(pair) = &mut self.pair {
            pair.release_near_list();
        }
        self.particles.clear_ghosts();
        self.remove_marked();
        self.remap_periodic();
        self.shrink_wrap();
        self.remove_lost()?;
        let t1 = self.timers.lap(Stage::Neigh, t0);
        self.comm
            .exchange(&mut self.particles, &self.domain, &mut self.neighbor);
        self.neighbor.merge_carried();
        let t2 = self.timers.lap(Stage::Comm, t1);
        self.sort_if_due();
        let cutoff = self.checked_cutoff()?;
        let t3 = self.timers.lap(Stage::Neigh, t2);
        if let Some(s) = &mut self.domain.shear {
            s.built = s.offset;
        }
        self.comm.borders(&mut self.particles, &self.domain, cutoff);
        let t4 = self.timers.lap(Stage::Comm, t3);
        before_build(&mut self.particles);
        self.neighbor.build(&self.particles, self.step);
        if let Some(b) = &mut self.bonds {
            b.link(&mut self.particles)?;
        }
        self.build_wall_candidates();
        self.timers.lap(Stage::Neigh, t4);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::{Boundary, Domain, Fix, FixKind, NewParticle};

    /// Records the velocity of particle 0 and the particle count at each hook.
    #[derive(Default)]
    struct Record {
        pre_exchange: Vec<(u64, f64, usize)>,
    }

    impl StepHooks for Record {
        fn pre_exchange(&mut self, w: &mut World) -> Result<()> {
            let p = &w.particles;
            self.pre_exchange.push((w.step, p.v[0].z, p.nlocal()));
            if w.step == 2 {
                w.add_particle(&NewParticle::at(DVec3::new(0.5, 0.5, 0.8), 0.01, 1000.0))?;
            }
            Ok(())
        }
    }

    /// A front end that records what its stages see: (stage, step argument, world
    /// step, velocity of particle 0, particle count).
    struct Host {
        world: World,
        hooks: Record,
        seen: Vec<(&'static str, u64, bool, u64, f64, usize)>,
    }

    impl Host {
        fn note(&mut self, stage: &'static str, step: u64, setup: bool) {
            let p = &self.world.particles;
            let row = (stage, step, setup, self.world.step, p.v[0].z, p.nlocal());
            self.seen.push(row);
        }
    }

    impl StepHost for Host {
        type Error = crate::Error;

        fn world(&mut self) -> &mut World {
            &mut self.world
        }

        fn with_hooks(
            &mut self,
            f: impl FnOnce(&mut World, &mut dyn StepHooks) -> Result<()>,
        ) -> Result<()> {
            f(&mut self.world, &mut self.hooks)
        }

        fn pre_step(&mut self, step: u64, setup: bool) -> Result<()> {
            self.note("pre_step", step, setup);
            Ok(())
        }

        fn end_of_step(&mut self, step: u64, setup: bool) -> Result<()> {
            self.note("end_of_step", step, setup);
            Ok(())
        }
    }

    /// A sphere falling freely under gravity g (velocity Verlet, dt): the front end's
    /// pre-step stage sees the state of the step before, the pre-exchange hook the
    /// velocity after the initial half kick, −g (n − ½) dt at step n, the end-of-step
    /// stage the velocity after the final one, −g n dt; a particle added in the
    /// pre-exchange hook of step 2 is there at the end of that step; the set-up calls
    /// the two front-end stages with `setup` at step 0; the hooks of [`NoHooks`] are
    /// never called.
    #[test]
    fn hooks_run_at_their_place_in_the_step() {
        let (g, dt) = (9.81, 1e-3);
        let domain = Domain::new(DVec3::ZERO, DVec3::ONE, [Boundary::Fixed; 3]).unwrap();
        let mut w = World::new(domain);
        w.set_timestep(dt).unwrap();
        w.add_particle(&NewParticle::at(DVec3::new(0.5, 0.5, 0.5), 0.01, 1000.0))
            .unwrap();
        w.add_fix(Fix::new("nve", 1, FixKind::NveSphere).unwrap())
            .unwrap();
        w.add_fix(Fix::gravity("g", 1, g, DVec3::NEG_Z).unwrap())
            .unwrap();
        let mut host = Host {
            world: w,
            hooks: Record::default(),
            seen: Vec::new(),
        };
        set_up(&mut host).unwrap();
        for _ in 0..3 {
            step(&mut host).unwrap();
        }
        let seen = &host.seen;
        assert_eq!(seen.len(), 8);
        assert_eq!(seen[0], ("pre_step", 0, true, 0, 0.0, 1));
        assert_eq!(seen[1], ("end_of_step", 0, true, 0, 0.0, 1));
        for n in 1..=3u64 {
            let (pre, end) = (seen[2 * n as usize], seen[2 * n as usize + 1]);
            let (s0, v0, n0) = host.hooks.pre_exchange[n as usize - 1];
            assert_eq!((pre.0, pre.1, pre.2, pre.3), ("pre_step", n, false, n - 1));
            assert!((pre.4 + g * (n - 1) as f64 * dt).abs() < 1e-15, "{pre:?}");
            assert_eq!(s0, n);
            assert!((v0 + g * (n as f64 - 0.5) * dt).abs() < 1e-15, "{v0}");
            assert_eq!(n0, if n <= 2 { 1 } else { 2 });
            assert_eq!((end.0, end.1, end.2, end.3), ("end_of_step", n, false, n));
            assert!((end.4 + g * n as f64 * dt).abs() < 1e-15, "{end:?}");
            assert_eq!(end.5, if n < 2 { 1 } else { 2 });
        }
        assert_eq!(NoHooks.mask(), HookMask::NONE);
        host.world.advance().unwrap();
        assert_eq!(host.world.step, 4);
    }
}
