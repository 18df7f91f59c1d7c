//! The `units` command's unit systems. rdem's granular physics holds no physical constant,
//! so a script in `cgs` or `micro` units runs the same motion as the same script in `si`
//! with every number converted; what a unit system changes is LIGGGHTS' defaults and
//! constants that carry a unit (LIGGGHTS 3.8 manual, `units.txt`):
//!
//! | style | mass | length | time | default `timestep` | default skin | k_B |
//! |---|---|---|---|---|---|---|
//! | `si` | kg | m | s | 1e-8 | 0.001 | 1.3806504e-23 J/K |
//! | `cgs` | g | cm | s | 1e-8 | 0.1 | 1.3806504e-16 erg/K |
//! | `micro` | pg | µm | µs | 2.0 | 0.1 | 1.3806504e-8 pg µm²/(µs² K) |
//!
//! LIGGGHTS 3.8 also checks `youngsModulus` (≥ 5e6 and ≤ 1e9 Pa in `si`, ≥ 5e7 and ≤ 1e10
//! dyne/cm² in `cgs`, none in `micro`; `soft_particles yes`, `hard_particles yes`
//! override); rdem has no such check in any unit system.

/// A unit system of the `units` command.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Units {
    /// kilograms, metres, seconds (rdem's default when a script gives no `units`).
    #[default]
    Si,
    /// grams, centimetres, seconds.
    Cgs,
    /// picograms, micrometres, microseconds.
    Micro,
}

impl Units {
    /// The styles rdem runs, as written in scripts.
    pub const NAMES: [&'static str; 3] = ["si", "cgs", "micro"];

    /// The style named `name`, if rdem runs it.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "si" => Some(Self::Si),
            "cgs" => Some(Self::Cgs),
            "micro" => Some(Self::Micro),
            _ => None,
        }
    }

    /// The name as written in scripts.
    pub fn name(self) -> &'static str {
        match self {
            Self::Si => "si",
            Self::Cgs => "cgs",
            Self::Micro => "micro",
        }
    }

    /// The default time step the `units` command sets.
    pub fn default_timestep(self) -> f64 {
        match self {
            Self::Si | Self::Cgs => rdem::world::DEFAULT_TIMESTEP,
            Self::Micro => 2.0,
        }
    }

    /// The default neighbor skin the `units` command sets.
    pub fn default_skin(self) -> f64 {
        match self {
            Self::Si => 0.001,
            Self::Cgs | Self::Micro => 0.1,
        }
    }

    /// Boltzmann's constant in the system's energy per kelvin (LIGGGHTS 3.8's values).
    pub fn boltzmann(self) -> f64 {
        match self {
            Self::Si => 1.3806504e-23,
            Self::Cgs => 1.3806504e-16,
            Self::Micro => 1.3806504e-8,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for n in Units::NAMES {
            assert_eq!(Units::from_name(n).unwrap().name(), n);
        }
        assert_eq!(Units::from_name("lj"), None);
    }

    /// k_B is one physical constant: 1.3806504e-23 J/K is 1e7 times more in erg/K, and
    /// 1 J = 1e15 pg · 1e12 µm² / 1e12 µs² = 1e15 micro energy units.
    #[test]
    fn boltzmann_converts() {
        let si = Units::Si.boltzmann();
        assert!((Units::Cgs.boltzmann() / (si * 1e7) - 1.0).abs() < 1e-15);
        assert!((Units::Micro.boltzmann() / (si * 1e15) - 1.0).abs() < 1e-15);
    }
}
