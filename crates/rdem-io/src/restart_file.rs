//! rdem's binary restart files: a fixed header that names the file's kind and format
//! version, then a payload (the front end's serialized state) guarded by its length and a
//! CRC-32 checksum.
//!
//! ```text
//! offset  size  content
//!      0    16  magic: "rdem restart\n\0\0\0"
//!     16     4  format version (u32, little-endian)
//!     20     4  CRC-32 (IEEE) of the payload (u32, little-endian)
//!     24     8  payload length in bytes (u64, little-endian)
//!     32     …  payload
//! ```
//!
//! This module only frames the payload; what the payload holds (and its serialization,
//! `postcard`) is the front end's, which writes the framed file whole under a temporary
//! name renamed into place ([`crate::atomic::write_atomic`]), so that a run killed while
//! writing leaves the previous file untouched. Reading checks, in order: the file is long enough for the
//! header, the magic, the version, the length, the checksum; each failure is a
//! [`RestartFileError`] that names the file and says what is wrong.

use std::path::{Path, PathBuf};

use crate::atomic::IoError;

/// The first 16 bytes of every rdem restart file.
pub const MAGIC: &[u8; 16] = b"rdem restart\n\0\0\0";
/// The format version this build writes (and the newest it reads).
pub const FORMAT_VERSION: u32 = 1;
/// Header length in bytes.
pub const HEADER_LEN: usize = 32;

/// Why a restart file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum RestartFileError {
    /// The file could not be opened or read.
    #[error(transparent)]
    Io(#[from] IoError),
    /// Shorter than the header.
    #[error("'{path}' is not a complete rdem restart file: {len} bytes, shorter than the {HEADER_LEN}-byte header")]
    TooShort {
        /// The file.
        path: PathBuf,
        /// Its length.
        len: usize,
    },
    /// Not an rdem restart file (the first bytes say what it looks like).
    #[error("'{path}' is not an rdem restart file ({looks_like})")]
    NotRestart {
        /// The file.
        path: PathBuf,
        /// What the file seems to be instead.
        looks_like: String,
    },
    /// Written by a newer rdem.
    #[error("'{path}' has restart format version {version}; this rdem reads versions 1 to {FORMAT_VERSION} (the file was written by a newer rdem)")]
    Newer {
        /// The file.
        path: PathBuf,
        /// Its format version.
        version: u32,
    },
    /// A format version this rdem does not know (0, or damaged).
    #[error("'{path}' has restart format version {version}, which no rdem writes (the header is damaged)")]
    BadVersion {
        /// The file.
        path: PathBuf,
        /// Its format version.
        version: u32,
    },
    /// Fewer (or more) payload bytes than the header says.
    #[error("'{path}' is truncated: the header announces {expected} bytes of data, the file holds {actual} (was it copied or written only in part?)")]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Payload length from the header.
        expected: u64,
        /// Payload bytes present.
        actual: u64,
    },
    /// The checksum does not match: the bytes were changed after writing.
    #[error(
        "'{path}' is corrupted: its data checksum is {actual:08x}, the header says {expected:08x}"
    )]
    Corrupted {
        /// The file.
        path: PathBuf,
        /// Checksum from the header.
        expected: u32,
        /// Checksum of the bytes read.
        actual: u32,
    },
}

/// Frames `payload` as a restart file of the current format version.
pub fn frame(payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len());
    out.resize(HEADER_LEN, 0);
    out.extend_from_slice(payload);
    fill_header(&mut out);
    out
}

/// Writes the header into the first [`HEADER_LEN`] bytes of `file`, whose payload
/// follows them (a file built in place, without copying the payload again).
pub fn fill_header(file: &mut [u8]) {
    let (head, payload) = file.split_at_mut(HEADER_LEN);
    head[..16].copy_from_slice(MAGIC);
    head[16..20].copy_from_slice(&FORMAT_VERSION.to_le_bytes());
    head[20..24].copy_from_slice(&crc32fast::hash(payload).to_le_bytes());
    head[24..32].copy_from_slice(&(payload.len() as u64).to_le_bytes());
}

/// Reads the restart file at `path`: its format version and payload.
pub fn read_restart_file(path: &Path) -> Result<(u32, Vec<u8>), RestartFileError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::new(path, "read", e))?;
    unframe(path, bytes)
}

