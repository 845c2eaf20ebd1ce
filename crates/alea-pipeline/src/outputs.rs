//! Every output of a study whose runs are done: warnings, statistics, error estimates,
//! `summary.json`, `samples.csv`, mean / std fields and the report - the files first, then
//! what is printed about them (issue 42: a closed stdout never leaves the files incomplete).

use std::path::{Path, PathBuf};
use std::time::Instant;

use alea_study::StudyError;
use alea_study::analysis::{AnalysisSettings, MethodResult};
use alea_study::estimate::ErrorSettings;
use alea_study::runner::{Study, StudyRuns};
use alea_study::store::RunRecord;

use super::estimate::{MethodEstimate, estimate_all};
use super::estimate_report::report_error;
use super::estimate_text::print_estimates;
use super::files::{write_samples, write_summary};
use super::input::{Drawn, report_input};
use super::result::{ResultParts, StudyResult};
use super::results::{Analysis, analyse};
use super::table::{print_reliability, print_table};
use crate::console::Deferred;
use crate::{Console, Error};
use alea_report::ReportFiles;

/// The files a study's outputs consist of, and the warnings they carry.
#[derive(Debug, Clone)]
pub struct Outputs {
    /// `summary.json`.
    pub summary: PathBuf,
    /// `samples.csv` (the main method's draws), unless switched off or no method has draws.
    pub samples: Option<PathBuf>,
    /// The mean / std fields (ParaView), when written.
    pub fields: Option<PathBuf>,
    /// The mean error densities (ParaView), when the study has error estimates.
    pub error_fields: Option<PathBuf>,
    /// The report (`report.html` and its plots), when asked for.
    pub report: Option<ReportFiles>,
    /// The warnings, as in `summary.json`'s notes.
    pub notes: Vec<String>,
}

/// Statistics and every output file of a study whose runs are in `runs`; `report`: write the
/// HTML report too; `notes`: warnings found before (kept in `summary.json` and the report).
/// The account (statistics tables, error estimates, the files written) and the warnings go to
/// `console` once every file is written, or once writing failed: a reader of the account that
/// stops reading early (`alea run study.toml | head -2`) leaves complete files behind.
///
/// # Errors
/// Any error of writing an output; after writing what it can,
/// [`StudyError::Failed`] if no run converged or no method produced statistics.
pub fn write_outputs(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    settings: &AnalysisSettings,
    notes: Vec<String>,
    report: bool,
    console: &dyn Console,
) -> Result<Outputs, Error> {
    let deferred = Deferred::default();
    let written = write_files(study, runs, dir, settings, notes, report, &deferred);
    deferred.replay(console);
    written
}

/// [`write_outputs`], saying its account to `console` as it goes.
fn write_files(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    settings: &AnalysisSettings,
    mut notes: Vec<String>,
    report: bool,
    console: &dyn Console,
) -> Result<Outputs, Error> {
    let mut warn = |msg: String| {
        console.warning(&msg);
        notes.push(msg);
    };
    run_warnings(study, runs, dir, &mut warn)?;
    let Analysis {
        results,
        seconds: analysis_seconds,
        reliability,
    } = analyse(study, runs, settings);
    method_warnings(study, runs, &results, settings.confidence, &mut warn);
    print_table(study, &results, settings.confidence, console);
    print_reliability(&reliability, console);
    for r in &reliability {
        for w in r.warnings.iter().chain(&r.errors) {
            warn(format!(
                "reliability of P({} > {}): {w}",
                r.quantity, r.threshold
            ));
        }
    }
    let main_index = results.iter().position(|r| !r.qois.is_empty());
    let t0 = Instant::now();
    let (err_settings, estimates) = estimate_all(study, runs, &results, dir, main_index, console)?;
    notes.extend(print_estimates(
        study,
        runs,
        &err_settings,
        &estimates,
        &results,
        console,
    ));
    let estimate_seconds = t0.elapsed().as_secs_f64();
    let result = StudyResult::new(
        study,
        &ResultParts {
            results: &results,
            runs,
            estimates: &estimates,
            reliability: &reliability,
            notes: &notes,
        },
    );
    let summary = write_summary(&result, dir, console)?;
    let mut samples = None;
    if study.output.samples_csv.unwrap_or(true)
        && let Some(main) = results.iter().find(|r| !r.qois.is_empty())
    {
        samples = write_samples(study, dir, main, console)?;
    }
    let fields = write_fields(study, runs, dir, &results, &mut notes, console);
    let mut files = None;
    if report {
        let parts = ReportParts {
            results: &results,
            result: &result,
            err_settings: &err_settings,
            estimates: &estimates,
            analysis_seconds,
            estimate_seconds,
        };
        files = Some(write_report_files(
            study, runs, dir, settings, &parts, &notes, console,
        )?);
    }
    check_produced(runs, &results)?;
    Ok(Outputs {
        summary,
        samples,
        fields,
        error_fields: estimates.iter().find_map(|e| e.vtu.clone()),
        report: files,
        notes,
    })
}

