//! Goal-oriented refinement of a linear surrogate for a failure probability
//! `P(q(x) > s)`: propose new runs where they most change `P_f`, i.e. near the surrogate's limit
//! state `q~(x) = s` in the region that carries the failure probability.
//!
//! 1. Candidates: the samples of a subset simulation on the current surrogate (all levels), which
//!    concentrate on the failure domain and its boundary, whatever the number of failure modes.
//! 2. Local error: `F`-fold refits of the surrogate (each without one fold of runs) give
//!    predictions `q_f(x)`; `sigma(x)` is their jackknife spread
//!    `sqrt((F - 1)/F sum_f (q_f - mean)^2)`.
//! 3. Score (the U function of AK-MCS, Echard et al., Struct. Saf. 33, 2011):
//!    `U(x) = |q~(x) - s| / sigma(x)`, small where the sign of `q~ - s` is uncertain; the
//!    candidates of smallest `U` are taken greedily, each at least `min_distance` (standard
//!    normal space) from the runs and from the points already proposed.
//! 4. Stated error: the surrogate's `P_f` (subset simulation, coefficient of variation `cov`)
//!    and the jackknife spread of the fold refits' `P_f` on common samples, `surrogate_error`
//!    (see [`Proposal::pf_folds`]); a refinement loop
//!    stops when `sqrt(cov^2 + surrogate_error^2)` ([`Proposal::relative_error`]) is small
//!    enough.

use super::LimitState;
use super::subset::{SubsetOptions, run};
use crate::error::{Result, UqError, invalid};
use crate::joint::JointLaw;
use crate::rng::chunk_rng;
use crate::surrogate::LinearSurrogate;
use rand::Rng;
use rayon::prelude::*;

/// Options of [`propose_runs`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefineOptions {
    /// Number of runs to propose (default 4).
    pub new_runs: usize,
    /// Folds of the local error estimate (default 5).
    pub folds: usize,
    /// Smallest distance between proposed points and runs, standard normal space (default 0.25).
    pub min_distance: f64,
    /// Subset simulation generating the candidates (and the surrogate's `P_f`).
    pub subset: SubsetOptions,
}

impl Default for RefineOptions {
    fn default() -> Self {
        Self {
            new_runs: 4,
            folds: 5,
            min_distance: 0.25,
            subset: SubsetOptions::default(),
        }
    }
}

/// Proposed runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Proposal {
    /// New points in the physical space, row-major `new_runs x dim`.
    pub points: Vec<f64>,
    /// Their scores `U` (ascending).
    pub scores: Vec<f64>,
    /// Failure probability of the current surrogate (subset simulation).
    pub pf: super::Estimate,
    /// Failure probability of each fold refit, `P_f n_f / n`, with `n_f`, `n` the failures of
    /// the fold refit and of the surrogate among the samples of the last subset level (common
    /// random numbers; failures of a refit outside the surrogate's last intermediate domain
    /// are not seen).
    pub pf_folds: Vec<f64>,
    /// Relative surrogate error of `P_f`: jackknife spread of `pf_folds`,
    /// `sqrt((F - 1)/F sum_f (P_f - mean)^2) / P_f` (infinite when `P_f = 0`). With the
    /// sampling coefficient of variation `pf.cov` it states the relative error of `P_f`:
    /// `sqrt(cov^2 + surrogate_error^2)`.
    pub surrogate_error: f64,
}

impl Proposal {
    /// Stated relative error of the surrogate's `P_f`: `sqrt(cov^2 + surrogate_error^2)`.
    pub fn relative_error(&self) -> f64 {
        self.pf.cov.hypot(self.surrogate_error)
    }
}

