//! One process at a time in a study directory.
//!
//! [`StudyLock::acquire`] takes an exclusive advisory lock (`flock` on Unix, `LockFileEx` on
//! Windows, through `std::fs::File::try_lock`) on an open descriptor of the study directory
//! itself (Unix) and on `<dir>/lock`, and writes who holds it in the lock file: process id, host
//! name, start time (UTC) and command. The lock on the directory is what holds: deleting or
//! replacing the lock file during a run does not free the directory for a second process (it
//! is refused, busy, even if it cannot say who holds the lock then); a directory removed and
//! created again is another directory, whose store starts empty. A second process finds the lock held and
//! refuses with [`StudyError::Busy`], naming the holder. The operating system releases the lock
//! when the holder exits, however it exits (SIGKILL, crash, power loss), so a lock file left by
//! a dead process is never an obstacle: the next process takes the lock, reports the previous
//! holder (see [`StudyLock::previous`]) and overwrites the record. No pid probing, no timeouts.
//!
//! On release (drop) the record is emptied before the lock is let go, so a non-empty record in
//! a free lock file always means its writer died while holding it.
//!
//! Limits: advisory locks bind only processes that ask for them (every `alea` command that
//! writes to a study directory does); on network file systems they are as reliable as the
//! file system's lock support (NFSv4 and SMB support them; some FUSE mounts do not, and then
//! acquiring fails with an I/O error rather than silently not locking).

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use crate::StudyError;

/// The exclusive lock of a study directory, held until dropped.
#[derive(Debug)]
pub struct StudyLock {
    /// The open study directory (locked on Unix; `None` elsewhere).
    _dir: Option<File>,
    file: File,
    path: PathBuf,
    previous: Option<String>,
}

/// The name of the lock file in a study directory.
pub const LOCK_FILE: &str = "lock";

impl StudyLock {
    /// Takes the lock of study directory `dir` (created if needed) for `command` (e.g.
    /// `"alea run study.toml"`).
    ///
    /// # Errors
    /// [`StudyError::Busy`] if another process holds it (the message names it);
    /// [`StudyError::Io`] if the directory or lock file cannot be created or locked.
    pub fn acquire(dir: &Path, command: &str) -> Result<Self, StudyError> {
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| StudyError::Io { path: p, source }
        };
        if dir.exists() && !dir.is_dir() {
            return Err(StudyError::Usage(format!(
                "{} is a file, not a study directory: give --dir a directory (it is created if \
                 missing)",
                dir.display()
            )));
        }
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let path = dir.join(LOCK_FILE);
        let dir_handle = lock_directory(dir, &path)?;
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(io(&path))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let holder = read_record(&mut file);
                return Err(StudyError::Busy {
                    dir: dir.to_path_buf(),
                    holder: if holder.is_empty() {
                        "another process (it has not written its details yet)".into()
                    } else {
                        holder
                    },
                });
            }
            Err(TryLockError::Error(source)) => return Err(StudyError::Io { path, source }),
        }
        let previous = Some(read_record(&mut file)).filter(|r| !r.is_empty());
        let record = format!(
            "pid {} on host {}, started {} ({command})",
            std::process::id(),
            host_name(),
            utc_now()
        );
        file.set_len(0).map_err(io(&path))?;
        file.seek(SeekFrom::Start(0)).map_err(io(&path))?;
        file.write_all(record.as_bytes()).map_err(io(&path))?;
        file.sync_all().map_err(io(&path))?;
        crate::temporaries::remove_stale(dir);
        Ok(StudyLock {
            _dir: dir_handle,
            file,
            path,
            previous,
        })
    }

    /// [`StudyLock::acquire`] on a directory that must already exist.
    ///
    /// # Errors
    /// [`StudyError::Usage`] if `dir` is not a directory; as [`StudyLock::acquire`].
    pub fn acquire_existing(dir: &Path, command: &str) -> Result<Self, StudyError> {
        if !dir.is_dir() {
            return Err(StudyError::Usage(format!(
                "{} is not a study directory (it does not exist or is not a directory)",
                dir.display()
            )));
        }
        Self::acquire(dir, command)
    }

    /// The record left by a previous holder that died holding the lock (the lock was taken
    /// over), if any.
    pub fn previous(&self) -> Option<&str> {
        self.previous.as_deref()
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for StudyLock {
    fn drop(&mut self) {
        // Whatever ends the command (success or error), no temporary of it stays behind.
        if let Some(dir) = self.path.parent() {
            crate::temporaries::remove_stale(dir);
        }
        // Empty record = released cleanly; the lock itself goes with the file handle.
        let _ = self.file.set_len(0);
        let _ = self.file.unlock();
    }
}

/// Locks the study directory through an open descriptor of it (Unix): the lock that holds even
/// if the lock file is removed. `Busy` names the holder from the lock file when it still can.
#[cfg(unix)]
fn lock_directory(dir: &Path, lock_file: &Path) -> Result<Option<File>, StudyError> {
    let handle = File::open(dir).map_err(|source| StudyError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    match handle.try_lock() {
        Ok(()) => Ok(Some(handle)),
        Err(TryLockError::WouldBlock) => {
            let holder = File::open(lock_file)
                .map(|mut f| read_record(&mut f))
                .unwrap_or_default();
            Err(StudyError::Busy {
                dir: dir.to_path_buf(),
                holder: if holder.is_empty() {
                    "another process (its lock file is empty or was removed)".into()
                } else {
                    holder
                },
            })
        }
        Err(TryLockError::Error(source)) => Err(StudyError::Io {
            path: dir.to_path_buf(),
            source,
        }),
    }
}

/// Elsewhere a directory cannot be opened as a file: the lock file alone.
#[cfg(not(unix))]
fn lock_directory(_dir: &Path, _lock_file: &Path) -> Result<Option<File>, StudyError> {
    Ok(None)
}

fn read_record(file: &mut File) -> String {
    let mut s = String::new();
    let _ = file.seek(SeekFrom::Start(0));
    let _ = file.take(4096).read_to_string(&mut s);
    s.trim().to_string()
}

/// The host name (Linux: the kernel's; elsewhere the usual environment variables).
fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .unwrap_or_else(|| "unknown".into())
}

/// The current time as `YYYY-MM-DD HH:MM:SS UTC`.
pub fn utc_now() -> String {
    utc_from_unix(
        SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()) as i64,
    )
}

