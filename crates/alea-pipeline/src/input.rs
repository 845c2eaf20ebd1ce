//! The report's input from a study's result ([`StudyResult`]: the header, the statistics and
//! their budgets, the reliability tables) and what the report draws beyond it (the draws and
//! their densities, the response surfaces, the runs' timings and a few LATIN histories): the
//! main method's quantities, the comparison of methods, the runs.

use alea_study::analysis::{AnalysisSettings, MethodResult, QoiStats, response_surface};
use alea_study::atoms::split_atoms;
use alea_study::method::Method;
use alea_study::qoi::Qoi;
use alea_study::runner::Study;
use alea_study::sensitivity::SobolStats;
use alea_study::store::RunRecord;

use super::result::StudyResult;
use super::summary_intervals::{Budget, QuantityStatistics};

use alea_report::{
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
        None => (Vec::new(), s.distribution.kde.clone()),
    }
}

/// What the report is drawn from besides the study's result: the analysis with its draws, the
/// runs with their timings and histories, the warnings and the timings of the stages.
pub(super) struct Drawn<'a> {
    /// The analysis settings (the densities' bandwidth, points and confidence).
    pub settings: &'a AnalysisSettings,
    /// The methods (their points, for the response surfaces).
    pub methods: &'a [Method],
    /// The statistics of every method with their draws, in method order.
    pub results: &'a [MethodResult],
    /// The finished runs.
    pub records: &'a [RunRecord],
    /// The warnings (those of the files written after `summary.json` too).
    pub notes: &'a [String],
    /// Wall time per stage.
    pub timings: &'a [(String, f64)],
}

/// The report's input (without the error section, which `estimate_report.rs` adds).
pub(super) fn report_input(study: &Study, result: &StudyResult, drawn: &Drawn) -> ReportInput {
    // The first method that produced statistics answers; the others are compared with it.
    let main_index = result.methods.iter().position(|r| !r.qois.is_empty());
    let qois = study
        .qois
        .iter()
        .enumerate()
        .filter_map(|(q, qoi)| {
            let m = main_index?;
            let quantity = result.methods[m].qois.get(q)?;
            let s = drawn.results[m].qois.get(q)?;
            let surface = surface_of(study, &drawn.methods[m], drawn.records, q);
            Some(qoi_report(
                study,
                drawn.settings,
                qoi,
                (quantity, s),
                surface,
                &result.methods[m].account.label,
            ))
        })
        .collect();
    let comparison = (result.methods.len() > 1).then(|| comparison_of(study, result, drawn));
    ReportInput {
        title: result.title.clone(),
        study_file: result.study_file.clone(),
        units: unit_list(result),
        method: main_index.map_or_else(
            || "no method produced statistics (see the notes)".to_string(),
            |m| {
                let r = &result.methods[m];
                format!("{}: {}", r.account.label, r.account.description)
            },
        ),
        parameters: result
            .parameters
            .iter()
            .map(|p| ParamInfo {
                name: p.name.clone(),
                law: p.law.clone(),
                lo: p.lo,
                hi: p.hi,
            })
            .collect(),
        runs: run_infos(drawn.records, main_index.is_some()),
        residual_histories: residual_histories(drawn.records),
        qois,
        comparison,
        timings: drawn.timings.to_vec(),
        notes: drawn.notes.to_vec(),
        error: None,
        reliability: reliability_report(&result.reliability),
    }
}

/// The study's units by name (the density only when given).
fn unit_list(result: &StudyResult) -> Vec<(String, String)> {
    let units = &result.units;
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

/// One quantity's part of the report from its statistics under the main method (`label`):
/// `quantity` as the study's result holds them, `s` with their draws.
fn qoi_report(
    study: &Study,
    settings: &AnalysisSettings,
    qoi: &Qoi,
    (quantity, s): (&QuantityStatistics, &QoiStats),
    surface: Option<Surface>,
    label: &str,
) -> QoiReport {
    let (atoms, kde) = density(s, settings);
    QoiReport {
        name: qoi.name.clone(),
        unit: qoi.unit.clone(),
        what: qoi.what.clone(),
        samples: s.samples.clone(),
        mean: quantity.distribution.mean,
        std: quantity.distribution.std,
        skewness: quantity.distribution.skewness,
        quantiles: quantity.distribution.quantiles.clone(),
        kde,
        atoms,
        failure: quantity
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
        budget: budget_rows(quantity),
        budget_basis: quantity.budget.as_ref().map_or_else(Vec::new, budget_basis),
        sobol: quantity.sobol.as_ref().map_or_else(Vec::new, |so| {
            study
                .params
                .names
                .iter()
                .zip(so.first.iter().zip(&so.total))
                .map(|(n, (f, t))| (n.clone(), *f, *t))
                .collect()
        }),
        sobol_basis: quantity
            .sobol
            .as_ref()
            .map_or_else(String::new, |so| sobol_basis(so, label)),
    }
}

/// The budget rows of a quantity's statistics (none without a budget).
fn budget_rows(quantity: &QuantityStatistics) -> Vec<alea_study::budget::BudgetRow> {
    quantity
        .budget
        .as_ref()
        .map_or_else(Vec::new, |b| b.rows.iter().map(|r| r.row.clone()).collect())
}

/// How each part of a quantity's error budget was obtained, one line each.
fn budget_basis(b: &Budget) -> Vec<String> {
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
fn comparison_of(study: &Study, result: &StudyResult, drawn: &Drawn) -> Comparison {
    Comparison {
        qoi: study.qois[0].name.clone(),
        rows: result
            .methods
            .iter()
            .zip(drawn.results)
            .filter_map(|(r, drawn_r)| {
                let quantity = r.qois.first()?;
                let (atoms, kde) = density(drawn_r.qois.first()?, drawn.settings);
                Some(ComparisonRow {
                    method: r.account.label.clone(),
                    runs: r.account.runs_used,
                    mean: quantity.distribution.mean,
                    std: quantity.distribution.std,
                    kde,
                    atoms,
                    budget: budget_rows(quantity),
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
fn reliability_report(
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
