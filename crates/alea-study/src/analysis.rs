//! Statistics of a study: for each method, the surrogate over its converged runs, Monte Carlo
//! on the surrogate (seeded, thread-count independent), moments, quantiles, a Gaussian kernel
//! density estimate of the PDF, and failure probabilities `P(q > threshold)` with Wilson
//! confidence intervals. The Monte Carlo method uses the run values themselves. The
//! surrogate's values at the draws, the comparison surrogates of the error budget there and
//! the validation pairs are in `analysis/draws.rs`.

mod draws;

use std::collections::HashMap;
use std::time::Instant;

use alea_uq::design;
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::stats::{Summary, failure_probability, quantile_sorted};
use serde::Serialize;

use crate::StudyError;
use crate::budget::{self, QoiBudget, SurrogatePart};
use crate::failure_region::{FailureRegion, binomial_region};
use crate::method::{Method, MethodKind};
use crate::store::{RunRecord, point_key};
use crate::study::Study;
use draws::{
    DrawEvaluator, DrawnValues, comparison_surrogates, comparisons_at_draws,
    failure_region_of_draws, smooth_fits_at_runs, surrogate_part,
};

/// `P(q > threshold)`.
#[derive(Clone, Debug, Serialize)]
pub struct FailureStat {
    /// Threshold.
    pub threshold: f64,
    /// Estimate.
    pub probability: f64,
    /// Lower bound of the confidence interval.
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
}

/// What the draws of one quantity give: its moments, range, quantiles and kernel density. One
/// part of [`QoiStats`], and of the typed result's statistics of a quantity (`alea-pipeline`),
/// flattened into both.
#[derive(Clone, Debug, Serialize)]
pub struct Distribution {
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub std: f64,
    /// Skewness.
    pub skewness: f64,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// Half width of the confidence interval of the mean (Monte Carlo error).
    pub mean_ci_half_width: f64,
    /// `(probability, value)` quantiles.
    pub quantiles: Vec<(f64, f64)>,
    /// KDE bandwidth.
    pub bandwidth: f64,
    /// `(x, pdf)` of the KDE.
    pub kde: Vec<(f64, f64)>,
}

/// Statistics of one quantity of interest under one method.
#[derive(Clone, Debug, Serialize)]
pub struct QoiStats {
    /// Name.
    pub name: String,
    /// Unit.
    pub unit: String,
    /// Moments, range, quantiles, density.
    #[serde(flatten)]
    pub distribution: Distribution,
    /// Failure probabilities.
    pub failure: Vec<FailureStat>,
    /// The error budget of each statistic (none for a study without random parameters).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub budget: Option<QoiBudget>,
    /// Sobol' indices of every parameter (studies with random fields; `crate::sensitivity`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sobol: Option<crate::sensitivity::SobolStats>,
    /// The samples (not serialised).
    #[serde(skip)]
    pub samples: Vec<f64>,
    /// A quantity that cannot be negative: the share of the surrogate's draws that were
    /// negative before their projection onto `>= 0`, and the lowest (`(0, inf)` otherwise; not
    /// serialised).
    #[serde(skip)]
    pub negative: (f64, f64),
}

/// What a method is and which runs it used: its label and description, its design, the runs
/// its surrogate used and those left out, the region of its failed runs, and why it gave no
/// statistics if it did not. One part of [`MethodResult`], and of the typed result's method
/// (`alea-pipeline`), flattened into both.
#[derive(Clone, Debug, Serialize)]
pub struct MethodAccount {
    /// Label.
    pub label: String,
    /// Description.
    pub description: String,
    /// Design points.
    pub design_runs: usize,
    /// Runs used by the surrogate.
    pub runs_used: usize,
    /// Runs left out (not converged): their parameters and status.
    pub left_out: Vec<(Vec<f64>, String)>,
    /// Why the method produced no statistics, if it did not.
    pub error: Option<String>,
    /// The region attributed to failed runs, left out of the statistics (`None`: no run of
    /// the method failed; module [`crate::failure_region`]).
    pub failure_region: Option<FailureRegion>,
}

/// The result of one method.
#[derive(Clone, Debug, Serialize)]
pub struct MethodResult {
    /// The method and its runs.
    #[serde(flatten)]
    pub account: MethodAccount,
    /// Statistics per quantity of interest.
    pub qois: Vec<QoiStats>,
    /// Seconds to build the surrogate.
    pub surrogate_seconds: f64,
    /// Seconds of Monte Carlo on it.
    pub monte_carlo_seconds: f64,
    /// Monte Carlo draws.
    pub draws: usize,
    /// The draws (physical parameter points, row-major; empty for the Monte Carlo method; not
    /// serialised).
    #[serde(skip)]
    pub points: Vec<f64>,
}

