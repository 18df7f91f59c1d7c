//! `fix ID group mcg` (LIGGGHTS_Multi-level_CG, Lokisphere/LIGGGHTS_Multi-level_CG; not in
//! LIGGGHTS 3.8, which stops with "Invalid fix style"): the multi-level coarse graining of
//! De et al. 2022 (Powder Technol. 398:117058) as that fork ships it, with its levels and
//! places fixed in its code for its hourglass example (the fork's README: "edit the file
//! fix_mcg.cpp" to change them). It takes no arguments. Every particle, whatever the
//! group:
//!
//! - **grows** each step: a fine sphere of radius in [1.8, 2.5) mm by 0.2 µm up to
//!   2.5 mm, a coarse one in [2.55, 5) mm by 0.4 µm up to 5 mm, its mass following at
//!   constant density;
//! - is **refined** when it is a coarse sphere (radius 5 mm) with 0.2 ≤ y ≤ 0.25 m: it is
//!   replaced by 8 spheres of radius 0.366 r at its centre ± 0.366 r along each axis,
//!   with its velocity, spin, type and density (they then grow to 2.5 mm);
//! - is **coarsened** when it is a fine sphere (radius 2.5 mm) with y < 0.15 m: such
//!   spheres are merged eight at a time into one sphere of radius 2.6 mm (which then
//!   grows to 5 mm) at the first one's position, with the eight's mass-weighted velocity
//!   and spin and the first one's type and density; fewer than eight left wait.
//!
//! Refining and coarsening are done on the first re-neighboring step after each step that
//! is a multiple of 100, where the fork's `pre_exchange` runs. The new spheres are in
//! group `all` only (as the fork creates them), their tags new.
//!
//! Where rdem differs from the fork: the fork merges the first eight fine spheres in its
//! local storage order, which depends on LIGGGHTS' atom sorting and the MPI ranks; rdem
//! takes them in tag order on each rank, so a run does not depend on the thread count.
//! The fork gives a refined sphere one eighth of its parent's mass until the end of the
//! step, rdem the mass of its radius at once. So a run follows the fork in its counts
//! and flow, not particle for particle: on the fork's hourglass example (wild/52) the
//! counts follow its published 8-rank run to 5 % over the first 60000 steps, but by the
//! end (500000 steps) rdem has 2472 spheres where the fork had 1716, more of the
//! material refined (measured; taking the spheres in LIGGGHTS' spatial-sort order
//! instead of tag order gave 2535).

use super::{style, FixHead, FixRow, Notes, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::error::Error;
use crate::sim::Sim;
use glam::DVec3;
use rdem::particles::NewParticle;
use rdem::World;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "mcg",
    parse,
    Stages::END_OF_STEP.and(Stages::PRE_EXCHANGE),
    "no arguments (LIGGGHTS_Multi-level_CG): coarse spheres (5 mm) refined into 8 in 0.2 ≤ y ≤ 0.25 m, fine ones (2.5 mm) merged 8 to 1 below y = 0.15 m, each growing to its size, as the fork's code fixes them",
)
.notes("the fork's levels and places are in its code, not its script; rdem merges the fine spheres in tag order where the fork takes its storage order, so a run follows the fork in counts, not particle for particle");

/// Fine level: radius after refinement growth.
const FINE: f64 = 0.0025;
/// Smallest radius that grows toward [`FINE`].
const FINE_FROM: f64 = 0.0018;
/// Fine growth per step.
const FINE_GROWTH: f64 = 0.2e-6;
/// Coarse level.
const COARSE: f64 = 0.005;
/// Smallest radius that grows toward [`COARSE`].
const COARSE_FROM: f64 = 0.51 * COARSE;
/// Coarse growth per step.
const COARSE_GROWTH: f64 = 0.4e-6;
/// A merged sphere's radius at its creation.
const MERGED: f64 = 0.52 * COARSE;
/// A refined sphere's radius and offset, as a fraction of its parent's radius.
const SPLIT: f64 = 0.366;
/// Radii within this of a level count as at it.
const TOL: f64 = 1e-9;
/// The refinement band in y.
const REFINE_Y: (f64, f64) = (0.2, 0.25);
/// Fine spheres below this y are merged.
const COARSEN_Y: f64 = 0.15;
/// Refining and coarsening come after each step that is a multiple of this.
const EVERY: u64 = 100;

/// The fix's state: whether a refinement is due, and a reused buffer of radii.
struct Mcg {
    due: bool,
    radii: Vec<f64>,
}

