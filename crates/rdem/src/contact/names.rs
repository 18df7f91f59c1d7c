//! The script names of the contact sub-models: one (name, kind) table per vocabulary, read
//! by the script parser (`pair_style gran`, `fix wall/gran`), its error messages and help,
//! the 2.x syntax, and the tests that replay LIGGGHTS scripts. A kind has exactly one name.

use super::{CohesionKind, NormalKind, RollingKind, SurfaceKind, TangentialKind};

/// Normal models (`model ...`): their names, from the table of normal laws in
/// `contact/mod.rs` (a law and its name are one row there).
pub const NORMAL_MODELS: &[(&str, NormalKind)] = NormalKind::NAMES;

/// Tangential models (`tangential ...`).
pub const TANGENTIAL_MODELS: &[(&str, TangentialKind)] = &[
    ("history", TangentialKind::History),
    ("no_history", TangentialKind::NoHistory),
];

/// Cohesion models (`cohesion ...`).
pub const COHESION_MODELS: &[(&str, CohesionKind)] = &[
    ("off", CohesionKind::Off),
    ("sjkr", CohesionKind::Sjkr),
    ("sjkr2", CohesionKind::Sjkr2),
    ("bond", CohesionKind::Bond),
    ("easo/capillary/viscous", CohesionKind::Easo),
];

/// Surface models (`surface ...`).
pub const SURFACE_MODELS: &[(&str, SurfaceKind)] = &[
    ("default", SurfaceKind::Default),
    ("multicontact", SurfaceKind::Multicontact),
];

/// Rolling friction models (`rolling_friction ...`).
pub const ROLLING_MODELS: &[(&str, RollingKind)] = &[
    ("off", RollingKind::Off),
    ("cdt", RollingKind::Cdt),
    ("epsd", RollingKind::Epsd),
    ("epsd2", RollingKind::Epsd2),
    ("epsd3", RollingKind::Epsd3),
];

#[cfg(test)]
mod tests {
    use super::*;

    /// `table` names each of `all` once, and no name twice.
    fn once<K: PartialEq + std::fmt::Debug>(table: &[(&'static str, K)], all: &[K]) {
        for k in all {
            let n = table.iter().filter(|(_, v)| v == k).count();
            assert_eq!(n, 1, "{k:?} has {n} names");
        }
        assert_eq!(table.len(), all.len());
        let mut names: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), table.len(), "a name is given twice");
    }

    /// Every kind has exactly one name. The lists below are checked by exhaustive matches:
    /// a new kind does not compile here until it is listed, and then fails until its
    /// table names it. The normal laws' names come from the same row as their kinds, so
    /// only the uniqueness of the names is left to check for them.
    #[test]
    fn every_model_kind_has_one_name() {
        use CohesionKind as C;
        use NormalKind as N;
        use RollingKind as R;
        use SurfaceKind as S;
        use TangentialKind as T;
        let normal: Vec<N> = NORMAL_MODELS.iter().map(|(_, k)| *k).collect();
        let tangential = [T::History, T::NoHistory];
        for k in tangential {
            match k {
                T::History | T::NoHistory => {}
            }
        }
        let cohesion = [C::Off, C::Sjkr, C::Sjkr2, C::Bond, C::Easo];
        for k in cohesion {
            match k {
                C::Off | C::Sjkr | C::Sjkr2 | C::Bond | C::Easo => {}
            }
        }
        let rolling = [R::Off, R::Cdt, R::Epsd, R::Epsd2, R::Epsd3];
        for k in rolling {
            match k {
                R::Off | R::Cdt | R::Epsd | R::Epsd2 | R::Epsd3 => {}
            }
        }
        let surface = [S::Default, S::Multicontact];
        for k in surface {
            match k {
                S::Default | S::Multicontact => {}
            }
        }
        once(NORMAL_MODELS, &normal);
        once(TANGENTIAL_MODELS, &tangential);
        once(COHESION_MODELS, &cohesion);
        once(ROLLING_MODELS, &rolling);
        once(SURFACE_MODELS, &surface);
    }
}
