//! The `Nevery Nrepeat Nfreq` sampling schedule that `fix ave/atom`, `fix ave/histo`
//! and `fix ave/spatial` share (LAMMPS' `nvalid`/`irepeat`): `Nrepeat` samples `Nevery`
//! steps apart, ending on each multiple of `Nfreq` (not before step `start`).

use crate::args::{Args, CmdResult};

/// A sampling schedule and where it stands.
#[derive(Debug, Clone)]
pub(super) struct Schedule {
    pub(super) nevery: u64,
    pub(super) nrepeat: u64,
    pub(super) nfreq: u64,
    /// No output before this step (`fix ave/histo start`).
    pub(super) start: u64,
    /// Next sampled step.
    nvalid: u64,
    /// Samples taken in the current window.
    irepeat: u64,
}

impl Schedule {
    /// Reads `Nevery Nrepeat Nfreq` and checks them as LAMMPS does.
    pub(super) fn parse(a: &mut Args) -> CmdResult<Self> {
        let nevery = a.count("Nevery")?;
        let nrepeat = a.count("Nrepeat")?;
        let nfreq = a.count("Nfreq")?;
        if nfreq % nevery != 0 || (nrepeat - 1) * nevery >= nfreq {
            return Err(a.error_at(
                a.pos() - 1,
                format!("Nfreq must be a multiple of Nevery and Nfreq > (Nrepeat-1)*Nevery (got {nevery} {nrepeat} {nfreq})"),
                None,
            ));
        }
        Ok(Self {
            nevery,
            nrepeat,
            nfreq,
            start: 0,
            nvalid: 0,
            irepeat: 0,
        })
    }

    /// Starts the schedule at `step` (the step of the definition).
    pub(super) fn begin(&mut self, step: u64) {
        self.nvalid = self.next_valid(step);
    }

    /// LAMMPS' `nextvalid` (with `start`): the first sampled step at or after `step`.
    fn next_valid(&self, step: u64) -> u64 {
        let mut n = (step / self.nfreq) * self.nfreq + self.nfreq;
        while n < self.start {
            n += self.nfreq;
        }
        if n - self.nfreq == step && self.nrepeat == 1 {
            n = step;
        } else {
            n -= (self.nrepeat - 1) * self.nevery;
        }
        if n < step {
            n += self.nfreq;
        }
        n
    }

    /// Whether `step` is sampled: `Some(true)` for the first sample of a window (the sums
    /// restart), `Some(false)` for a later one, `None` for a step that is not sampled. A
    /// run that starts past the next sampled step restarts the schedule (LAMMPS' init).
    pub(super) fn due(&mut self, step: u64) -> Option<bool> {
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
        (step == self.nvalid).then_some(self.irepeat == 0)
    }

    /// After the sample of `step`: true if it completed the window (output now); the
    /// next sampled step is set either way.
    pub(super) fn sampled(&mut self, step: u64) -> bool {
        self.irepeat += 1;
        if self.irepeat < self.nrepeat {
            self.nvalid += self.nevery;
            return false;
        }
        self.irepeat = 0;
        self.nvalid = step + self.nfreq - (self.nrepeat - 1) * self.nevery;
        true
    }
}
