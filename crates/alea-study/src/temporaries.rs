//! Temporary files left in a study directory by a killed process.
//!
//! Every file of a study directory is written to a hidden temporary beside it,
//! `.<name>.tmp-<pid>` ([`alea_mesh::atomic::temporary_path`]), then renamed into place; a
//! process killed in between leaves its temporary (a samples file, the report's input, a
//! ParaView file can be megabytes). [`remove_stale`] removes them from the directory and its
//! sub-directories (`report/`, `paraview/`, `vtu/`, and `fields/`, `cre/` of directories
//! written when each run's data was a file, ... down to [`MAX_DEPTH`] levels). It runs when the directory's lock is taken and again when it is released (on
//! success and on error), so the only writer of the directory is the caller: a temporary of a
//! dead process is removed, and so is one of this process (nothing of it is being written
//! while it takes or lets go of the lock). A temporary of another live process (which would be
//! writing there without the lock) is kept.

use std::path::Path;

/// Levels of sub-directories searched below the study directory.
pub const MAX_DEPTH: usize = 3;

/// The process id in a temporary's name `.<name>.tmp-<pid>`, `None` for any other name.
pub fn temporary_pid(name: &str) -> Option<u32> {
    if !name.starts_with('.') {
        return None;
    }
    let (_, pid) = name.rsplit_once(".tmp-")?;
    if pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// True if process `pid` is running (Linux: `/proc/<pid>` exists; where `/proc` is missing, only
/// this process is known to run).
fn running(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    proc.join("self").exists() && proc.join(pid.to_string()).exists()
}

/// Removes the temporaries of dead processes and of this process from `dir` and its
/// sub-directories; returns how many were removed. Best effort: a file that cannot be removed
/// is left.
pub fn remove_stale(dir: &Path) -> usize {
    remove_in(dir, MAX_DEPTH)
}

fn remove_in(dir: &Path, depth: usize) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut removed = 0;
    for e in entries.flatten() {
        let Ok(kind) = e.file_type() else { continue };
        if kind.is_dir() {
            if depth > 0 {
                removed += remove_in(&e.path(), depth - 1);
            }
            continue;
        }
        let name = e.file_name();
        let Some(pid) = temporary_pid(&name.to_string_lossy()) else {
            continue;
        };
        if (pid == std::process::id() || !running(pid)) && std::fs::remove_file(e.path()).is_ok() {
            removed += 1;
        }
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporaries_of_dead_processes_go_and_everything_else_stays() {
        let d = std::env::temp_dir().join(format!("alea-tmp-sweep-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        for sub in ["fields", "report/plots"] {
            std::fs::create_dir_all(d.join(sub)).unwrap();
        }
        // pid 1 is running on any Unix; 4 000 000 is above Linux's pid_max.
        let dead = 4_000_000;
        let stale = [
            format!(".samples.csv.tmp-{dead}"),
            format!("report/.report-input.json.tmp-{dead}"),
            format!("fields/.run_0123456789abcdef.bin.tmp-{dead}"),
            format!("report/plots/.pdf.png.tmp-{}", std::process::id()),
        ];
        let kept = [
            "samples.csv".to_string(),
            "fields/run_0123456789abcdef.bin".into(),
            ".hidden".into(),
            "x.tmp-12".into(),
            ".y.tmp-12a".into(),
        ];
        for f in stale.iter().chain(&kept) {
            std::fs::write(d.join(f), b"x").unwrap();
        }
        let live = ".summary.json.tmp-1";
        if Path::new("/proc/1").exists() {
            std::fs::write(d.join(live), b"x").unwrap();
        }
        assert_eq!(remove_stale(&d), stale.len());
        for f in &stale {
            assert!(!d.join(f).exists(), "{f} removed");
        }
        for f in &kept {
            assert!(d.join(f).exists(), "{f} kept");
        }
        if Path::new("/proc/1").exists() {
            assert!(d.join(live).exists(), "a live process's temporary is kept");
        }
        assert_eq!(temporary_pid(".a.tmp-77"), Some(77));
        assert_eq!(temporary_pid("a.tmp-77"), None);
        assert_eq!(temporary_pid(".a.tmp-"), None);
    }
}
