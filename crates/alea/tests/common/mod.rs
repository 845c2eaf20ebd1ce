//! Helpers shared by the CLI tests: a fresh scratch directory and a command's whole output.

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
