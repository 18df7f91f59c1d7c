//! `fix insert/pack`: at each insertion step, insert as many particles as needed to bring
//! the region to a target volume fraction, particle count or mass, at random positions
//! (whole spheres inside the region with `all_in yes`), without overlaps (with
//! `overlapcheck yes`; `maxattempt` tries per particle, pooled over one insertion as
//! LIGGGHTS does), largest templates first.

use glam::DVec3;
use rand::Rng;

use super::place::{add_placed, choose, OverlapGrid, TagCursor};
use super::{Distribution, InsertRng};
use crate::error::{check, Error, Result};
use crate::region::Region;
use crate::world::World;

/// What the region is filled to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PackTarget {
    /// `volumefraction_region f`.
    VolumeFraction(f64),
    /// `particles_in_region n`.
    Count(u64),
    /// `mass_in_region m`.
    Mass(f64),
}

/// Initial velocity of inserted particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VelocityLaw {
    /// `vel constant vx vy vz`.
    Constant(DVec3),
    /// `vel uniform vx vy vz dvx dvy dvz`: mean ± half-width per component.
    Uniform(DVec3, DVec3),
    /// `vel gaussian vx vy vz sx sy sz`.
    Gaussian(DVec3, DVec3),
}

/// How inserted clumps are turned (`orientation`; spheres ignore it).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Orientation {
    /// `orientation random`: uniform over all rotations.
    Random,
    /// `orientation template`: as the template's spheres were given. The default, as in
    /// LIGGGHTS 3.8 (its manual names none; three dumbbells inserted by `insert/pack`
    /// without the keyword all had the template's orientation, measured).
    #[default]
    Template,
    /// `orientation constant q0 q1 q2 q3`: this rotation of the template as given.
    Constant(glam::DQuat),
}

/// `fix pour`'s vertical velocity: each particle gets the speed it would have reached
/// falling from the top of the insertion volume, at height `top`, with initial vertical
/// speed `vz`, under gravity `g` (> 0, along −z): v_z = −√(vz² + 2 g (top − z)) (as LAMMPS'
/// fix pour does).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FallFromTop {
    /// Gravity's magnitude.
    pub g: f64,
    /// Top of the insertion volume.
    pub top: f64,
    /// Vertical velocity at the top.
    pub vz: f64,
}

/// What one insertion did (LIGGGHTS prints the same two numbers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InsertReport {
    /// Particles the target asked for.
    pub wanted: u64,
    /// Particles inserted.
    pub inserted: u64,
    /// Their total mass.
    pub mass: f64,
}

/// Settings and state of one `fix insert/pack`.
#[derive(Debug, Clone)]
pub struct InsertPack {
    /// Fix ID.
    pub id: String,
    /// Group bits given to inserted particles (besides `all`).
    pub groupbit: u32,
    /// Insertion region.
    pub region: Region,
    /// Particle mix.
    pub dist: Distribution,
    /// Fill target.
    pub target: PackTarget,
    /// `insert_every N`, or `None` for `once`.
    pub every: Option<u64>,
    /// First insertion step (`start`; default: the first step of the run).
    pub start: Option<u64>,
    /// `overlapcheck yes`.
    pub overlap_check: bool,
    /// `all_in yes`.
    pub all_in: bool,
    /// `maxattempt`.
    pub max_attempt: usize,
    /// Velocity law.
    pub velocity: VelocityLaw,
    /// Angular velocity (`omega constant wx wy wz`).
    pub omega: DVec3,
    /// How clumps are turned.
    pub orientation: Orientation,
    /// `fix pour`: the vertical velocity is that of a fall from the top (replaces the
    /// velocity law's z component).
    pub fall: Option<FallFromTop>,
    /// LIGGGHTS-PFM's `pos x y z`: every try puts the particle (a template's centre)
    /// there, so that with the overlap check one particle is inserted (measured in the
    /// fork: `particles_in_region 2 pos ...` inserts one template, unturned).
    pub position: Option<DVec3>,
    rng: InsertRng,
    last: Option<u64>,
    /// The thin-subdomain warning was given.
    warned_extent: bool,
}

