//! Benchmark functions with their exact statistics (for tests, examples and benchmarks).

use std::f64::consts::PI;

/// Ishigami function `f(x) = sin x1 + a sin^2 x2 + b x3^4 sin x1`, `x ~ U(-pi, pi)^3`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ishigami {
    /// Coefficient `a` (7 in the usual benchmark).
    pub a: f64,
    /// Coefficient `b` (0.1 in the usual benchmark).
    pub b: f64,
}

impl Default for Ishigami {
    fn default() -> Self {
        Self { a: 7.0, b: 0.1 }
    }
}

impl Ishigami {
    /// Value at `x` (length 3).
    pub fn eval(&self, x: &[f64]) -> f64 {
        x[0].sin() + self.a * x[1].sin().powi(2) + self.b * x[2].powi(4) * x[0].sin()
    }
    /// `E[f] = a / 2`.
    pub fn mean(&self) -> f64 {
        self.a / 2.0
    }
    /// `Var f = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2`.
    pub fn variance(&self) -> f64 {
        self.a.powi(2) / 8.0 + self.b * PI.powi(4) / 5.0 + self.b.powi(2) * PI.powi(8) / 18.0 + 0.5
    }
    /// First-order Sobol' indices `(V1, V2, V3) / Var`.
    pub fn sobol_first(&self) -> [f64; 3] {
        let v = self.variance();
        let v1 = 0.5 * (1.0 + self.b * PI.powi(4) / 5.0).powi(2);
        let v2 = self.a.powi(2) / 8.0;
        [v1 / v, v2 / v, 0.0]
    }
    /// Total Sobol' indices.
    pub fn sobol_total(&self) -> [f64; 3] {
        let v = self.variance();
        let v1 = 0.5 * (1.0 + self.b * PI.powi(4) / 5.0).powi(2);
        let v2 = self.a.powi(2) / 8.0;
        let v13 = self.b.powi(2) * PI.powi(8) * (1.0 / 18.0 - 1.0 / 50.0);
        [(v1 + v13) / v, v2 / v, v13 / v]
    }
}
