//! Writing files so that no reader ever sees a half-written one.
//!
//! [`write_atomic`] writes the whole content to a temporary file in the target's directory
//! (so the final rename cannot cross file systems) and renames it over the target only
//! when every byte was written; on any error the temporary file is removed and the old
//! target, if any, is left as it was. Missing parent directories are created, as
//! LIGGGHTS does for the `post/` directory its tutorials write to.
//!
//! A dump without `*` in its name collects every snapshot in one file. Copying that file
//! for each snapshot would make a long run quadratic, so [`AppendFile`] creates the file
//! atomically with the first snapshot and then appends each further snapshot with one
//! write; if that write fails, the file is cut back to its previous length, so it always
//! ends with a complete snapshot.
//!
//! Files are not `fsync`ed: the guarantee is against a crashed or killed run, not against
//! a power failure.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A file operation that failed: which file, what was being done, and why.
#[derive(Debug, thiserror::Error)]
#[error("cannot {op} '{}': {source}", path.display())]
pub struct IoError {
    /// The file (or directory) concerned.
    pub path: PathBuf,
    /// What was being done, e.g. "write", "read", "create directory".
    pub op: &'static str,
    /// The operating system's reason.
    #[source]
    pub source: io::Error,
}

impl IoError {
    /// Wraps `source` with the path and operation.
    pub fn new(path: impl Into<PathBuf>, op: &'static str, source: io::Error) -> Self {
        Self {
            path: path.into(),
            op,
            source,
        }
    }
}

/// Creates the parent directory of `path` (and its ancestors) if it is missing.
pub fn create_parent_dir(path: &Path) -> Result<(), IoError> {
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() && !dir.is_dir() {
            fs::create_dir_all(dir).map_err(|e| IoError::new(dir, "create directory", e))?;
        }
    }
    Ok(())
}

/// A fresh temporary name next to `path`: `.<name>.<pid>.<n>.tmp`.
fn temp_path(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "rdem".into());
    path.with_file_name(format!(".{name}.{}.{n}.tmp", std::process::id()))
}

/// Writes `contents` to `path` atomically (temporary file + rename), creating missing
/// parent directories.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), IoError> {
    create_parent_dir(path)?;
    let tmp = temp_path(path);
    let result = (|| {
        let mut f = File::create(&tmp).map_err(|e| IoError::new(&tmp, "create", e))?;
        f.write_all(contents)
            .and_then(|_| f.flush())
            .map_err(|e| IoError::new(path, "write", e))?;
        drop(f);
        fs::rename(&tmp, path).map_err(|e| IoError::new(path, "rename temporary file onto", e))
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// A file that grows by whole records: created atomically with its first record, then
/// appended to; a failed append is rolled back to the previous length.
#[derive(Debug)]
pub struct AppendFile {
    path: PathBuf,
    file: Option<File>,
    len: u64,
}

impl AppendFile {
    /// A file at `path`, not yet created (an existing file is replaced by the first
    /// record, as LIGGGHTS truncates a dump file when the dump is defined).
    pub fn new(path: impl Into<PathBuf>) -> Self {
        Self {
            path: path.into(),
            file: None,
            len: 0,
        }
    }

    /// The file at `path` opened for appending (created, with missing parent
    /// directories, if it does not exist): records go after what it holds.
    pub fn appending(path: impl Into<PathBuf>) -> Result<Self, IoError> {
        let path = path.into();
        create_parent_dir(&path)?;
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| IoError::new(&path, "open for appending", e))?;
        let len = file
            .metadata()
            .map_err(|e| IoError::new(&path, "read the length of", e))?
            .len();
        Ok(Self {
            path,
            file: Some(file),
            len,
        })
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one complete record.
    pub fn append(&mut self, record: &[u8]) -> Result<(), IoError> {
        let Some(file) = self.file.as_mut() else {
            write_atomic(&self.path, record)?;
            let file = OpenOptions::new()
                .append(true)
                .open(&self.path)
                .map_err(|e| IoError::new(&self.path, "open for appending", e))?;
            self.file = Some(file);
            self.len = record.len() as u64;
            return Ok(());
        };
        match file.write_all(record).and_then(|_| file.flush()) {
            Ok(()) => {
                self.len += record.len() as u64;
                Ok(())
            }
            Err(e) => {
                // Cut off whatever part of the record made it to the file.
                let _ = file.set_len(self.len);
                Err(IoError::new(&self.path, "append to", e))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("rdem-io-atomic-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn appending_keeps_what_the_file_holds() {
        let d = scratch("appending");
        let p = d.join("sub/log.txt");
        let mut f = AppendFile::appending(&p).unwrap();
        f.append(b"one\n").unwrap();
        drop(f);
        let mut f = AppendFile::appending(&p).unwrap();
        f.append(b"two\n").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "one\ntwo\n");
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn creates_parents_and_leaves_no_temporaries() {
        let d = scratch("parents");
        let p = d.join("post/deep/file.txt");
        write_atomic(&p, b"hello").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "hello");
        write_atomic(&p, b"again").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "again");
        let names: Vec<_> = fs::read_dir(p.parent().unwrap())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("file.txt")]);
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn failure_names_the_file_and_keeps_the_old_one() {
        let d = scratch("fail");
        fs::create_dir_all(&d).unwrap();
        // A directory where the file should go: the rename must fail.
        let p = d.join("target");
        fs::create_dir_all(p.join("inner")).unwrap();
        let err = write_atomic(&p, b"x").unwrap_err();
        let msg = err.to_string();
        assert!(msg.contains("target"), "{msg}");
        assert_eq!(err.path, p);
        assert!(p.join("inner").is_dir());
        // The temporary file was removed.
        assert_eq!(fs::read_dir(&d).unwrap().count(), 1);
        // A parent that is a file cannot be created.
        let f = d.join("plain");
        fs::write(&f, b"").unwrap();
        let err = write_atomic(&f.join("x.txt"), b"x").unwrap_err();
        assert_eq!(err.op, "create directory");
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn append_file_replaces_then_appends() {
        let d = scratch("append");
        let p = d.join("out/all.txt");
        create_parent_dir(&p).unwrap();
        fs::write(&p, b"old content from an earlier run\n").unwrap();
        let mut a = AppendFile::new(&p);
        a.append(b"one\n").unwrap();
        a.append(b"two\n").unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "one\ntwo\n");
        assert_eq!(a.path(), p);
        fs::remove_dir_all(&d).unwrap();
    }
}
