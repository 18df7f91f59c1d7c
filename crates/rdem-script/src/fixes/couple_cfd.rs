//! `fix ID group couple/cfd couple_every N mpi`, `fix ID group couple/cfd/force` and
//! `fix ID group couple/cfd/force/implicit`: CFDEMcoupling's fixes, which exchange data
//! with a CFD solver. rdem has no CFD coupling. LIGGGHTS 3.8 run alone (no CFD solver)
//! defines these fixes and runs with no fluid force (measured: the trajectory is the one
//! without them, the per-particle properties stay 0). rdem does the same and warns once,
//! at `couple/cfd`, that no fluid force acts.
//!
//! What the definitions bring, as LIGGGHTS 3.8 (measured with `compute reduce`):
//! `couple/cfd/force` the per-particle vectors `dragforce` and `hdtorque` (3 values),
//! `couple/cfd/force/implicit` also the scalar `Ksl` and the vector `uf`, each a
//! `fix property/atom` whose ID is its name, all zero. `couple/cfd/force` without a
//! `couple/cfd` is an error, as in LIGGGHTS. `couple/cfd ... file`: LIGGGHTS 3.8 waits for
//! the CFD's files at the first coupling step, forever when there is no CFD; rdem stops
//! with an error instead.

use super::property_atom::{self, PropertyAtom};
use super::{style, FixHead, FixRow, ScriptFix, Stages, STYLE_WORD};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

const NOTES: &str = "rdem has no CFD coupling: as LIGGGHTS 3.8 run without a CFD solver, the fix is defined and no fluid force acts; rdem warns once that CFD coupling is not supported and no fluid force acts. `file` coupling stops with an error (LIGGGHTS 3.8 waits for the CFD's files forever); words after `mpi` are an error (LIGGGHTS ignores them)";

/// The registry row of `couple/cfd`.
pub(super) const ROW: FixRow = style(
    "couple/cfd",
    parse_coupling,
    Stages::NONE,
    "`couple_every N mpi`: accepted, no CFD coupling (see notes)",
)
.notes(NOTES);

/// The registry row of `couple/cfd/force`.
pub(super) const ROW_FORCE: FixRow = style(
    "couple/cfd/force",
    parse_force,
    Stages::NONE,
    "no keywords: defines the per-particle `dragforce`, `hdtorque` (zero: no fluid force)",
)
.notes("needs a `couple/cfd`, as LIGGGHTS; its keywords (`transfer_density`, `transfer_type`, ...) are not supported yet");

/// The registry row of `couple/cfd/force/implicit`.
pub(super) const ROW_IMPLICIT: FixRow = style(
    "couple/cfd/force/implicit",
    parse_force,
    Stages::NONE,
    "no keywords: defines the per-particle `dragforce`, `hdtorque`, `Ksl`, `uf` (zero: no fluid force)",
)
.notes("needs a `couple/cfd`, as LIGGGHTS; its keywords (`CrankNicolson`, ...) are not supported yet");

/// The warning printed at `couple/cfd`.
pub const WARNING: &str =
    "fix couple/cfd: CFD coupling is not supported: no fluid force acts on the particles (as LIGGGHTS 3.8 run without a CFD solver)";

/// A defined `couple/cfd` (its `couple_every` is read and checked; without a CFD solver
/// nothing is exchanged).
#[derive(Debug)]
pub struct CoupleCfd;

/// A defined `couple/cfd/force` or `couple/cfd/force/implicit`.
#[derive(Debug)]
pub struct CoupleCfdForce {
    /// The `/implicit` variant.
    pub implicit: bool,
}

fn parse_coupling(sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    sim.world_ref(a)?;
    a.keyword("couple/cfd keyword", &["couple_every"])?;
    a.count("couple_every")?;
    match a.keyword("data coupling style", &["mpi", "MPI", "file"])? {
        "file" => {
            return Err(a.error_prev(
                "couple/cfd file: rdem has no CFD coupling (LIGGGHTS 3.8 alone waits forever for the CFD's files)",
                Some("use mpi: the run then goes on without fluid forces, as LIGGGHTS 3.8 alone".into()),
            ))
        }
        _ => a.done()?,
    }
    a.warn_at(STYLE_WORD, WARNING);
    Ok(Box::new(CoupleCfd))
}

fn parse_force(sim: &Sim, a: &mut Args, head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    sim.world_ref(a)?;
    if !sim
        .defs
        .fixes
        .iter()
        .any(|f| f.downcast::<CoupleCfd>().is_some())
    {
        return Err(a.error_at(
            STYLE_WORD,
            format!("fix {} needs a fix of style couple/cfd", head.style),
            Some("define `fix ID all couple/cfd couple_every N mpi` before it, as LIGGGHTS".into()),
        ));
    }
    if let Some(w) = a.peek() {
        return Err(a.error_at(
            a.pos(),
            format!("{}: keyword '{w}' is not supported yet", head.style),
            Some("rdem has no CFD coupling: leave the keywords out".into()),
        ));
    }
    Ok(Box::new(CoupleCfdForce {
        implicit: head.style.ends_with("/implicit"),
    }))
}

impl ScriptFix for CoupleCfd {
    /// Nothing to undo: the fix exchanges nothing.
    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}

impl ScriptFix for CoupleCfdForce {
    fn install(&mut self, sim: &mut Sim, a: &Args, _head: &FixHead) -> CmdResult<()> {
        let mut props = vec![("dragforce", 3), ("hdtorque", 3)];
        if self.implicit {
            props.extend([("Ksl", 1), ("uf", 3)]);
        }
        for (name, width) in props {
            property_atom::redefine(
                sim,
                a,
                PropertyAtom {
                    name: name.to_string(),
                    vector: width > 1,
                    defaults: vec![0.0; width],
                    forward: false,
                    restart: true,
                },
            )?;
        }
        Ok(())
    }

    /// The properties stay (fixes of their own, as `heat/gran`'s): nothing to undo.
    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
