//! Rare events from study files (issue 19): the `[[reliability]]` tables, each a failure
//! probability `P(q > t)` of one quantity computed on the surrogate of one method by FORM,
//! SORM, importance sampling and subset simulation (crate `alea-uq`, module `reliability`:
//! the limit state `g(x) = t - q~(x)` in the standard normal space of the joint law).
//!
//! - FORM is started from the median point and from `+-3` along every axis of the standard
//!   normal space (`2 d + 1` starts); the distinct design points (apart by more than 10 % of the
//!   smallest `beta`) are all reported, and a warning says so when more than one lies within
//!   `beta_min + 1`: FORM, SORM and importance sampling around one design point then miss the
//!   others' share (subset simulation does not rely on one).
//! - SORM (Breitung, Tvedt) at the best design point; importance sampling centred there, until
//!   its coefficient of variation reaches `target_cov`; subset simulation from the median.
//!
//! The surrogate's own error is not in these intervals: the error budget of the method's
//! `P(q > t)` ([`crate::budget`]) gives it.

use alea_uq::reliability::{
    FormOptions, ImportanceOptions, LimitState, SubsetOptions, form, importance_sampling, sorm,
    subset_simulation,
};
use serde::Serialize;

use crate::method::{Method, MethodKind};
use crate::qoi::Qoi;
use crate::spec::ReliabilitySpec;
use crate::store::{RunRecord, point_key};
use crate::study::Study;
use crate::{ParamSpace, Source, StudyError};

/// The algorithms of a `[[reliability]]` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algorithm {
    /// First-order reliability method.
    Form,
    /// Second order (Breitung, Tvedt).
    Sorm,
    /// Importance sampling around the design point.
    Importance,
    /// Subset simulation.
    Subset,
}

/// A checked `[[reliability]]` table.
#[derive(Clone, Debug, PartialEq)]
pub struct ReliabilityTask {
    /// Index of the quantity.
    pub quantity: usize,
    /// Threshold.
    pub threshold: f64,
    /// Index of the method whose surrogate is the limit state.
    pub method: usize,
    /// Algorithms to run.
    pub algorithms: Vec<Algorithm>,
    /// Target coefficient of variation of importance sampling.
    pub target_cov: f64,
}

