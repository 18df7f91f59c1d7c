//! Typed engine errors. The engine never panics on anything a user controls: every
//! constructor validates its input and returns one of these, and the time loop stops with
//! one when the state stops being finite.

use crate::particles::Tag;

/// Everything the engine can refuse or stop on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A scalar parameter outside its valid range.
    #[error("invalid {what} = {value}: {reason}")]
    InvalidParameter {
        /// Which parameter (e.g. "radius", "Poisson's ratio").
        what: &'static str,
        /// The offending value.
        value: f64,
        /// The valid range, in words.
        reason: &'static str,
    },
    /// A parameter that is not a single number (a vector, a name, a count).
    #[error("invalid {what}: {reason}")]
    Invalid {
        /// Which parameter.
        what: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// A particle placed outside a fixed (non-periodic, non-shrink-wrapped) box.
    #[error("particle at ({x}, {y}, {z}) is outside the simulation box along {axis} [{lo}, {hi}]")]
    OutsideBox {
        /// Position.
        x: f64,
        /// Position.
        y: f64,
        /// Position.
        z: f64,
        /// The axis it is outside on ('x', 'y' or 'z').
        axis: char,
        /// Box bounds on that axis.
        lo: f64,
        /// Box bounds on that axis.
        hi: f64,
    },
    /// A position, velocity or force became NaN or infinite.
    #[error("non-finite {quantity} on particle {tag} at step {step}")]
    NonFinite {
        /// "position", "velocity", "force", ...
        quantity: &'static str,
        /// Tag of the particle.
        tag: Tag,
        /// Timestep at which it was detected.
        step: u64,
    },
    /// Particles left a fixed box and the lost-particle policy is `error`.
    #[error("{count} particle(s) lost at step {step} (they left a fixed boundary); first lost tag {first_tag} {detail}")]
    LostParticles {
        /// How many were lost at this reneighboring.
        count: usize,
        /// First lost tag.
        first_tag: Tag,
        /// Where that particle was found, its velocity, and the wall surface its path
        /// back crosses first ([`crate::lost::crossing`]).
        detail: String,
        /// Timestep.
        step: u64,
    },
    /// Tags are not 1..=N.
    #[error("particle tags are not consecutive: min {min}, max {max}, count {count} (need min 1 and max = count)")]
    TagsNotConsecutive {
        /// Smallest tag.
        min: Tag,
        /// Largest tag.
        max: Tag,
        /// Number of particles.
        count: usize,
    },
    /// Two particles share a tag.
    #[error("particle tag {0} is used twice")]
    DuplicateTag(Tag),
    /// Per-type radius consistency failed.
    #[error("particles of type {ty} have different radii ({r1} and {r2}), but this setting needs one radius per type")]
    InconsistentRadius {
        /// The type.
        ty: u32,
        /// One radius.
        r1: f64,
        /// Another radius.
        r2: f64,
    },
    /// A particle type outside 1..=ntypes.
    #[error("particle type {ty} is out of range 1..={ntypes}")]
    TypeOutOfRange {
        /// The offending type.
        ty: u32,
        /// Number of types.
        ntypes: u32,
    },
    /// A periodic box shorter than twice the largest contact distance: a particle could
    /// touch two images of one partner (or its own image), which rdem does not support.
    /// Boxes between that and twice the neighbor cutoff run (see [`crate::domain`]).
    #[error("periodic box length {len} along {axis} is less than twice the largest contact distance {contact} (twice the largest radius, times the contact distance factor, or the longest bond): a particle could touch two periodic images of one partner, which rdem does not support; enlarge the box along {axis}")]
    PeriodicBoxTooSmall {
        /// Axis.
        axis: char,
        /// Box length.
        len: f64,
        /// Largest contact distance (the neighbor cutoff without the skin).
        contact: f64,
    },
}

/// Result with the engine's error.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks `value` with `ok`, else an [`Error::InvalidParameter`].
pub(crate) fn check(what: &'static str, value: f64, ok: bool, reason: &'static str) -> Result<f64> {
    if ok && value.is_finite() {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            what,
            value,
            reason,
        })
    }
}
