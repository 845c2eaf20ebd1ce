//! The report's input from a study's results: the main method's quantities with their
//! response surfaces, the comparison of methods, the runs and a few LATIN histories.

use alea_study::analysis::{AnalysisSettings, MethodResult, QoiStats, response_surface};
use alea_study::atoms::split_atoms;
use alea_study::budget::QoiBudget;
use alea_study::method::Method;
use alea_study::qoi::Qoi;
use alea_study::runner::Study;
use alea_study::sensitivity::SobolStats;
use alea_study::store::RunRecord;

use crate::report::{
    Atom, Comparison, ComparisonRow, FailureInfo, ParamInfo, QoiReport, ReliabilityReport,
    ReliabilityRow, ReportInput, RunInfo, Surface,
};

/// The density a plot draws of a quantity's samples: with probability atoms (values that 1 %
/// of the samples or more take exactly), the atoms and the kernel density of the rest scaled
/// by its share; else the analysis's kernel density as it is.
fn density(s: &QoiStats, settings: &AnalysisSettings) -> (Vec<Atom>, Vec<(f64, f64)>) {
    match split_atoms(
        &s.samples,
        settings.bandwidth,
        settings.kde_points,
        settings.confidence,
    ) {
        Some(law) => (law.atoms, law.kde),
        None => (Vec::new(), s.kde.clone()),
    }
}

/// The report's input (without the error section, which `estimate_report.rs` adds).
pub(super) fn report_input(
    study: &Study,
    settings: &AnalysisSettings,
    methods: &[Method],
    results: &[MethodResult],
    records: &[RunRecord],
    notes: &[String],
    timings: &[(String, f64)],
) -> ReportInput {
    // The first method that produced statistics answers; the others are compared with it.
    let main_index = results.iter().position(|r| !r.qois.is_empty());
    let qois = study
        .qois
        .iter()
        .enumerate()
        .filter_map(|(q, qoi)| {
            let m = main_index?;
            let s = results[m].qois.get(q)?;
            let surface = surface_of(study, &methods[m], records, q);
            Some(qoi_report(
                study,
                settings,
                qoi,
                s,
                surface,
                &results[m].label,
            ))
        })
        .collect();
    let comparison = (results.len() > 1).then(|| comparison_of(study, settings, results));
    ReportInput {
        title: study.title(),
        study_file: study.file_name(),
        units: unit_list(study),
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
        runs: run_infos(records, main_index.is_some()),
        residual_histories: residual_histories(records),
        qois,
        comparison,
        timings: timings.to_vec(),
        notes: notes.to_vec(),
        error: None,
        reliability: Vec::new(),
    }
}

/// The study's units by name (the density only when given).
fn unit_list(study: &Study) -> Vec<(String, String)> {
    let units = &study.model.units;
    let mut unit_list = vec![
        ("length".to_string(), units.length.clone()),
        ("force".into(), units.force.clone()),
        ("stress".into(), units.stress.clone()),
    ];
    if let Some(d) = &units.density {
        unit_list.push(("density".into(), d.clone()));
    }
    unit_list
}

/// Quantity `q`'s response surface under `method` over the first two parameters, with the
/// converged runs on it (none with fewer than two parameters).
fn surface_of(study: &Study, method: &Method, records: &[RunRecord], q: usize) -> Option<Surface> {
    response_surface(study, method, records, q, 41).map(|(x, y, values)| Surface {
        param_names: [study.params.names[0].clone(), study.params.names[1].clone()],
        x,
        y,
        values,
        points: method
            .points
            .iter()
            .filter_map(|p| {
                let r = records.iter().find(|r| &r.params == p)?;
                r.converged().then(|| [p[0], p[1], r.qois[q]])
            })
            .collect(),
    })
}

/// One quantity's part of the report from its statistics `s` under the main method (`label`).
fn qoi_report(
    study: &Study,
    settings: &AnalysisSettings,
    qoi: &Qoi,
    s: &QoiStats,
    surface: Option<Surface>,
    label: &str,
) -> QoiReport {
    let (atoms, kde) = density(s, settings);
    QoiReport {
        name: qoi.name.clone(),
        unit: qoi.unit.clone(),
        what: qoi.what.clone(),
        samples: s.samples.clone(),
        mean: s.mean,
        std: s.std,
        skewness: s.skewness,
        quantiles: s.quantiles.clone(),
        kde,
        atoms,
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
        budget: s.budget.as_ref().map_or_else(Vec::new, |b| b.rows.clone()),
        budget_basis: s.budget.as_ref().map_or_else(Vec::new, budget_basis),
        sobol: s.sobol.as_ref().map_or_else(Vec::new, |so| {
            study
                .params
                .names
                .iter()
                .zip(so.first.iter().zip(&so.total))
                .map(|(n, (f, t))| (n.clone(), *f, *t))
                .collect()
        }),
        sobol_basis: s
            .sobol
            .as_ref()
            .map_or_else(String::new, |so| sobol_basis(so, label)),
    }
}

