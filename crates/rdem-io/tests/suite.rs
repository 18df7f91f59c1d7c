//! The integration tests of this crate, one module per file of `tests/`, built as one
//! test binary: one link instead of one per file (see `autotests` in Cargo.toml).

mod liggghts_reference;
mod liggghts_restart;
