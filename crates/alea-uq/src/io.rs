//! CSV in and out for designs, samples and run values: a header line of column names, then one
//! row of numbers per point, comma separated (`#` starts a comment line, blank lines are
//! skipped). Numbers are written with Rust's shortest round-trip formatting, so writing then
//! reading gives back the same bits. Reading errors name the file, the line and the column.
//!
//! Written by hand (a few dozen lines) rather than with the `csv` crate: the format is fixed,
//! numeric, and the error messages must name line and column.

use crate::design::Design;
use crate::error::{Result, UqError};
use std::io::Write;
use std::path::Path;

/// A numeric table: column names and row-major values (`rows x names.len()`).
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Column names.
    pub names: Vec<String>,
    /// Row-major values.
    pub values: Vec<f64>,
}

impl Table {
    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.names.len()
    }
    /// Number of rows.
    pub fn rows(&self) -> usize {
        if self.names.is_empty() {
            0
        } else {
            self.values.len() / self.names.len()
        }
    }
    /// Column `name` as a vector, if present.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let j = self.names.iter().position(|n| n == name)?;
        Some(
            self.values
                .iter()
                .skip(j)
                .step_by(self.cols())
                .copied()
                .collect(),
        )
    }
}

fn file_err(path: &Path, message: String) -> UqError {
    UqError::File {
        path: path.display().to_string(),
        message,
    }
}

/// Write `names` and the row-major `values` as CSV.
///
/// # Errors
/// If `values.len()` is not a multiple of `names.len()`, a value is not finite (never a NaN in
/// a result file), a name contains a comma or newline, or the file cannot be written.
pub fn write_csv(path: impl AsRef<Path>, names: &[&str], values: &[f64]) -> Result<()> {
    let path = path.as_ref();
    let n = names.len();
    if n == 0 || !values.len().is_multiple_of(n) {
        return Err(file_err(
            path,
            format!("{} values do not fill rows of {n} columns", values.len()),
        ));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(file_err(
            path,
            format!(
                "row {}, column {:?}: value {} is not finite",
                i / n + 1,
                names[i % n],
                values[i]
            ),
        ));
    }
    if let Some(bad) = names.iter().find(|s| s.contains([',', '\n', '\r'])) {
        return Err(file_err(
            path,
            format!("column name {bad:?} contains a separator"),
        ));
    }
    let mut out = String::with_capacity(values.len() * 20);
    out.push_str(&names.join(","));
    out.push('\n');
    for row in values.chunks_exact(n) {
        for (j, v) in row.iter().enumerate() {
            if j > 0 {
                out.push(',');
            }
            out.push_str(&format!("{v:?}"));
        }
        out.push('\n');
    }
    std::fs::File::create(path)
        .and_then(|mut f| f.write_all(out.as_bytes()))
        .map_err(|e| file_err(path, e.to_string()))
}

/// Read a CSV written by [`write_csv`] (or by hand): header, then numeric rows.
///
/// # Errors
/// If the file cannot be read, has no header, a row has the wrong number of fields, or a field
/// is not a finite number (the message names line and column).
pub fn read_csv(path: impl AsRef<Path>) -> Result<Table> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| file_err(path, e.to_string()))?;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(file_err(path, "empty file (no header line)".into()));
    };
    let names: Vec<String> = header.split(',').map(|s| s.trim().to_string()).collect();
    let mut values = Vec::new();
    for (i, line) in lines {
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != names.len() {
            return Err(file_err(
                path,
                format!(
                    "line {}: {} fields, expected {} ({})",
                    i + 1,
                    fields.len(),
                    names.len(),
                    names.join(",")
                ),
            ));
        }
        for (f, name) in fields.iter().zip(&names) {
            let v: f64 = f.trim().parse().map_err(|_| {
                file_err(
                    path,
                    format!(
                        "line {}, column {name:?}: {:?} is not a number",
                        i + 1,
                        f.trim()
                    ),
                )
            })?;
            if !v.is_finite() {
                return Err(file_err(
                    path,
                    format!("line {}, column {name:?}: {v} is not finite", i + 1),
                ));
            }
            values.push(v);
        }
    }
    Ok(Table { names, values })
}

impl Design {
    /// Write the points as CSV with columns `names` (one per variable).
    ///
    /// # Errors
    /// If `names.len() != dim()` or the file cannot be written.
    pub fn to_csv(&self, path: impl AsRef<Path>, names: &[&str]) -> Result<()> {
        crate::error::check_len("design CSV", "names", self.dim(), names.len())?;
        write_csv(path, names, self.points())
    }
    /// Read a design from a CSV of points (every column is a variable).
    ///
    /// # Errors
    /// As [`read_csv`], or if the file has no rows.
    pub fn from_csv(path: impl AsRef<Path>) -> Result<(Self, Vec<String>)> {
        let t = read_csv(path.as_ref())?;
        if t.rows() == 0 {
            return Err(file_err(path.as_ref(), "no data rows".into()));
        }
        Ok((Design::new(t.cols(), t.values)?, t.names))
    }
}