/// The warnings on the runs: those that did not converge, maxima on corners, sliding beyond
/// small sliding.
fn run_warnings(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    warn: &mut dyn FnMut(String),
) -> Result<(), Error> {
    let failed: Vec<&RunRecord> = runs.records.iter().filter(|r| !r.converged()).collect();
    if !failed.is_empty() {
        warn(format!(
            "{} run(s) did not converge and are left out of the surrogates: {}",
            failed.len(),
            failed
                .iter()
                .take(10)
                .map(|r| format!(
                    "{:?} ({}, error indicator {:.1e} after {} iterations)",
                    r.params, r.status, r.residual, r.iterations
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ));
    }
    for w in alea_study::qoi::warnings::corner_warnings(study, &runs.records, dir)? {
        warn(w.to_string());
    }
    for w in
        alea_study::sliding_note::sliding_warnings(&runs.records, &runs.solver, &study.params.names)
    {
        warn(w);
    }
    Ok(())
}

/// The warnings on the methods' statistics: no statistics, a failure region left out, draws
/// out of the runs' range.
fn method_warnings(
    study: &Study,
    runs: &StudyRuns,
    results: &[MethodResult],
    confidence: f64,
    warn: &mut dyn FnMut(String),
) {
    for r in results {
        if let Some(e) = &r.account.error {
            warn(format!(
                "method '{}' gave no statistics: {e}",
                r.account.label
            ));
        }
        if let Some(f) = &r.account.failure_region {
            warn(format!(
                "method '{}': {} run(s) failed; the region they stand for has probability {:.4} \
                 ({:.0}% interval [{:.4}, {:.4}]; {}) and its statistics describe the rest of the \
                 law ({:.2}% of it left out)",
                r.account.label,
                f.failed_runs,
                f.probability,
                100.0 * confidence,
                f.ci_low,
                f.ci_high,
                f.basis,
                100.0 * f.left_out
            ));
        }
    }
    for (r, m) in results.iter().zip(&runs.methods) {
        for w in alea_study::draw_range::draw_range_warnings(study, m, r, &runs.records) {
            warn(w);
        }
    }
}

/// The mean / std fields of the first method with statistics and draws, unless switched off
/// or the study has no parameter; a failure to write them is a warning (pushed on `notes`).
fn write_fields(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    results: &[MethodResult],
    notes: &mut Vec<String>,
    console: &dyn Console,
) -> Option<PathBuf> {
    if study.output.mean_fields.unwrap_or(true)
        && !study.params.names.is_empty()
        && let Some(m) = results
            .iter()
            .position(|r| !r.qois.is_empty() && !r.points.is_empty())
    {
        let t0 = Instant::now();
        match alea_study::fields::write_mean_std_fields(study, runs, dir, m, &results[m].points) {
            Ok(path) => {
                console.line(&format!(
                    "mean / std fields: {} ({}, {:.2} s)",
                    path.display(),
                    results[m].account.label,
                    t0.elapsed().as_secs_f64()
                ));
                return Some(path);
            }
            Err(e) => {
                let msg = format!("mean / std fields not written: {e}");
                console.warning(&msg);
                notes.push(msg);
            }
        }
    }
    None
}

/// What the report is written from, besides the study and its runs.
struct ReportParts<'a> {
    /// The statistics with their draws.
    results: &'a [MethodResult],
    /// The study's result.
    result: &'a StudyResult,
    err_settings: &'a ErrorSettings,
    estimates: &'a [MethodEstimate],
    /// Seconds of the surrogates and Monte Carlo.
    analysis_seconds: f64,
    /// Seconds of the stochastic error estimates.
    estimate_seconds: f64,
}

/// The HTML report and its plots in `dir/report`.
fn write_report_files(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    settings: &AnalysisSettings,
    parts: &ReportParts,
    notes: &[String],
    console: &dyn Console,
) -> Result<ReportFiles, Error> {
    let t0 = Instant::now();
    let timings = [
        ("solver set-up".into(), runs.setup_seconds),
        ("solves".into(), runs.solve_seconds),
        ("surrogates + Monte Carlo".into(), parts.analysis_seconds),
        ("stochastic error estimates".into(), parts.estimate_seconds),
    ];
    let drawn = Drawn {
        settings,
        methods: &runs.methods,
        results: parts.results,
        records: &runs.records,
        notes,
        timings: &timings,
    };
    let mut input = report_input(study, parts.result, &drawn);
    input.error = report_error(
        study,
        runs,
        parts.result,
        parts.err_settings,
        parts.estimates,
    );
    let written = alea_report::write_report(&dir.join("report"), &input)?;
    // Directories written before 2026-11-28 kept the report's input beside it
    // (`report-input.json`, as large as every draw): an intermediate nothing reads, removed
    // when the report is written again.
    let _ = std::fs::remove_file(dir.join("report").join("report-input.json"));
    console.line(&format!(
        "report: {} ({} plots, {:.2} s)",
        written.html.display(),
        written.plots.len(),
        t0.elapsed().as_secs_f64()
    ));
    Ok(written)
}

/// [`StudyError::Failed`] if no run converged or no method produced statistics.
fn check_produced(runs: &StudyRuns, results: &[MethodResult]) -> Result<(), Error> {
    if !runs.records.iter().any(|r| r.converged()) {
        return Err(StudyError::Failed(format!(
            "no run converged ({} run(s); see summary.json for their status and error indicators): \
             raise [solver] max_iterations or check the model",
            runs.records.len()
        ))
        .into());
    }
    if results.iter().all(|r| r.qois.is_empty()) {
        return Err(StudyError::Failed(
            "no method produced statistics (the warnings above say why)".into(),
        )
        .into());
    }
    Ok(())
}
