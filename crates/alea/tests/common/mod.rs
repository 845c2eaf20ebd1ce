//! Helpers shared by the CLI tests: a fresh scratch directory, a command's whole output, and
//! access to the runs' data in a study directory's database.

use std::path::{Path, PathBuf};
use std::process::Output;

/// An empty directory `<temp>/<prefix>-<pid>-<name>` (removed first if it exists).
#[allow(dead_code)]
pub fn fresh_dir(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("{prefix}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Standard output then standard error of `o`, as text.
#[allow(dead_code)]
pub fn text(o: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Writes `<dir>/<name>.toml`: `text` with `edits` (`from`, `to`: each the first occurrence,
/// which must exist) applied and `tail` appended; returns its path and text.
#[allow(dead_code)]
pub fn write_case(
    dir: &Path,
    name: &str,
    text: &str,
    edits: &[(&str, &str)],
    tail: &str,
) -> (PathBuf, String) {
    let mut s = text.to_string();
    for (from, to) in edits {
        assert!(s.contains(from), "{from}");
        s = s.replacen(from, to, 1);
    }
    s.push_str(tail);
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(&p, &s).unwrap();
    (p, s)
}

/// The number of runs of the study in `dir` with stored data in `column` of the database's
/// `run_data` table (`fields`, or `cre`: the error estimate); 0 while there is no database yet.
#[allow(dead_code)]
pub fn stored_runs(dir: &Path, column: &str) -> usize {
    let count = || -> rusqlite::Result<i64> {
        let c = rusqlite::Connection::open_with_flags(
            dir.join("study.db"),
            rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY,
        )?;
        c.busy_timeout(std::time::Duration::from_secs(5))?;
        c.query_row(
            &format!("SELECT COUNT(*) FROM run_data WHERE {column} IS NOT NULL"),
            [],
            |r| r.get(0),
        )
    };
    count().map(|n| n as usize).unwrap_or(0)
}

/// Runs `sql` on the database of the study directory `dir` (a test damaging its runs' data).
#[allow(dead_code)]
pub fn run_sql(dir: &Path, sql: &str) {
    let c = rusqlite::Connection::open(dir.join("study.db")).unwrap();
    c.execute_batch(sql).unwrap();
}