fn parse(_sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    if !a.is_done() {
        return Err(a.error_at(
            a.pos(),
            "fix mcg takes no arguments",
            Some("its levels and places are fixed, as in LIGGGHTS_Multi-level_CG: write 'fix ID group mcg'".into()),
        ));
    }
    Ok(Box::new(Mcg {
        due: false,
        radii: Vec::new(),
    }))
}

/// The radius a sphere of radius `r` grows to in one step.
fn grown(r: f64) -> f64 {
    if (FINE_FROM..FINE).contains(&r) {
        (r + FINE_GROWTH).min(FINE)
    } else if (COARSE_FROM..COARSE).contains(&r) {
        (r + COARSE_GROWTH).min(COARSE)
    } else {
        r
    }
}

impl Mcg {
    /// Refines and coarsens the owned particles (this rank's, as the fork does).
    fn exchange(world: &mut World) -> rdem::Result<()> {
        let p = &world.particles;
        let n = p.nlocal();
        let mut remove = vec![false; n];
        let mut new = Vec::new();
        for (i, gone) in remove.iter_mut().enumerate() {
            let y = p.x[i].y;
            if (p.radius[i] - COARSE).abs() < TOL && y >= REFINE_Y.0 && y <= REFINE_Y.1 {
                *gone = true;
                let d = SPLIT * p.radius[i];
                for k in 0..8 {
                    let s = |b: usize| if k & b != 0 { d } else { -d };
                    new.push(NewParticle {
                        tag: 0,
                        ty: p.ty[i],
                        mask: 1,
                        x: p.x[i] + DVec3::new(s(4), s(2), s(1)),
                        v: p.v[i],
                        omega: p.omega[i],
                        radius: d,
                        density: p.density[i],
                    });
                }
            }
        }
        let mut fine: Vec<usize> = (0..n)
            .filter(|&i| (p.radius[i] - FINE).abs() < TOL && p.x[i].y < COARSEN_Y)
            .collect();
        fine.sort_by_key(|&i| p.tag[i]);
        for eight in fine.chunks_exact(8) {
            let mass: f64 = eight.iter().map(|&i| p.rmass[i]).sum();
            let mean = |f: &dyn Fn(usize) -> DVec3| {
                eight.iter().map(|&i| p.rmass[i] * f(i)).sum::<DVec3>() / mass
            };
            let first = eight[0];
            new.push(NewParticle {
                tag: 0,
                ty: p.ty[first],
                mask: 1,
                x: p.x[first],
                v: mean(&|i| p.v[i]),
                omega: mean(&|i| p.omega[i]),
                radius: MERGED,
                density: p.density[first],
            });
            for &i in eight {
                remove[i] = true;
            }
        }
        if !new.is_empty() {
            world.remove_particles(&remove);
            for np in &new {
                world.add_particle(np)?;
            }
        }
        Ok(())
    }
}

impl ScriptFix for Mcg {
    fn end_of_step(&mut self, ctx: &mut StageCtx, _head: &FixHead) -> Result<(), Error> {
        if ctx.setup {
            return Ok(());
        }
        let step = ctx.step;
        let w = ctx.world();
        let n = w.particles.nlocal();
        self.radii.clear();
        self.radii
            .extend(w.particles.radius[..n].iter().map(|&r| grown(r)));
        w.set_radii(&self.radii)?;
        if step % EVERY == 0 {
            self.due = true;
        }
        Ok(())
    }

    fn due(&self, _step: u64) -> bool {
        self.due
    }

    fn pre_exchange(
        &mut self,
        _head: &FixHead,
        world: &mut World,
        _notes: &mut Notes,
    ) -> rdem::Result<()> {
        if self.due && world.rebuild_pending() {
            self.due = false;
            Self::exchange(world)?;
        }
        Ok(())
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn growth_stops_at_the_levels() {
        assert_eq!(grown(0.0017), 0.0017);
        assert_eq!(grown(0.0018), 0.0018 + FINE_GROWTH);
        assert_eq!(grown(FINE - 0.1e-6), FINE);
        assert_eq!(grown(FINE), FINE);
        assert_eq!(grown(MERGED), MERGED + COARSE_GROWTH);
        assert_eq!(grown(COARSE - 0.1e-6), COARSE);
        assert_eq!(grown(COARSE), COARSE);
        assert_eq!(grown(0.01), 0.01);
        // A refined sphere starts on the fine ramp, a merged one on the coarse ramp.
        assert!((FINE_FROM..FINE).contains(&(SPLIT * COARSE)));
        assert!((COARSE_FROM..COARSE).contains(&MERGED));
    }
}
