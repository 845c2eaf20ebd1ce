//! User-tabulated law: a piecewise-linear density through the points `(x_i, f_i)`, normalised
//! to integrate to one. On each segment the cdf is quadratic, so the quantile is the root of a
//! quadratic; the moments are exact (Simpson's rule is exact for the cubic `x^2 f(x)`).

use super::Marginal;
use crate::error::{Result, UqError, invalid};

/// Piecewise-linear density given at increasing nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    x: Vec<f64>,
    f: Vec<f64>,
    /// cdf at the nodes.
    c: Vec<f64>,
    mean: f64,
    std: f64,
}

impl Tabulated {
    /// `x`: strictly increasing nodes (at least 2), `f`: density values `>= 0` (any scale).
    ///
    /// # Errors
    /// If the lengths differ, the nodes are not increasing, a value is negative or the total
    /// mass is zero.
    pub fn new(x: Vec<f64>, f: Vec<f64>) -> Result<Self> {
        let what = "tabulated law";
        crate::error::check_len(what, "pdf values", x.len(), f.len())?;
        if x.len() < 2 {
            return Err(UqError::Invalid {
                what,
                message: "needs at least 2 nodes".into(),
            });
        }
        for i in 0..x.len() {
            if !x[i].is_finite() {
                return Err(invalid(what, "x", "finite", x[i]));
            }
            if i > 0 && x[i] <= x[i - 1] {
                return Err(invalid(what, "x", "strictly increasing", x[i]));
            }
            if !(f[i].is_finite() && f[i] >= 0.0) {
                return Err(invalid(what, "pdf value", ">= 0", f[i]));
            }
        }
        let mut c = vec![0.0; x.len()];
        for i in 1..x.len() {
            c[i] = c[i - 1] + 0.5 * (f[i] + f[i - 1]) * (x[i] - x[i - 1]);
        }
        let total = c[x.len() - 1];
        if !(total > 0.0) {
            return Err(UqError::Invalid {
                what,
                message: "density has zero mass".into(),
            });
        }
        let f: Vec<f64> = f.iter().map(|v| v / total).collect();
        for v in &mut c {
            *v /= total;
        }
        let (mut m1, mut m2) = (0.0, 0.0);
        for i in 1..x.len() {
            let (a, b) = (x[i - 1], x[i]);
            let m = 0.5 * (a + b);
            let fm = 0.5 * (f[i - 1] + f[i]);
            let h = (b - a) / 6.0;
            m1 += h * (a * f[i - 1] + 4.0 * m * fm + b * f[i]);
            m2 += h * (a * a * f[i - 1] + 4.0 * m * m * fm + b * b * f[i]);
        }
        let std = (m2 - m1 * m1).max(0.0).sqrt();
        Ok(Self {
            x,
            f,
            c,
            mean: m1,
            std,
        })
    }

    fn segment(&self, x: f64) -> usize {
        // index i with x in [x_i, x_{i+1}]
        match self.x.partition_point(|&v| v <= x) {
            0 => 0,
            k => (k - 1).min(self.x.len() - 2),
        }
    }
}

impl Marginal for Tabulated {
    fn name(&self) -> &'static str {
        "tabulated law"
    }
    fn pdf(&self, x: f64) -> f64 {
        let n = self.x.len();
        if x < self.x[0] || x > self.x[n - 1] {
            return 0.0;
        }
        let i = self.segment(x);
        let t = (x - self.x[i]) / (self.x[i + 1] - self.x[i]);
        self.f[i] + t * (self.f[i + 1] - self.f[i])
    }
    fn cdf(&self, x: f64) -> f64 {
        let n = self.x.len();
        if x <= self.x[0] {
            return 0.0;
        }
        if x >= self.x[n - 1] {
            return 1.0;
        }
        let i = self.segment(x);
        let d = x - self.x[i];
        let slope = (self.f[i + 1] - self.f[i]) / (self.x[i + 1] - self.x[i]);
        (self.c[i] + self.f[i] * d + 0.5 * slope * d * d).clamp(0.0, 1.0)
    }
    fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        let n = self.x.len();
        let k = self.c.partition_point(|&v| v < p);
        let i = k.saturating_sub(1).min(n - 2);
        let r = p - self.c[i];
        let h = self.x[i + 1] - self.x[i];
        let slope = (self.f[i + 1] - self.f[i]) / h;
        // f_i d + slope d^2 / 2 = r, stable root.
        let d = if slope.abs() < 1e-14 * (self.f[i].abs() + 1.0) {
            if self.f[i] > 0.0 { r / self.f[i] } else { 0.0 }
        } else {
            let disc = (self.f[i] * self.f[i] + 2.0 * slope * r).max(0.0);
            2.0 * r / (self.f[i] + disc.sqrt()).max(f64::MIN_POSITIVE)
        };
        (self.x[i] + d).clamp(self.x[i], self.x[i + 1])
    }
    fn mean(&self) -> f64 {
        self.mean
    }
    fn std(&self) -> f64 {
        self.std
    }
    fn support(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }
}
