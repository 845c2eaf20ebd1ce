//! Output files written all at once or not at all.
//!
//! [`write_atomic`] writes into a temporary file beside the target (same directory, so the same
//! file system), flushes and syncs it, then renames it over the target and syncs the directory.
//! A process killed at any moment leaves either the previous file or the complete new one,
//! never a truncated one. A killed writer may leave its hidden temporary `.<name>.tmp-<pid>`
//! behind; nothing reads it, and the next write replaces the target whole.
//!
//! Every output file of alea (VTU/VTM, `summary.json`, `samples.csv`, report pages and plots,
//! contact CSVs) goes through here. Written by hand: `tempfile::NamedTempFile::persist` does the
//! same rename but neither syncs the file nor the directory, and the whole is 40 lines.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The temporary file used while writing `path`: `.<name>.tmp-<pid>` in the same directory.
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or("output".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// A name made safe for a file name: ASCII letters, digits, `-` and `_` kept, anything else
/// replaced by `_` (one per character).
pub fn safe_file_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes `path` atomically: `write` fills a buffered writer on a temporary file, which is then
/// synced and renamed over `path`. On any error the temporary file is removed and `path` is
/// left as it was.
///
/// # Errors
/// The first I/O error of creating, writing, syncing or renaming.
pub fn write_atomic<F>(path: &Path, write: F) -> std::io::Result<()>
where
    F: FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
{
    let tmp = temporary_path(path);
    let result = (|| {
        let mut w = BufWriter::new(File::create(&tmp)?);
        write(&mut w)?;
        w.flush()?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
        return result;
    }
    sync_parent(path);
    Ok(())
}

/// [`write_atomic`] of a byte buffer.
///
/// # Errors
/// As [`write_atomic`].
pub fn write_bytes_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic(path, |w| w.write_all(bytes))
}

/// [`write_bytes_atomic`] without syncing the directory: the file's bytes are synced and it is
/// renamed into place, and the caller syncs the directory ([`sync_parent`]) once after a
/// group of such writes, before anything that relies on them surviving a power loss.
///
/// # Errors
/// As [`write_atomic`].
pub fn write_bytes_atomic_unsynced_dir(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = temporary_path(path);
    let result = (|| {
        let mut file = File::create(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Syncs the directory holding `path`, so that a rename into it survives a power loss (best
/// effort: not every platform can open a directory).
pub fn sync_parent(path: &Path) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("alea-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_failed_write_leaves_the_previous_file_and_no_temporary() {
        let d = dir("fail");
        let p = d.join("summary.json");
        write_bytes_atomic(&p, b"old complete content").unwrap();
        let err = write_atomic(&p, |w| {
            w.write_all(b"new half")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk full");
        assert_eq!(std::fs::read(&p).unwrap(), b"old complete content");
        let names: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("summary.json")]);
    }

    #[test]
    fn a_successful_write_replaces_the_file_whole() {
        let d = dir("ok");
        let p = d.join("samples.csv");
        write_bytes_atomic(&p, b"a,b\n1,2\n").unwrap();
        write_atomic(&p, |w| {
            for i in 0..1000 {
                writeln!(w, "{i},{}", 2 * i)?;
            }
            Ok(())
        })
        .unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert_eq!(text.lines().count(), 1000);
        assert!(text.ends_with("999,1998\n"));
        assert!(!temporary_path(&p).exists());
    }

    #[test]
    fn a_missing_directory_is_an_error_not_a_panic() {
        let p = Path::new("/nonexistent-alea-dir/x.vtu");
        assert!(write_bytes_atomic(p, b"x").is_err());
    }
}
