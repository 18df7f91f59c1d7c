//! `displace_atoms group-ID move|ramp|random|rotate args [units box|lattice]` (LIGGGHTS
//! 3.8, from LAMMPS): moves the group's particles once, between runs.
//!
//! - `move dx dy dz`: by the same vector;
//! - `ramp ddim dlo dhi dim clo chi`: along `ddim` by dlo + f (dhi − dlo), f the
//!   fraction of the particle's `dim` coordinate between clo and chi (clamped to [0, 1]);
//! - `random dx dy dz seed`: by uniform amounts in [−dx, dx], ... drawn from a generator
//!   seeded per particle with `seed` and its position (LAMMPS' Park–Miller generator and
//!   seeding, so the same particle moves the same way on any number of ranks, and as in
//!   LIGGGHTS);
//! - `rotate Px Py Pz Rx Ry Rz theta`: by the angle θ (degrees, right-hand rule) about the
//!   axis R through P, from the positions in the box (not the unwrapped ones: LIGGGHTS
//!   3.8 turns a particle of periodic image 1 as if it were in image 0, measured). Spins
//!   and velocities are left alone.
//!
//! Distances (and P) are in box units, or lattice spacings with `units lattice`: the
//! default is `box` in LIGGGHTS 3.8, whatever its manual says (`move 1 0 0` after
//! `lattice sc 0.2` moved by 1, measured). Particles are then wrapped into a periodic box; one that ends outside a
//! fixed face stays where it is until the next run loses it, as in LIGGGHTS 3.8 (a
//! warning says so). Spheres of clumps are not moved, with a warning: their positions
//! are their body's (LIGGGHTS 3.8 moves them, and its `fix multisphere` puts them back
//! at the next step, measured on LIGGGHTS-PFM's `cornerghost` example).

use glam::DVec3;

use crate::args::{Args, CmdResult};
use crate::park_miller::ParkMiller;
use crate::sim::Sim;

enum Displace {
    Move(DVec3),
    Ramp {
        ddim: usize,
        dlo: f64,
        dhi: f64,
        dim: usize,
        clo: f64,
        chi: f64,
    },
    Random(DVec3, i32),
    Rotate {
        point: DVec3,
        axis: DVec3,
        theta: f64,
    },
}

fn axis(a: &mut Args, what: &str) -> CmdResult<usize> {
    Ok(match a.keyword(what, &["x", "y", "z"])? {
        "x" => 0,
        "y" => 1,
        _ => 2,
    })
}

/// `displace_atoms`.
pub(super) fn displace_atoms(sim: &mut Sim, a: &mut Args) -> CmdResult {
    let bit = sim.group_bit(a, "group ID")?;
    let style = a.keyword(
        "displace_atoms style",
        &["move", "ramp", "random", "rotate"],
    )?;
    let mut op = match style {
        "move" => Displace::Move(a.vec3("displacement")?),
        "ramp" => Displace::Ramp {
            ddim: axis(a, "displaced dimension")?,
            dlo: a.f64("dlo")?,
            dhi: a.f64("dhi")?,
            dim: axis(a, "coordinate dimension")?,
            clo: a.f64("clo")?,
            chi: a.f64("chi")?,
        },
        "random" => {
            let d = a.vec3("random displacement")?;
            let seed = a.seed()?;
            let seed =
                i32::try_from(seed).map_err(|_| a.error_prev("seed must be below 2^31", None))?;
            Displace::Random(d, seed)
        }
        _ => {
            let point = a.vec3("axis point")?;
            let at = a.pos();
            let r = a.vec3("axis vector")?;
            if r == DVec3::ZERO {
                return Err(a.error_at(at, "displace_atoms rotate: the axis vector is zero", None));
            }
            Displace::Rotate {
                point,
                axis: r.normalize(),
                theta: a.f64("angle")?.to_radians(),
            }
        }
    };
    let mut lattice = false;
    while !a.is_done() {
        a.keyword("displace_atoms keyword", &["units"])?;
        lattice = a.keyword("units", &["box", "lattice"])? == "lattice";
    }
    if lattice && sim.defs.lattice.is_none() {
        return Err(a.error_cmd(
            "displace_atoms units lattice: no lattice is defined",
            Some("define one with 'lattice' first, or use 'units box'".into()),
        ));
    }
    sim.outputs.out.line("Displacing atoms ...");
    let s = super::region::scale_of(sim, a, lattice)?;
    match &mut op {
        Displace::Move(d) | Displace::Random(d, _) => *d *= s,
        Displace::Ramp {
            ddim,
            dlo,
            dhi,
            dim,
            clo,
            chi,
        } => {
            (*dlo, *dhi) = (*dlo * s[*ddim], *dhi * s[*ddim]);
            (*clo, *chi) = (*clo * s[*dim], *chi * s[*dim]);
        }
        Displace::Rotate { point, .. } => *point *= s,
    }
    let w = sim.world_mut(a)?;
    let (members, clumped) = {
        let of = w.clump_of();
        let p = &w.particles;
        let group: Vec<usize> = (0..p.nlocal()).filter(|&i| p.mask[i] & bit != 0).collect();
        let clumped = group.iter().filter(|&&i| of(i).is_some()).count();
        let free: Vec<usize> = group.into_iter().filter(|&i| of(i).is_none()).collect();
        (free, clumped)
    };
    let clumped = w.comm.sum_count(clumped as u64);
    let (domain, p) = (&w.domain, &mut w.particles);
    for &i in &members {
        let x = p.x[i];
        p.x[i] += match &op {
            Displace::Move(d) => *d,
            Displace::Ramp {
                ddim,
                dlo,
                dhi,
                dim,
                clo,
                chi,
            } => {
                let f = ((x[*dim] - clo) / (chi - clo)).clamp(0.0, 1.0);
                let mut d = DVec3::ZERO;
                d[*ddim] = dlo + f * (dhi - dlo);
                d
            }
            Displace::Random(d, seed) => {
                let mut g = ParkMiller::seeded(*seed, x);
                let mut r = DVec3::ZERO;
                for k in 0..3 {
                    r[k] = d[k] * 2.0 * (g.uniform() - 0.5);
                }
                r
            }
            Displace::Rotate { point, axis, theta } => {
                let d = x - *point;
                let along = d.dot(*axis) * *axis;
                let radial = d - along;
                let normal = axis.cross(radial);
                radial * (theta.cos() - 1.0) + normal * theta.sin()
            }
        };
        let (mut x, mut im) = (p.x[i], p.image[i].get());
        domain.remap(&mut x, &mut im);
        (p.x[i], p.image[i]) = (x, im.into());
    }
    let outside = members
        .iter()
        .filter(|&&i| domain.check_inside_fixed(p.x[i]).is_err())
        .count();
    let outside = w.comm.sum_count(outside as u64);
    if clumped > 0 {
        sim.outputs.out.warning(&format!(
            "displace_atoms: {clumped} sphere(s) of clumps (fix multisphere) not moved: their positions are their bodies' (LIGGGHTS 3.8 moves them and puts them back at the next step)"
        ));
    }
    if outside > 0 {
        sim.outputs.out.warning(&format!(
            "displace_atoms moved {outside} particle(s) outside a fixed face of the box: the next run loses them, as LIGGGHTS does"
        ));
    }
    Ok(())
}