/// Settings of the analysis.
#[derive(Clone, Debug)]
pub struct AnalysisSettings {
    /// Draws on the surrogate.
    pub samples: usize,
    /// KDE bandwidth rule.
    pub bandwidth: Bandwidth,
    /// KDE curve points.
    pub kde_points: usize,
    /// Confidence level.
    pub confidence: f64,
}

/// The `[statistics]` settings of a study, checked.
///
/// # Errors
/// [`StudyError::Input`] naming the bad field.
pub fn analysis_settings(study: &Study) -> Result<AnalysisSettings, StudyError> {
    let s = &study.file.statistics;
    let samples = s.samples.as_ref().map_or(250_000, |v| *v.get_ref());
    let bandwidth = match s.bandwidth.as_ref().map(|v| v.get_ref().as_str()) {
        None | Some("isj") => Bandwidth::Isj,
        Some("silverman") => Bandwidth::Silverman,
        Some(other) => {
            let span = s.bandwidth.as_ref().map_or(0..0, |v| v.span());
            return Err(study.source.error(
                span,
                "statistics.bandwidth",
                format!("unknown rule '{other}'; expected isj or silverman"),
            ));
        }
    };
    let confidence = s.confidence.as_ref().map_or(0.95, |v| *v.get_ref());
    if !(confidence > 0.0 && confidence < 1.0) {
        let span = s.confidence.as_ref().map_or(0..0, |v| v.span());
        return Err(study
            .source
            .error(span, "statistics.confidence", "must be in (0, 1)"));
    }
    if samples < 2 {
        let span = s.samples.as_ref().map_or(0..0, |v| v.span());
        return Err(study
            .source
            .error(span, "statistics.samples", "must be at least 2"));
    }
    Ok(AnalysisSettings {
        samples,
        bandwidth,
        kde_points: s.kde_points.as_ref().map_or(512, |v| *v.get_ref()),
        confidence,
    })
}

/// The orders of the quantiles reported for every quantity.
pub const QUANTILES: [f64; 7] = [0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99];

fn qoi_stats(
    study: &Study,
    q: usize,
    samples: Vec<f64>,
    s: &AnalysisSettings,
    surrogate: Option<SurrogatePart<'_>>,
    validation: Option<budget::validation::Sample<'_>>,
) -> QoiStats {
    let qoi = &study.qois[q];
    let budget = surrogate.map(|part| {
        budget::qoi_budget(
            &samples,
            part,
            &QUANTILES,
            &qoi.thresholds,
            s.confidence,
            validation,
        )
    });
    let sum = Summary::of(&samples);
    let mut sorted = samples.clone();
    sorted.sort_by(|a, b| a.total_cmp(b));
    let quantiles = QUANTILES
        .iter()
        .map(|&p| (p, quantile_sorted(&sorted, p)))
        .collect();
    let kde = Kde::new(&samples, s.bandwidth).or_else(|_| Kde::new(&samples, Bandwidth::Silverman));
    let (bandwidth, kde_curve) = match kde {
        Ok(k) => {
            let h = k.bandwidth();
            let (a, b) = (sum.min - 3.0 * h, sum.max + 3.0 * h);
            let n = s.kde_points.max(2);
            let xs: Vec<f64> = (0..n)
                .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
                .collect();
            let ys = k.eval_binned(&xs);
            (h, xs.into_iter().zip(ys).collect())
        }
        Err(_) => (0.0, Vec::new()),
    };
    let failure = qoi
        .thresholds
        .iter()
        .map(|&t| {
            let f = failure_probability(&samples, t, s.confidence);
            FailureStat {
                threshold: t,
                probability: f.p,
                ci_low: f.lower,
                ci_high: f.upper,
            }
        })
        .collect();
    QoiStats {
        name: qoi.name.clone(),
        unit: qoi.unit.clone(),
        distribution: Distribution {
            mean: sum.mean,
            std: if sum.std.is_finite() { sum.std } else { 0.0 },
            skewness: if sum.skewness.is_finite() {
                sum.skewness
            } else {
                0.0
            },
            min: sum.min,
            max: sum.max,
            mean_ci_half_width: {
                let h = sum.mean_ci_half_width(s.confidence);
                if h.is_finite() { h } else { 0.0 }
            },
            quantiles,
            bandwidth,
            kde: kde_curve,
        },
        failure,
        budget,
        sobol: None,
        samples,
        negative: (0.0, f64::INFINITY),
    }
}

