//! The region of the parameter space where runs fail, and what the statistics leave out
//! (issue 35).
//!
//! A run that still does not converge after its retries (module `run`), or that has no static
//! equilibrium, has no value of the quantities. It does not sink its method: the method's
//! statistics describe the law **outside the region attributed to failed runs**, and the
//! probability of that region is reported with an interval. The rule, per kind of method:
//!
//! - **local surrogates** (piecewise linear, adaptive meshes): the failure indicator (1 at a
//!   failed run, 0 at a converged one) interpolated by the method's own surrogate gives, at
//!   each draw, the weight `t(x)` in [0, 1] that the draw puts on failed runs. A draw with
//!   `t > 0` (a cell with a failed node) is left out of the statistics. The estimate of the
//!   failure probability is the mean of `t`; its interval runs from the share of draws with
//!   `t = 1` (every node of the cell failed) to the share with `t > 0`, each widened by its
//!   Wilson sampling interval. Assumed: the design resolves the region (a failure between
//!   converged nodes is not seen; the interval is a statement about the region the design
//!   sees).
//! - **global surrogates** (chaos, polynomials): fitted on the converged runs only; a draw
//!   whose nearest design run (in the parameter box mapped to the unit cube) failed is left
//!   out. The estimate is the share of those draws; the interval runs from the share whose two
//!   nearest runs both failed to the share with either failed, each widened by its Wilson
//!   interval.
//! - **Monte Carlo on the model**: the failed runs are a binomial sample of the region:
//!   `k / n` with its Wilson interval; the statistics are those of the converged runs.

use alea_uq::special::norm_quantile;
use serde::Serialize;

/// The Wilson interval `(lower, upper)` of a share of `k` in `n` at `confidence` (exactly 0 /
/// 1 at `k = 0` / `k = n`), as `alea_uq::stats::failure_probability` gives it for a sample.
fn wilson(k: usize, n: usize, confidence: f64) -> (f64, f64) {
    let (kf, nf) = (k as f64, n as f64);
    let p = kf / nf;
    let z = norm_quantile(0.5 + 0.5 * confidence);
    let z2 = z * z;
    let denom = 1.0 + z2 / nf;
    let centre = (p + z2 / (2.0 * nf)) / denom;
    let half = z * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt() / denom;
    let lower = if k == 0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let upper = if k == n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    (lower, upper)
}

/// The region where runs failed, as one method sees it.
#[derive(Clone, Debug, Serialize)]
pub struct FailureRegion {
    /// Runs of the method that failed (not converged after retries, or without equilibrium).
    pub failed_runs: usize,
    /// Estimate of the probability of the region.
    pub probability: f64,
    /// Lower end of its interval (the study's confidence level).
    pub ci_low: f64,
    /// Upper end.
    pub ci_high: f64,
    /// Share of the law left out of the method's statistics (they describe the rest).
    pub left_out: f64,
    /// How the region was delimited (module doc).
    pub basis: String,
}

/// The counts behind a region: per draw, the weight it puts on failed runs (`t` of the
/// module doc), whether it is wholly in the region and whether it is left out.
#[derive(Default)]
pub(crate) struct RegionTally {
    weight_sum: f64,
    whole: usize,
    touched: usize,
    left_out: usize,
    draws: usize,
}

impl RegionTally {
    /// Counts one draw.
    pub(crate) fn add(&mut self, weight: f64, whole: bool, touched: bool, left_out: bool) {
        self.weight_sum += weight;
        self.whole += usize::from(whole);
        self.touched += usize::from(touched);
        self.left_out += usize::from(left_out);
        self.draws += 1;
    }

    /// The region from the tally at `confidence`.
    pub(crate) fn region(&self, failed_runs: usize, confidence: f64, basis: &str) -> FailureRegion {
        let n = self.draws.max(1);
        let lower = wilson(self.whole, n, confidence).0;
        let upper = wilson(self.touched, n, confidence).1;
        let probability = self.weight_sum / n as f64;
        FailureRegion {
            failed_runs,
            probability,
            ci_low: lower.min(probability),
            ci_high: upper.max(probability),
            left_out: self.left_out as f64 / n as f64,
            basis: basis.to_string(),
        }
    }
}

