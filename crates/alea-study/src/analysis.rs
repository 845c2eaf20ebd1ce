//! Statistics of a study: for each method, the surrogate over its converged runs, Monte Carlo
//! on the surrogate (seeded, thread-count independent), moments, quantiles, a Gaussian kernel
//! density estimate of the PDF, and failure probabilities `P(q > threshold)` with Wilson
//! confidence intervals. The Monte Carlo method uses the run values themselves.

use std::time::Instant;

use alea_uq::design;
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::stats::{Summary, failure_probability, quantile_sorted};
use rayon::prelude::*;
use serde::Serialize;

use crate::StudyError;
use crate::budget::{self, QoiBudget, SurrogatePart};
use crate::failure_region::{
    FailureRegion, RegionTally, binomial_region, local_weight, touches, two_nearest,
};
use crate::method::{Method, MethodKind};
use crate::store::{RunRecord, point_key};
use crate::study::Study;

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

/// Statistics of one quantity of interest under one method.
#[derive(Clone, Debug, Serialize)]
pub struct QoiStats {
    /// Name.
    pub name: String,
    /// Unit.
    pub unit: String,
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

/// The result of one method.
#[derive(Clone, Debug, Serialize)]
pub struct MethodResult {
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
        failure,
        budget,
        sobol: None,
        samples,
        negative: (0.0, f64::INFINITY),
    }
}

