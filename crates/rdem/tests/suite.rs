//! The integration tests of this crate, one module per file of `tests/`, built as one
//! test binary: one link instead of one per file (see `autotests` in Cargo.toml).

mod bad_input;
mod clumps;
mod common;
mod dense_packing;
mod domain_predicates;
mod energy_gas;
mod fixes;
mod history_persistence;
mod lees_edwards;
mod liggghts_golden;
mod mesh_walls;
mod neighbor_lists;
mod normal_impact;
mod oblique_impact;
mod particles_tags;
mod removal;
mod rolling;
mod short_periodic;
mod sorting;
mod tet_mesh_region;
mod threads_bit_identical;
