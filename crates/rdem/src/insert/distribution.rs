//! `fix particledistribution/discrete[/massbased|/numberbased]`: a mix of templates by
//! mass or number fraction. Weights are normalised (with a warning when they do not sum
//! to 1, as LIGGGHTS), templates are ordered largest first (LIGGGHTS inserts large
//! particles first), and a count of particles to insert is split over the templates
//! exactly (largest remainder).

use rand::Rng;

use super::{InsertRng, ParticleTemplate};
use crate::error::{check, Error, Result};

/// What the weights mean.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Weighting {
    /// Mass fractions (`discrete`, `discrete/massbased`).
    Mass,
    /// Number fractions (`discrete/numberbased`).
    Number,
}

/// A discrete distribution of templates.
#[derive(Debug, Clone)]
pub struct Distribution {
    /// Fix ID.
    pub id: String,
    /// Templates, largest first.
    pub templates: Vec<ParticleTemplate>,
    /// Number fraction of each template (sums to 1).
    pub number_fraction: Vec<f64>,
    /// Mass fraction of each template (sums to 1).
    pub mass_fraction: Vec<f64>,
    /// Set when the weights had to be normalised.
    pub warning: Option<String>,
    /// Groups its particles join besides the inserting fix's and the template's (the
    /// distribution fix's group, as LIGGGHTS 3.8 adds it).
    pub groupbit: u32,
    rng: InsertRng,
}

impl Distribution {
    /// The generators: the distribution's, then each template's (restart files).
    pub fn rngs(&self) -> Vec<InsertRng> {
        let mut r = vec![self.rng.clone()];
        r.extend(self.templates.iter().map(|t| t.rng.clone()));
        r
    }

    /// Sets the generators [`Distribution::rngs`] gave; false if their number does not
    /// match (another distribution).
    pub fn set_rngs(&mut self, r: &[InsertRng]) -> bool {
        if r.len() != 1 + self.templates.len() {
            return false;
        }
        self.rng = r[0].clone();
        for (t, g) in self.templates.iter_mut().zip(&r[1..]) {
            t.rng = g.clone();
        }
        true
    }

    /// A distribution of `parts` (template, weight).
    pub fn new(
        id: &str,
        seed: u64,
        weighting: Weighting,
        parts: Vec<(ParticleTemplate, f64)>,
    ) -> Result<Self> {
        if parts.is_empty() {
            return Err(Error::Invalid {
                what: "particle distribution",
                reason: "needs at least one template".into(),
            });
        }
        // A weight of 0 is allowed (LIGGGHTS 3.8 takes it: that template is never drawn).
        for (_, w) in &parts {
            check("template weight", *w, *w >= 0.0, "must be >= 0")?;
        }
        let sum: f64 = parts.iter().map(|p| p.1).sum();
        check(
            "sum of the template weights",
            sum,
            sum > 0.0,
            "must be > 0 (LIGGGHTS 3.8 goes on with NaN fractions)",
        )?;
        let warning = ((sum - 1.0).abs() > 1e-10).then(|| {
            format!("particle distribution {id}: weights sum to {sum}, not 1; normalised")
        });
        let mut parts = parts;
        // Largest first; stable, so equal sizes keep their script order.
        parts.sort_by(|a, b| b.0.max_radius().total_cmp(&a.0.max_radius()));
        let w: Vec<f64> = parts.iter().map(|p| p.1 / sum).collect();
        let masses: Vec<f64> = parts.iter().map(|p| p.0.mean_mass()).collect();
        let (number, mass) = match weighting {
            Weighting::Mass => {
                let n: Vec<f64> = w.iter().zip(&masses).map(|(w, m)| w / m).collect();
                let t: f64 = n.iter().sum();
                (n.iter().map(|x| x / t).collect::<Vec<_>>(), w)
            }
            Weighting::Number => {
                let m: Vec<f64> = w.iter().zip(&masses).map(|(w, m)| w * m).collect();
                let t: f64 = m.iter().sum();
                (w, m.iter().map(|x| x / t).collect::<Vec<_>>())
            }
        };
        Ok(Self {
            id: id.to_string(),
            templates: parts.into_iter().map(|p| p.0).collect(),
            number_fraction: number,
            mass_fraction: mass,
            warning,
            groupbit: 0,
            rng: super::rng(seed),
        })
    }

    /// Mean mass of one particle of the mix.
    pub fn mean_particle_mass(&self) -> f64 {
        self.templates
            .iter()
            .zip(&self.number_fraction)
            .map(|(t, n)| n * t.mean_mass())
            .sum()
    }

    /// Mean volume of one particle of the mix.
    pub fn mean_particle_volume(&self) -> f64 {
        self.templates
            .iter()
            .zip(&self.number_fraction)
            .map(|(t, n)| n * t.mean_mass() / t.density)
            .sum()
    }

    /// Largest radius of any template.
    pub fn max_radius(&self) -> f64 {
        self.templates
            .iter()
            .map(|t| t.max_radius())
            .fold(0.0, f64::max)
    }