/// How each part of a quantity's error budget was obtained, one line each.
fn budget_basis(b: &QoiBudget) -> Vec<String> {
    let mut lines = vec![
        format!("Surrogate: {}.", b.surrogate_basis),
        format!(
            "Sampling: half-width of the confidence interval from the {} draws.",
            b.draws
        ),
        format!("Mesh: {}.", b.mesh_basis),
    ];
    if let Some(sliding) = &b.sliding_basis {
        lines.push(format!("Sliding: {sliding}."));
    }
    lines
}

/// How the Sobol' indices were computed on the surrogate of method `label`.
fn sobol_basis(so: &SobolStats, label: &str) -> String {
    if so.estimator == "pc_expansion" {
        format!(
            "From the coefficients of the chaos expansion of method '{label}' (exact for the surrogate)."
        )
    } else {
        format!(
            "Saltelli / Jansen pick-freeze estimators on {} base draws of the surrogate of method '{label}'.",
            alea_study::sensitivity::PICK_FREEZE_SAMPLES,
        )
    }
}

/// The comparison of the methods on the first quantity.
fn comparison_of(
    study: &Study,
    settings: &AnalysisSettings,
    results: &[MethodResult],
) -> Comparison {
    Comparison {
        qoi: study.qois[0].name.clone(),
        rows: results
            .iter()
            .filter_map(|r| {
                let s = r.qois.first()?;
                let (atoms, kde) = density(s, settings);
                Some(ComparisonRow {
                    method: r.label.clone(),
                    runs: r.runs_used,
                    mean: s.mean,
                    std: s.std,
                    kde,
                    atoms,
                    budget: s.budget.as_ref().map_or_else(Vec::new, |b| b.rows.clone()),
                })
            })
            .collect(),
    }
}

/// The LATIN residual histories of the first four runs and of the slowest one.
fn residual_histories(records: &[RunRecord]) -> Vec<(String, Vec<f64>)> {
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
    histories
}

/// Every run's line in the report (its quantities only when a method produced statistics,
/// `with_qois`).
fn run_infos(records: &[RunRecord], with_qois: bool) -> Vec<RunInfo> {
    records
        .iter()
        .map(|r| RunInfo {
            params: r.params.clone(),
            status: r.status.clone(),
            iterations: r.iterations,
            seconds: r.seconds,
            // Non-finite values only occur in runs that did not converge.
            qois: if with_qois {
                r.qois
                    .iter()
                    .map(|v| if v.is_finite() { *v } else { 0.0 })
                    .collect()
            } else {
                Vec::new()
            },
        })
        .collect()
}

/// The report's rare-event section from the `[[reliability]]` results.
pub(super) fn reliability_report(
    results: &[alea_study::reliability::ReliabilityResult],
) -> Vec<ReliabilityReport> {
    results
        .iter()
        .map(|r| {
            let mut rows = Vec::new();
            if let Some(f) = r.design_points.first() {
                rows.push(ReliabilityRow {
                    algorithm: "FORM".to_string(),
                    pf: f.pf,
                    interval: None,
                    evaluations: r.form_evaluations,
                });
            }
            if let Some(s) = &r.sorm {
                rows.push(ReliabilityRow {
                    algorithm: "SORM (Breitung)".into(),
                    pf: s.pf_breitung,
                    interval: None,
                    evaluations: s.evaluations,
                });
                rows.push(ReliabilityRow {
                    algorithm: "SORM (Tvedt)".into(),
                    pf: s.pf_tvedt,
                    interval: None,
                    evaluations: s.evaluations,
                });
            }
            if let Some(e) = &r.importance {
                rows.push(ReliabilityRow {
                    algorithm: "importance sampling".into(),
                    pf: e.pf,
                    interval: Some((e.lower, e.upper)),
                    evaluations: e.evaluations,
                });
            }
            if let Some(e) = &r.subset {
                rows.push(ReliabilityRow {
                    algorithm: "subset simulation".into(),
                    pf: e.pf,
                    interval: Some((e.lower, e.upper)),
                    evaluations: e.evaluations,
                });
            }
            if let Some(c) = &r.solver {
                rows.push(ReliabilityRow {
                    algorithm: format!(
                        "importance sampling on the solver (at beta {:.3}{})",
                        c.beta,
                        if c.failed > 0 {
                            format!(", {} runs left out", c.failed)
                        } else {
                            String::new()
                        }
                    ),
                    pf: c.pf,
                    interval: Some((c.lower, c.upper)),
                    evaluations: c.runs,
                });
            }
            ReliabilityReport {
                quantity: r.quantity.clone(),
                threshold: r.threshold,
                method: r.method.clone(),
                rows,
                notes: r.warnings.iter().chain(&r.errors).cloned().collect(),
            }
        })
        .collect()
}

/// `(p1, p2, ...)` with 4 decimals.
fn fmt_point(p: &[f64]) -> String {
    format!(
        "({})",
        p.iter()
            .map(|v| format!("{v:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    )
}
