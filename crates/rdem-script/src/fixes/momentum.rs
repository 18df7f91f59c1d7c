//! `fix ID group momentum N [linear xflag yflag zflag] [angular]` (LIGGGHTS 3.8, from
//! LAMMPS): every N steps, after the step's final integration, the group's linear
//! and/or angular momentum is zeroed by changing its particles' velocities.
//!
//! - **linear**: the group's centre-of-mass velocity Σmv/Σm is taken from each particle's
//!   velocity, along the axes whose flag is non-zero.
//! - **angular** (after linear): the group's angular momentum L about its centre of mass
//!   (unwrapped positions, the particles taken as point masses) and its inertia tensor I
//!   give ω = I⁻¹L; each particle's velocity loses ω × (x − x_cm). The spins (omega) are
//!   left alone, as in LIGGGHTS. When I is singular (fewer than three particles, or all
//!   on a line) LIGGGHTS 3.8 divides by nothing and gets an arbitrary ω; rdem leaves the
//!   velocities as they are then.
//!
//! Sums are per rank then over ranks, so the result does not depend on the thread count.
//! Particles of clumps (`fix multisphere`) are refused: their velocities are their
//! body's.

use crate::error::Error;
use glam::{DMat3, DVec3};

use super::{style, FixHead, FixRow, ScriptFix, StageCtx, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "momentum",
    parse,
    Stages::END_OF_STEP,
    "`N [linear xflag yflag zflag] [angular]`: every N steps the group's centre-of-mass velocity (along the flagged axes) and/or its rigid rotation about the centre of mass is taken from its velocities",
);

struct Momentum {
    every: u64,
    /// Axes whose centre-of-mass velocity is removed (`None`: no `linear`).
    linear: Option<[bool; 3]>,
    angular: bool,
}

fn parse(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let every = a.count("N")?;
    let (mut linear, mut angular) = (None, false);
    while !a.is_done() {
        match a.keyword("fix momentum keyword", &["linear", "angular"])? {
            "linear" => {
                let mut flags = [false; 3];
                for (flag, axis) in flags.iter_mut().zip(["xflag", "yflag", "zflag"]) {
                    *flag = a.u64(axis)? != 0;
                }
                linear = Some(flags);
            }
            _ => angular = true,
        }
    }
    if linear.is_none() && !angular {
        return Err(a.error_cmd(
            "fix momentum: give 'linear xflag yflag zflag', 'angular' or both",
            None,
        ));
    }
    sim.world_ref(a)?;
    Ok(Box::new(Momentum {
        every,
        linear,
        angular,
    }))
}

/// The inverse of the symmetric `m`, `None` when its determinant is not positive.
fn inverse(m: DMat3) -> Option<DMat3> {
    let det = m.determinant();
    (det > 0.0).then(|| m.inverse())
}

impl Momentum {
    fn zero(&self, w: &mut rdem::World, groupbit: u32) -> Result<(), Error> {
        let n = w.particles.nlocal();
        let members: Vec<usize> = {
            let p = &w.particles;
            (0..n).filter(|&i| p.mask[i] & groupbit != 0).collect()
        };
        {
            let of = w.clump_of();
            if members.iter().any(|&i| of(i).is_some()) {
                return Err(
                    "fix momentum: the group holds spheres of clumps (fix multisphere), whose velocities are their bodies'"
                        .into(),
                );
            }
        }
        let mut s = [0.0; 4];
        {
            let p = &w.particles;
            for &i in &members {
                let mv = p.rmass[i] * p.v[i];
                s[0] += mv.x;
                s[1] += mv.y;
                s[2] += mv.z;
                s[3] += p.rmass[i];
            }
        }
        w.comm.sum_slice(&mut s);
        let mass = s[3];
        if mass <= 0.0 {
            return Ok(());
        }
        if let Some(flags) = self.linear {
            let vcm = DVec3::new(s[0], s[1], s[2]) / mass;
            let p = &mut w.particles;
            for &i in &members {
                for (a, _) in flags.iter().enumerate().filter(|(_, &f)| f) {
                    p.v[i][a] -= vcm[a];
                }
            }
        }
        if !self.angular {
            return Ok(());
        }
        let unwrapped: Vec<DVec3> = {
            let p = &w.particles;
            members
                .iter()
                .map(|&i| w.domain.unmap(p.x[i], p.image[i].get()))
                .collect()
        };
        let xcm = crate::computes::kernels::group_com(w, groupbit).1;
        // L (3) then I's xx yy zz xy yz xz.
        let mut li = [0.0; 9];
        {
            let p = &w.particles;
            for (&i, x) in members.iter().zip(&unwrapped) {
                let (m, d) = (p.rmass[i], *x - xcm);
                let l = m * d.cross(p.v[i]);
                li[0] += l.x;
                li[1] += l.y;
                li[2] += l.z;
                li[3] += m * (d.y * d.y + d.z * d.z);
                li[4] += m * (d.x * d.x + d.z * d.z);
                li[5] += m * (d.x * d.x + d.y * d.y);
                li[6] -= m * d.x * d.y;
                li[7] -= m * d.y * d.z;
                li[8] -= m * d.x * d.z;
            }
        }
        w.comm.sum_slice(&mut li);
        let inertia = DMat3::from_cols_array(&[
            li[3], li[6], li[8], //
            li[6], li[4], li[7], //
            li[8], li[7], li[5],
        ]);
        let Some(inv) = inverse(inertia) else {
            return Ok(());
        };
        let omega = inv * DVec3::new(li[0], li[1], li[2]);
        let p = &mut w.particles;
        for (&i, x) in members.iter().zip(&unwrapped) {
            p.v[i] -= omega.cross(*x - xcm);
        }
        Ok(())
    }
}

impl ScriptFix for Momentum {
    fn end_of_step(&mut self, ctx: &mut StageCtx, head: &FixHead) -> Result<(), Error> {
        if ctx.setup || ctx.step % self.every != 0 {
            return Ok(());
        }
        self.zero(ctx.world(), head.groupbit)
    }

    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
