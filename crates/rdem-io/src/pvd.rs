//! ParaView collection files (`.pvd`) beside a series of VTK snapshots, so that ParaView
//! opens the whole series as one time-dependent data set with the simulated time (not the
//! step number) on its time axis:
//!
//! ```text
//! <?xml version="1.0"?>
//! <VTKFile type="Collection" version="0.1" byte_order="LittleEndian">
//!   <Collection>
//!     <DataSet timestep="0" group="" part="0" file="packing_0.vtk"/>
//!     <DataSet timestep="0.001" group="" part="0" file="packing_1000.vtk"/>
//!   </Collection>
//! </VTKFile>
//! ```
//!
//! * The collection of a file name pattern with `*` ([`pvd_path`]) is the pattern with the
//!   `*` and the separator (`_`, `-` or `.`) just before it removed and the suffix
//!   replaced by `.pvd`: `post/packing_*.vtk` → `post/packing.pvd`, `post/dump*.vtu` →
//!   `post/dump.pvd`, `out/*.vtk` → `out/series.pvd`. When the `*` is in a directory
//!   name the collection goes next to that directory (`run*/p.vtk` → `run.pvd`).
//! * File names in the collection are relative to the collection's directory, so the
//!   directory can be moved as a whole.
//! * The collection is rewritten (atomically) after every snapshot, so it is always
//!   complete up to the last snapshot written, even if the run is killed. A snapshot
//!   written again under the same file name (e.g. `run 0` twice) replaces its entry.
//! * A dump without `*` overwrites one file with each snapshot: there is no series and no
//!   collection ([`PvdSeries::for_pattern`] returns `None`); ParaView opens the file itself.

use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};

use crate::atomic::{write_atomic, IoError};

/// The collection file of a dump file name pattern with `*` (see the module
/// documentation), `%` replaced by `rank`; `None` without `*`.
pub fn pvd_path(pattern: &str, rank: usize) -> Option<PathBuf> {
    let star = pattern.find('*')?;
    let pattern = pattern.replacen('%', &rank.to_string(), 1);
    let star = pattern.find('*').unwrap_or(star);
    // The path component holding the '*'.
    let start = pattern[..star].rfind('/').map_or(0, |k| k + 1);
    let end = pattern[star..]
        .find('/')
        .map_or(pattern.len(), |k| star + k);
    let in_dir = end < pattern.len();
    let comp = &pattern[start..end];
    let at = star - start;
    let (before, after) = (&comp[..at], &comp[at + 1..]);
    let is_sep = |c: char| matches!(c, '_' | '-' | '.');
    // Drop the suffix of a file name (not of a directory name).
    let after = match after.rfind('.') {
        Some(k) if !in_dir => &after[..k],
        _ => after,
    };
    let name = match before.strip_suffix(is_sep) {
        Some(b) => format!("{b}{after}"),
        None => format!("{before}{after}"),
    };
    let stem = name.as_str();
    let stem = if stem.is_empty() { "series" } else { stem };
    Some(PathBuf::from(format!("{}{stem}.pvd", &pattern[..start])))
}

/// `path` relative to `dir`, when `path` lies under it (else `path` as it is).
fn relative_to(path: &Path, dir: &Path) -> PathBuf {
    let clean = |p: &Path| -> PathBuf {
        p.components()
            .filter(|c| !matches!(c, Component::CurDir))
            .collect()
    };
    let (p, d) = (clean(path), clean(dir));
    match p.strip_prefix(&d) {
        Ok(rel) => rel.to_path_buf(),
        Err(_) => path.to_path_buf(),
    }
}

/// One entry of a collection.
#[derive(Debug, Clone, PartialEq)]
pub struct PvdEntry {
    /// Simulated time of the snapshot.
    pub time: f64,
    /// The file, relative to the collection's directory.
    pub file: PathBuf,
}

/// A ParaView collection that grows by one snapshot at a time.
#[derive(Debug, Clone, PartialEq)]
pub struct PvdSeries {
    path: PathBuf,
    entries: Vec<PvdEntry>,
}