    /// Splits `n` particles over the templates: floor of n × fraction each, the rest to the
    /// largest remainders (ties to the earlier, larger template). Sums to `n` exactly.
    pub fn counts_for(&self, n: usize) -> Vec<usize> {
        let exact: Vec<f64> = self.number_fraction.iter().map(|f| f * n as f64).collect();
        let mut counts: Vec<usize> = exact.iter().map(|x| x.floor() as usize).collect();
        let mut left = n.saturating_sub(counts.iter().sum());
        // Templates of weight 0 get none.
        let mut order: Vec<usize> = (0..counts.len())
            .filter(|&k| self.number_fraction[k] > 0.0)
            .collect();
        order.sort_by(|&a, &b| {
            (exact[b] - exact[b].floor())
                .total_cmp(&(exact[a] - exact[a].floor()))
                .then(a.cmp(&b))
        });
        for &k in order.iter().cycle() {
            if left == 0 {
                break;
            }
            counts[k] += 1;
            left -= 1;
        }
        counts
    }

    /// Picks one template at random by number fraction.
    pub fn pick(&mut self) -> usize {
        let u: f64 = self.rng.gen();
        let mut acc = 0.0;
        for (k, f) in self.number_fraction.iter().enumerate() {
            acc += f;
            if u < acc {
                return k;
            }
        }
        // Rounding left u above the sum: the last template that can be drawn.
        self.number_fraction
            .iter()
            .rposition(|&f| f > 0.0)
            .expect("the weights sum to > 0")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::insert::RadiusDist;

    fn t(id: &str, r: f64) -> ParticleTemplate {
        ParticleTemplate::new(id, 15485863, 1, 2500.0, RadiusDist::Constant(r)).unwrap()
    }

    /// in.dense: 30 % by mass of 1.5 mm, 70 % of 2 mm spheres. Number fractions follow
    /// n_i ∝ w_i / r_i³: 0.3/3.375 : 0.7/8 = 0.0889 : 0.0875, i.e. 50.39 % small.
    #[test]
    fn mass_fractions_become_number_fractions() {
        let d = Distribution::new(
            "pdd1",
            32452843,
            Weighting::Mass,
            vec![(t("pts1", 0.0015), 0.3), (t("pts2", 0.002), 0.7)],
        )
        .unwrap();
        assert_eq!(d.templates[0].id, "pts2", "largest first");
        let small = (0.3 / 3.375) / (0.3 / 3.375 + 0.7 / 8.0);
        assert!((d.number_fraction[1] - small).abs() < 1e-12);
        assert!((d.mass_fraction[0] - 0.7).abs() < 1e-12);
        assert!(d.warning.is_none());
        let counts = d.counts_for(8656);
        assert_eq!(counts.iter().sum::<usize>(), 8656);
        assert!((counts[1] as f64 - small * 8656.0).abs() <= 1.0);
        // Mean mass × number = total mass.
        let m: f64 = counts
            .iter()
            .zip(&d.templates)
            .map(|(n, t)| *n as f64 * t.mean_mass())
            .sum();
        assert!((m / (8656.0 * d.mean_particle_mass()) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn number_weights_normalised_with_a_warning() {
        let mut d = Distribution::new(
            "d",
            7,
            Weighting::Number,
            vec![(t("a", 0.001), 1.0), (t("b", 0.002), 3.0)],
        )
        .unwrap();
        assert!(d.warning.is_some());
        assert_eq!(d.number_fraction, vec![0.75, 0.25]);
        assert_eq!(d.counts_for(7), vec![5, 2]);
        assert_eq!(d.counts_for(0), vec![0, 0]);
        let n = 40_000;
        let picks = (0..n).filter(|_| d.pick() == 0).count();
        let sigma = (0.75f64 * 0.25 / n as f64).sqrt();
        assert!((picks as f64 / n as f64 - 0.75).abs() < 3.0 * sigma);
    }

    #[test]
    fn bad_distributions_are_refused() {
        assert!(Distribution::new("d", 1, Weighting::Mass, vec![]).is_err());
        assert!(Distribution::new("d", 1, Weighting::Mass, vec![(t("a", 0.001), 0.0)]).is_err());
        assert!(
            Distribution::new("d", 1, Weighting::Mass, vec![(t("a", 0.001), f64::NAN)]).is_err()
        );
        assert!(Distribution::new("d", 1, Weighting::Mass, vec![(t("a", 0.001), -1.0)]).is_err());
        let zeros = vec![(t("a", 0.001), 0.0), (t("b", 0.002), 0.0)];
        assert!(Distribution::new("d", 1, Weighting::Mass, zeros).is_err());
    }

    /// A template of weight 0 (LIGGGHTS 3.8 takes it and prints mass% = 0) is never drawn
    /// and gets no share of a count, but its radius still bounds the mix.
    #[test]
    fn a_template_of_weight_zero_is_never_drawn() {
        for weighting in [Weighting::Mass, Weighting::Number] {
            let mut d = Distribution::new(
                "d",
                7,
                weighting,
                vec![(t("a", 0.0025), 0.0), (t("b", 0.002), 1.0)],
            )
            .unwrap();
            assert!(d.warning.is_none());
            assert_eq!(d.templates[0].id, "a");
            assert_eq!(d.number_fraction, vec![0.0, 1.0]);
            assert_eq!(d.mass_fraction, vec![0.0, 1.0]);
            assert_eq!(d.max_radius(), 0.0025);
            for n in [0, 1, 7, 1000] {
                assert_eq!(d.counts_for(n), vec![0, n]);
            }
            assert!((0..10_000).all(|_| d.pick() == 1));
        }
    }
}
