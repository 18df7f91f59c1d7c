//! `fix particletemplate/sphere`: the type, density and radius law of inserted spheres;
//! `fix particletemplate/multisphere`: a rigid clump's shape in place of the radius law.

use std::sync::Arc;

use glam::{DQuat, DVec3};
use rand::Rng;
use rand_distr::{Distribution as _, Normal};

use super::InsertRng;
use crate::error::{check, Error, Result};

/// How a template draws radii.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RadiusDist {
    /// `radius constant r`.
    Constant(f64),
    /// `radius uniform lo hi`.
    Uniform(f64, f64),
    /// `radius gaussian mu sigma`, redrawn until positive.
    Gaussian(f64, f64),
    /// `radius gaussian number mu sigma` (the forks' form): redrawn until within three
    /// standard deviations of the mean (which must leave it positive).
    GaussianWithin3(f64, f64),
    /// `radius lognormal number mu sigma` (the forks'): exp(mu + sigma N), redrawn until
    /// N is within three standard deviations.
    Lognormal(f64, f64),
}

/// The shape of a multisphere template: the clump, and the flags its bodies start with.
#[derive(Debug, Clone, PartialEq)]
pub struct ClumpShape {
    /// The spheres and mass properties.
    pub template: crate::multisphere::ClumpTemplate,
    /// `fflag`: the translational degrees of freedom (x, y, z) that move.
    pub fflag: [bool; 3],
    /// `tflag`: the rotational degrees of freedom (x, y, z) that move.
    pub tflag: [bool; 3],
    /// The template's multisphere type (`type MT`, from 1).
    pub clump_type: u32,
    /// True for a rigid body (`particletemplate/multisphere`); false for
    /// `particletemplate/multiplespheres`, whose spheres are inserted as separate
    /// particles (placed as the clump would be; each sphere's mass from the density).
    pub rigid: bool,
    /// Bonds between the spheres of a non-rigid template (the forks' `bonded yes`):
    /// (sphere, sphere, bond type), spheres counted from 0.
    pub bonds: Vec<(u32, u32, u32)>,
    /// LIGGGHTS-INL's `bonded yes` without bond atoms: the spheres of each inserted copy
    /// share a [`crate::bond::RANDOM_ID`] value, which lets `cohesion bond` bond them at
    /// the step they are inserted.
    pub random_bond_id: bool,
    /// `relative yes` (LIGGGHTS-INL): positions and radii are in units of the bounding
    /// radius of what `fix insert/fragments` replaces; no other insertion takes it.
    pub relative: bool,
    /// Each sphere's atom type (LIGGGHTS-INL's `spheres_different_types`), in the order
    /// of [`crate::multisphere::ClumpTemplate::spheres`]; empty: the template's type.
    pub sphere_types: Vec<u32>,
    /// Each sphere's centre as given, from the centre of the spheres' bounding sphere
    /// ([`crate::multisphere::template::enclosing_sphere`]), in the frame the spheres
    /// were given in: where `create_particles` puts them about its point (LIGGGHTS-INL
    /// computes them so; a zero stays exactly zero, so spheres given touching stay
    /// exactly touching). Empty for a rigid template.
    pub bound_offsets: Vec<DVec3>,
}

impl ClumpShape {
    /// The atom type of sphere `k`, when the template gives each sphere its own.
    pub fn sphere_type(&self, k: usize) -> Option<u32> {
        self.sphere_types.get(k).copied()
    }

    /// The orientation (body frame to space frame) that shows the clump as its spheres
    /// were given (`orientation template`).
    pub fn q_template(&self) -> DQuat {
        DQuat::from_mat3(&self.template.axes).normalize()
    }
}

