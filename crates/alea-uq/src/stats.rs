//! Monte Carlo statistics: sampling a model or surrogate under a joint law (parallel,
//! reproducible), moments, empirical quantiles and failure probabilities.
//!
//! * [`Summary`]: mean, unbiased variance, skewness `m3/m2^1.5` and excess kurtosis `m4/m2^2 - 3`
//!   (population moments), computed by a two-pass algorithm.
//! * [`quantile`]: linear interpolation of the order statistics (type 7 of Hyndman & Fan).
//! * [`failure_probability`]: `p^ = #{q_i > s} / N` with the Wilson score interval
//!   `(p^ + z^2/2N +- z sqrt(p^(1-p^)/N + z^2/4N^2)) / (1 + z^2/N)`, valid also when no failure
//!   is observed, and the coefficient of variation `sqrt((1-p)/(N p))`.

use crate::joint::JointLaw;
use crate::rng::{CHUNK, chunk_rng};
use crate::special::norm_quantile;
use rayon::prelude::*;

/// Evaluate `f` at `n` i.i.d. draws of `law` (seeded; identical for any thread count).
pub fn sample_model(
    law: &dyn JointLaw,
    n: usize,
    seed: u64,
    f: impl Fn(&[f64]) -> f64 + Sync,
) -> Vec<f64> {
    let d = law.dim();
    let mut out = vec![0.0; n];
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(c, block)| {
            let mut rng = chunk_rng(seed, c as u64);
            let mut x = vec![0.0; d];
            for o in block.iter_mut() {
                law.sample(&mut rng, &mut x);
                *o = f(&x);
            }
        });
    out
}

/// Moments of a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Sample size.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Unbiased variance.
    pub variance: f64,
    /// Standard deviation `sqrt(variance)`.
    pub std: f64,
    /// Skewness.
    pub skewness: f64,
    /// Excess kurtosis.
    pub kurtosis: f64,
    /// Minimum.
    pub min: f64,
    /// Maximum.
    pub max: f64,
}

impl Summary {
    /// Summary of `x` (NaN fields for an empty sample). Parallel over fixed chunks, so the
    /// result does not depend on the number of threads.
    pub fn of(x: &[f64]) -> Self {
        let n = x.len();
        let sum: f64 = x
            .par_chunks(CHUNK)
            .map(|c| c.iter().sum::<f64>())
            .collect::<Vec<_>>()
            .iter()
            .sum();
        let mean = sum / n as f64;
        let parts: Vec<[f64; 5]> = x
            .par_chunks(CHUNK)
            .map(|c| {
                let mut a = [0.0, 0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY];
                for &v in c {
                    let e = v - mean;
                    let e2 = e * e;
                    a[0] += e2;
                    a[1] += e2 * e;
                    a[2] += e2 * e2;
                    a[3] = a[3].min(v);
                    a[4] = a[4].max(v);
                }
                a
            })
            .collect();
        let mut m = [0.0, 0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY];
        for p in &parts {
            m[0] += p[0];
            m[1] += p[1];
            m[2] += p[2];
            m[3] = m[3].min(p[3]);
            m[4] = m[4].max(p[4]);
        }
        let nf = n as f64;
        let (m2, m3, m4) = (m[0] / nf, m[1] / nf, m[2] / nf);
        let variance = if n > 1 { m[0] / (nf - 1.0) } else { f64::NAN };
        Self {
            n,
            mean,
            variance,
            std: variance.sqrt(),
            skewness: m3 / m2.powf(1.5),
            kurtosis: m4 / (m2 * m2) - 3.0,
            min: m[3],
            max: m[4],
        }
    }

    /// Half-width of the asymptotic confidence interval of the mean at level `level`.
    pub fn mean_ci_half_width(&self, level: f64) -> f64 {
        norm_quantile(0.5 + 0.5 * level) * self.std / (self.n as f64).sqrt()
    }
}

/// Empirical quantile of order `p` in `[0, 1]` (type 7); `NaN` for an empty sample or `p`
/// outside `[0, 1]`. Sorts a copy.
pub fn quantile(x: &[f64], p: f64) -> f64 {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    quantile_sorted(&s, p)
}

/// As [`quantile`] on already sorted data.
pub fn quantile_sorted(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() || !(0.0..=1.0).contains(&p) {
        return f64::NAN;
    }
    let h = (sorted.len() - 1) as f64 * p;
    let i = h.floor() as usize;
    let f = h - i as f64;
    if i + 1 < sorted.len() {
        sorted[i] + f * (sorted[i + 1] - sorted[i])
    } else {
        sorted[i]
    }
}

/// Estimated failure probability `P(q > threshold)` with a confidence interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FailureProbability {
    /// Estimate `#{q_i > s} / N`.
    pub p: f64,
    /// Lower bound of the Wilson interval.
    pub lower: f64,
    /// Upper bound of the Wilson interval.
    pub upper: f64,
    /// Number of failures.
    pub failures: usize,
    /// Sample size.
    pub n: usize,
    /// Coefficient of variation of the estimator `sqrt((1 - p)/(N p))` (infinite if `p = 0`).
    pub cov: f64,
}

/// `P(q > threshold)` from a sample with a Wilson score interval at confidence `level`
/// (e.g. 0.95).
pub fn failure_probability(q: &[f64], threshold: f64, level: f64) -> FailureProbability {
    let n = q.len();
    let failures = q.iter().filter(|&&v| v > threshold).count();
    let nf = n as f64;
    let p = failures as f64 / nf;
    let z = norm_quantile(0.5 + 0.5 * level);
    let z2 = z * z;
    let denom = 1.0 + z2 / nf;
    let centre = (p + z2 / (2.0 * nf)) / denom;
    let half = z * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt() / denom;
    // The Wilson bounds are exactly 0 (1) when no (every) draw fails: centre = half there in
    // exact arithmetic, not in floating point.
    FailureProbability {
        p,
        lower: if failures == 0 {
            0.0
        } else {
            (centre - half).max(0.0)
        },
        upper: if failures == n {
            1.0
        } else {
            (centre + half).min(1.0)
        },
        failures,
        n,
        cov: ((1.0 - p) / (nf * p)).sqrt(),
    }
}