/// Seconds since 1970-01-01 00:00:00 UTC as `YYYY-MM-DD HH:MM:SS UTC`.
pub fn utc_from_unix(secs: i64) -> String {
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("alea-lock-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn a_second_holder_is_refused_with_the_first_named() {
        let d = dir("busy");
        let first = StudyLock::acquire(&d, "alea run a.toml").unwrap();
        assert!(first.previous().is_none());
        // A second open file description conflicts even within one process.
        let err = StudyLock::acquire(&d, "alea run b.toml").unwrap_err();
        let msg = err.to_string();
        assert_eq!(err.exit_code(), 5, "{msg}");
        assert!(
            msg.contains(&format!("pid {}", std::process::id()))
                && msg.contains("host ")
                && msg.contains("UTC")
                && msg.contains("alea run a.toml"),
            "{msg}"
        );
        drop(first);
        // Released cleanly: the next holder finds no previous record.
        let again = StudyLock::acquire(&d, "alea run b.toml").unwrap();
        assert!(again.previous().is_none());
    }

    #[test]
    fn a_lock_left_by_a_dead_process_is_taken_over() {
        let d = dir("stale");
        std::fs::create_dir_all(&d).unwrap();
        // What a SIGKILLed holder leaves: its record, and no lock (the OS released it).
        let stale = "pid 999999 on host elsewhere, started 2020-01-01 00:00:00 UTC (alea run)";
        std::fs::write(d.join(LOCK_FILE), stale).unwrap();
        let lock = StudyLock::acquire(&d, "alea run c.toml").unwrap();
        assert_eq!(lock.previous(), Some(stale));
        let now = std::fs::read_to_string(lock.path()).unwrap();
        assert!(
            now.starts_with(&format!("pid {} ", std::process::id())),
            "{now}"
        );
        drop(lock);
        assert_eq!(std::fs::read_to_string(d.join(LOCK_FILE)).unwrap(), "");
    }

    #[test]
    #[cfg(unix)]
    fn the_lock_holds_when_its_file_is_removed() {
        let d = dir("removed");
        let first = StudyLock::acquire(&d, "alea run a.toml").unwrap();
        std::fs::remove_file(d.join(LOCK_FILE)).unwrap();
        let err = StudyLock::acquire(&d, "alea run --restart b.toml").unwrap_err();
        assert_eq!(err.exit_code(), 5, "{err}");
        assert!(err.to_string().contains("was removed"), "{err}");
        // Replaced by an empty file: still refused.
        std::fs::write(d.join(LOCK_FILE), "").unwrap();
        assert_eq!(
            StudyLock::acquire(&d, "alea run b.toml")
                .unwrap_err()
                .exit_code(),
            5
        );
        drop(first);
        StudyLock::acquire(&d, "alea run b.toml").unwrap();
    }

    #[test]
    fn a_file_named_as_the_directory_is_a_usage_error() {
        let d = dir("file");
        std::fs::write(&d, "not a directory").unwrap();
        let err = StudyLock::acquire(&d, "alea run a.toml").unwrap_err();
        assert_eq!(err.exit_code(), 2, "{err}");
        assert!(
            err.to_string().contains("is a file, not a study directory"),
            "{err}"
        );
        let _ = std::fs::remove_file(&d);
    }

    #[test]
    fn utc_dates_are_civil_dates() {
        assert_eq!(utc_from_unix(0), "1970-01-01 00:00:00 UTC");
        assert_eq!(utc_from_unix(951_782_400), "2000-02-29 00:00:00 UTC");
        assert_eq!(
            utc_from_unix(1_709_208_000 + 3_723),
            "2024-02-29 13:02:03 UTC"
        );
        assert_eq!(utc_from_unix(4_102_444_799), "2099-12-31 23:59:59 UTC");
    }
}