/// A particle template: a sphere's radius law, or a clump's shape.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticleTemplate {
    /// Fix ID of the template.
    pub id: String,
    /// Atom type of inserted particles.
    pub ty: u32,
    /// Density (`density constant ρ`).
    pub density: f64,
    /// Radius law (a clump: its bounding radius, constant).
    pub radius: RadiusDist,
    /// A multisphere template's clump (`None`: spheres).
    pub clump: Option<Arc<ClumpShape>>,
    /// Groups its particles join besides the inserting fix's (the template fix's group,
    /// as LIGGGHTS 3.8 adds it).
    pub groupbit: u32,
    pub(crate) rng: InsertRng,
}

impl ParticleTemplate {
    /// A template after checking its numbers; `seed` seeds its own generator.
    pub fn new(id: &str, seed: u64, ty: u32, density: f64, radius: RadiusDist) -> Result<Self> {
        if ty == 0 {
            return Err(Error::Invalid {
                what: "atom_type",
                reason: "types start at 1".into(),
            });
        }
        check("density", density, density > 0.0, "must be > 0")?;
        match radius {
            RadiusDist::Constant(r) => {
                check("radius", r, r > 0.0, "must be > 0")?;
            }
            RadiusDist::Uniform(lo, hi) => {
                check("radius lower bound", lo, lo > 0.0, "must be > 0")?;
                check(
                    "radius upper bound",
                    hi,
                    hi >= lo,
                    "must be >= the lower bound",
                )?;
            }
            RadiusDist::GaussianWithin3(mu, sigma) => {
                check(
                    "radius standard deviation",
                    sigma,
                    sigma >= 0.0,
                    "must be >= 0",
                )?;
                check(
                    "radius mean",
                    mu,
                    mu - 3.0 * sigma > 0.0,
                    "must be more than 3 standard deviations (the radii are drawn within 3 of them)",
                )?;
            }
            RadiusDist::Lognormal(mu, sigma) => {
                check("log-radius mean", mu, mu.is_finite(), "must be finite")?;
                check(
                    "log-radius standard deviation",
                    sigma,
                    sigma >= 0.0 && sigma.is_finite(),
                    "must be >= 0",
                )?;
            }
            RadiusDist::Gaussian(mu, sigma) => {
                check("radius mean", mu, mu > 0.0, "must be > 0")?;
                check(
                    "radius standard deviation",
                    sigma,
                    sigma >= 0.0 && sigma < mu,
                    "must be >= 0 and below the mean",
                )?;
            }
        }
        Ok(Self {
            id: id.to_string(),
            ty,
            density,
            radius,
            clump: None,
            groupbit: 0,
            rng: super::rng(seed),
        })
    }

    /// A multisphere template of `shape`, its spheres of type `ty`. `density` is the
    /// clump's mass over its volume (the volume inserted per clump is its mass over it).
    pub fn clump(id: &str, seed: u64, ty: u32, density: f64, shape: ClumpShape) -> Result<Self> {
        let bound = shape.template.bound_radius;
        let mut t = Self::new(id, seed, ty, density, RadiusDist::Constant(bound))?;
        t.clump = Some(Arc::new(shape));
        Ok(t)
    }

    /// Draws one radius.
    pub fn draw_radius(&mut self) -> f64 {
        match self.radius {
            RadiusDist::Constant(r) => r,
            RadiusDist::Uniform(lo, hi) => {
                if hi > lo {
                    self.rng.gen_range(lo..hi)
                } else {
                    lo
                }
            }
            RadiusDist::Gaussian(mu, sigma) => {
                if sigma == 0.0 {
                    return mu;
                }
                let n = Normal::new(mu, sigma).expect("validated in new");
                loop {
                    let r = n.sample(&mut self.rng);
                    if r > 0.0 {
                        return r;
                    }
                }
            }
            RadiusDist::GaussianWithin3(mu, sigma) => mu + sigma * self.normal_within3(sigma),
            RadiusDist::Lognormal(mu, sigma) => (mu + sigma * self.normal_within3(sigma)).exp(),
        }
    }