/// Propose runs that most change `P(q > threshold)` for a linear surrogate fitted by `fit`
/// (called on run points `K x d` and values; refitted on fold subsets).
///
/// # Errors
/// If sizes disagree, `folds < 2` or larger than the number of runs, a fit fails, or the
/// subset simulation on the surrogate fails.
pub fn propose_runs<S: LinearSurrogate>(
    law: &dyn JointLaw,
    points: &[f64],
    values: &[f64],
    threshold: f64,
    fit: impl Fn(&[f64], &[f64]) -> Result<S> + Sync,
    opts: &RefineOptions,
) -> Result<Proposal> {
    let what = "goal-oriented refinement";
    let d = law.dim();
    if d == 0 || !points.len().is_multiple_of(d) {
        return Err(UqError::Invalid {
            what,
            message: format!(
                "{} coordinates do not form points of dimension {d}",
                points.len()
            ),
        });
    }
    let k = points.len() / d;
    crate::error::check_len(what, "values", k, values.len())?;
    if opts.folds < 2 || opts.folds > k {
        return Err(invalid(
            what,
            "folds",
            ">= 2 and <= number of runs",
            opts.folds as f64,
        ));
    }
    if !(opts.min_distance >= 0.0) {
        return Err(invalid(what, "min_distance", ">= 0", opts.min_distance));
    }
    let full = fit(points, values)?;
    let ls = LimitState::exceedance(law, |x| full.eval(x, values), threshold);
    let mut cand: Vec<f64> = Vec::new();
    let mut last: Vec<f64> = Vec::new();
    let (pf, _) = run(&ls, &opts.subset, |pop| {
        cand.extend_from_slice(&pop.u);
        last.clone_from(&pop.u);
    })?;
    let nc = cand.len() / d;
    // Folds: a seeded shuffle of the runs.
    let mut perm: Vec<usize> = (0..k).collect();
    let mut rng = chunk_rng(opts.subset.seed, u64::MAX);
    for i in (1..k).rev() {
        let j = rng.random_range(0..=i);
        perm.swap(i, j);
    }
    let fold_models = (0..opts.folds)
        .map(|f| {
            let keep: Vec<usize> = perm
                .iter()
                .enumerate()
                .filter(|(i, _)| i % opts.folds != f)
                .map(|(_, &r)| r)
                .collect();
            let p: Vec<f64> = keep
                .iter()
                .flat_map(|&r| points[r * d..(r + 1) * d].to_vec())
                .collect();
            let v: Vec<f64> = keep.iter().map(|&r| values[r]).collect();
            fit(&p, &v).map(|s| (s, v))
        })
        .collect::<Result<Vec<_>>>()?;
    let ff = opts.folds as f64;
    // Common random numbers: every fold model classifies the same last-level population (the
    // samples of the full surrogate's last conditional level, or the i.i.d. sample if there is
    // one level), so the ratio of failure counts isolates the surrogate's variability from the
    // sampling noise.
    let fails = |f: &(dyn Fn(&[f64]) -> f64 + Sync)| -> usize {
        last.par_chunks_exact(d)
            .filter(|u| {
                let mut x = vec![0.0; d];
                law.standard_normal_to_x(u, &mut x);
                f(&x) > threshold
            })
            .count()
    };
    let n_full = fails(&|x| full.eval(x, values));
    let pf_folds: Vec<f64> = fold_models
        .iter()
        .map(|(s, v)| {
            if n_full == 0 {
                0.0
            } else {
                pf.p * fails(&|x| s.eval(x, v)) as f64 / n_full as f64
            }
        })
        .collect();
    let mf = pf_folds.iter().sum::<f64>() / ff;
    let spread = ((ff - 1.0) / ff * pf_folds.iter().map(|p| (p - mf).powi(2)).sum::<f64>()).sqrt();
    let surrogate_error = if pf.p > 0.0 {
        spread / pf.p
    } else {
        f64::INFINITY
    };
    let scored: Vec<(f64, usize)> = (0..nc)
        .into_par_iter()
        .map(|c| {
            let mut x = vec![0.0; d];
            law.standard_normal_to_x(&cand[c * d..(c + 1) * d], &mut x);
            let mu = full.eval(&x, values);
            let preds: Vec<f64> = fold_models.iter().map(|(s, v)| s.eval(&x, v)).collect();
            let m = preds.iter().sum::<f64>() / ff;
            let var = (ff - 1.0) / ff * preds.iter().map(|p| (p - m).powi(2)).sum::<f64>();
            let u = (mu - threshold).abs() / var.sqrt().max(1e-300);
            (if u.is_finite() { u } else { f64::INFINITY }, c)
        })
        .collect();
    let mut order = scored;
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    // Existing runs in the standard normal space.
    let mut taken: Vec<Vec<f64>> = points
        .chunks_exact(d)
        .map(|x| {
            let mut u = vec![0.0; d];
            law.x_to_standard_normal(x, &mut u);
            u
        })
        .collect();
    let (mut out, mut scores) = (Vec::new(), Vec::new());
    let md2 = opts.min_distance * opts.min_distance;
    for (score, c) in order {
        if scores.len() == opts.new_runs {
            break;
        }
        let u = &cand[c * d..(c + 1) * d];
        let far = taken
            .iter()
            .all(|t| t.iter().zip(u).map(|(a, b)| (a - b).powi(2)).sum::<f64>() >= md2);
        if far {
            let mut x = vec![0.0; d];
            law.standard_normal_to_x(u, &mut x);
            out.extend_from_slice(&x);
            scores.push(score);
            taken.push(u.to_vec());
        }
    }
    Ok(Proposal {
        points: out,
        scores,
        pf,
        pf_folds,
        surrogate_error,
    })
}
