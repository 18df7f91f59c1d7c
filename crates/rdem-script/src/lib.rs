//! LIGGGHTS-compatible input scripts for rdem: the parsing rules of LIGGGHTS' manual
//! section 3.2 with every word's place in the file kept, the command table that maps
//! LIGGGHTS commands onto the engine, and diagnostics that show the script line with a
//! caret under the offending word.
//!
//! [`Interpreter`] runs a script; [`Sim`] is the state it builds.

#![warn(missing_docs)]

pub mod args;
pub mod atom_fields;
pub mod atom_formula;
pub mod check;
pub mod coarse_graining;
pub mod commands;
pub mod computes;
pub mod context;
pub mod diagnostic;
pub mod dumps;
pub mod error;
pub mod euler;
pub mod expr;
pub mod fixes;
pub mod input;
pub mod lattice;
pub mod lexer;
pub mod liggghts_restart;
pub mod materials;
pub mod models;
pub mod old_gran;
pub mod output;
pub mod park_miller;
pub mod ranmars;
pub mod regions;
pub mod registry;
pub mod restart_state;
pub mod run;
pub mod sim;
pub mod source;
pub mod sph;
pub mod thermo;
pub mod units;
pub mod variables;

pub use diagnostic::{ScriptError, ScriptReport};
pub use input::Interpreter;
pub use lexer::{commands as split_commands, substitute, words, Command, Reference, Word};
pub use output::Output;
pub use sim::Sim;