impl InsertPack {
    /// An insertion fix after checking its numbers; `seed` seeds its generator.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        id: &str,
        seed: u64,
        groupbit: u32,
        region: Region,
        dist: Distribution,
        target: PackTarget,
        every: Option<u64>,
    ) -> Result<Self> {
        match target {
            PackTarget::VolumeFraction(f) => {
                check(
                    "volumefraction_region",
                    f,
                    f > 0.0 && f < 1.0,
                    "must be in (0, 1)",
                )?;
            }
            PackTarget::Mass(m) => {
                check("mass_in_region", m, m > 0.0, "must be > 0")?;
            }
            PackTarget::Count(_) => {}
        }
        if every == Some(0) {
            return Err(Error::Invalid {
                what: "insert_every",
                reason: "must be 'once' or >= 1".into(),
            });
        }
        Ok(Self {
            id: id.to_string(),
            groupbit,
            region,
            dist,
            target,
            every,
            start: None,
            overlap_check: true,
            all_in: false,
            max_attempt: 50,
            velocity: VelocityLaw::Constant(DVec3::ZERO),
            omega: DVec3::ZERO,
            orientation: Orientation::Template,
            fall: None,
            position: None,
            rng: super::rng(seed),
            last: None,
            warned_extent: false,
        })
    }

    /// True if an insertion is due at `step`.
    pub fn due(&self, step: u64) -> bool {
        let start = self.start.unwrap_or(step);
        if step < start {
            return false;
        }
        match (self.every, self.last) {
            (None, Some(_)) => false,
            (None, None) => true,
            (Some(_), None) => true,
            (Some(n), Some(last)) => step >= last + n,
        }
    }

    /// Inserts into `world` at its current step (call when [`InsertPack::due`]).
    pub fn insert(&mut self, world: &mut World) -> Result<InsertReport> {
        self.last = Some(world.step);
        let domain = (world.domain.boxlo, world.domain.boxhi);
        // What is already there (centres in the region).
        let p = &world.particles;
        let n = p.nlocal();
        let (mut have_n, mut have_m, mut have_v) = (0u64, 0.0, 0.0);
        for i in 0..n {
            if self.region.contains(p.x[i]) {
                have_n += 1;
                have_m += p.rmass[i];
                have_v += p.rmass[i] / p.density[i];
            }
        }
        let have_n = world.comm.sum_count(have_n);
        let have_m = world.comm.sum(have_m);
        let have_v = world.comm.sum(have_v);
        // How many to add, and how full the region already is (a fraction of the
        // target: the count, mass or volume there over the one asked for).
        let (wanted, filled) = match self.target {
            PackTarget::Count(c) => (c.saturating_sub(have_n), have_n as f64 / c as f64),
            // Fractional counts round up with probability equal to the fraction, as in
            // LIGGGHTS: the expected mass or volume is then exactly the target.
            PackTarget::Mass(m) => {
                let u: f64 = self.rng.gen();
                let n = ((m - have_m) / self.dist.mean_particle_mass() + u)
                    .floor()
                    .max(0.0) as u64;
                (n, have_m / m)
            }
            PackTarget::VolumeFraction(f) => {
                let rng = &mut self.rng;
                let vol = self.region.volume(domain, 1_000_000, || rng.gen());
                let u: f64 = rng.gen();
                let n = ((f * vol - have_v) / self.dist.mean_particle_volume() + u)
                    .floor()
                    .max(0.0) as u64;
                (n, have_v / (f * vol))
            }
        };
        let (inserted, mass) = self.place(world, wanted, filled)?;
        Ok(InsertReport {
            wanted,
            inserted,
            mass,
        })
    }

    /// Inserts `n` particles into the region regardless of what it holds
    /// (`fix insert/rate/region`); the same placement rules as [`InsertPack::insert`].
    pub fn insert_n(&mut self, world: &mut World, n: u64) -> Result<InsertReport> {
        self.last = Some(world.step);
        let (inserted, mass) = self.place(world, n, 0.0)?;
        Ok(InsertReport {
            wanted: n,
            inserted,
            mass,
        })
    }

    /// Places up to `wanted` particles into a region already `filled` (a fraction of the
    /// target, 0 for `insert/rate/region`); returns how many and their mass.
    ///
    /// The tries are `maxattempt` per particle, divided by 1 − `filled`: a region that is
    /// already half full gets twice the tries per particle, since a random point there
    /// finds room half as often. LIGGGHTS 3.8 does so (its manual names only the
    /// `maxattempt` per particle; measured on the tutorial movingMeshGran, where the later
    /// waves fill a half-full region: LIGGGHTS with `maxattempt 25` ends with 1299
    /// particles, rdem without the division and `maxattempt 50` with 1294, LIGGGHTS
    /// with 100 with 1377).
    fn place(&mut self, world: &mut World, wanted: u64, filled: f64) -> Result<(u64, f64)> {
        let domain = (world.domain.boxlo, world.domain.boxhi);
        // Seed 000: a subdomain thinner than 2.2 bounding radii along some axis makes the
        // insertion unreliable across its faces.
        let (ext, axis) = world.domain.min_subbox_extent();
        let rbound = self.dist.max_radius();
        if world.comm.size() > 1 && ext < 2.2 * rbound && !self.warned_extent {
            self.warned_extent = true;
            world.warnings.push(format!(
                "insertion: the subdomain extent along {} ({ext}) is less than 2.2 times the \
                 largest particle radius ({rbound}); use fewer processors along that axis",
                ["x", "y", "z"][axis]
            ));
        }
        let mut grid = self
            .overlap_check
            .then(|| OverlapGrid::gather(world, self.region.bounding_box(), rbound));
        let region = &self.region;
        let all_in = self.all_in;
        let position = self.position;
        // A try is a position where the sphere fits the region (LIGGGHTS draws from the
        // region shrunk by the radius), so positions too close to the boundary are drawn
        // again without using up a try. Whatever `all_in` says, the centre is drawn at
        // least one (bounding) radius inside every face of the box, so that the whole
        // sphere or clump starts in the box: LIGGGHTS 3.8 does so (measured: spheres of
        // radius 1 mm drawn in a region as large as the box have their centres within
        // ±(L/2 − 1 mm), on fixed and periodic faces alike; ten-sphere clumps keep their
        // bounding sphere in the box).
        let budget = tries(wanted, self.max_attempt, filled);
        let mut placed = choose(
            &mut self.dist,
            &mut self.rng,
            wanted,
            budget,
            grid.as_mut(),
            self.orientation,
            |rng, r| {
                if position.is_some() {
                    return position;
                }
                for _ in 0..1000 {
                    let inside = (domain.0 + DVec3::splat(r), domain.1 - DVec3::splat(r));
                    match region.sample(inside, || rng.gen(), 1000) {
                        Some(y) if !all_in || region.contains_sphere(y, r) => return Some(y),
                        Some(_) => {}
                        None => return None,
                    }
                }
                None
            },
            self.velocity,
        );
        if let Some(f) = self.fall {
            for pl in &mut placed {
                pl.v.z = -(f.vz * f.vz + 2.0 * f.g * (f.top - pl.x.z)).max(0.0).sqrt();
            }
        }
        let (mut inserted, mut mass) = (0u64, 0.0);
        let mut tags = TagCursor::new(world);
        for pl in &placed {
            mass += add_placed(world, &self.dist, pl, self.omega, self.groupbit, &mut tags)?.0;
            inserted += 1;
        }
        world.extend_tags();
        Ok((inserted, mass))
    }
}

