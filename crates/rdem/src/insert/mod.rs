//! Particle insertion: templates (`fix particletemplate/sphere`), discrete distributions
//! (`fix particledistribution/discrete`), and the seeded generator they draw from. Each
//! template and distribution has its own generator seeded from its script seed, so a run
//! is reproducible; positions and sizes differ from LIGGGHTS' (another generator), their
//! statistics do not.

pub mod dense;
pub mod distribution;
pub mod pack;
mod place;
pub mod single;
pub mod stream;
pub mod template;

pub use dense::{DensePack, DenseReport};
pub use distribution::{Distribution, Weighting};
pub use pack::{FallFromTop, InsertPack, InsertReport, Orientation, PackTarget, VelocityLaw};
pub use single::{create_single, Single};
pub use stream::{InsertStream, StreamFace};
pub use template::{ClumpShape, ParticleTemplate, RadiusDist};

/// The generator used for insertion: PCG64, reproducible across platforms and crate
/// versions (unlike `StdRng`).
pub type InsertRng = rand_pcg::Pcg64;

/// Where an insertion fix stands, for restart files: every generator it draws from (its
/// own, its distribution's, its templates') and its schedule, so that a continued run
/// inserts what the unbroken run would.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InsertProgress {
    /// The fix's own generator.
    pub rng: InsertRng,
    /// The distribution's generator, then each template's.
    pub dist: Vec<InsertRng>,
    /// Step of the last insertion.
    pub last: Option<u64>,
    /// First insertion step.
    pub start: Option<u64>,
    /// Particles inserted so far (`insert/stream`'s limit).
    pub inserted: u64,
}

/// A generator seeded from a script seed.
pub fn rng(seed: u64) -> InsertRng {
    use rand::SeedableRng;
    InsertRng::seed_from_u64(seed)
}