/// Checks the framing of `bytes` (read from `path`) and returns the format version and
/// the payload.
pub fn unframe(path: &Path, mut bytes: Vec<u8>) -> Result<(u32, Vec<u8>), RestartFileError> {
    let path_buf = || path.to_path_buf();
    if !bytes.starts_with(MAGIC) {
        // Shorter than the magic but a prefix of it: a file cut short.
        if !bytes.is_empty() && MAGIC.starts_with(&bytes) {
            return Err(RestartFileError::TooShort {
                path: path_buf(),
                len: bytes.len(),
            });
        }
        return Err(RestartFileError::NotRestart {
            path: path_buf(),
            looks_like: looks_like(&bytes),
        });
    }
    if bytes.len() < HEADER_LEN {
        return Err(RestartFileError::TooShort {
            path: path_buf(),
            len: bytes.len(),
        });
    }
    let u32_at = |k: usize| u32::from_le_bytes(bytes[k..k + 4].try_into().expect("4 bytes"));
    let version = u32_at(16);
    let crc = u32_at(20);
    let len = u64::from_le_bytes(bytes[24..32].try_into().expect("8 bytes"));
    if version > FORMAT_VERSION {
        return Err(RestartFileError::Newer {
            path: path_buf(),
            version,
        });
    }
    if version == 0 {
        return Err(RestartFileError::BadVersion {
            path: path_buf(),
            version,
        });
    }
    let actual = (bytes.len() - HEADER_LEN) as u64;
    if actual != len {
        return Err(RestartFileError::Truncated {
            path: path_buf(),
            expected: len,
            actual,
        });
    }
    let payload = bytes.split_off(HEADER_LEN);
    let sum = crc32fast::hash(&payload);
    if sum != crc {
        return Err(RestartFileError::Corrupted {
            path: path_buf(),
            expected: crc,
            actual: sum,
        });
    }
    Ok((version, payload))
}

/// A short description of what a file that is not an rdem restart file seems to be.
fn looks_like(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        return "it is empty".into();
    }
    let head = &bytes[..bytes.len().min(512)];
    if head.starts_with(b"LammpS RestartT") {
        return "it is a LAMMPS binary restart file".into();
    }
    let text = head
        .iter()
        .all(|&b| b.is_ascii_graphic() || b.is_ascii_whitespace());
    if text {
        let s = String::from_utf8_lossy(head);
        if s.contains("atoms") && (s.contains("xlo xhi") || s.contains("atom types")) {
            return "it is a LAMMPS data file, as rdem's restart files were before format \
                    version 1: read it with read_data (it holds no contact histories)"
                .into();
        }
        return "it is a text file".into();
    }
    // LIGGGHTS 3.8 (LAMMPS 2013) binary restart files begin with an int header flag, an
    // int length and the program's version string, "Version LIGGGHTS-PUBLIC 3.8.0, ...".
    if crate::liggghts_restart::is_liggghts_restart(head) {
        return "it is a LIGGGHTS binary restart file: read_restart reads those through \
                rdem_io::liggghts_restart, not as rdem restart files"
            .into();
    }
    "its first bytes are not rdem's".into()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(bytes: Vec<u8>, want: &str) {
        let err = unframe(Path::new("x.restart"), bytes)
            .unwrap_err()
            .to_string();
        assert!(err.contains(want), "{err}");
        assert!(err.contains("x.restart"), "{err}");
    }

    #[test]
    fn frame_roundtrips() {
        let payload = b"some state".to_vec();
        let (v, p) = unframe(Path::new("x"), frame(&payload)).unwrap();
        assert_eq!((v, p), (FORMAT_VERSION, payload));
        let (_, p) = unframe(Path::new("x"), frame(&[])).unwrap();
        assert!(p.is_empty());
    }

    #[test]
    fn every_kind_of_bad_file_is_named() {
        let good = frame(&[7u8; 100]);
        // Truncated anywhere: in the magic, in the header, in the payload.
        check(good[..5].to_vec(), "shorter than the 32-byte header");
        check(good[..20].to_vec(), "shorter than the 32-byte header");
        check(
            good[..90].to_vec(),
            "truncated: the header announces 100 bytes",
        );
        // One payload byte changed.
        let mut bad = good.clone();
        bad[60] ^= 1;
        check(bad, "corrupted");
        // A later format version.
        let mut later = good.clone();
        later[16..20].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
        check(later, "written by a newer rdem");
        let mut zero = good.clone();
        zero[16..20].copy_from_slice(&0u32.to_le_bytes());
        check(zero, "header is damaged");
        // Other programs' files.
        check(Vec::new(), "it is empty");
        check(
            b"LAMMPS data file via write_data\n\n2 atoms\n1 atom types\n".to_vec(),
            "read it with read_data",
        );
        check(b"hello world\n".to_vec(), "text file");
        let mut lig = vec![0u8, 0, 0, 0, 40, 0, 0, 0];
        lig.extend_from_slice(b"Version LIGGGHTS-PUBLIC 3.8.0, compiled ...\0");
        check(lig, "LIGGGHTS binary restart file");
        check(vec![0xff; 64], "first bytes are not rdem's");
    }
}
