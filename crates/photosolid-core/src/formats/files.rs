//! Reading and writing files safely: the one capped reader and the one
//! atomic writer of the crate.
//!
//! Reading: only regular files are read (a FIFO, `/dev/zero` or a directory
//! would block, grow without bound or fail late), and never more than a cap
//! of bytes, checked while reading (a file can grow after `stat`).
//!
//! Writing: every file the library and the CLI write goes through
//! [`write_atomic_with`]: the bytes go to a temporary file in the target's
//! directory, which is flushed to disk (`fsync`) and renamed over the
//! target. A reader, or a later run after a crash, a full disk or Ctrl-C,
//! sees either the old file or the whole new one, never a part. On error the
//! temporary file is removed and the error names the target path. A target
//! that exists and is a device or FIFO (`/dev/null`, `/dev/full`) is written
//! in place instead, since renaming over it would replace the device node.

use std::fs::File;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Result};

/// Why a capped read failed.
#[derive(Debug)]
pub enum ReadCappedError {
    /// The path is not a regular file (a directory, FIFO, device, socket).
    NotRegular(&'static str),
    /// The file holds more than the cap (bytes).
    TooLarge(u64),
    /// The operating system refused.
    Io(std::io::Error),
}

impl std::fmt::Display for ReadCappedError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadCappedError::NotRegular(what) => write!(f, "it is a {what}, not a regular file"),
            ReadCappedError::TooLarge(cap) => write!(f, "it holds more than {cap} bytes"),
            ReadCappedError::Io(e) => write!(f, "{e}"),
        }
    }
}

fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = meta.file_type();
    if t.is_dir() {
        "directory"
    } else if t.is_fifo() {
        "FIFO (named pipe)"
    } else if t.is_char_device() {
        "character device"
    } else if t.is_block_device() {
        "block device"
    } else if t.is_socket() {
        "socket"
    } else {
        "special file"
    }
}

/// Read the whole regular file at `path`, at most `cap` bytes.
///
/// The type is checked on the path before opening (opening a FIFO would
/// block until a writer appears) and again on the open handle; the cap is
/// enforced while reading, so a file that grows meanwhile is still refused.
pub fn read_capped(path: &Path, cap: u64) -> std::result::Result<Vec<u8>, ReadCappedError> {
    let meta = std::fs::metadata(path).map_err(ReadCappedError::Io)?;
    if !meta.is_file() {
        return Err(ReadCappedError::NotRegular(kind_of(&meta)));
    }
    if meta.len() > cap {
        return Err(ReadCappedError::TooLarge(cap));
    }
    let file = File::open(path).map_err(ReadCappedError::Io)?;
    let meta = file.metadata().map_err(ReadCappedError::Io)?;
    if !meta.is_file() {
        return Err(ReadCappedError::NotRegular(kind_of(&meta)));
    }
    let mut bytes = Vec::with_capacity(meta.len().min(cap) as usize);
    file.take(cap + 1)
        .read_to_end(&mut bytes)
        .map_err(ReadCappedError::Io)?;
    if bytes.len() as u64 > cap {
        return Err(ReadCappedError::TooLarge(cap));
    }
    Ok(bytes)
}

/// Temporary files of this process get distinct names even when several
/// threads write into one directory.
static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A hidden temporary name next to `path`, unique in this process.
fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let k = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}-{k}.tmp", std::process::id()))
}

/// Write `contents` to `path` atomically (see the module docs).
///
/// # Errors
/// [`Error::Io`] naming `path` when the directory is not writable, the disk
/// is full or the rename fails; the target is then untouched and no
/// temporary file is left.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<()> {
    write_atomic_with(path, |f| f.write_all(contents))
}

/// Write `path` atomically through `fill`, which writes the contents into
/// the open temporary file (e.g. an encoder that needs `Seek`).
///
/// # Errors
/// As [`write_atomic`]; an error of `fill` is returned the same way.
pub fn write_atomic_with(path: &Path, fill: impl FnOnce(&mut File) -> std::io::Result<()>) -> Result<()> {
    if path.file_name().is_none() {
        return Err(Error::io(
            path,
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
        ));
    }
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.is_dir() {
            return Err(Error::io(
                path,
                std::io::Error::new(std::io::ErrorKind::IsADirectory, "is a directory"),
            ));
        }
        if !meta.is_file() {
            // A device or FIFO (`/dev/null`, `/dev/full`, a pipe) is written
            // in place: renaming a temporary file over it would replace the
            // device node itself.
            let result = (|| -> std::io::Result<()> {
                let mut f = std::fs::OpenOptions::new().write(true).open(path)?;
                fill(&mut f)?;
                f.flush()
            })();
            return result.map_err(|e| Error::io(path, e));
        }
    }
    let tmp = temp_path(path);
    let result = (|| -> std::io::Result<()> {
        let mut f = std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp)?;
        fill(&mut f)?;
        f.flush()?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(path, e));
    }
    // Make the rename itself durable; a directory that cannot be opened or
    // synced (some file systems) does not undo a completed write.
    if let Some(dir) = path.parent() {
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        if let Ok(d) = File::open(dir) {
            let _ = d.sync_all();
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capped_reader_refuses_special_files_and_large_ones() {
        let dir = tempfile::tempdir().unwrap();
        assert!(matches!(
            read_capped(dir.path(), 10),
            Err(ReadCappedError::NotRegular("directory"))
        ));
        assert!(matches!(
            read_capped(Path::new("/dev/zero"), 10),
            Err(ReadCappedError::NotRegular("character device"))
        ));
        let p = dir.path().join("f");
        std::fs::write(&p, b"0123456789a").unwrap();
        assert!(matches!(read_capped(&p, 10), Err(ReadCappedError::TooLarge(10))));
        assert_eq!(read_capped(&p, 11).unwrap(), b"0123456789a");
    }

    #[test]
    fn atomic_write_replaces_whole_file_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        write_atomic(&p, b"first").unwrap();
        write_atomic(&p, b"second").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"second");
        // A failing fill leaves the old file and no temporary behind.
        let e = write_atomic_with(&p, |f| {
            f.write_all(b"par")?;
            Err(std::io::Error::other("encoder failed"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("out.txt"), "{e}");
        assert_eq!(std::fs::read(&p).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }
}
