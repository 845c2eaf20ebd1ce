//! `alea run`: a stochastic study end to end - runs (resumable), surrogate, Monte Carlo,
//! statistics, `summary.json`, `samples.csv` and the HTML report.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use alea_study::StudyError;
use alea_study::analysis::{AnalysisSettings, MethodResult, analyse_method, response_surface};
use alea_study::runner::{Progress, Study, StudyRuns, run_study};
use alea_study::store::RunRecord;
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

use crate::report::{
    self, Comparison, ComparisonRow, FailureInfo, ParamInfo, QoiReport, ReportInput, RunInfo,
    Surface,
};

/// Progress bar: runs done, ETA, mean LATIN iterations, failures.
struct Bar {
    bar: ProgressBar,
    iterations: AtomicUsize,
    runs: AtomicUsize,
    failures: AtomicUsize,
}

impl Progress for Bar {
    fn begin(&self, total: usize, done: usize) {
        self.bar.set_length(total as u64);
        self.bar.set_position(done as u64);
        if done > 0 {
            self.bar.println(format!(
                "resuming: {done} of {total} runs already in the study directory"
            ));
        }
    }
    fn finished(&self, rec: &RunRecord) {
        let n = self.runs.fetch_add(1, Ordering::Relaxed) + 1;
        let it = self.iterations.fetch_add(rec.iterations, Ordering::Relaxed) + rec.iterations;
        let f = self.failures.load(Ordering::Relaxed) + usize::from(!rec.converged());
        if !rec.converged() {
            self.failures.fetch_add(1, Ordering::Relaxed);
        }
        self.bar.set_message(format!(
            "mean LATIN iterations {:.0}, not converged {f}",
            it as f64 / n as f64
        ));
        self.bar.inc(1);
    }
    fn end(&self) {
        self.bar.finish();
    }
    fn note(&self, message: &str) {
        // A hidden bar (--quiet, no terminal) prints nothing: notes go to stderr then.
        if self.bar.is_hidden() {
            eprintln!("note: {message}");
        } else {
            self.bar.println(format!("note: {message}"));
        }
    }
}

/// `alea report`: rebuilds every output of a study directory (statistics, `summary.json`,
/// `samples.csv`, mean / std fields, the report) from its store alone, computing no run - after
/// a kill during the outputs, or for a study that ran with `report = false`.
pub fn rebuild_report(dir: &Path) -> Result<()> {
    let t_all = Instant::now();
    let re = alea_study::reopen::reopen(dir, "alea report")?;
    let settings = alea_study::analysis::analysis_settings(&re.study)?;
    let mut notes = Vec::new();
    let total = re.runs.records.len() + re.missing;
    println!(
        "study '{}' in {}: {} of {total} runs finished",
        re.study.title(),
        dir.display(),
        re.runs.records.len()
    );
    if re.missing > 0 {
        let msg = format!(
            "{} of {total} runs are not in the study directory (the study was stopped before it finished): \
             these results use the finished runs only; resume with `alea run {} --dir {}`",
            re.missing,
            re.study.source.path.display(),
            dir.display()
        );
        eprintln!("warning: {msg}");
        notes.push(msg);
    }
    write_outputs(&re.study, &re.runs, dir, &settings, notes, true)?;
    println!("done in {:.2} s", t_all.elapsed().as_secs_f64());
    Ok(())
}

