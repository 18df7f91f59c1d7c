//! The script names of the contact sub-models: one (name, kind) table per vocabulary, read
//! by the script parser (`pair_style gran`, `fix wall/gran`), its error messages and help,
//! the 2.x syntax, and the tests that replay LIGGGHTS scripts. Each name is declared with
//! its kind, in one row of `contact/mod.rs`.

use super::{CohesionKind, NormalKind, RollingKind, SurfaceKind, TangentialKind};

/// Normal models (`model ...`): their names, from the table of normal laws in
/// `contact/mod.rs` (a law and its name are one row there).
pub const NORMAL_MODELS: &[(&str, NormalKind)] = NormalKind::NAMES;

/// Tangential models (`tangential ...`).
pub const TANGENTIAL_MODELS: &[(&str, TangentialKind)] = TangentialKind::NAMES;

/// Cohesion models (`cohesion ...`).
pub const COHESION_MODELS: &[(&str, CohesionKind)] = CohesionKind::NAMES;

/// Surface models (`surface ...`).
pub const SURFACE_MODELS: &[(&str, SurfaceKind)] = SurfaceKind::NAMES;

/// Rolling friction models (`rolling_friction ...`).
pub const ROLLING_MODELS: &[(&str, RollingKind)] = RollingKind::NAMES;

/// The script name of `kind` in `table` (every kind of a model table has one: a law and
/// its name are one row of `contact/mod.rs`, and the tests below check the tables).
pub fn name_of<K: PartialEq + std::fmt::Debug>(
    table: &[(&'static str, K)],
    kind: K,
) -> &'static str {
    table
        .iter()
        .find(|(_, v)| *v == kind)
        .map(|(n, _)| *n)
        .unwrap_or_else(|| panic!("{kind:?} has no name in its table"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No two names of `table` are the same, no two kinds either, and no name is empty.
    /// (Each kind has its name by construction: both are one row of `contact/mod.rs`.)
    fn unique<K: PartialEq + std::fmt::Debug>(table: &[(&'static str, K)]) {
        for (i, (n, k)) in table.iter().enumerate() {
            assert!(!n.is_empty(), "{k:?} has an empty name");
            for (m, l) in &table[i + 1..] {
                assert_ne!(n, m, "the name '{n}' is given twice");
                assert_ne!(k, l, "{k:?} has two names");
            }
        }
    }

    /// The names of `table`, in order, as one line.
    fn names<K>(table: &[(&str, K)]) -> String {
        table.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(" ")
    }

    #[test]
    fn names_are_unique() {
        unique(NORMAL_MODELS);
        unique(TANGENTIAL_MODELS);
        unique(COHESION_MODELS);
        unique(ROLLING_MODELS);
        unique(SURFACE_MODELS);
        // The names scripts use, in the order the help lists them.
        assert_eq!(
            names(NORMAL_MODELS),
            "hertz hooke hooke/hysteresis hertz/stiffness hooke/stiffness jkr jkr/pfm hysteretic/nonlinear1 hysteretic/nonlinear2"
        );
        assert_eq!(
            names(TANGENTIAL_MODELS),
            "off history no_history incremental_history"
        );
        assert_eq!(
            names(COHESION_MODELS),
            "off sjkr sjkr2 bond bond/nonlinear easo/capillary/viscous"
        );
        assert_eq!(
            names(ROLLING_MODELS),
            "off cdt cdtnonlinear2 epsd epsd2 epsd3"
        );
        assert_eq!(names(SURFACE_MODELS), "default multicontact");
    }
}
