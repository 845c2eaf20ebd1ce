//! Validation of surrogates: the error a user should report.
//!
//! * [`q2`]: predictivity on a test set, `Q2 = 1 - sum (y - y~)^2 / sum (y - mean y)^2`
//!   (so `1 - Q2` is the relative mean squared error);
//! * [`k_fold`]: `K`-fold cross-validation of any surrogate built by a closure on (points,
//!   values): the runs are split into `K` folds by a seeded shuffle, each fold predicted by the
//!   surrogate fitted on the others; error `sum_k (y_k - y~_(-k)(x_k))^2 / sum (y - mean y)^2`;
//! * leave-one-out and corrected LOO of least-squares surrogates:
//!   [`crate::surrogate::PcSurrogate::loo_error`] /
//!   [`crate::surrogate::PcSurrogate::corrected_loo_error`] and the same on
//!   [`crate::surrogate::MonomialSurface`] (hat matrix, no refit; the correction
//!   `T = K/(K - P) (1 + tr((Psi^T Psi)^-1))` of [`crate::surrogate::corrected_loo_factor`]).

use crate::error::{Result, UqError, check_len, invalid};
use crate::rng::chunk_rng;
use crate::surrogate::LinearSurrogate;
use rand::Rng;
use rayon::prelude::*;

/// `Q2 = 1 - sum (observed - predicted)^2 / sum (observed - mean)^2`.
///
/// # Errors
/// If the lengths differ, fewer than 2 values are given, a value is not finite, or the
/// observed values are constant.
pub fn q2(predicted: &[f64], observed: &[f64]) -> Result<f64> {
    let what = "Q2";
    check_len(what, "predicted", observed.len(), predicted.len())?;
    if observed.len() < 2 {
        return Err(invalid(
            what,
            "test set size",
            ">= 2",
            observed.len() as f64,
        ));
    }
    if let Some(v) = observed.iter().chain(predicted).find(|v| !v.is_finite()) {
        return Err(invalid(what, "value", "finite", *v));
    }
    let m = observed.iter().sum::<f64>() / observed.len() as f64;
    let sst: f64 = observed.iter().map(|v| (v - m).powi(2)).sum();
    if !(sst > 0.0) {
        return Err(UqError::Invalid {
            what,
            message: "the observed values are constant".into(),
        });
    }
    let sse: f64 = observed
        .iter()
        .zip(predicted)
        .map(|(a, b)| (a - b).powi(2))
        .sum();
    Ok(1.0 - sse / sst)
}

/// `Q2` of a linear surrogate (run values `values`) on test points (row-major) and their
/// model values.
///
/// # Errors
/// As [`q2`], or if the sizes disagree with the surrogate.
pub fn q2_surrogate(
    s: &dyn LinearSurrogate,
    values: &[f64],
    test_points: &[f64],
    test_values: &[f64],
) -> Result<f64> {
    check_len("Q2", "values", s.num_runs(), values.len())?;
    check_len(
        "Q2",
        "test points",
        test_values.len() * s.dim(),
        test_points.len(),
    )?;
    let pred: Vec<f64> = test_points
        .par_chunks_exact(s.dim())
        .map(|x| s.eval(x, values))
        .collect();
    q2(&pred, test_values)
}

/// Result of [`k_fold`].
#[derive(Debug, Clone, PartialEq)]
pub struct KFold {
    /// Relative cross-validation error `sum (y - y~_(-k))^2 / sum (y - mean)^2`.
    pub error: f64,
    /// The same per fold (normalised by the variance of all values).
    pub per_fold: Vec<f64>,
    /// Out-of-fold prediction of every run.
    pub predictions: Vec<f64>,
}

/// `folds`-fold cross-validation: `fit(train_points, train_values)` builds a surrogate on the
/// other folds, which predicts the held-out runs. Seeded split, identical for any thread count.
///
/// # Errors
/// If sizes disagree, `folds < 2` or more than the runs, the values are constant, or a fit
/// fails.
pub fn k_fold<S: LinearSurrogate>(
    dim: usize,
    points: &[f64],
    values: &[f64],
    folds: usize,
    seed: u64,
    fit: impl Fn(&[f64], &[f64]) -> Result<S> + Sync,
) -> Result<KFold> {
    let what = "K-fold cross-validation";
    if dim == 0 || !points.len().is_multiple_of(dim) {
        return Err(UqError::Invalid {
            what,
            message: format!(
                "{} coordinates do not form points of dimension {dim}",
                points.len()
            ),
        });
    }
    let n = points.len() / dim;
    check_len(what, "values", n, values.len())?;
    if folds < 2 || folds > n {
        return Err(invalid(
            what,
            "folds",
            ">= 2 and <= number of runs",
            folds as f64,
        ));
    }
    let mut perm: Vec<usize> = (0..n).collect();
    let mut rng = chunk_rng(seed, 0);
    for i in (1..n).rev() {
        perm.swap(i, rng.random_range(0..=i));
    }
    let fold_of: Vec<usize> = {
        let mut f = vec![0; n];
        for (pos, &r) in perm.iter().enumerate() {
            f[r] = pos % folds;
        }
        f
    };
    let parts = (0..folds)
        .into_par_iter()
        .map(|f| {
            let train: Vec<usize> = (0..n).filter(|&r| fold_of[r] != f).collect();
            let tp: Vec<f64> = train
                .iter()
                .flat_map(|&r| points[r * dim..(r + 1) * dim].to_vec())
                .collect();
            let tv: Vec<f64> = train.iter().map(|&r| values[r]).collect();
            let s = fit(&tp, &tv)?;
            Ok((0..n)
                .filter(|&r| fold_of[r] == f)
                .map(|r| (r, s.eval(&points[r * dim..(r + 1) * dim], &tv)))
                .collect::<Vec<_>>())
        })
        .collect::<Result<Vec<_>>>()?;
    let mut predictions = vec![0.0; n];
    for part in &parts {
        for &(r, v) in part {
            predictions[r] = v;
        }
    }
    let m = values.iter().sum::<f64>() / n as f64;
    let sst: f64 = values.iter().map(|v| (v - m).powi(2)).sum();
    if !(sst > 0.0) {
        return Err(UqError::Invalid {
            what,
            message: "the run values are constant".into(),
        });
    }
    let per_fold: Vec<f64> = parts
        .iter()
        .map(|p| p.iter().map(|&(r, v)| (values[r] - v).powi(2)).sum::<f64>() / sst)
        .collect();
    Ok(KFold {
        error: per_fold.iter().sum(),
        per_fold,
        predictions,
    })
}
