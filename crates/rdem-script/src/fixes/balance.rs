//! `fix ID group balance Nfreq dimstr Niter thresh [out file]` (LAMMPS, LIGGGHTS-PFM;
//! not in LIGGGHTS 3.8, which stops with "Invalid fix style"): dynamic load balancing,
//! which moves the cutting planes between the MPI subdomains so that each holds about as
//! many particles.
//!
//! rdem's subdomains are equal bricks of the box (`rdem::Domain::update_subdomain`), so it
//! cannot move the planes yet: the fix reads and checks its words as the LIGGGHTS-PFM
//! manual gives them and warns once that it changes nothing. Which rank owns a particle
//! changes neither forces nor trajectories, only the time a run takes.

use super::{style, FixHead, FixRow, ScriptFix, Stages};
use crate::args::{Args, CmdResult};
use crate::sim::Sim;

/// The registry row.
pub(super) const ROW: FixRow = style(
    "balance",
    parse,
    Stages::NONE,
    "`Nfreq dimstr Niter thresh` (LIGGGHTS-PFM's words, checked): accepted with a warning, no balancing",
)
.notes("rdem keeps its equal MPI subdomains: it does not move them to balance the particle counts yet; the results do not depend on it, only the speed of an MPI run with very uneven counts. LIGGGHTS 3.8 has no fix balance (\"Invalid fix style\"). `out FILE`: not supported yet");

/// The checked words; nothing acts on them.
struct Balance;

fn parse(_sim: &Sim, a: &mut Args, _head: &FixHead) -> CmdResult<Box<dyn ScriptFix>> {
    a.u64("Nfreq (steps between rebalancings, 0: at every re-neighboring)")?;
    let at = a.pos();
    let dims = a.word("dimstr (x, y and/or z, each at most once)")?;
    let ok = !dims.is_empty()
        && dims.chars().all(|c| matches!(c, 'x' | 'y' | 'z'))
        && ["x", "y", "z"].iter().all(|d| dims.matches(d).count() <= 1);
    if !ok {
        return Err(a.error_at(
            at,
            format!("fix balance: dimstr '{dims}' must be letters x, y, z, each at most once"),
            Some("e.g. 'z' or 'xy'".into()),
        ));
    }
    a.count("Niter (iterations per dimension)")?;
    let thresh = a.f64("thresh (imbalance threshold)")?;
    if thresh < 1.0 {
        return Err(a.error_prev(
            format!("fix balance: thresh {thresh} must be >= 1 (the max/average particle count)"),
            None,
        ));
    }
    if !a.is_done() {
        a.keyword("fix balance keyword", &["out"])?;
        return Err(a.error_prev(
            "fix balance: 'out' is not supported yet (rdem does not balance)",
            None,
        ));
    }
    a.warn_at(
        super::STYLE_WORD,
        "fix balance: rdem keeps its equal MPI subdomains (no load balancing yet); the results do not depend on it, only an MPI run's speed",
    );
    Ok(Box::new(Balance))
}

impl ScriptFix for Balance {
    fn unfix(&mut self, _sim: &mut Sim, _head: &FixHead) {}
}
