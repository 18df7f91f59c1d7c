//! `fix ID group pour N type seed keyword values ...`: the particle pouring of LAMMPS and
//! LIGGGHTS 1.x (LIGGGHTS 3.8 no longer has it). Every few steps a batch of spheres is
//! placed at random in a block or z-cylinder region, until N have been inserted:
//!
//! - the batch size is the volume fraction `vol` of the region over the volume of the
//!   largest sphere, or the mean one of a `poly` mix (as LAMMPS: a block's y extent counts as at least 1 length unit, its
//!   rule for quasi-2d boxes);
//! - the interval is the time a sphere takes to fall through the region under `fix
//!   gravity` (which must point along −z), starting at the `vel` z velocity, so batches do
//!   not meet; the first batch comes at the next step;
//! - each sphere gets its x and y velocity from `vel` and the z velocity it would have
//!   reached falling from the top of the region, −√(vz² + 2 g (top − z)), as LAMMPS does;
//! - spheres lie wholly inside the region (LIGGGHTS 1.x's change to LAMMPS, which only
//!   keeps centres inside) and overlap neither each other nor existing particles, with
//!   `vol`'s attempts per sphere pooled over the batch (rdem's insertion rules);
//!
//! Syntax: LIGGGHTS 1.x's `diam|dens uniform lo hi`, `diam|dens gaussian mu sigma`, `vel
//! uniform|gaussian vx1 vx2 vy1 vy2 vz`, and LAMMPS' `diam one D`, `diam range lo hi`,
//! `diam poly N D1 P1 ...`, `diam lo hi`, `dens lo hi`, `vel vxlo vxhi vylo vyhi vz`. It
//! prints LAMMPS' line "Particle insertion: n every m steps, N by step s".

use glam::DVec3;
use rdem::insert::{
    Distribution, FallFromTop, InsertPack, PackTarget, ParticleTemplate, RadiusDist, VelocityLaw,
    Weighting,
};
use rdem::region::Shape;
use rdem::FixKind;

use super::insert::{InsertEngine, Inserter, PerInsertion, RateState};
use super::{style, FixHead, FixRow, Notes, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "pour",
    parse,
    Stages::PRE_EXCHANGE.and(Stages::VALUES),
    "`N type seed region ID`; `diam uniform\\|gaussian a b`, `diam one D\\|range lo hi\\|poly n D P ...`; `dens uniform\\|gaussian a b` or `dens lo hi`; `vol fraction attempts`; `vel [uniform\\|gaussian] vx1 vx2 vy1 vy2 vz` (LAMMPS and LIGGGHTS 1.x)",
)
.notes("batches every fall time through the region, sized by `vol` over the largest sphere's volume or a `poly` mix's mean one (a block's y extent counted as at least 1, as LAMMPS); z velocity of a fall from the region's top; spheres wholly inside the region (LIGGGHTS 1.x); only a constant density, `rate 0` and 3d; rdem's random generator");

/// The diameter law.
enum Diam {
    /// One diameter.
    One(f64),
    /// Uniform in [lo, hi] (by number).
    Range(f64, f64),
    /// Gaussian (mean, sigma).
    Gaussian(f64, f64),
    /// Diameters with number fractions.
    Poly(Vec<(f64, f64)>),
}