/// The tries an insertion of `wanted` particles may make in all: `max_attempt` per
/// particle, divided by 1 − `filled` (the fraction of the target already in the region;
/// see [`InsertPack::place`]).
fn tries(wanted: u64, max_attempt: usize, filled: f64) -> u64 {
    let tries = wanted.saturating_mul(max_attempt.max(1) as u64);
    if (0.0..1.0).contains(&filled) {
        (tries as f64 / (1.0 - filled)) as u64
    } else {
        tries
    }
}

impl InsertPack {
    /// Where the fix stands (restart files).
    pub fn progress(&self) -> super::InsertProgress {
        super::InsertProgress {
            rng: self.rng.clone(),
            dist: self.dist.rngs(),
            last: self.last,
            start: self.start,
            inserted: 0,
        }
    }

    /// Takes back what [`InsertPack::progress`] gave; false if it belongs to another
    /// distribution.
    pub fn set_progress(&mut self, p: &super::InsertProgress) -> bool {
        if !self.dist.set_rngs(&p.dist) {
            return false;
        }
        self.rng = p.rng.clone();
        self.last = p.last;
        self.start = p.start;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::insert::{ParticleTemplate, RadiusDist, Weighting};
    use crate::region::Shape;
    use crate::{Boundary, Domain};

    fn setup(target: PackTarget, all_in: bool) -> (World, InsertPack) {
        let w = World::new(
            Domain::new(
                DVec3::new(-0.05, -0.05, 0.0),
                DVec3::new(0.05, 0.05, 0.06),
                [Boundary::Fixed; 3],
            )
            .unwrap(),
        );
        let t1 = ParticleTemplate::new("pts1", 15485863, 1, 2500.0, RadiusDist::Constant(0.0015))
            .unwrap();
        let t2 = ParticleTemplate::new("pts2", 15485867, 1, 2500.0, RadiusDist::Constant(0.002))
            .unwrap();
        let d = Distribution::new(
            "pdd1",
            32452843,
            Weighting::Mass,
            vec![(t1, 0.3), (t2, 0.7)],
        )
        .unwrap();
        let reg = Region::new(Shape::Block {
            lo: DVec3::new(-0.05, -0.05, 0.0),
            hi: DVec3::new(0.05, 0.05, 0.06),
        })
        .unwrap();
        let mut ins = InsertPack::new("ins", 32452867, 0, reg, d, target, None).unwrap();
        ins.all_in = all_in;
        ins.max_attempt = 200;
        (w, ins)
    }

    /// The try budget grows as the region fills: twice the tries at half full, four
    /// times at three quarters; an empty or overfull region gets `maxattempt` each.
    #[test]
    fn tries_grow_with_the_filled_fraction() {
        assert_eq!(tries(10, 50, 0.0), 500);
        assert_eq!(tries(10, 50, 0.5), 1000);
        assert_eq!(tries(10, 50, 0.75), 2000);
        assert_eq!(tries(10, 50, 1.0), 500);
        assert_eq!(tries(10, 50, 1.5), 500);
        assert_eq!(tries(10, 0, 0.5), 20);
    }

    /// in.dense's insertion at a feasible 25 %: the requested volume fraction is reached
    /// (within one particle), every sphere lies inside the box, none overlap, and the
    /// number split follows the 30/70 mass mix.
    #[test]
    fn fills_to_a_volume_fraction_without_overlaps() {
        let (mut w, mut ins) = setup(PackTarget::VolumeFraction(0.25), true);
        assert!(ins.due(0));
        let rep = ins.insert(&mut w).unwrap();
        assert_eq!(rep.inserted, rep.wanted, "{rep:?}");
        let p = &w.particles;
        let vol: f64 = (0..p.nlocal()).map(|i| p.rmass[i] / p.density[i]).sum();
        let box_vol = 0.1 * 0.1 * 0.06;
        assert!(
            (vol / box_vol - 0.25).abs()
                < 4.0 / 3.0 * std::f64::consts::PI * 0.002f64.powi(3) / box_vol
        );
        for i in 0..p.nlocal() {
            let r = p.radius[i];
            assert!(w.domain.is_in_domain(p.x[i] - r) && w.domain.is_in_domain(p.x[i] + r));
            for j in i + 1..p.nlocal() {
                assert!((p.x[i] - p.x[j]).length() >= r + p.radius[j]);
            }
        }
        let small =
            (0..p.nlocal()).filter(|&i| p.radius[i] < 0.0017).count() as f64 / p.nlocal() as f64;
        assert!((small - 0.5039).abs() < 0.001, "{small}");
        assert!(w.particles.check_tags_consecutive().is_ok());
        // `once`: not due again.
        assert!(!ins.due(1));
        // Masses add up.
        assert!((rep.mass - p.rmass.iter().sum::<f64>()).abs() < 1e-12);
    }

    /// Across a periodic boundary: a dense fill of a slab at the lower x face of a box
    /// periodic in x and y, next to particles at the upper x face, overlaps none of
    /// them through the boundary (minimum-image distances), nor itself.
    #[test]
    fn periodic_images_are_checked() {
        let (lo, hi) = (DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.02, 0.02, 0.02));
        let periodic = [Boundary::Periodic, Boundary::Periodic, Boundary::Fixed];
        let mut w = World::new(Domain::new(lo, hi, periodic).unwrap());
        let r = 0.001;
        // A wall of spheres whose centres sit half a radius inside the upper x face.
        for j in 0..10 {
            for k in 0..10 {
                let x = DVec3::new(
                    0.02 - 0.5 * r,
                    0.001 + 0.002 * j as f64,
                    0.001 + 0.002 * k as f64,
                );
                w.add_particle(&crate::NewParticle::at(x, r, 2500.0))
                    .unwrap();
            }
        }
        w.extend_tags();
        let t = ParticleTemplate::new("t", 15485863, 1, 2500.0, RadiusDist::Constant(r)).unwrap();
        let d = Distribution::new("d", 32452843, Weighting::Number, vec![(t, 1.0)]).unwrap();
        let reg = Region::new(Shape::Block {
            lo: DVec3::new(0.0, 0.0, 0.0),
            hi: DVec3::new(0.004, 0.02, 0.02),
        })
        .unwrap();
        let mut ins =
            InsertPack::new("ins", 32452867, 0, reg, d, PackTarget::Count(100), None).unwrap();
        ins.max_attempt = 1000;
        let rep = ins.insert(&mut w).unwrap();
        assert!(rep.inserted > 50, "{rep:?}");
        let p = &w.particles;
        let n = p.nlocal();
        let mut closest = f64::INFINITY;
        for i in 0..n {
            for j in i + 1..n {
                let mut dx = p.x[i] - p.x[j];
                for a in 0..2 {
                    dx[a] -= 0.02 * (dx[a] / 0.02).round();
                }
                closest = closest.min(dx.length() - p.radius[i] - p.radius[j]);
            }
        }
        // Touching is allowed; rounding of the image shift is 1e-18 here.
        assert!(
            closest >= -1e-15,
            "overlap of {} through the boundary",
            -closest
        );
    }

