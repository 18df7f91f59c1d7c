//! Per-particle quantities by their LIGGGHTS names (`x`, `vx`, `radius`, ...), for
//! `compute property/atom`, `compute reduce`, atom-style variables and `x[ID]`
//! references: the same table `dump custom` uses ([`rdem_io::Field`]).

use rdem::World;
use rdem_io::Field;

/// Every valid name.
pub const NAMES: [&str; 34] = Field::NAMES;

/// True if `name` is a per-particle quantity.
pub fn is_field(name: &str) -> bool {
    Field::parse(name).is_some()
}

/// The value of `name` for particle `i` (`None` for an unknown name).
pub fn value(w: &World, name: &str, i: usize) -> Option<f64> {
    Field::parse(name).map(|f| f.value(&w.particles, &w.domain, i))
}