/// Default study directory: `out/<file stem>`.
pub fn default_dir(study: &Path) -> PathBuf {
    let stem = study
        .file_stem()
        .map_or("study".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(stem)
}

/// Runs the study in `path` into `dir`.
pub fn run(path: &Path, dir: &Path, restart: bool, quiet: bool) -> Result<()> {
    let t_all = Instant::now();
    let study = Study::load(path)?;
    let settings = alea_study::analysis::analysis_settings(&study)?;
    println!(
        "study '{}': {} parameter(s), {} quantit{} of interest, {} method(s), {} distinct runs -> {}",
        study.title(),
        study.params.names.len(),
        study.qois.len(),
        if study.qois.len() == 1 { "y" } else { "ies" },
        study.methods.len(),
        study.all_points().len(),
        dir.display()
    );
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(0)
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} runs {pos}/{len} [{bar:30}] {elapsed_precise} ETA {eta} {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    let progress = Bar {
        bar,
        iterations: AtomicUsize::new(0),
        runs: AtomicUsize::new(0),
        failures: AtomicUsize::new(0),
    };
    let runs = run_study(&study, dir, restart, &progress)?;
    let per_run_estimates = if runs.estimate_seconds > 0.0 {
        format!(
            "; per-run error estimates {:.2} s summed over the runs",
            runs.estimate_seconds
        )
    } else {
        String::new()
    };
    println!(
        "runs: {} computed, {} resumed; solver set-up {:.2} s, solves {:.2} s ({:.1} runs/s{per_run_estimates})",
        runs.computed,
        runs.resumed,
        runs.setup_seconds,
        runs.solve_seconds,
        runs.computed as f64 / runs.solve_seconds.max(1e-9)
    );
    let iterations: Vec<usize> = runs
        .records
        .iter()
        .filter(|r| r.converged())
        .map(|r| r.iterations)
        .collect();
    if let (Some(lo), Some(hi)) = (iterations.iter().min(), iterations.iter().max()) {
        println!(
            "LATIN iterations per converged run: min {lo}, mean {:.1}, max {hi}",
            iterations.iter().sum::<usize>() as f64 / iterations.len() as f64
        );
    }
    let report = study.output.report.unwrap_or(true);
    write_outputs(&study, &runs, dir, &settings, Vec::new(), report)?;
    println!("done in {:.2} s", t_all.elapsed().as_secs_f64());
    Ok(())
}

/// Statistics and every output file of a study whose runs are in `runs`; `report`: write the
/// HTML report too. Fails (exit code 4) after writing what it can if no run converged or no
/// method produced statistics.
fn write_outputs(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    settings: &AnalysisSettings,
    mut notes: Vec<String>,
    report: bool,
) -> Result<()> {
    let failed: Vec<&RunRecord> = runs.records.iter().filter(|r| !r.converged()).collect();
    if !failed.is_empty() {
        let msg = format!(
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
        );
        eprintln!("warning: {msg}");
        notes.push(msg);
    }
    for w in alea_study::qoi::warnings::corner_warnings(study, &runs.records, dir)? {
        let msg = w.to_string();
        eprintln!("warning: {msg}");
        notes.push(msg);
    }
    let t0 = Instant::now();
    let results: Vec<MethodResult> = runs
        .methods
        .iter()
        .map(|m| analyse_method(study, m, &runs.records, settings))
        .collect();
    let analysis_seconds = t0.elapsed().as_secs_f64();
    for r in &results {
        if let Some(e) = &r.error {
            let msg = format!("method '{}' gave no statistics: {e}", r.label);
            eprintln!("warning: {msg}");
            notes.push(msg);
        }
    }
    print_table(study, &results, settings.confidence);
    let main_index = results.iter().position(|r| !r.qois.is_empty());
    let t0 = Instant::now();
    let (err_settings, estimates) =
        crate::estimate_out::estimate_all(study, runs, &results, dir, main_index)?;
    notes.extend(crate::estimate_out::print(
        study,
        runs,
        &err_settings,
        &estimates,
    ));
    let estimate_seconds = t0.elapsed().as_secs_f64();
    write_summary(study, dir, &results, runs, &estimates, &notes)?;
    if study.output.samples_csv.unwrap_or(true)
        && let Some(main) = results.iter().find(|r| !r.qois.is_empty())
    {
        write_samples(study, dir, main)?;
    }
    if study.output.mean_fields.unwrap_or(true)
        && !study.params.names.is_empty()
        && let Some(m) = results
            .iter()
            .position(|r| !r.qois.is_empty() && !r.points.is_empty())
    {
        let t0 = Instant::now();
        match alea_study::fields::write_mean_std_fields(study, runs, dir, m, &results[m].points) {
            Ok(path) => println!(
                "mean / std fields: {} ({}, {:.2} s)",
                path.display(),
                results[m].label,
                t0.elapsed().as_secs_f64()
            ),
            Err(e) => {
                let msg = format!("mean / std fields not written: {e}");
                eprintln!("warning: {msg}");
                notes.push(msg);
            }
        }
    }
    if report {
        let t0 = Instant::now();
        let mut input = report_input(
            study,
            &runs.methods,
            &results,
            &runs.records,
            &notes,
            &[
                ("solver set-up".into(), runs.setup_seconds),
                ("solves".into(), runs.solve_seconds),
                ("surrogates + Monte Carlo".into(), analysis_seconds),
                ("stochastic error estimates".into(), estimate_seconds),
            ],
        )?;
        input.error = crate::estimate_out::report_error(study, runs, &err_settings, &estimates);
        let files = report::write_report(&dir.join("report"), &input)?;
        input.save_json(&dir.join("report").join("report-input.json"))?;
        println!(
            "report: {} ({} plots, {:.2} s)",
            files.html.display(),
            files.plots.len(),
            t0.elapsed().as_secs_f64()
        );
    }
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

fn print_table(study: &Study, results: &[MethodResult], confidence: f64) {
    if study.params.names.is_empty() {
        // One deterministic run: the values themselves, at full precision.
        println!();
        for (q, qoi) in study.qois.iter().enumerate() {
            if let Some(s) = results.first().and_then(|r| r.qois.get(q)) {
                println!("{} = {:e} {}", qoi.name, s.mean, qoi.unit);
            }
        }
        println!();
        return;
    }
    for (q, qoi) in study.qois.iter().enumerate() {
        println!("\n{} [{}]: {}", qoi.name, qoi.unit, qoi.what);
        println!(
            "  {:<34} {:>5} {:>14} {:>14} {:>10}",
            "method", "runs", "mean", "std", "skewness"
        );
        for r in results {
            match r.qois.get(q) {
                Some(s) => println!(
                    "  {:<34} {:>5} {:>14.6e} {:>14.6e} {:>10.3}",
                    r.label, r.runs_used, s.mean, s.std, s.skewness
                ),
                None => println!(
                    "  {:<34} {:>5} {:>14} {:>14} {:>10}",
                    r.label, r.runs_used, "-", "-", "-"
                ),
            }
        }
        if let Some(s) = results.iter().find_map(|r| r.qois.get(q)) {
            for f in &s.failure {
                println!(
                    "  P({} > {}) = {:.4e}  ({:.0}% interval [{:.4e}, {:.4e}])",
                    qoi.name,
                    f.threshold,
                    f.probability,
                    100.0 * confidence,
                    f.ci_low,
                    f.ci_high
                );
            }
        }
    }
    println!();
}

fn write_summary(
    study: &Study,
    dir: &Path,
    results: &[MethodResult],
    study_runs: &StudyRuns,
    estimates: &[crate::estimate_out::MethodEstimate],
    notes: &[String],
) -> Result<()> {
    let records = &study_runs.records;
    let runs: Vec<serde_json::Value> = records
        .iter()
        .map(|r| {
            serde_json::json!({
                "params": r.params, "status": r.status, "iterations": r.iterations,
                "residual": r.residual, "qois": r.qois,
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
                "draws": r.draws, "qois": r.qois,
            });
            if let Some(e) = estimates.iter().find(|e| e.method == m) {
                v["error_estimate"] = match &e.result {
                    Ok(me) => crate::estimate_out::error_json(me),
                    Err(why) => serde_json::json!({ "unavailable": why }),
                };
            }
            if let Some(a) = study_runs.adaptive.iter().find(|a| a.method == m) {
                v["adaptive"] = crate::estimate_out::adaptive_json(a);
            }
            v
        })
        .collect();
    let v = serde_json::json!({
        "title": study.title(),
        "study_file": study.source.path.display().to_string(),
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
        "runs": runs,
        "notes": notes,
    });
    let text = serde_json::to_string_pretty(&v)?;
    if text.contains("NaN") {
        anyhow::bail!("internal error: a non-finite value reached summary.json");
    }
    let path = dir.join("summary.json");
    alea_mesh::atomic::write_bytes_atomic(&path, text.as_bytes())
        .with_context(|| format!("writing {}", path.display()))?;
    println!("summary: {}", path.display());
    Ok(())
}

fn write_samples(study: &Study, dir: &Path, r: &MethodResult) -> Result<()> {
    if r.qois.is_empty() || r.points.is_empty() {
        return Ok(());
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
    alea_mesh::atomic::write_atomic(&path, |w| {
        writeln!(w, "{}", header.join(","))?;
        for i in 0..r.draws {
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
    .with_context(|| format!("writing {}", path.display()))?;
    println!(
        "samples: {} ({} draws on the {} surrogate)",
        path.display(),
        r.draws,
        r.label
    );
    Ok(())
}

fn report_input(
    study: &Study,
    methods: &[alea_study::method::Method],
    results: &[MethodResult],
    records: &[RunRecord],
    notes: &[String],
    timings: &[(String, f64)],
) -> Result<ReportInput> {
    // The first method that produced statistics answers; the others are compared with it.
    let main_index = results.iter().position(|r| !r.qois.is_empty());
    let units = &study.model.units;
    let mut unit_list = vec![
        ("length".to_string(), units.length.clone()),
        ("force".into(), units.force.clone()),
        ("stress".into(), units.stress.clone()),
    ];
    if let Some(d) = &units.density {
        unit_list.push(("density".into(), d.clone()));
    }
    let qois = study
        .qois
        .iter()
        .enumerate()
        .filter_map(|(q, qoi)| {
            let m = main_index?;
            let s = results[m].qois.get(q)?;
            let surface =
                response_surface(study, &methods[m], records, q, 41).map(|(x, y, values)| {
                    Surface {
                        param_names: [study.params.names[0].clone(), study.params.names[1].clone()],
                        x,
                        y,
                        values,
                        points: methods[m]
                            .points
                            .iter()
                            .filter_map(|p| {
                                let r = records.iter().find(|r| &r.params == p)?;
                                r.converged().then(|| [p[0], p[1], r.qois[q]])
                            })
                            .collect(),
                    }
                });
            Some(QoiReport {
                name: qoi.name.clone(),
                unit: qoi.unit.clone(),
                what: qoi.what.clone(),
                samples: s.samples.clone(),
                mean: s.mean,
                std: s.std,
                skewness: s.skewness,
                quantiles: s.quantiles.clone(),
                kde: s.kde.clone(),
                failure: s
                    .failure
                    .iter()
                    .map(|f| FailureInfo {
                        threshold: f.threshold,
                        probability: f.probability,
                        ci_low: f.ci_low,
                        ci_high: f.ci_high,
                    })
                    .collect(),
                surface,
            })
        })
        .collect();
    let comparison = (results.len() > 1).then(|| Comparison {
        qoi: study.qois[0].name.clone(),
        rows: results
            .iter()
            .filter_map(|r| {
                let s = r.qois.first()?;
                Some(ComparisonRow {
                    method: r.label.clone(),
                    runs: r.runs_used,
                    mean: s.mean,
                    std: s.std,
                    kde: s.kde.clone(),
                })
            })
            .collect(),
    });
    let mut histories: Vec<(String, Vec<f64>)> = records
        .iter()
        .take(4)
        .map(|r| {
            (
                format!("run at {}", fmt_point(&r.params)),
                r.history.clone(),
            )
        })
        .collect();
    if let Some(worst) = records.iter().max_by_key(|r| r.iterations)
        && !histories.iter().any(|h| h.1 == worst.history)
    {
        histories.push((
            format!("slowest: {}", fmt_point(&worst.params)),
            worst.history.clone(),
        ));
    }
    Ok(ReportInput {
        title: study.title(),
        study_file: study.source.path.display().to_string(),
        units: unit_list,
        method: main_index.map_or_else(
            || "no method produced statistics (see the notes)".to_string(),
            |m| format!("{}: {}", results[m].label, results[m].description),
        ),
        parameters: study
            .params
            .names
            .iter()
            .enumerate()
            .map(|(j, n)| ParamInfo {
                name: n.clone(),
                law: study.params.descriptions[j].clone(),
                lo: study.params.lo[j],
                hi: study.params.hi[j],
            })
            .collect(),
        runs: records
            .iter()
            .map(|r| RunInfo {
                params: r.params.clone(),
                status: r.status.clone(),
                iterations: r.iterations,
                seconds: r.seconds,
                // Non-finite values only occur in runs that did not converge.
                qois: if main_index.is_some() {
                    r.qois
                        .iter()
                        .map(|v| if v.is_finite() { *v } else { 0.0 })
                        .collect()
                } else {
                    Vec::new()
                },
            })
            .collect(),
        residual_histories: histories,
        qois,
        comparison,
        timings: timings.to_vec(),
        notes: notes.to_vec(),
        error: None,
    })
}

fn fmt_point(p: &[f64]) -> String {
    format!(
        "({})",
        p.iter()
            .map(|v| format!("{v:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    )
}