fn parse(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    let w = sim.world_ref(a)?;
    if sim.setup.dimension != 3 {
        return Err(a.error_at(
            STYLE_WORD,
            "fix pour in a 2d simulation is not supported yet",
            Some("use fix insert/rate/region".into()),
        ));
    }
    let n = a.count("number of particles to insert")?;
    let ty = a.count("atom type of inserted particles")? as u32;
    if ty as usize > w.materials.ntypes {
        return Err(a.error_prev(
            format!("atom type {ty} is not a type of the box"),
            Some(format!("types are 1..{}", w.materials.ntypes)),
        ));
    }
    let seed = a.u64("seed")?;
    if seed == 0 {
        return Err(a.error_prev("seed must be a positive integer", None));
    }
    let mut region = None;
    let mut diam = Diam::One(1.0);
    let mut density = 1.0;
    let (mut volfrac, mut attempts) = (0.25, 50);
    let (mut vx, mut vy, mut gaussian, mut vz) = ((0.0, 0.0), (0.0, 0.0), false, 0.0);
    while !a.is_done() {
        let kw = a.keyword(
            "fix pour keyword",
            &["region", "diam", "dens", "vol", "rate", "vel"],
        )?;
        match kw {
            "region" => {
                let at = a.pos();
                let r = sim.fixed_region(a, "fix pour")?;
                let ok = !r.outside
                    && matches!(
                        r.shape,
                        Shape::Block { .. } | Shape::Cylinder { axis: 2, .. }
                    );
                if !ok {
                    return Err(a.error_at(
                        at,
                        "fix pour needs a block region or a cylinder along z (side in)",
                        None,
                    ));
                }
                region = Some(r);
            }
            "diam" => diam = read_diam(a)?,
            "dens" => density = read_density(a)?,
            "vol" => {
                volfrac = a.f64("volume fraction")?;
                if !(volfrac > 0.0 && volfrac <= 1.0) {
                    return Err(a.error_prev("the volume fraction must be in (0, 1]", None));
                }
                attempts = a.count("attempts per particle")? as usize;
            }
            "rate" => {
                if a.f64("rate (velocity of the insertion volume)")? != 0.0 {
                    return Err(a.error_prev(
                        "fix pour: a moving insertion volume (rate other than 0) is not supported yet",
                        Some("write 'rate 0' or leave it out".into()),
                    ));
                }
            }
            "vel" => {
                gaussian = gaussian_word(a);
                vx = (a.f64("vx (low or mean)")?, a.f64("vx (high or sigma)")?);
                vy = (a.f64("vy (low or mean)")?, a.f64("vy (high or sigma)")?);
                vz = a.f64("vz")?;
            }
            _ => unreachable!(),
        }
    }
    let region = region.ok_or_else(|| {
        a.error_at(
            STYLE_WORD,
            "fix pour needs 'region ID'",
            Some("a block or a z-cylinder region".into()),
        )
    })?;
    let g = w
        .fixes
        .iter()
        .find_map(|f| match f.kind {
            FixKind::Gravity { accel } => Some(accel),
            _ => None,
        })
        .ok_or_else(|| {
            a.error_at(
                STYLE_WORD,
                "fix pour needs fix gravity (defined before it): the insertion interval is a fall time",
                None,
            )
        })?;
    if g.x != 0.0 || g.y != 0.0 || g.z >= 0.0 {
        return Err(a.error_at(
            STYLE_WORD,
            format!(
                "fix pour needs gravity along -z, not ({}, {}, {})",
                g.x, g.y, g.z
            ),
            None,
        ));
    }
    let g = -g.z;
    let (zlo, zhi, volume) = match region.shape {
        Shape::Block { lo, hi } => {
            let d = hi - lo;
            (lo.z, hi.z, d.x * d.y.max(1.0) * d.z)
        }
        Shape::Cylinder { radius, lo, hi, .. } => {
            (lo, hi, std::f64::consts::PI * radius * radius * (hi - lo))
        }
        _ => unreachable!("checked above"),
    };
    if !(zlo.is_finite() && zhi.is_finite() && volume.is_finite()) {
        return Err(a.error_at(STYLE_WORD, "fix pour needs a region of finite size", None));
    }
    let templates = templates(&head.id, seed, ty, density, &diam)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    let dist = Distribution::new(&head.id, seed, Weighting::Number, templates)
        .map_err(|e| a.error_cmd(e.to_string(), None))?;
    // The volume of one sphere: the largest (LAMMPS; a gaussian's mean + 5σ), or the
    // number-weighted mean of a `poly` mix (as LAMMPS).
    let sphere = |d: f64| std::f64::consts::PI / 6.0 * d * d * d;
    let volume_one = match &diam {
        Diam::Poly(parts) => parts.iter().map(|&(d, p)| p * sphere(d)).sum(),
        _ => sphere(2.0 * dist.max_radius()),
    };
    let per = (volfrac * volume / volume_one) as u64;
    if per == 0 {
        return Err(a.error_at(
            STYLE_WORD,
            "fix pour: not one particle fits the region at this volume fraction",
            Some("a larger region, a higher 'vol' fraction or smaller particles".into()),
        ));
    }
    // The fall time through the region: top + vz t − g t²/2 = bottom.
    let t = (vz + (vz * vz + 2.0 * g * (zhi - zlo)).sqrt()) / g;
    let every = ((t / sim.dt() + 0.5) as u64).max(1);
    let first = w.step + 1;
    let last = first + (n - 1) / per * every;
    let mut pack = InsertPack::new(
        &head.id,
        seed,
        head.groupbit,
        region,
        dist,
        PackTarget::Count(0),
        Some(every),
    )
    .map_err(|e| a.error_cmd(e.to_string(), None))?;
    pack.all_in = true;
    pack.overlap_check = true;
    pack.max_attempt = attempts;
    pack.start = Some(first);
    pack.velocity = if gaussian {
        VelocityLaw::Gaussian(DVec3::new(vx.0, vy.0, 0.0), DVec3::new(vx.1, vy.1, 0.0))
    } else {
        VelocityLaw::Uniform(
            DVec3::new(0.5 * (vx.0 + vx.1), 0.5 * (vy.0 + vy.1), 0.0),
            DVec3::new(0.5 * (vx.1 - vx.0).abs(), 0.5 * (vy.1 - vy.0).abs(), 0.0),
        )
    };
    pack.fall = Some(FallFromTop { g, top: zhi, vz });
    let mut notes = Notes::default();
    notes.line(format!(
        "Particle insertion: {per} every {every} steps, {n} by step {last}"
    ));
    Ok(Box::new(Inserter {
        pack: InsertEngine::Pack(pack),
        total: 0,
        total_mass: 0.0,
        rate: Some(RateState {
            limit: Some(n),
            per: PerInsertion::Fixed(per as f64),
            carry: 0.0,
        }),
        verbose: false,
        announce: Some(notes),
        rate_line_due: false,
        set_property: Vec::new(),
        stream_tracers: Vec::new(),
    }))
}

