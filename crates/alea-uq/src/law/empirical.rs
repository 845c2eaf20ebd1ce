//! Laws built from data.
//!
//! * [`Empirical`]: the linearly interpolated empirical law of `n` sorted values
//!   `x_(0) <= ... <= x_(n-1)`: cdf piecewise linear through `(x_(i), i/(n-1))`, so its
//!   quantile is the type-7 sample quantile ([`crate::stats::quantile`]) and each of the
//!   `n - 1` gaps carries mass `1/(n-1)` uniformly: `E[X] = sum_i (x_i + x_{i+1}) / (2(n-1))`,
//!   `E[X^2] = sum_i (x_i^2 + x_i x_{i+1} + x_{i+1}^2) / (3(n-1))`. Tied values make a point
//!   mass (the cdf jumps there; `pdf` is the density of the continuous part).
//! * [`KdeLaw`]: the Gaussian kernel density estimate as a law,
//!   `f(x) = 1/(N h) sum phi((x - x_i)/h)`, `F(x) = 1/N sum Phi((x - x_i)/h)` (samples beyond
//!   `8h` counted as 0 or 1, found by bisection in the sorted data), quantile by safeguarded
//!   Newton, `E[X] = mean(x_i)`, `Var X = (1/N) sum (x_i - mean)^2 + h^2`; drawn as
//!   `x_J + h Z` with `J` uniform on the samples, `Z ~ N(0, 1)`.

use super::Marginal;
use crate::error::{Result, UqError, invalid};
use crate::kde::Kde;
use crate::special::{norm_cdf, norm_quantile, quantile_ends, safeguarded_newton};
use rand::RngCore;

/// Linearly interpolated empirical law.
#[derive(Debug, Clone, PartialEq)]
pub struct Empirical {
    sorted: Vec<f64>,
    mean: f64,
    std: f64,
}

impl Empirical {
    /// # Errors
    /// If fewer than 2 values, a value is not finite, or all values are equal.
    pub fn new(data: &[f64]) -> Result<Self> {
        let what = "empirical law";
        if data.len() < 2 {
            return Err(invalid(what, "sample size", ">= 2", data.len() as f64));
        }
        if let Some(v) = data.iter().find(|v| !v.is_finite()) {
            return Err(invalid(what, "value", "finite", *v));
        }
        let mut sorted = data.to_vec();
        sorted.sort_by(f64::total_cmp);
        if sorted[0] == sorted[sorted.len() - 1] {
            return Err(UqError::Invalid {
                what,
                message: "all values are equal".into(),
            });
        }
        let m = (sorted.len() - 1) as f64;
        let (mut s1, mut s2) = (0.0, 0.0);
        for w in sorted.windows(2) {
            let (a, b) = (w[0], w[1]);
            s1 += 0.5 * (a + b);
            s2 += (a * a + a * b + b * b) / 3.0;
        }
        let mean = s1 / m;
        let std = (s2 / m - mean * mean).max(0.0).sqrt();
        Ok(Self { sorted, mean, std })
    }
    /// The sorted data.
    pub fn data(&self) -> &[f64] {
        &self.sorted
    }
}

impl Marginal for Empirical {
    fn name(&self) -> &'static str {
        "empirical"
    }
    fn pdf(&self, x: f64) -> f64 {
        let n = self.sorted.len();
        if x < self.sorted[0] || x > self.sorted[n - 1] {
            return 0.0;
        }
        let i = self.sorted.partition_point(|&v| v <= x).clamp(1, n - 1) - 1;
        let w = self.sorted[i + 1] - self.sorted[i];
        if w > 0.0 {
            1.0 / ((n - 1) as f64 * w)
        } else {
            0.0
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        let n = self.sorted.len();
        if x < self.sorted[0] {
            return 0.0;
        }
        if x >= self.sorted[n - 1] {
            return 1.0;
        }
        // Last i with x_i <= x (ties: the top of the jump).
        let i = self.sorted.partition_point(|&v| v <= x) - 1;
        let (a, b) = (self.sorted[i], self.sorted[i + 1]);
        let t = if b > a { (x - a) / (b - a) } else { 0.0 };
        (i as f64 + t) / (n - 1) as f64
    }
    fn quantile(&self, p: f64) -> f64 {
        crate::stats::quantile_sorted(&self.sorted, p)
    }
    fn mean(&self) -> f64 {
        self.mean
    }
    fn std(&self) -> f64 {
        self.std
    }
    fn support(&self) -> (f64, f64) {
        (self.sorted[0], self.sorted[self.sorted.len() - 1])
    }
}

/// A Gaussian kernel density estimate used as a law.
#[derive(Debug, Clone)]
pub struct KdeLaw {
    kde: Kde,
    mean: f64,
    std: f64,
}

impl KdeLaw {
    /// The law of the estimate `kde` (any bandwidth rule).
    pub fn new(kde: Kde) -> Self {
        let x = kde.samples();
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
        let h = kde.bandwidth();
        Self {
            kde,
            mean,
            std: (var + h * h).sqrt(),
        }
    }
    /// The underlying estimate.
    pub fn kde(&self) -> &Kde {
        &self.kde
    }
}

impl Marginal for KdeLaw {
    fn name(&self) -> &'static str {
        "kernel density"
    }
    fn pdf(&self, x: f64) -> f64 {
        self.kde.pdf(x)
    }
    fn cdf(&self, x: f64) -> f64 {
        let s = self.kde.samples();
        let h = self.kde.bandwidth();
        let a = s.partition_point(|&v| v < x - 8.0 * h);
        let b = s.partition_point(|&v| v <= x + 8.0 * h);
        let window: f64 = s[a..b].iter().map(|&v| norm_cdf((x - v) / h)).sum();
        ((a as f64 + window) / s.len() as f64).clamp(0.0, 1.0)
    }
    fn quantile(&self, p: f64) -> f64 {
        if let Some(q) = quantile_ends(p, f64::NEG_INFINITY, f64::INFINITY) {
            return q;
        }
        let s = self.kde.samples();
        let h = self.kde.bandwidth();
        // Bracket: every kernel's p-quantile lies in [min + h z_p, max + h z_p].
        let z = norm_quantile(p);
        let (lo, hi) = (s[0] + h * z, s[s.len() - 1] + h * z);
        if hi <= lo {
            return lo;
        }
        let x0 = crate::stats::quantile_sorted(s, p).clamp(lo, hi);
        safeguarded_newton(p, lo, hi, x0, |x| self.cdf(x), |x| self.pdf(x))
    }
    fn mean(&self) -> f64 {
        self.mean
    }
    fn std(&self) -> f64 {
        self.std
    }
    fn support(&self) -> (f64, f64) {
        (f64::NEG_INFINITY, f64::INFINITY)
    }
    fn sample(&self, rng: &mut dyn RngCore) -> f64 {
        let s = self.kde.samples();
        let j = ((crate::rng::open01(rng) * s.len() as f64) as usize).min(s.len() - 1);
        s[j] + self.kde.bandwidth() * norm_quantile(crate::rng::open01(rng))
    }
}