/// The runs of a method's design, as the records hold them.
struct MethodRuns {
    /// The design points of the converged runs, in design order.
    used_points: Vec<Vec<f64>>,
    /// Per quantity, its values at them.
    values: Vec<Vec<f64>>,
    /// Per design point, whether its run ran and failed (not converged after its retries, or
    /// without equilibrium).
    failed: Vec<bool>,
    /// How many did.
    failed_runs: usize,
    /// How many design points have no run.
    missing: usize,
}

/// Analyses one method over the records of a study (records in any order).
pub fn analyse_method(
    study: &Study,
    method: &Method,
    records: &[RunRecord],
    s: &AnalysisSettings,
) -> MethodResult {
    let by_key: HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    let (runs, left_out) = method_runs(study, method, &by_key);
    let mut out = MethodResult {
        account: MethodAccount {
            label: method.label.clone(),
            description: method.description.clone(),
            design_runs: method.points.len(),
            runs_used: runs.used_points.len(),
            left_out,
            error: None,
            failure_region: None,
        },
        qois: Vec::new(),
        surrogate_seconds: 0.0,
        monte_carlo_seconds: 0.0,
        draws: 0,
        points: Vec::new(),
    };
    if method.kind == MethodKind::MonteCarlo {
        monte_carlo_stats(study, s, runs, &mut out);
    } else {
        surrogate_stats(study, method, &by_key, &runs, s, &mut out);
    }
    out
}

/// The runs of `method`'s design found in `by_key`, and those left out (not converged or
/// missing) with their status.
#[allow(clippy::type_complexity)]
fn method_runs(
    study: &Study,
    method: &Method,
    by_key: &HashMap<String, &RunRecord>,
) -> (MethodRuns, Vec<(Vec<f64>, String)>) {
    let mut used_points = Vec::new();
    let mut values: Vec<Vec<f64>> = vec![Vec::new(); study.qois.len()];
    let mut left_out = Vec::new();
    for p in &method.points {
        match by_key.get(&point_key(p)) {
            Some(r) if r.converged() => {
                used_points.push(p.clone());
                for (q, v) in r.qois.iter().enumerate() {
                    values[q].push(*v);
                }
            }
            Some(r) => left_out.push((p.clone(), r.status.clone())),
            None => left_out.push((p.clone(), "missing".into())),
        }
    }
    // Runs that ran and failed (not converged after their retries, or without equilibrium):
    // the region they stand for is left out of the statistics (module `failure_region`).
    let failed: Vec<bool> = method
        .points
        .iter()
        .map(|p| by_key.get(&point_key(p)).is_some_and(|r| !r.converged()))
        .collect();
    let failed_runs = failed.iter().filter(|&&f| f).count();
    let missing = method.points.len() - used_points.len() - failed_runs;
    let runs = MethodRuns {
        used_points,
        values,
        failed,
        failed_runs,
        missing,
    };
    (runs, left_out)
}

/// The Monte Carlo method's statistics: the run values themselves (their failed share as the
/// failure region).
fn monte_carlo_stats(
    study: &Study,
    s: &AnalysisSettings,
    runs: MethodRuns,
    out: &mut MethodResult,
) {
    let used = runs.used_points.len();
    out.draws = used;
    // Two runs at least, except the single run of a study without parameters.
    let needed = if study.params.names.is_empty() { 1 } else { 2 };
    if used < needed {
        out.account.error = Some(format!(
            "fewer than {needed} converged runs{}",
            left_out_words(&out.account.left_out)
        ));
        return;
    }
    let has_params = !study.params.names.is_empty();
    out.qois = runs
        .values
        .into_iter()
        .enumerate()
        .map(|(q, v)| {
            qoi_stats(
                study,
                q,
                v,
                s,
                has_params.then_some(SurrogatePart::Exact),
                None,
            )
        })
        .collect();
    if runs.failed_runs > 0 {
        out.account.failure_region = Some(binomial_region(
            runs.failed_runs,
            used + runs.failed_runs,
            s.confidence,
        ));
    }
}

