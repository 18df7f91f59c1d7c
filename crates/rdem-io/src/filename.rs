//! Dump file names with LIGGGHTS' wildcards: the first `*` becomes the timestep
//! (zero-padded to `pad` digits when `pad > 0`, `dump_modify pad`) and the first `%`
//! becomes the rank of the writing process. A name without `*` is one file holding every
//! snapshot. Parent directories are created when the file is written (see
//! [`crate::atomic`]).

use std::path::PathBuf;

/// A dump file name pattern.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DumpFileName {
    pattern: String,
    pad: usize,
}

impl DumpFileName {
    /// The pattern as written in the dump command, without padding.
    pub fn new(pattern: impl Into<String>) -> Self {
        Self {
            pattern: pattern.into(),
            pad: 0,
        }
    }

    /// Sets the timestep padding (`dump_modify pad N`; 0 = none).
    pub fn with_pad(mut self, pad: usize) -> Self {
        self.pad = pad;
        self
    }

    /// Sets the timestep padding.
    pub fn set_pad(&mut self, pad: usize) {
        self.pad = pad;
    }

    /// The timestep padding.
    pub fn pad(&self) -> usize {
        self.pad
    }

    /// The pattern as written.
    pub fn pattern(&self) -> &str {
        &self.pattern
    }

    /// True when the name contains `*`: one file per snapshot.
    pub fn per_step(&self) -> bool {
        self.pattern.contains('*')
    }

    /// True when the name contains `%`: one file per process.
    pub fn per_rank(&self) -> bool {
        self.pattern.contains('%')
    }

    /// The file name for `step` written by `rank`.
    pub fn path(&self, step: u64, rank: usize) -> PathBuf {
        let step = format!("{step:0width$}", width = self.pad);
        let name = self
            .pattern
            .replacen('*', &step, 1)
            .replacen('%', &rank.to_string(), 1);
        PathBuf::from(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wildcards() {
        let n = DumpFileName::new("post/dump*.liggghts");
        assert!(n.per_step() && !n.per_rank());
        assert_eq!(n.path(1200, 0), PathBuf::from("post/dump1200.liggghts"));
        let n = n.with_pad(7);
        assert_eq!(n.pad(), 7);
        assert_eq!(n.path(1200, 0), PathBuf::from("post/dump0001200.liggghts"));
        // pad never truncates.
        assert_eq!(
            DumpFileName::new("a*").with_pad(2).path(12345, 0),
            PathBuf::from("a12345")
        );
        let n = DumpFileName::new("out.%.*.*");
        assert!(n.per_rank() && n.per_step());
        assert_eq!(n.path(5, 3), PathBuf::from("out.3.5.*"));
        let mut n = DumpFileName::new("all.txt");
        n.set_pad(3);
        assert!(!n.per_step());
        assert_eq!(n.path(10, 0), PathBuf::from("all.txt"));
        assert_eq!(n.pattern(), "all.txt");
    }
}