/// Analyses one method over the records of a study (records in any order).
pub fn analyse_method(
    study: &Study,
    method: &Method,
    records: &[RunRecord],
    s: &AnalysisSettings,
) -> MethodResult {
    let by_key: std::collections::HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
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
    let mut out = MethodResult {
        label: method.label.clone(),
        description: method.description.clone(),
        design_runs: method.points.len(),
        runs_used: used_points.len(),
        left_out,
        error: None,
        failure_region: None,
        qois: Vec::new(),
        surrogate_seconds: 0.0,
        monte_carlo_seconds: 0.0,
        draws: 0,
        points: Vec::new(),
    };
    if method.kind == MethodKind::MonteCarlo {
        out.draws = used_points.len();
        // Two runs at least, except the single run of a study without parameters.
        let needed = if study.params.names.is_empty() { 1 } else { 2 };
        if used_points.len() < needed {
            out.error = Some(format!(
                "fewer than {needed} converged runs{}",
                left_out_words(&out.left_out)
            ));
            return out;
        }
        let has_params = !study.params.names.is_empty();
        out.qois = values
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
        if failed_runs > 0 {
            out.failure_region = Some(binomial_region(
                failed_runs,
                used_points.len() + failed_runs,
                s.confidence,
            ));
        }
        return out;
    }
    // A local surrogate (piecewise linear, adaptive mesh) with failed runs is built on every
    // node, the failed ones holding a placeholder 0 that no kept draw uses.
    let local = matches!(
        method.kind,
        MethodKind::PiecewiseLinear { .. } | MethodKind::Adaptive(_)
    );
    let tolerant = failed_runs > 0 && missing == 0 && local;
    let (sur_points, sur_values) = if tolerant {
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
        (used_points.clone(), values.clone())
    };
    let t0 = Instant::now();
    let sur = match method.surrogate(&study.params, &sur_points) {
        Ok(sur) => sur,
        Err(e) => {
            out.error = Some(format!(
                "{}{}",
                String::from(e),
                left_out_words(&out.left_out)
            ));
            return out;
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
    // Weights once per draw, reused for every quantity; with failed runs, the draw's weight on
    // them (module `failure_region`).
    let design_norm: Vec<Vec<f64>> = if failed_runs > 0 && !tolerant {
        method.points.iter().map(|p| study.normalise(p)).collect()
    } else {
        Vec::new()
    };
    // A draw's values on the surrogate and where it stands with respect to the failed runs.
    let evaluate = |x: &[f64], t: &mut Vec<f64>, w: &mut Vec<(usize, f64)>| {
        sur.weights(x, t, w);
        let v: Vec<f64> = (0..nq)
            .map(|q| w.iter().map(|&(k, wk)| wk * sur_values[q][k]).sum())
            .collect();
        let region = if tolerant {
            let weight = local_weight(w, &failed);
            DrawRegion {
                weight,
                whole: weight >= 1.0 - 1e-12,
                touched: touches(w, &failed),
            }
        } else if design_norm.is_empty() {
            DrawRegion::default()
        } else {
            let (a, b) = two_nearest(&study.normalise(x), &design_norm);
            DrawRegion {
                weight: f64::from(u8::from(failed[a])),
                whole: failed[a] && failed[b],
                touched: failed[a] || failed[b],
            }
        };
        (v, region)
    };
    // Draws kept for the statistics: those outside the failure region.
    let kept = |r: &DrawRegion| {
        if tolerant {
            !r.touched
        } else {
            r.weight == 0.0
        }
    };
    let per_draw: Vec<(Vec<f64>, DrawRegion)> = pts
        .par_chunks(d)
        .map_init(|| (vec![0.0; d], Vec::new()), |(t, w), x| evaluate(x, t, w))
        .collect();
    let keep: Vec<bool> = per_draw.iter().map(|(_, r)| kept(r)).collect();
    // The validation runs (module `crate::validation_runs`): the model and the surrogate at each
    // converged one outside the failure region, per quantity.
    let validation = {
        let found = crate::validation_runs::found(study, &|k| by_key.contains_key(k));
        let (mut t, mut w) = (vec![0.0; d], Vec::new());
        let mut pairs: Vec<(Vec<f64>, Vec<f64>)> = vec![(Vec::new(), Vec::new()); nq];
        for p in &found {
            let Some(r) = by_key.get(&point_key(p)).filter(|r| r.converged()) else {
                continue;
            };
            let (v, region) = evaluate(p, &mut t, &mut w);
            if kept(&region) {
                for (q, (model, surrogate)) in pairs.iter_mut().enumerate() {
                    model.push(r.qois[q]);
                    surrogate.push(v[q]);
                }
            }
        }
        pairs
    };
    if failed_runs > 0 {
        let mut tally = RegionTally::default();
        for ((_, r), &k) in per_draw.iter().zip(&keep) {
            tally.add(r.weight, r.whole, r.touched, !k);
        }
        let basis = if tolerant {
            "the failure indicator interpolated by the method's surrogate; interval from the \
             draws whose every node failed to those with any failed node"
        } else {
            "the draws whose nearest run failed; interval from those whose two nearest runs \
             failed to those with either failed"
        };
        out.failure_region = Some(tally.region(failed_runs, s.confidence, basis));
        if keep.iter().all(|&k| !k) {
            out.error = Some(format!(
                "every draw lies in the region of the failed runs{}",
                left_out_words(&out.left_out)
            ));
            return out;
        }
    }
    // The comparison surrogates of the error budget, at the same draws (with failed runs, a
    // local method's coarser mesh would need them: only its smooth fits on the converged runs).
    let comparisons = if tolerant {
        let fits = budget::smooth_fits(&study.params, &used_points);
        if fits.is_empty() {
            Err(format!(
                "{failed_runs} run(s) failed and the coarser mesh needs them; too few converged \
                 runs for a smooth fit"
            ))
        } else {
            Ok(fits)
        }
    } else {
        budget::comparisons(method, &study.params, &used_points)
    };
    let coarse_per_draw: Vec<Vec<Vec<f64>>> = comparisons
        .iter()
        .flatten()
        .map(|c| {
            pts.par_chunks(d)
                .map_init(
                    || (vec![0.0; d], Vec::new()),
                    |(t, w), x| {
                        c.surrogate.weights(x, t, w);
                        (0..nq)
                            .map(|q| w.iter().map(|&(k, wk)| wk * values[q][c.runs[k]]).sum())
                            .collect::<Vec<f64>>()
                    },
                )
                .collect()
        })
        .collect();
    // The smooth fits at the runs, for the check of their credibility per quantity.
    let fits_at_runs: Vec<Vec<Vec<f64>>> = comparisons
        .iter()
        .flatten()
        .map(|c| {
            if !c.smooth {
                return Vec::new();
            }
            let (mut t, mut w) = (vec![0.0; d], Vec::new());
            used_points
                .iter()
                .map(|x| {
                    c.surrogate.weights(x, &mut t, &mut w);
                    (0..nq)
                        .map(|q| w.iter().map(|&(k, wk)| wk * values[q][c.runs[k]]).sum())
                        .collect()
                })
                .collect()
        })
        .collect();
    out.qois = (0..nq)
        .map(|q| {
            // A quantity that cannot be negative: every surrogate's draws projected onto `>= 0`
            // (the model's value is >= 0, so the projection only brings a draw nearer to it;
            // a surrogate that spreads an atom at 0 - a contact that opens - below 0 otherwise
            // puts its low quantiles there), the share and lowest of the negative ones kept for
            // the draw-range warning.
            let floor = study.qois[q].kind.nonnegative();
            let project = |v: f64| if floor { v.max(0.0) } else { v };
            let raw: Vec<f64> = per_draw
                .iter()
                .zip(&keep)
                .filter(|(_, k)| **k)
                .map(|(v, _)| v.0[q])
                .collect();
            let negative = if floor {
                let below = raw.iter().filter(|&&v| v < 0.0).count();
                let lowest = raw.iter().copied().fold(f64::INFINITY, f64::min);
                (below as f64 / raw.len().max(1) as f64, lowest)
            } else {
                (0.0, f64::INFINITY)
            };
            let mine: Vec<f64> = raw.into_iter().map(project).collect();
            let coarse: Vec<Vec<f64>> = coarse_per_draw
                .iter()
                .map(|c| {
                    c.iter()
                        .zip(&keep)
                        .filter(|(_, k)| **k)
                        .map(|(v, _)| project(v[q]))
                        .collect()
                })
                .collect();
            let part = match &comparisons {
                Ok(cs) => {
                    // A smooth fit counts for this quantity only where it follows the runs.
                    let kept: Vec<usize> = (0..cs.len())
                        .filter(|&i| {
                            !cs[i].smooth
                                || budget::credible_fit(
                                    &fits_at_runs[i].iter().map(|v| v[q]).collect::<Vec<_>>(),
                                    &values[q],
                                    &coarse[i],
                                    &mine,
                                )
                        })
                        .collect();
                    SurrogatePart::Comparison(
                        kept.iter()
                            .map(|&i| (coarse[i].as_slice(), cs[i].coarser, cs[i].sees_mean))
                            .collect(),
                        kept.iter()
                            .map(|&i| cs[i].description.as_str())
                            .collect::<Vec<_>>()
                            .join(" and "),
                    )
                }
                Err(why) => SurrogatePart::Unavailable(why),
            };
            let (model, at_runs) = &validation[q];
            let surrogate: Vec<f64> = at_runs.iter().map(|&v| project(v)).collect();
            let sample = (model.len() >= 2).then_some(budget::validation::Sample {
                model,
                surrogate: &surrogate,
                nonnegative: floor,
            });
            let mut stats = qoi_stats(study, q, mine, s, Some(part), sample);
            stats.negative = negative;
            stats
        })
        .collect();
    // Sobol' indices are variances over the whole box: not computed where a region is left out.
    if failed_runs == 0 {
        for (q, stats) in out.qois.iter_mut().enumerate() {
            stats.sobol =
                crate::sensitivity::sobol_stats(study, method, &sur, &used_points, &values[q]);
        }
    }
    out.monte_carlo_seconds = t0.elapsed().as_secs_f64();
    out.draws = keep.iter().filter(|&&k| k).count();
    out.points = if failed_runs == 0 {
        pts.to_vec()
    } else {
        pts.chunks(d)
            .zip(&keep)
            .filter(|(_, k)| **k)
            .flat_map(|(x, _)| x.iter().copied())
            .collect()
    };
    out
}

/// Where one draw stands with respect to the failed runs (module `failure_region`).
#[derive(Clone, Copy, Default)]
struct DrawRegion {
    /// Its weight on failed runs, in [0, 1].
    weight: f64,
    /// Wholly in the region.
    whole: bool,
    /// Touching it.
    touched: bool,
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
