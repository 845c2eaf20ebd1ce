//! `summary.json` (everything a study found, for programs; the total intervals beside the
//! sampling-only ones: `summary_intervals.rs`) and `samples.csv` (the main method's draws).

use std::io::Write;
use std::path::{Path, PathBuf};

use alea_study::analysis::MethodResult;
use alea_study::runner::{Study, StudyRuns};

use super::estimate::{MethodEstimate, adaptive_json, error_json};
use super::summary_intervals::add_intervals;
use crate::{Console, Error};

/// Writes `summary.json` into `dir`; returns its path.
pub(super) fn write_summary(
    study: &Study,
    dir: &Path,
    results: &[MethodResult],
    study_runs: &StudyRuns,
    estimates: &[MethodEstimate],
    reliability: &[alea_study::reliability::ReliabilityResult],
    notes: &[String],
    console: &dyn Console,
) -> Result<PathBuf, Error> {
    let records = &study_runs.records;
    let runs: Vec<serde_json::Value> = records
        .iter()
        .map(|r| {
            serde_json::json!({
                "params": r.params, "status": r.status, "iterations": r.iterations,
                "residual": r.residual, "qois": r.qois,
                "slide": r.slide.as_ref().map(|s| serde_json::json!({
                    "interface": s.interface, "slip": s.slip, "ratio": s.ratio,
                })),
            })
        })
        .collect();
    let methods: Vec<serde_json::Value> = results
        .iter()
        .enumerate()
        .map(|(m, r)| {
            let mut v = serde_json::json!({
                "label": r.label, "description": r.description, "design_runs": r.design_runs,
                "runs_used": r.runs_used, "left_out": r.left_out, "error": r.error,
                "failure_region": r.failure_region,
                "draws": r.draws, "qois": r.qois,
            });
            add_intervals(&mut v["qois"], &r.qois);
            if let Some(e) = estimates.iter().find(|e| e.method == m) {
                v["error_estimate"] = match &e.result {
                    Ok(me) => error_json(me),
                    Err(why) => serde_json::json!({ "unavailable": why }),
                };
            }
            if let Some(a) = study_runs.adaptive.iter().find(|a| a.method == m) {
                v["adaptive"] = adaptive_json(a);
            }
            v
        })
        .collect();
    let v = serde_json::json!({
        "title": study.title(),
        "study_file": study.file_name(),
        "study_hash": study.hash,
        "seed": study.seed,
        "units": {
            "length": study.model.units.length, "force": study.model.units.force,
            "stress": study.model.units.stress, "density": study.model.units.density,
        },
        "parameters": study.params.names.iter().enumerate().map(|(j, n)| serde_json::json!({
            "name": n, "law": study.params.descriptions[j], "unit": study.params.units[j],
            "lo": study.params.lo[j], "hi": study.params.hi[j], "nominal": study.params.nominal[j],
        })).collect::<Vec<_>>(),
        "methods": methods,
        "reliability": reliability,
        "runs": runs,
        "notes": notes,
    });
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
        r.label
    ));
    Ok(Some(path))
}
