//! `dump atom/vtk`: one VTK XML UnstructuredGrid (`.vtu`) per snapshot, one vertex cell
//! per particle of the dump group, sorted by id, with the point arrays `radii`, `id`,
//! `type`, `proc`, `mass`, `velocity_lin`, `velocity_ang`, `force` (LIGGGHTS 3.8's
//! `dump atom/vtk`; file layout in [`crate::vtk_xml`]).
//!
//! Where LIGGGHTS 3.8 crashes, rdem does the sane thing: a name without `*` is one file,
//! overwritten by each snapshot, and `dump_modify pad` pads the step in the name.
//!
//! Formatting an ASCII snapshot of many particles costs as much as a good number of
//! steps, so [`AtomVtkDump::start`] copies the snapshot's data and formats and writes it
//! on a thread of its own while the simulation goes on; the next snapshot of the same
//! dump, [`AtomVtkDump::finish`] (the front end calls it at the end of every run) or
//! dropping the dump waits for it. A write error is reported by the call that waits for
//! it, with the file's name.

use std::path::PathBuf;
use std::thread::JoinHandle;

use rdem::Particles;

use crate::atomic::{write_atomic, IoError};
use crate::filename::DumpFileName;
use crate::vtk_xml::{AtomVtu, XmlEncoding};

/// Compression of binary VTK XML data (`dump_modify compressor`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compressor {
    /// `none`.
    #[default]
    None,
    /// `zlib`.
    Zlib,
    /// `lz4`.
    Lz4,
}

impl Compressor {
    /// The names `dump_modify compressor` accepts.
    pub const NAMES: [&'static str; 3] = ["none", "zlib", "lz4"];

    /// The compressor called `name`.
    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "none" => Some(Compressor::None),
            "zlib" => Some(Compressor::Zlib),
            "lz4" => Some(Compressor::Lz4),
            _ => None,
        }
    }

    /// The XML encoding for `binary` output with this compressor (ASCII when not binary).
    pub fn encoding(self, binary: bool) -> XmlEncoding {
        match (binary, self) {
            (false, _) => XmlEncoding::Ascii,
            (true, Compressor::None) => XmlEncoding::Binary,
            (true, Compressor::Zlib) => XmlEncoding::Zlib,
            (true, Compressor::Lz4) => XmlEncoding::Lz4,
        }
    }
}

/// A snapshot being written in the background: its tag (e.g. the simulated time) and the
/// thread writing it.
type Pending = (f64, JoinHandle<Result<PathBuf, IoError>>);

/// A `dump atom/vtk`.
#[derive(Debug)]
pub struct AtomVtkDump {
    name: DumpFileName,
    /// `dump_modify binary` (off by default).
    pub binary: bool,
    /// `dump_modify compressor` (applies to binary output).
    pub compressor: Compressor,
    /// Rank substituted for `%`, and written as `proc` when no per-particle ranks are
    /// given.
    pub rank: usize,
    pending: Option<Pending>,
}

impl AtomVtkDump {
    /// A dump writing to `name`, ASCII.
    pub fn new(name: DumpFileName) -> Self {
        Self {
            name,
            binary: false,
            compressor: Compressor::None,
            rank: 0,
            pending: None,
        }
    }

    /// The file name pattern.
    pub fn name(&self) -> &DumpFileName {
        &self.name
    }

    /// The file name pattern (mutable for `dump_modify pad`).
    pub fn name_mut(&mut self) -> &mut DumpFileName {
        &mut self.name
    }

    /// The encoding of the data arrays.
    pub fn encoding(&self) -> XmlEncoding {
        self.compressor.encoding(self.binary)
    }

    /// Writes the snapshot of the particles `selection` (sorted by id here) and returns
    /// the file's path. `procs`, when given, is the owning rank of each particle index
    /// (written as `proc`; otherwise [`AtomVtkDump::rank`]).
    pub fn write(
        &self,
        step: u64,
        p: &Particles,
        selection: &[usize],
        procs: Option<&[i32]>,
    ) -> Result<PathBuf, IoError> {
        let (path, snap) = self.capture(step, p, selection, procs);
        write_atomic(&path, snap.format(self.encoding()).as_bytes())?;
        Ok(path)
    }

    fn capture(
        &self,
        step: u64,
        p: &Particles,
        selection: &[usize],
        procs: Option<&[i32]>,
    ) -> (PathBuf, AtomVtu) {
        let mut order = selection.to_vec();
        order.sort_by_key(|&i| p.tag[i]);
        let path = self.name.path(step, self.rank);
        let snap = match procs {
            Some(procs) => AtomVtu::capture_procs(p, &order, procs),
            None => AtomVtu::capture(p, &order, self.rank as i32),
        };
        (path, snap)
    }

    /// Starts writing the snapshot in the background (see the module documentation),
    /// tagged with `tag` (`procs` as in [`AtomVtkDump::write`]). Waits for the previous snapshot first; returns the tags and
    /// paths of the snapshots completed by this call (the previous one; this one too if
    /// no thread could be started and it was written at once), or the first error.
    pub fn start(
        &mut self,
        step: u64,
        tag: f64,
        p: &Particles,
        selection: &[usize],
        procs: Option<&[i32]>,
    ) -> Result<Vec<(f64, PathBuf)>, IoError> {
        let mut done: Vec<(f64, PathBuf)> = self.finish()?.into_iter().collect();
        let (path, snap) = self.capture(step, p, selection, procs);
        let enc = self.encoding();
        let job = std::thread::Builder::new()
            .name("rdem-atom-vtk".into())
            .spawn({
                let path = path.clone();
                move || {
                    write_atomic(&path, snap.format(enc).as_bytes())?;
                    Ok(path)
                }
            });
        match job {
            Ok(h) => self.pending = Some((tag, h)),
            // No thread to be had: write it now.
            Err(_) => done.push((tag, self.write(step, p, selection, procs)?)),
        }
        Ok(done)
    }

    /// Waits for the snapshot being written, if any; returns its tag and path.
    pub fn finish(&mut self) -> Result<Option<(f64, PathBuf)>, IoError> {
        let Some((tag, h)) = self.pending.take() else {
            return Ok(None);
        };
        let path = h.join().expect("the writer thread does not panic")?;
        Ok(Some((tag, path)))
    }
}

impl Drop for AtomVtkDump {
    fn drop(&mut self) {
        let _ = self.finish();
    }
}