/// A surrogate method's statistics: its surrogate over the runs, Monte Carlo on it outside
/// the region of the failed runs, the error budget of each statistic and the Sobol' indices.
fn surrogate_stats(
    study: &Study,
    method: &Method,
    by_key: &HashMap<String, &RunRecord>,
    runs: &MethodRuns,
    s: &AnalysisSettings,
    out: &mut MethodResult,
) {
    // A local surrogate (piecewise linear, adaptive mesh) with failed runs is built on every
    // node, the failed ones holding a placeholder 0 that no kept draw uses.
    let local = matches!(
        method.kind,
        MethodKind::PiecewiseLinear { .. } | MethodKind::Adaptive(_)
    );
    let tolerant = runs.failed_runs > 0 && runs.missing == 0 && local;
    let (sur_points, sur_values) = surrogate_data(study, method, by_key, runs, tolerant);
    let t0 = Instant::now();
    let sur = match method.surrogate(&study.params, &sur_points) {
        Ok(sur) => sur,
        Err(e) => {
            out.account.error = Some(format!(
                "{}{}",
                String::from(e),
                left_out_words(&out.account.left_out)
            ));
            return;
        }
    };
    out.surrogate_seconds = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let d = study.params.names.len();
    let draws = design::monte_carlo(
        study.params.joint.as_ref(),
        s.samples,
        study.seed.wrapping_add(0x9e37_79b9),
    );
    let pts = draws.points();
    let nq = study.qois.len();
    let evaluator = DrawEvaluator::new(study, method, &sur, &sur_values, tolerant, &runs.failed);
    let per_draw = evaluator.at_draws(pts);
    let keep: Vec<bool> = per_draw.iter().map(|(_, r)| evaluator.kept(r)).collect();
    let validation = evaluator.validation_pairs(by_key);
    if runs.failed_runs > 0 {
        out.account.failure_region = Some(failure_region_of_draws(
            &per_draw,
            &keep,
            tolerant,
            runs.failed_runs,
            s.confidence,
        ));
        if keep.iter().all(|&k| !k) {
            out.account.error = Some(format!(
                "every draw lies in the region of the failed runs{}",
                left_out_words(&out.account.left_out)
            ));
            return;
        }
    }
    let comparisons =
        comparison_surrogates(study, method, &runs.used_points, runs.failed_runs, tolerant);
    let drawn = DrawnValues {
        per_draw: &per_draw,
        keep: &keep,
        coarse_per_draw: &comparisons_at_draws(&comparisons, pts, d, nq, &runs.values),
        comparisons: &comparisons,
        fits_at_runs: &smooth_fits_at_runs(&comparisons, &runs.used_points, d, nq, &runs.values),
        validation: &validation,
        values: &runs.values,
    };
    out.qois = (0..nq)
        .map(|q| quantity_stats(study, q, s, &drawn))
        .collect();
    // Sobol' indices are variances over the whole box: not computed where a region is left out.
    if runs.failed_runs == 0 {
        for (q, stats) in out.qois.iter_mut().enumerate() {
            stats.sobol = crate::sensitivity::sobol_stats(
                study,
                method,
                &sur,
                &runs.used_points,
                &runs.values[q],
            );
        }
    }
    out.monte_carlo_seconds = t0.elapsed().as_secs_f64();
    out.draws = keep.iter().filter(|&&k| k).count();
    out.points = if runs.failed_runs == 0 {
        pts.to_vec()
    } else {
        pts.chunks(d)
            .zip(&keep)
            .filter(|(_, k)| **k)
            .flat_map(|(x, _)| x.iter().copied())
            .collect()
    };
}

/// The points and values the surrogate is built on: the converged runs, or with a `tolerant`
/// (local) surrogate every design point, a failed one holding 0.
fn surrogate_data(
    study: &Study,
    method: &Method,
    by_key: &HashMap<String, &RunRecord>,
    runs: &MethodRuns,
    tolerant: bool,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    if tolerant {
        let all: Vec<Vec<f64>> = (0..study.qois.len())
            .map(|q| {
                method
                    .points
                    .iter()
                    .map(|p| match by_key.get(&point_key(p)) {
                        Some(r) if r.converged() => r.qois[q],
                        _ => 0.0,
                    })
                    .collect()
            })
            .collect();
        (method.points.clone(), all)
    } else {
        (runs.used_points.clone(), runs.values.clone())
    }
}

