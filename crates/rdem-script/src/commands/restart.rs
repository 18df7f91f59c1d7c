//! `restart 0`, `restart N root`, `restart N file1 file2`: a restart file every N steps
//! of a run, written by the `write_restart` writer ([`crate::restart_state`]).
//!
//! As the LIGGGHTS 3.8 manual (`restart.txt`) says: files are written on steps that are
//! multiples of N, but not on the first step of a run (its set-up); with one name a `*`
//! in it is replaced by the step, and a name without `*` gets `.STEP` appended; with two
//! names the files go to them in turn, the first one first. Each file is written under a
//! temporary name and renamed when complete (as every file rdem writes), so a run
//! stopped while writing never leaves a half restart file under the final name. A script may have one
//! schedule of each kind (one name, two names) at once; `restart 0` ends both.

use crate::args::{Args, CmdResult};
use crate::diagnostic::{Origin, RunError};
use crate::sim::Sim;

/// Where the periodic restart files go.
#[derive(Debug, Clone)]
pub enum RestartNames {
    /// One name: `*` replaced by the step, or `.STEP` appended.
    Series(String),
    /// Two names written in turn; `next` is the index of the next one.
    Toggle {
        /// The two names.
        names: [String; 2],
        /// The one written next.
        next: usize,
    },
}

impl RestartNames {
    /// The file name for step `step` (and, for two names, the turn moves on).
    pub fn take(&mut self, step: u64) -> String {
        match self {
            Self::Series(root) if root.contains('*') => root.replace('*', &step.to_string()),
            Self::Series(root) => format!("{root}.{step}"),
            Self::Toggle { names, next } => {
                let name = names[*next].clone();
                *next = 1 - *next;
                name
            }
        }
    }
}

/// `restart N ...`: the schedule of periodic restart files.
#[derive(Debug, Clone)]
pub struct RestartSchedule {
    /// Every this many steps.
    pub every: u64,
    /// The file names.
    pub names: RestartNames,
    /// The `restart` command's N, for errors while writing.
    pub origin: Option<Origin>,
}

/// `restart 0 | N root | N file1 file2`.
pub(super) fn restart(sim: &mut Sim, a: &mut Args) -> CmdResult {
    if a.peek().is_some_and(|w| w.starts_with("v_")) {
        a.word("N")?;
        return Err(a.error_prev(
            "restart with a variable N is not supported yet",
            Some("give N as a number of steps".into()),
        ));
    }
    let every = a.u64("N (steps between restart files, 0 = none)")?;
    if every == 0 {
        a.done()?;
        sim.outputs.restart.clear();
        return Ok(());
    }
    let mut names = Vec::new();
    while let Some(w) = a.peek() {
        if names.len() == 2 || matches!(w, "fileper" | "nfile") {
            break;
        }
        let at = a.pos();
        let name = a.word("file name")?;
        if name.contains('%') {
            return Err(a.error_at(
                at,
                "restart files per processor ('%' in the name) are not supported yet",
                Some("rdem writes one restart file: leave '%' out".into()),
            ));
        }
        names.push(name.to_string());
    }
    if !a.is_done() {
        let k = a.keyword("restart keyword", &["fileper", "nfile"])?;
        return Err(a.error_prev(
            format!("restart {k} is not supported yet"),
            Some("rdem writes one restart file per step: leave the keyword out".into()),
        ));
    }
    let names = match names.as_slice() {
        [] => {
            return Err(a.error_at(
                a.pos(),
                "restart N needs a file name",
                Some(
                    "restart N root (step appended or put at '*'), or restart N file1 file2".into(),
                ),
            ))
        }
        [one] => RestartNames::Series(one.clone()),
        [f1, f2] => RestartNames::Toggle {
            names: [f1.clone(), f2.clone()],
            next: 0,
        },
        _ => unreachable!("at most two names are read"),
    };
    let origin = sim.origin(a, 1);
    // One schedule of each mode, as LIGGGHTS: a new one replaces the old one of its mode.
    let toggle = matches!(names, RestartNames::Toggle { .. });
    sim.outputs
        .restart
        .retain(|r| matches!(r.names, RestartNames::Toggle { .. }) != toggle);
    sim.outputs.restart.push(RestartSchedule {
        every,
        names,
        origin,
    });
    Ok(())
}

/// Writes the restart file of `step` if one is due (after the step's dumps; never at a
/// run's set-up). Collective: every rank takes part in gathering the particles.
pub fn write_due(sim: &mut Sim, step: u64) -> Result<(), RunError> {
    for k in 0..sim.outputs.restart.len() {
        let r = &mut sim.outputs.restart[k];
        if step % r.every != 0 {
            continue;
        }
        let name = r.names.take(step);
        let origin = r.origin.clone();
        crate::restart_state::write(sim, &name)
            .map_err(|m| RunError::at(origin.as_ref(), "rdem::run::restart", m))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_manual() {
        let mut s = RestartNames::Series("restart.*.equil".into());
        assert_eq!(s.take(1000), "restart.1000.equil");
        let mut s = RestartNames::Series("poly.restart".into());
        assert_eq!(s.take(2000), "poly.restart.2000");
        let mut t = RestartNames::Toggle {
            names: ["a".into(), "b".into()],
            next: 0,
        };
        let got: Vec<String> = (1..=3).map(|k| t.take(k * 10)).collect();
        assert_eq!(got, ["a", "b", "a"]);
    }
}
