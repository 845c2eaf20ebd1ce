//! Confirmation of a surrogate's failure probability by the solver itself (issue 19): with
//! `solver_runs = N` in a `[[reliability]]` table, importance sampling of `P(q > t)` with `N`
//! model runs, centred at the design point `u*` of FORM on the method's surrogate (the best of
//! the starts of [`super::form_from_starts`]):
//!
//! ```text
//! u_i = u* + z_i,  z_i ~ N(0, I_d),  x_i = T^-1(u_i)   (the joint law's map to the parameters)
//! w_i = phi_d(u_i) / phi_d(u_i - u*) = exp(-u_i . u* + |u*|^2 / 2)
//! P   = (1/N) sum_i 1[q(x_i) > t] w_i
//! var = (1/N) ( (1/N) sum_i 1[q(x_i) > t] w_i^2 - P^2 )
//! ```
//!
//! with the interval `P +- z sqrt(var)` (clipped at 0) at the study's level and the
//! coefficient of variation `sqrt(var) / P`. The runs are study runs: stored, resumed after a
//! kill and warm-started like every other; their points depend only on the seed, the table's
//! index and the design point, itself a deterministic function of the method's runs. A run that
//! does not converge is left out and counted (`failed`): the estimate then uses the others, and
//! says so. The surrogate's own probability has its error budget (`crate::budget`); this is the
//! model's, with only the sampling error.

use alea_uq::reliability::LimitState;
use alea_uq::rng::{chunk_rng, open01};
use alea_uq::special::norm_quantile;
use serde::Serialize;

use super::{Lookup, ReliabilityTask, evaluate, form_from_starts, surrogate_of};
use crate::method::Method;
use crate::study::Study;

/// The points of a confirmation.
#[derive(Clone, Debug)]
pub struct SolverPlan {
    /// The surrogate's design point in the standard normal space.
    pub u_star: Vec<f64>,
    /// Its reliability index.
    pub beta: f64,
    /// The sampling points in the standard normal space.
    pub u: Vec<Vec<f64>>,
    /// The same in the parameters: the runs.
    pub x: Vec<Vec<f64>>,
}

/// A failure probability from runs of the solver.
#[derive(Clone, Debug, Serialize)]
pub struct SolverConfirmation {
    /// Estimate.
    pub pf: f64,
    /// Lower bound of the interval (the study's confidence level).
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Coefficient of variation (`None` when no run failed the limit state).
    pub cov: Option<f64>,
    /// Runs used (converged).
    pub runs: usize,
    /// Runs missing or not converged, left out.
    pub failed: usize,
    /// Reliability index of the surrogate's design point the sampling is centred at.
    pub beta: f64,
}

/// The confirmation runs of task `index` (`task.solver_runs` of them) on `method`'s
/// surrogate built on the runs that `lookup` finds.
pub fn plan(
    study: &Study,
    index: usize,
    task: &ReliabilityTask,
    method: &Method,
    lookup: &Lookup<'_>,
) -> Result<SolverPlan, String> {
    let (sur, values) = surrogate_of(study, task, method, lookup)?;
    let law = study.params.joint.as_ref();
    let q = |x: &[f64]| evaluate(study, &sur, &values, x);
    let ls = LimitState::exceedance(law, q, task.threshold);
    let alea_uq::reliability::MultiStart {
        best, first_error, ..
    } = form_from_starts(&ls);
    let Some((f, _)) = best else {
        return Err(format!(
            "no FORM design point on the surrogate ({})",
            first_error.unwrap_or_else(|| "no start converged".into())
        ));
    };
    let d = f.u_star.len();
    let mut rng = chunk_rng(study.seed ^ 0x736f_6c76_6572, index as u64);
    let u: Vec<Vec<f64>> = (0..task.solver_runs)
        .map(|_| {
            f.u_star
                .iter()
                .map(|&s| s + norm_quantile(open01(&mut rng)))
                .collect()
        })
        .collect();
    let x = u
        .iter()
        .map(|ui| {
            let mut xi = vec![0.0; d];
            law.standard_normal_to_x(ui, &mut xi);
            xi
        })
        .collect();
    Ok(SolverPlan {
        u_star: f.u_star,
        beta: f.beta,
        u,
        x,
    })
}

/// The importance-sampling estimate from the runs of `plan` that `lookup` finds converged.
pub fn estimate(
    plan: &SolverPlan,
    task: &ReliabilityTask,
    lookup: &Lookup<'_>,
    confidence: f64,
) -> SolverConfirmation {
    let half_beta2: f64 = 0.5 * plan.u_star.iter().map(|s| s * s).sum::<f64>();
    let (mut sum, mut sum2, mut runs, mut failed) = (0.0, 0.0, 0usize, 0usize);
    for (u, x) in plan.u.iter().zip(&plan.x) {
        match lookup(x).filter(|r| r.converged()) {
            Some(r) => {
                runs += 1;
                if r.qois[task.quantity] > task.threshold {
                    let dot: f64 = u.iter().zip(&plan.u_star).map(|(a, b)| a * b).sum();
                    let w = (half_beta2 - dot).exp();
                    sum += w;
                    sum2 += w * w;
                }
            }
            None => failed += 1,
        }
    }
    let n = runs.max(1) as f64;
    let pf = sum / n;
    let var = ((sum2 / n - pf * pf) / n).max(0.0);
    let z = norm_quantile(0.5 + 0.5 * confidence);
    SolverConfirmation {
        pf,
        lower: (pf - z * var.sqrt()).max(0.0),
        upper: pf + z * var.sqrt(),
        cov: (pf > 0.0).then(|| var.sqrt() / pf),
        runs,
        failed,
        beta: plan.beta,
    }
}

/// The parameter points of every confirmation of the study, for the runner: the tasks with
/// `solver_runs > 0`, on `methods` (after their runs) and the runs `lookup` finds. A task
/// whose surrogate or design point cannot be built has no points (its analysis says why).
pub fn confirmation_points(
    study: &Study,
    methods: &[Method],
    lookup: &Lookup<'_>,
) -> Vec<Vec<f64>> {
    study
        .reliability
        .iter()
        .enumerate()
        .filter(|(_, t)| t.solver_runs > 0)
        .filter_map(|(i, t)| plan(study, i, t, &methods[t.method], lookup).ok())
        .flat_map(|p| p.x)
        .collect()
}