/// Quantity `q`'s statistics on the kept draws, with its error budget.
fn quantity_stats(study: &Study, q: usize, s: &AnalysisSettings, drawn: &DrawnValues) -> QoiStats {
    // A quantity that cannot be negative: every surrogate's draws projected onto `>= 0`
    // (the model's value is >= 0, so the projection only brings a draw nearer to it;
    // a surrogate that spreads an atom at 0 - a contact that opens - below 0 otherwise
    // puts its low quantiles there), the share and lowest of the negative ones kept for
    // the draw-range warning.
    let floor = study.qois[q].kind.nonnegative();
    let project = |v: f64| if floor { v.max(0.0) } else { v };
    let raw = drawn.kept_draws(q);
    let negative = if floor {
        let below = raw.iter().filter(|&&v| v < 0.0).count();
        let lowest = raw.iter().copied().fold(f64::INFINITY, f64::min);
        (below as f64 / raw.len().max(1) as f64, lowest)
    } else {
        (0.0, f64::INFINITY)
    };
    let mine: Vec<f64> = raw.into_iter().map(project).collect();
    let coarse = drawn.kept_coarse_draws(q, project);
    let part = surrogate_part(drawn, q, &coarse, &mine);
    let (model, at_runs) = &drawn.validation[q];
    let surrogate: Vec<f64> = at_runs.iter().map(|&v| project(v)).collect();
    let sample = (model.len() >= 2).then_some(budget::validation::Sample {
        model,
        surrogate: &surrogate,
        nonnegative: floor,
    });
    let mut stats = qoi_stats(study, q, mine, s, Some(part), sample);
    stats.negative = negative;
    stats
}

/// Response surface of the first quantity... of quantity `q` under `method` over the first two
/// parameters (others at their nominal values), on an `n x n` grid of the parameter box:
/// `(x, y, values row-major by y)`.
pub fn response_surface(
    study: &Study,
    method: &Method,
    records: &[RunRecord],
    q: usize,
    n: usize,
) -> Option<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let d = study.params.names.len();
    if d < 2 || method.kind == MethodKind::MonteCarlo {
        return None;
    }
    let by_key: std::collections::HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    let mut pts = Vec::new();
    let mut vals = Vec::new();
    for p in &method.points {
        if let Some(r) = by_key.get(&point_key(p))
            && r.converged()
        {
            pts.push(p.clone());
            vals.push(r.qois[q]);
        }
    }
    let sur = method.surrogate(&study.params, &pts).ok()?;
    let (lo, hi) = (&study.params.lo, &study.params.hi);
    let xs: Vec<f64> = (0..n)
        .map(|i| lo[0] + (hi[0] - lo[0]) * i as f64 / (n - 1) as f64)
        .collect();
    let ys: Vec<f64> = (0..n)
        .map(|i| lo[1] + (hi[1] - lo[1]) * i as f64 / (n - 1) as f64)
        .collect();
    let mut t = vec![0.0; d];
    let mut w = Vec::new();
    let mut z = Vec::with_capacity(n * n);
    for &y in &ys {
        for &x in &xs {
            let mut p = study.params.nominal.clone();
            p[0] = x;
            p[1] = y;
            sur.weights(&p, &mut t, &mut w);
            z.push(w.iter().map(|&(k, wk)| wk * vals[k]).sum());
        }
    }
    Some((xs, ys, z))
}

/// Why runs were left out, for a method's error: ` (3 runs did not converge, 19 runs are
/// missing: ...)`; empty if none was.
pub fn left_out_words(left_out: &[(Vec<f64>, String)]) -> String {
    let missing = left_out.iter().filter(|(_, s)| s == "missing").count();
    let failed = left_out.len() - missing;
    let mut parts = Vec::new();
    if failed > 0 {
        parts.push(format!(
            "{failed} run{} did not converge",
            if failed == 1 { "" } else { "s" }
        ));
    }
    if missing > 0 {
        parts.push(format!(
            "{missing} run{} missing from the study directory (the study was stopped before it \
             finished: `alea run` computes them)",
            if missing == 1 { " is" } else { "s are" }
        ));
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!(" ({})", parts.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::left_out_words;

    #[test]
    fn missing_runs_are_not_called_runs_that_did_not_converge() {
        let missing = |n: usize| vec![(vec![0.0], "missing".to_string()); n];
        let words = left_out_words(&missing(19));
        assert!(words.contains("19 runs are missing"), "{words}");
        assert!(!words.contains("converge"), "{words}");
        let mut both = missing(1);
        both.push((vec![1.0], "not converged".into()));
        both.push((vec![2.0], "diverged".into()));
        assert_eq!(
            left_out_words(&both),
            " (2 runs did not converge, 1 run is missing from the study directory (the study was \
             stopped before it finished: `alea run` computes them))"
        );
        assert_eq!(left_out_words(&[]), "");
    }
}