/// Checks the `[[reliability]]` tables of a study file (at load, before any run).
///
/// # Errors
/// [`StudyError::Input`] naming the table and field: an unknown quantity, method or algorithm,
/// a method without surrogate, a study without random parameters, a target outside (0, 1).
pub fn build_reliability(
    src: &Source,
    specs: &[ReliabilitySpec],
    qois: &[Qoi],
    methods: &[Method],
    params: &ParamSpace,
) -> Result<Vec<ReliabilityTask>, StudyError> {
    let mut out = Vec::new();
    for (i, r) in specs.iter().enumerate() {
        let f = |k: &str| format!("reliability[{i}].{k}");
        if params.names.is_empty() {
            return Err(src.error(
                r.quantity.span(),
                f("quantity"),
                "a reliability analysis needs random parameters ([[parameter]])",
            ));
        }
        let name = r.quantity.get_ref();
        let quantity = qois.iter().position(|q| &q.name == name).ok_or_else(|| {
            src.error(
                r.quantity.span(),
                f("quantity"),
                format!(
                    "unknown quantity '{name}'; the study's quantities are {}",
                    qois.iter()
                        .map(|q| q.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
        let threshold = *r.threshold.get_ref();
        if !threshold.is_finite() {
            return Err(src.error(r.threshold.span(), f("threshold"), "must be finite"));
        }
        let with_surrogate = |m: &Method| m.kind != MethodKind::MonteCarlo;
        let method = match &r.method {
            Some(label) => {
                let m = methods
                    .iter()
                    .position(|m| &m.label == label.get_ref())
                    .ok_or_else(|| {
                        src.error(
                            label.span(),
                            f("method"),
                            format!(
                                "no method is labelled '{}'; the labels are {}",
                                label.get_ref(),
                                methods
                                    .iter()
                                    .map(|m| format!("'{}'", m.label))
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        )
                    })?;
                if !with_surrogate(&methods[m]) {
                    return Err(src.error(
                        label.span(),
                        f("method"),
                        "Monte Carlo on the model has no surrogate to analyse",
                    ));
                }
                m
            }
            None => methods.iter().position(with_surrogate).ok_or_else(|| {
                src.error(
                    r.quantity.span(),
                    f("method"),
                    "no method of the study has a surrogate",
                )
            })?,
        };
        let algorithms = match &r.algorithms {
            None => vec![
                Algorithm::Form,
                Algorithm::Sorm,
                Algorithm::Importance,
                Algorithm::Subset,
            ],
            Some(list) => {
                let mut a = Vec::new();
                for name in list.get_ref() {
                    a.push(match name.as_str() {
                        "form" => Algorithm::Form,
                        "sorm" => Algorithm::Sorm,
                        "importance" => Algorithm::Importance,
                        "subset" => Algorithm::Subset,
                        other => {
                            return Err(src.error(
                                list.span(),
                                f("algorithms"),
                                format!("unknown algorithm '{other}'; expected form, sorm, importance or subset"),
                            ));
                        }
                    });
                }
                if a.is_empty() {
                    return Err(src.error(list.span(), f("algorithms"), "is empty"));
                }
                a
            }
        };
        let target_cov = match &r.target_cov {
            Some(v) if !(*v.get_ref() > 0.0 && *v.get_ref() < 1.0) => {
                return Err(src.error(
                    v.span(),
                    f("target_cov"),
                    format!("must be in (0, 1), got {}", v.get_ref()),
                ));
            }
            Some(v) => *v.get_ref(),
            None => 0.05,
        };
        out.push(ReliabilityTask {
            quantity,
            threshold,
            method,
            algorithms,
            target_cov,
        });
    }
    Ok(out)
}

/// A FORM design point.
#[derive(Clone, Debug, Serialize)]
pub struct DesignPoint {
    /// Reliability index `|u*|`.
    pub beta: f64,
    /// `Phi(-beta)`.
    pub pf: f64,
    /// The point in the physical parameters.
    pub point: Vec<f64>,
    /// Importance factors `alpha_i^2`.
    pub importance: Vec<f64>,
}

/// A probability with its interval and cost.
#[derive(Clone, Debug, Serialize)]
pub struct Probability {
    /// Estimate.
    pub pf: f64,
    /// Lower bound of the interval (the study's confidence level).
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Coefficient of variation of the estimator (`None` when no failure was drawn).
    pub cov: Option<f64>,
    /// Evaluations of the surrogate.
    pub evaluations: usize,
}

/// SORM at the best design point.
#[derive(Clone, Debug, Serialize)]
pub struct Sorm {
    /// Breitung's approximation.
    pub pf_breitung: f64,
    /// Tvedt's.
    pub pf_tvedt: f64,
    /// Principal curvatures.
    pub curvatures: Vec<f64>,
    /// Evaluations (FORM's included).
    pub evaluations: usize,
}

/// The outcome of one `[[reliability]]` table.
#[derive(Clone, Debug, Serialize)]
pub struct ReliabilityResult {
    /// Quantity.
    pub quantity: String,
    /// Threshold.
    pub threshold: f64,
    /// Label of the method whose surrogate was analysed.
    pub method: String,
    /// The distinct FORM design points, smallest `beta` first (empty without FORM).
    pub design_points: Vec<DesignPoint>,
    /// FORM evaluations over all its starts.
    pub form_evaluations: usize,
    /// SORM.
    pub sorm: Option<Sorm>,
    /// Importance sampling.
    pub importance: Option<Probability>,
    /// Subset simulation.
    pub subset: Option<Probability>,
    /// Warnings (several design points).
    pub warnings: Vec<String>,
    /// Algorithms that failed, with why.
    pub errors: Vec<String>,
}

/// Runs every `[[reliability]]` table of a study on the surrogates of `methods` (the study's
/// methods after the runs: adaptive ones carry their meshes) built on `records`.
pub fn analyse_reliability(
    study: &Study,
    tasks: &[ReliabilityTask],
    methods: &[Method],
    records: &[RunRecord],
    confidence: f64,
) -> Vec<ReliabilityResult> {
    let by_key: std::collections::HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    tasks
        .iter()
        .map(|task| {
            let method = &methods[task.method];
            let mut out = ReliabilityResult {
                quantity: study.qois[task.quantity].name.clone(),
                threshold: task.threshold,
                method: method.label.clone(),
                design_points: Vec::new(),
                form_evaluations: 0,
                sorm: None,
                importance: None,
                subset: None,
                warnings: Vec::new(),
                errors: Vec::new(),
            };
            let (points, values): (Vec<Vec<f64>>, Vec<f64>) = method
                .points
                .iter()
                .filter_map(|p| {
                    by_key
                        .get(&point_key(p))
                        .filter(|r| r.converged())
                        .map(|r| (p.clone(), r.qois[task.quantity]))
                })
                .unzip();
            let sur = match method.surrogate(&study.params, &points) {
                Ok(s) => s,
                Err(e) => {
                    out.errors.push(format!("surrogate: {e}"));
                    return out;
                }
            };
            let d = study.params.names.len();
            let q = |x: &[f64]| {
                let mut t = vec![0.0; d];
                let mut w = Vec::new();
                sur.weights(x, &mut t, &mut w);
                w.iter().map(|&(k, wk)| wk * values[k]).sum::<f64>()
            };
            let law = study.params.joint.as_ref();
            let ls = LimitState::exceedance(law, q, task.threshold);
            run_algorithms(task, &ls, study.seed, confidence, &mut out);
            out
        })
        .collect()
}

fn run_algorithms(
    task: &ReliabilityTask,
    ls: &LimitState,
    seed: u64,
    confidence: f64,
    out: &mut ReliabilityResult,
) {
    let d = ls.dim();
    let wants = |a: Algorithm| task.algorithms.contains(&a);
    let needs_form =
        wants(Algorithm::Form) || wants(Algorithm::Sorm) || wants(Algorithm::Importance);
    let mut best: Option<(alea_uq::reliability::FormResult, FormOptions)> = None;
    if needs_form {
        let before = ls.calls();
        let mut starts: Vec<Option<Vec<f64>>> = vec![None];
        for j in 0..d {
            for s in [3.0, -3.0] {
                let mut u = vec![0.0; d];
                u[j] = s;
                starts.push(Some(u));
            }
        }
        let mut found: Vec<alea_uq::reliability::FormResult> = Vec::new();
        let mut first_error = None;
        for start in starts {
            let opts = FormOptions {
                start: start.clone(),
                ..FormOptions::default()
            };
            match form(ls, &opts) {
                Ok(f) => {
                    let distinct = found.iter().all(|g| {
                        let dist: f64 = g
                            .u_star
                            .iter()
                            .zip(&f.u_star)
                            .map(|(a, b)| (a - b).powi(2))
                            .sum::<f64>()
                            .sqrt();
                        dist > 0.1 * g.beta.min(f.beta).max(1e-3)
                    });
                    if distinct {
                        found.push(f.clone());
                    }
                    if best.as_ref().is_none_or(|(b, _)| f.beta < b.beta) {
                        best = Some((f, opts));
                    }
                }
                Err(e) => {
                    first_error.get_or_insert(e.to_string());
                }
            }
        }
        out.form_evaluations = ls.calls() - before;
        found.sort_by(|a, b| a.beta.total_cmp(&b.beta));
        if let Some(b0) = found.first().map(|f| f.beta) {
            let close = found.iter().filter(|f| f.beta <= b0 + 1.0).count();
            if close > 1 {
                out.warnings.push(format!(
                    "{close} design points within beta {b0:.3} + 1: FORM, SORM and importance sampling around the first miss the others' share of the probability; compare with subset simulation"
                ));
            }
        }
        out.design_points = found
            .iter()
            .map(|f| DesignPoint {
                beta: f.beta,
                pf: f.pf,
                point: f.x_star.clone(),
                importance: f.alpha.iter().map(|a| a * a).collect(),
            })
            .collect();
        if best.is_none() {
            out.errors.push(format!(
                "FORM: {}",
                first_error.unwrap_or_else(|| "no start converged".into())
            ));
        }
    }
    if wants(Algorithm::Sorm)
        && let Some((_, opts)) = &best
    {
        match sorm(ls, opts) {
            Ok(s) => {
                out.sorm = Some(Sorm {
                    pf_breitung: s.pf_breitung,
                    pf_tvedt: s.pf_tvedt,
                    curvatures: s.curvatures,
                    evaluations: s.evaluations,
                })
            }
            Err(e) => out.errors.push(format!("SORM: {e}")),
        }
    }
    if wants(Algorithm::Importance)
        && let Some((f, _)) = &best
    {
        let opts = ImportanceOptions {
            target_cov: task.target_cov,
            level: confidence,
            seed,
            ..ImportanceOptions::default()
        };
        match importance_sampling(ls, f, &opts) {
            Ok(e) => out.importance = Some(probability(&e)),
            Err(e) => out.errors.push(format!("importance sampling: {e}")),
        }
    }
    if wants(Algorithm::Subset) {
        let opts = SubsetOptions {
            level: confidence,
            seed,
            ..SubsetOptions::default()
        };
        match subset_simulation(ls, &opts) {
            Ok(e) => out.subset = Some(probability(&e)),
            Err(e) => out.errors.push(format!("subset simulation: {e}")),
        }
    }
}

fn probability(e: &alea_uq::reliability::Estimate) -> Probability {
    Probability {
        pf: e.p,
        lower: e.lower,
        upper: e.upper,
        cov: e.cov.is_finite().then_some(e.cov),
        evaluations: e.evaluations,
    }
}
