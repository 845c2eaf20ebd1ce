//! `summary.json` (everything a study found, for programs: a [`StudyResult`] written by
//! `serde_json`) and `samples.csv` (the main method's draws).

use std::io::Write;
use std::path::{Path, PathBuf};

use alea_study::analysis::MethodResult;
use alea_study::runner::Study;

use super::result::StudyResult;
use crate::{Console, Error};

/// Writes `summary.json` (`result`) into `dir`; returns its path.
pub(super) fn write_summary(
    result: &StudyResult,
    dir: &Path,
    console: &dyn Console,
) -> Result<PathBuf, Error> {
    // Through a `serde_json::Value`: its maps keep their keys sorted, the order the file has
    // always had.
    let v = serde_json::to_value(result)?;
    let text = serde_json::to_string_pretty(&v)?;
    if text.contains("NaN") {
        return Err(Error::NonFinite);
    }
    let path = dir.join("summary.json");
    alea_mesh::atomic::write_bytes_atomic(&path, text.as_bytes()).map_err(|source| {
        Error::Write {
            path: path.clone(),
            source,
        }
    })?;
    console.line(&format!("summary: {}", path.display()));
    Ok(path)
}

/// Writes `samples.csv` (parameters then quantities, one line per draw of method `r`: its first
/// draws up to the study's `[output] samples_rows`, or all of them) into `dir`; returns its
/// path, `None` if `r` has no draws.
pub(super) fn write_samples(
    study: &Study,
    dir: &Path,
    r: &MethodResult,
    console: &dyn Console,
) -> Result<Option<PathBuf>, Error> {
    if r.qois.is_empty() || r.points.is_empty() {
        return Ok(None);
    }
    let path = dir.join("samples.csv");
    let d = study.params.names.len();
    let header: Vec<String> = study
        .params
        .names
        .iter()
        .cloned()
        .chain(study.qois.iter().map(|q| q.name.clone()))
        .collect();
    let rows = study.samples_rows.map_or(r.draws, |n| n.min(r.draws));
    alea_mesh::atomic::write_atomic(&path, |w| {
        writeln!(w, "{}", header.join(","))?;
        for i in 0..rows {
            let mut line = String::new();
            for j in 0..d {
                line.push_str(&format!("{:.10e},", r.points[i * d + j]));
            }
            let vals: Vec<String> = r
                .qois
                .iter()
                .map(|q| format!("{:.10e}", q.samples[i]))
                .collect();
            line.push_str(&vals.join(","));
            writeln!(w, "{line}")?;
        }
        Ok(())
    })
    .map_err(|source| Error::Write {
        path: path.clone(),
        source,
    })?;
    let written = if rows < r.draws {
        format!("the first {rows} of {} draws", r.draws)
    } else {
        format!("{} draws", r.draws)
    };
    console.line(&format!(
        "samples: {} ({written} on the {} surrogate)",
        path.display(),
        r.account.label
    ));
    Ok(Some(path))
}
