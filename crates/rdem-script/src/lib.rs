//! LIGGGHTS-compatible input scripts for rdem: the parsing rules of LIGGGHTS' manual
//! section 3.2 with every word's place in the file kept, and diagnostics that show the
//! script line with a caret under the offending word.
//!
//! This is the start of the front end (issue "LIGGGHTS-compatible input scripts"): the
//! lexer, the diagnostics, equal-style formulas and the variable table. The command table
//! and the binary come next.

#![warn(missing_docs)]

pub mod diagnostic;
pub mod expr;
pub mod lexer;
pub mod variables;

pub use diagnostic::{ScriptError, ScriptReport};
pub use lexer::{commands, substitute, words, Command, Reference, Word};