/// The weight a draw with surrogate weights `w` puts on failed runs (`failed[k]`), clamped to
/// [0, 1] (a piecewise-multilinear surrogate's weights are a partition of unity).
pub(crate) fn local_weight(w: &[(usize, f64)], failed: &[bool]) -> f64 {
    w.iter()
        .filter(|(k, wk)| failed[*k] && *wk != 0.0)
        .map(|(_, wk)| *wk)
        .sum::<f64>()
        .clamp(0.0, 1.0)
}

/// Whether any of the weights `w` is on a failed run.
pub fn touches(w: &[(usize, f64)], failed: &[bool]) -> bool {
    w.iter().any(|(k, wk)| failed[*k] && *wk != 0.0)
}

/// The two design runs nearest to the normalised point `x` (squared distances in the unit
/// cube; ties to the lower index): `(nearest, second)`, `second` = `nearest` with one run.
pub(crate) fn two_nearest(x: &[f64], design: &[Vec<f64>]) -> (usize, usize) {
    let (mut best, mut second) = ((f64::INFINITY, 0usize), (f64::INFINITY, 0usize));
    for (k, p) in design.iter().enumerate() {
        let d2: f64 = p.iter().zip(x).map(|(a, b)| (a - b) * (a - b)).sum();
        if d2 < best.0 {
            second = best;
            best = (d2, k);
        } else if d2 < second.0 {
            second = (d2, k);
        }
    }
    if second.0.is_infinite() {
        second = best;
    }
    (best.1, second.1)
}

/// The Monte Carlo method's region: `failed` of `runs` runs failed.
pub(crate) fn binomial_region(failed: usize, runs: usize, confidence: f64) -> FailureRegion {
    let mut tally = RegionTally::default();
    for i in 0..runs {
        let f = i < failed;
        tally.add(f64::from(u8::from(f)), f, f, f);
    }
    tally.region(
        failed,
        confidence,
        "the share of the Monte Carlo runs that failed (a binomial sample of the region), Wilson interval",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tally's estimate is the mean weight and its interval brackets it from the whole to the
    /// touched share; Monte Carlo's is the Wilson interval of k / n.
    #[test]
    fn region_brackets_its_estimate() {
        let mut t = RegionTally::default();
        for i in 0..1000 {
            // 100 draws wholly failed, 100 half, 800 clean.
            let w = if i < 100 {
                1.0
            } else if i < 200 {
                0.5
            } else {
                0.0
            };
            t.add(w, w == 1.0, w > 0.0, w > 0.0);
        }
        let r = t.region(3, 0.95, "test");
        assert!((r.probability - 0.15).abs() < 1e-12);
        assert!(r.ci_low < 0.1 && r.ci_low > 0.08, "{r:?}");
        assert!(r.ci_high > 0.2 && r.ci_high < 0.23, "{r:?}");
        assert!((r.left_out - 0.2).abs() < 1e-12);
        let mc = binomial_region(2, 40, 0.95);
        assert!((mc.probability - 0.05).abs() < 1e-12);
        assert!(mc.ci_low > 0.0 && mc.ci_low < 0.05 && mc.ci_high > 0.15 && mc.ci_high < 0.2);
        // The same bounds as the toolkit's Wilson interval of a sample.
        let sample: Vec<f64> = (0..40).map(|i| f64::from(u8::from(i < 2))).collect();
        let f = alea_uq::stats::failure_probability(&sample, 0.5, 0.95);
        assert!((f.lower - mc.ci_low).abs() < 1e-15 && (f.upper - mc.ci_high).abs() < 1e-15);
    }

    #[test]
    fn the_two_nearest_runs() {
        let design = vec![vec![0.0, 0.0], vec![1.0, 1.0], vec![0.4, 0.4]];
        assert_eq!(two_nearest(&[0.1, 0.1], &design), (0, 2));
        assert_eq!(two_nearest(&[0.9, 0.8], &design), (1, 2));
        assert_eq!(two_nearest(&[0.9, 0.8], &design[..1]), (0, 0));
    }
}