impl PvdSeries {
    /// An empty collection to be written at `path`.
    pub fn new(path: impl Into<PathBuf>) -> Self {
        Self {
            path: path.into(),
            entries: Vec::new(),
        }
    }

    /// The collection for a dump file name pattern ([`pvd_path`]); `None` without `*`.
    pub fn for_pattern(pattern: &str, rank: usize) -> Option<Self> {
        pvd_path(pattern, rank).map(Self::new)
    }

    /// Where the collection is written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The entries so far.
    pub fn entries(&self) -> &[PvdEntry] {
        &self.entries
    }

    /// Adds the snapshot `file` (a path as written, e.g. `post/a_100.vtk`) at simulated
    /// `time` and rewrites the collection. A file already listed gets the new time.
    pub fn add(&mut self, time: f64, file: &Path) -> Result<(), IoError> {
        let dir = self.path.parent().unwrap_or(Path::new(""));
        let file = relative_to(file, dir);
        match self.entries.iter_mut().find(|e| e.file == file) {
            Some(e) => e.time = time,
            None => self.entries.push(PvdEntry { time, file }),
        }
        write_atomic(&self.path, self.format().as_bytes())
    }

    /// The text of the collection.
    pub fn format(&self) -> String {
        let mut out = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" \
             byte_order=\"LittleEndian\">\n  <Collection>\n",
        );
        for e in &self.entries {
            out.push_str("    <DataSet timestep=\"");
            crate::vtk_xml::write_number(&mut out, e.time);
            let file = e.file.to_string_lossy();
            let file = file
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('"', "&quot;");
            let _ = writeln!(out, "\" group=\"\" part=\"0\" file=\"{file}\"/>");
        }
        out.push_str("  </Collection>\n</VTKFile>\n");
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collection_names() {
        let p = |s: &str| pvd_path(s, 0).map(|p| p.to_string_lossy().into_owned());
        assert_eq!(p("post/packing_*.vtk").unwrap(), "post/packing.pvd");
        assert_eq!(p("post/dump*.vtu").unwrap(), "post/dump.pvd");
        assert_eq!(p("dump*.myforce.vtu").unwrap(), "dump.myforce.pvd");
        assert_eq!(p("out/*.vtk").unwrap(), "out/series.pvd");
        assert_eq!(p("out/*_x.vtk").unwrap(), "out/_x.pvd");
        assert_eq!(p("a-*-b.vtp").unwrap(), "a-b.pvd");
        assert_eq!(p("run*/p.vtk").unwrap(), "run.pvd");
        assert_eq!(p("post/p%_*.vtu").unwrap(), "post/p0.pvd");
        assert_eq!(p("post/nostar.vtk"), None);
        assert_eq!(p("*").unwrap(), "series.pvd");
    }

    #[test]
    fn entries_are_relative_and_replaced() {
        let d = std::env::temp_dir().join(format!("rdem-io-pvd-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        let pattern = d.join("post/a_*.vtk").to_string_lossy().into_owned();
        let mut s = PvdSeries::for_pattern(&pattern, 0).unwrap();
        assert_eq!(s.path(), d.join("post/a.pvd"));
        s.add(0.0, &d.join("post/a_0.vtk")).unwrap();
        s.add(0.5e-3, &d.join("post/a_50.vtk")).unwrap();
        s.add(1e-3, &d.join("post/a_50.vtk")).unwrap();
        let text = std::fs::read_to_string(s.path()).unwrap();
        assert_eq!(
            text,
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" \
             byte_order=\"LittleEndian\">\n  <Collection>\n    \
             <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"a_0.vtk\"/>\n    \
             <DataSet timestep=\"0.001\" group=\"\" part=\"0\" file=\"a_50.vtk\"/>\n  \
             </Collection>\n</VTKFile>\n"
        );
        assert_eq!(s.entries().len(), 2);
        // Relative patterns too.
        let r = PvdSeries::for_pattern("./post/b*.vtu", 0).unwrap();
        assert_eq!(r.path(), Path::new("./post/b.pvd"));
        assert_eq!(
            relative_to(Path::new("./post/b1.vtu"), Path::new("./post")),
            Path::new("b1.vtu")
        );
        std::fs::remove_dir_all(&d).unwrap();
    }
}
