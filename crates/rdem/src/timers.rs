//! Wall-clock time spent per stage of the step, for the breakdown printed after a run.

use std::time::{Duration, Instant};

/// Stages timed separately (the LAMMPS breakdown).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Particle–particle forces.
    Pair,
    /// Neighbor list builds, sorting, remapping.
    Neigh,
    /// Ghost and migration communication.
    Comm,
    /// Output (dumps, thermo), timed by the caller.
    Output,
    /// Fixes: integration, walls, gravity, ...
    Modify,
    /// Everything else.
    Other,
}

/// Accumulated time per stage.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timers {
    /// Per stage, in [`Stage`] order.
    pub total: [Duration; 6],
}

impl Timers {
    /// Adds the time since `start` to `stage` and returns now.
    #[inline]
    pub fn lap(&mut self, stage: Stage, start: Instant) -> Instant {
        let now = Instant::now();
        self.total[stage as usize] += now - start;
        now
    }
    /// Time in one stage.
    pub fn get(&self, stage: Stage) -> Duration {
        self.total[stage as usize]
    }
    /// Clears all stages.
    pub fn reset(&mut self) {
        *self = Self::default();
    }
}