    /// A standard normal number within [-3, 3] (0 when `sigma` is 0).
    fn normal_within3(&mut self, sigma: f64) -> f64 {
        if sigma == 0.0 {
            return 0.0;
        }
        loop {
            let z: f64 = self.rng.sample(rand_distr::StandardNormal);
            if z.abs() <= 3.0 {
                return z;
            }
        }
    }

    /// Mean mass of one particle (a clump: its mass; to convert mass fractions to number fractions): exact
    /// for constant and uniform radii; for gaussian from E[r³] = μ³ + 3μσ² (ignoring the
    /// redraw of non-positive radii, negligible for σ < μ/3).
    pub fn mean_mass(&self) -> f64 {
        if let Some(c) = &self.clump {
            return c.template.props.mass;
        }
        let r3 = match self.radius {
            RadiusDist::Constant(r) => r * r * r,
            RadiusDist::Uniform(lo, hi) => {
                if hi > lo {
                    (hi.powi(4) - lo.powi(4)) / (4.0 * (hi - lo))
                } else {
                    lo.powi(3)
                }
            }
            // As the forks estimate it (the truncation at 3σ left out: 0.3 % of draws).
            RadiusDist::Gaussian(mu, s) | RadiusDist::GaussianWithin3(mu, s) => {
                mu * mu * mu + 3.0 * mu * s * s
            }
            RadiusDist::Lognormal(mu, s) => (3.0 * mu + 4.5 * s * s).exp(),
        };
        self.density * 4.0 / 3.0 * std::f64::consts::PI * r3
    }