    #[test]
    fn counts_and_masses_top_up() {
        let (mut w, mut ins) = setup(PackTarget::Count(300), false);
        ins.every = Some(100);
        assert_eq!(ins.insert(&mut w).unwrap().inserted, 300);
        w.step = 50;
        assert!(!ins.due(50));
        w.step = 100;
        assert!(ins.due(100));
        assert_eq!(ins.insert(&mut w).unwrap().wanted, 0, "already full");
        let (mut w, mut ins) = setup(PackTarget::Mass(0.01), false);
        let rep = ins.insert(&mut w).unwrap();
        assert!((rep.mass - 0.01).abs() < 8.4e-5, "{rep:?}"); // within one large sphere
    }

    #[test]
    fn bad_settings_are_refused() {
        let (_, ins) = setup(PackTarget::Count(1), false);
        for t in [
            PackTarget::VolumeFraction(0.0),
            PackTarget::VolumeFraction(1.2),
            PackTarget::Mass(-1.0),
        ] {
            assert!(
                InsertPack::new("i", 1, 0, ins.region.clone(), ins.dist.clone(), t, None).is_err()
            );
        }
        assert!(InsertPack::new(
            "i",
            1,
            0,
            ins.region.clone(),
            ins.dist.clone(),
            PackTarget::Count(1),
            Some(0)
        )
        .is_err());
    }
}
