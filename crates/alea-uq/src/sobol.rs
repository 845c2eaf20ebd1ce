//! Sobol' sensitivity indices by Monte Carlo for any model with independent inputs
//! (Saltelli et al., Comput. Phys. Commun. 181, 2010, Table 2).
//!
//! Two independent `N x d` samples `A`, `B`; `AB_i` is `A` with column `i` taken from `B`.
//! With `V = Var[f(A), f(B)]` (pooled):
//!
//! ```text
//! S_i  = (1/N) sum_j f(B)_j (f(AB_i)_j - f(A)_j) / V          (Saltelli 2010)
//! S_Ti = (1/2N) sum_j (f(A)_j - f(AB_i)_j)^2 / V               (Jansen 1999)
//! ```
//!
//! Cost `N (d + 2)` model evaluations. Standard errors are the CLT standard deviations of the
//! per-sample terms divided by `sqrt(N)` (ignoring the variance of `V`).

use crate::error::{Result, UqError};
use crate::joint::JointLaw;
use crate::rng::{CHUNK, chunk_rng, open01};
use rayon::prelude::*;

/// Per chunk: `f(A)`, `f(B)` and `f(AB_i)` for every `i`.
type ChunkEvals = (Vec<f64>, Vec<f64>, Vec<Vec<f64>>);

/// Monte Carlo Sobol' indices.
#[derive(Debug, Clone, PartialEq)]
pub struct SobolIndices {
    /// First-order indices `S_i`.
    pub first: Vec<f64>,
    /// Total indices `S_Ti`.
    pub total: Vec<f64>,
    /// Standard errors of `first`.
    pub first_se: Vec<f64>,
    /// Standard errors of `total`.
    pub total_se: Vec<f64>,
    /// Pooled variance estimate.
    pub variance: f64,
    /// Number of model evaluations `N (d + 2)`.
    pub evaluations: usize,
}

/// Saltelli/Jansen estimators with base sample size `n` (seeded; identical for any thread count).
///
/// # Errors
/// If the law's variables are not independent or `n < 2`.
pub fn sobol_indices(
    law: &dyn JointLaw,
    n: usize,
    seed: u64,
    model: impl Fn(&[f64]) -> f64 + Sync,
) -> Result<SobolIndices> {
    if !law.is_independent() {
        return Err(UqError::Invalid {
            what: "Sobol' indices",
            message: "the Monte Carlo estimators need independent inputs".into(),
        });
    }
    if n < 2 {
        return Err(crate::error::invalid(
            "Sobol' indices",
            "sample size",
            ">= 2",
            n as f64,
        ));
    }
    let d = law.dim();
    let nchunks = n.div_ceil(CHUNK);
    // Per chunk: f(A), f(B), f(AB_i) for i in 0..d, each of chunk length.
    let parts: Vec<ChunkEvals> = (0..nchunks)
        .into_par_iter()
        .map(|c| {
            let len = CHUNK.min(n - c * CHUNK);
            let mut rng = chunk_rng(seed, c as u64);
            let mut ua = vec![0.0; d];
            let mut ub = vec![0.0; d];
            let mut x = vec![0.0; d];
            let mut fa = Vec::with_capacity(len);
            let mut fb = Vec::with_capacity(len);
            let mut fab = vec![Vec::with_capacity(len); d];
            for _ in 0..len {
                for v in ua.iter_mut().chain(ub.iter_mut()) {
                    *v = open01(&mut rng);
                }
                law.unit_to_x(&ua, &mut x);
                fa.push(model(&x));
                law.unit_to_x(&ub, &mut x);
                fb.push(model(&x));
                for i in 0..d {
                    let save = ua[i];
                    ua[i] = ub[i];
                    law.unit_to_x(&ua, &mut x);
                    fab[i].push(model(&x));
                    ua[i] = save;
                }
            }
            (fa, fb, fab)
        })
        .collect();
    let fa: Vec<f64> = parts.iter().flat_map(|p| p.0.iter().copied()).collect();
    let fb: Vec<f64> = parts.iter().flat_map(|p| p.1.iter().copied()).collect();
    let nf = n as f64;
    let mean = (fa.iter().sum::<f64>() + fb.iter().sum::<f64>()) / (2.0 * nf);
    let var = (fa
        .iter()
        .chain(&fb)
        .map(|v| (v - mean).powi(2))
        .sum::<f64>())
        / (2.0 * nf - 1.0);
    let mut first = vec![0.0; d];
    let mut total = vec![0.0; d];
    let mut first_se = vec![0.0; d];
    let mut total_se = vec![0.0; d];
    for i in 0..d {
        let fab: Vec<f64> = parts.iter().flat_map(|p| p.2[i].iter().copied()).collect();
        let t1: Vec<f64> = (0..n).map(|j| fb[j] * (fab[j] - fa[j])).collect();
        let t2: Vec<f64> = (0..n).map(|j| 0.5 * (fa[j] - fab[j]).powi(2)).collect();
        let (m1, s1) = mean_se(&t1);
        let (m2, s2) = mean_se(&t2);
        first[i] = m1 / var;
        total[i] = m2 / var;
        first_se[i] = s1 / var;
        total_se[i] = s2 / var;
    }
    Ok(SobolIndices {
        first,
        total,
        first_se,
        total_se,
        variance: var,
        evaluations: n * (d + 2),
    })
}

fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let v = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}