/// The sphere templates of the diameter law, with their number weights.
fn templates(
    id: &str,
    seed: u64,
    ty: u32,
    density: f64,
    diam: &Diam,
) -> rdem::Result<Vec<(ParticleTemplate, f64)>> {
    let one = |k: u64, r: RadiusDist| ParticleTemplate::new(id, seed + k, ty, density, r);
    Ok(match diam {
        Diam::One(d) => vec![(one(1, RadiusDist::Constant(d / 2.0))?, 1.0)],
        Diam::Range(lo, hi) => vec![(one(1, RadiusDist::Uniform(lo / 2.0, hi / 2.0))?, 1.0)],
        Diam::Gaussian(mu, s) => vec![(one(1, RadiusDist::Gaussian(mu / 2.0, s / 2.0))?, 1.0)],
        Diam::Poly(parts) => parts
            .iter()
            .enumerate()
            .map(|(k, &(d, p))| Ok((one(k as u64 + 1, RadiusDist::Constant(d / 2.0))?, p)))
            .collect::<rdem::Result<_>>()?,
    })
}

/// `diam uniform lo hi | gaussian mu sigma | one D | range lo hi | poly N D P ... | lo hi`.
fn read_diam(a: &mut Args) -> CmdResult<Diam> {
    let style = a.peek().unwrap_or("");
    let d = match style {
        "uniform" | "range" => {
            a.seek(a.pos() + 1);
            diam_range(a)?
        }
        "gaussian" => {
            a.seek(a.pos() + 1);
            Diam::Gaussian(
                a.positive("mean diameter")?,
                a.non_negative("diameter sigma")?,
            )
        }
        "one" => {
            a.seek(a.pos() + 1);
            Diam::One(a.positive("diameter")?)
        }
        "poly" => {
            a.seek(a.pos() + 1);
            let k = a.count("number of diameters")?;
            let mut parts = Vec::new();
            for _ in 0..k {
                parts.push((a.positive("diameter")?, a.positive("fraction")?));
            }
            let sum: f64 = parts.iter().map(|p| p.1).sum();
            if (sum - 1.0).abs() > 1e-6 {
                return Err(a.error_prev(format!("the poly fractions sum to {sum}, not 1"), None));
            }
            Diam::Poly(parts)
        }
        _ => diam_range(a)?,
    };
    Ok(d)
}

/// `lo hi` of a uniform diameter law.
fn diam_range(a: &mut Args) -> CmdResult<Diam> {
    let lo = a.positive("smallest diameter")?;
    let hi = a.positive("largest diameter")?;
    if hi < lo {
        return Err(a.error_prev("the largest diameter is below the smallest", None));
    }
    Ok(Diam::Range(lo, hi))
}

/// Reads an optional `uniform` or `gaussian` law word (LIGGGHTS 1.x); true for
/// `gaussian`. Without one the values are LAMMPS' (a uniform range).
fn gaussian_word(a: &mut Args) -> bool {
    let law = a.peek();
    let gaussian = law == Some("gaussian");
    if gaussian || law == Some("uniform") {
        a.seek(a.pos() + 1);
    }
    gaussian
}

/// `dens uniform lo hi | gaussian mu sigma | lo hi`: only one density is supported.
fn read_density(a: &mut Args) -> CmdResult<f64> {
    let at = a.pos() - 1;
    let gaussian = gaussian_word(a);
    let first = a.positive("density")?;
    let second = if gaussian {
        a.non_negative("density sigma")?
    } else {
        a.positive("density")?
    };
    let constant = if gaussian {
        second == 0.0
    } else {
        second == first
    };
    if !constant {
        return Err(a.error_at(
            at,
            "fix pour: a spread of densities is not supported yet (only one density)",
            Some(format!("write 'dens {first} {first}'")),
        ));
    }
    Ok(first)
}
