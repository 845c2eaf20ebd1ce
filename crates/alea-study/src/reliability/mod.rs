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
    FormOptions, ImportanceOptions, LimitState, SubsetOptions, importance_sampling, sorm_at,
    subset_simulation,
};
use serde::Serialize;

pub mod solver;
pub mod task;

pub use task::{Algorithm, ReliabilityTask, build_reliability};

use crate::method::Method;
use crate::store::{RunRecord, point_key};
use crate::study::Study;

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
    /// Importance sampling with runs of the solver itself (`solver_runs`).
    pub solver: Option<solver::SolverConfirmation>,
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
        .enumerate()
        .map(|(t, task)| {
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
                solver: None,
                warnings: Vec::new(),
                errors: Vec::new(),
            };
            let (sur, values) =
                match surrogate_of(study, task, method, &|p| by_key.get(&point_key(p)).copied()) {
                    Ok(s) => s,
                    Err(e) => {
                        out.errors.push(e);
                        return out;
                    }
                };
            let q = |x: &[f64]| evaluate(study, &sur, &values, x);
            let law = study.params.joint.as_ref();
            let ls = LimitState::exceedance(law, q, task.threshold);
            run_algorithms(task, &ls, study.seed, confidence, &mut out);
            if task.solver_runs > 0 {
                let lookup = |p: &[f64]| by_key.get(&point_key(p)).copied();
                match solver::plan(study, t, task, method, &lookup) {
                    Ok(plan) => {
                        out.solver = Some(solver::estimate(&plan, task, &lookup, confidence));
                    }
                    Err(e) => out.errors.push(format!("solver confirmation: {e}")),
                }
            }
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
    let wants = |a: Algorithm| task.algorithms.contains(&a);
    let needs_form =
        wants(Algorithm::Form) || wants(Algorithm::Sorm) || wants(Algorithm::Importance);
    let mut best: Option<(alea_uq::reliability::FormResult, FormOptions)> = None;
    if needs_form {
        let before = ls.calls();
        let starts = form_from_starts(ls);
        out.form_evaluations = ls.calls() - before;
        out.warnings.extend(starts.several_design_points());
        let alea_uq::reliability::MultiStart {
            found,
            best: best_start,
            first_error,
        } = starts;
        best = best_start;
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
        && let Some((f, opts)) = &best
    {
        // At the design point FORM found (not FORM again: `2 d^2 + 1` evaluations in all).
        match sorm_at(ls, f.clone(), opts) {
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

/// A run record by its parameter point.
pub(crate) type Lookup<'a> = dyn Fn(&[f64]) -> Option<&'a RunRecord> + 'a;

/// The surrogate of `method` for the task's quantity, on the method's converged runs, with
/// the quantity's values at them.
pub(crate) fn surrogate_of(
    study: &Study,
    task: &ReliabilityTask,
    method: &Method,
    lookup: &Lookup<'_>,
) -> Result<(crate::method::Surrogate, Vec<f64>), String> {
    let (points, values): (Vec<Vec<f64>>, Vec<f64>) = method
        .points
        .iter()
        .filter_map(|p| {
            lookup(p)
                .filter(|r| r.converged())
                .map(|r| (p.clone(), r.qois[task.quantity]))
        })
        .unzip();
    let sur = method
        .surrogate(&study.params, &points)
        .map_err(|e| format!("surrogate: {e}"))?;
    Ok((sur, values))
}

/// The surrogate's value at `x`.
pub(crate) fn evaluate(
    study: &Study,
    sur: &crate::method::Surrogate,
    values: &[f64],
    x: &[f64],
) -> f64 {
    let mut t = vec![0.0; study.params.names.len()];
    let mut w = Vec::new();
    sur.weights(x, &mut t, &mut w);
    w.iter().map(|&(k, wk)| wk * values[k]).sum::<f64>()
}

/// FORM from the median and `+-3` along every axis of the standard normal space
/// (`alea_uq::reliability::form_from_starts`, shared with the Python binding).
pub(crate) fn form_from_starts(ls: &LimitState) -> alea_uq::reliability::MultiStart {
    alea_uq::reliability::form_from_starts(
        ls,
        &alea_uq::reliability::axis_starts(ls.dim()),
        &FormOptions::default(),
    )
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