    /// Largest radius it can produce (for bounding checks); gaussian: mean + 5σ.
    pub fn max_radius(&self) -> f64 {
        match self.radius {
            RadiusDist::Constant(r) => r,
            RadiusDist::Uniform(_, hi) => hi,
            RadiusDist::Gaussian(mu, s) => mu + 5.0 * s,
            RadiusDist::GaussianWithin3(mu, s) => mu + 3.0 * s,
            RadiusDist::Lognormal(mu, s) => (mu + 3.0 * s).exp(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The forks' `gaussian number` and `lognormal number`: every draw within 3σ (of r,
    /// of ln r), the means and spreads of the truncated laws (a normal cut at ±3σ keeps
    /// its mean and 98.7 % of its σ), and the mean mass from E[r³] as the forks give it.
    #[test]
    fn forks_gaussian_and_lognormal_stay_within_three_sigma() {
        let n = 20_000;
        let (mu, s) = (0.008, 0.0025);
        let mut g =
            ParticleTemplate::new("g", 15485863, 1, 1000.0, RadiusDist::GaussianWithin3(mu, s))
                .unwrap();
        let rs: Vec<f64> = (0..n).map(|_| g.draw_radius()).collect();
        assert!(rs.iter().all(|&r| (r - mu).abs() <= 3.0 * s + 1e-15));
        let m = rs.iter().sum::<f64>() / n as f64;
        let sd = (rs.iter().map(|r| (r - m).powi(2)).sum::<f64>() / n as f64).sqrt();
        assert!((m - mu).abs() < 3.0 * s / (n as f64).sqrt(), "{m}");
        assert!((sd / (0.9865 * s) - 1.0).abs() < 0.03, "{sd}");
        assert_eq!(g.max_radius(), mu + 3.0 * s);
        let want = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * mu * (mu * mu + 3.0 * s * s);
        assert!((g.mean_mass() / want - 1.0).abs() < 1e-12);
        let (lm, ls) = ((0.002f64).ln(), 0.2);
        let mut l =
            ParticleTemplate::new("l", 32452843, 1, 1000.0, RadiusDist::Lognormal(lm, ls)).unwrap();
        let ln: Vec<f64> = (0..n).map(|_| l.draw_radius().ln()).collect();
        assert!(ln.iter().all(|&x| (x - lm).abs() <= 3.0 * ls + 1e-12));
        let m = ln.iter().sum::<f64>() / n as f64;
        assert!((m - lm).abs() < 3.0 * ls / (n as f64).sqrt(), "{m}");
        assert!((l.max_radius() - (lm + 3.0 * ls).exp()).abs() < 1e-15);
        // A mean within 3σ of zero is refused, as the forks refuse it.
        assert!(
            ParticleTemplate::new("x", 7, 1, 1.0, RadiusDist::GaussianWithin3(0.002, 0.001))
                .is_err()
        );
    }

    #[test]
    fn radii_follow_their_law() {
        let mut c =
            ParticleTemplate::new("t", 15485863, 1, 2500.0, RadiusDist::Constant(0.002)).unwrap();
        assert_eq!(c.draw_radius(), 0.002);
        let mut u =
            ParticleTemplate::new("u", 15485867, 1, 2500.0, RadiusDist::Uniform(0.001, 0.003))
                .unwrap();
        let n = 20_000;
        let rs: Vec<f64> = (0..n).map(|_| u.draw_radius()).collect();
        assert!(rs.iter().all(|&r| (0.001..0.003).contains(&r)));
        let mean = rs.iter().sum::<f64>() / n as f64;
        // Uniform on [1, 3] mm: mean 2 mm, σ of the mean 0.577 mm/√n.
        assert!(
            (mean - 0.002).abs() < 3.0 * 0.000577 / (n as f64).sqrt(),
            "{mean}"
        );
        let mut g = ParticleTemplate::new(
            "g",
            32452843,
            2,
            2500.0,
            RadiusDist::Gaussian(0.002, 0.0002),
        )
        .unwrap();
        let gs: Vec<f64> = (0..n).map(|_| g.draw_radius()).collect();
        let gm = gs.iter().sum::<f64>() / n as f64;
        let gv = gs.iter().map(|r| (r - gm).powi(2)).sum::<f64>() / n as f64;
        assert!(
            (gm - 0.002).abs() < 3.0 * 0.0002 / (n as f64).sqrt(),
            "{gm}"
        );
        assert!((gv.sqrt() - 0.0002).abs() < 0.05 * 0.0002, "{}", gv.sqrt());
        // Same seed, same sequence.
        let mut a = ParticleTemplate::new("a", 7, 1, 1.0, RadiusDist::Uniform(1.0, 2.0)).unwrap();
        let mut b = ParticleTemplate::new("b", 7, 1, 1.0, RadiusDist::Uniform(1.0, 2.0)).unwrap();
        assert_eq!(a.draw_radius(), b.draw_radius());
    }

    #[test]
    fn mean_mass_matches_sampling() {
        let mut u =
            ParticleTemplate::new("u", 3, 1, 1000.0, RadiusDist::Uniform(0.001, 0.003)).unwrap();
        let n = 50_000;
        let m: f64 = (0..n)
            .map(|_| 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * u.draw_radius().powi(3))
            .sum::<f64>()
            / n as f64;
        assert!(
            (m / u.mean_mass() - 1.0).abs() < 0.01,
            "{m} vs {}",
            u.mean_mass()
        );
    }

    #[test]
    fn bad_templates_are_refused() {
        assert!(ParticleTemplate::new("t", 1, 0, 2500.0, RadiusDist::Constant(0.002)).is_err());
        assert!(ParticleTemplate::new("t", 1, 1, 0.0, RadiusDist::Constant(0.002)).is_err());
        assert!(ParticleTemplate::new("t", 1, 1, 2500.0, RadiusDist::Constant(-1.0)).is_err());
        assert!(
            ParticleTemplate::new("t", 1, 1, 2500.0, RadiusDist::Uniform(0.003, 0.001)).is_err()
        );
        assert!(
            ParticleTemplate::new("t", 1, 1, 2500.0, RadiusDist::Gaussian(0.001, 0.002)).is_err()
        );
        assert!(
            ParticleTemplate::new("t", 1, 1, 2500.0, RadiusDist::Gaussian(f64::NAN, 0.0)).is_err()
        );
    }
}
