//! Beta law on `[a, b]`: `f(x) = t^(alpha-1) (1-t)^(beta-1) / (B(alpha, beta) (b - a))`,
//! `t = (x - a)/(b - a)`; `E[X] = a + (b - a) alpha/(alpha + beta)`,
//! `Var[X] = (b - a)^2 alpha beta / ((alpha + beta)^2 (alpha + beta + 1))`.

use super::{Marginal, PolyFamily};
use crate::error::{Result, invalid};
use crate::special::{inc_beta, inc_beta_inv, ln_gamma};

/// Beta law with shapes `alpha`, `beta` on `[a, b]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beta {
    alpha: f64,
    beta: f64,
    a: f64,
    b: f64,
    ln_b: f64,
}

impl Beta {
    /// # Errors
    /// If a shape is not `> 0` or `a >= b`.
    pub fn new(alpha: f64, beta: f64, a: f64, b: f64) -> Result<Self> {
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(invalid("beta", "alpha", "> 0", alpha));
        }
        if !(beta.is_finite() && beta > 0.0) {
            return Err(invalid("beta", "beta", "> 0", beta));
        }
        if !a.is_finite() {
            return Err(invalid("beta", "a", "finite", a));
        }
        if !(b.is_finite() && b > a) {
            return Err(invalid("beta", "b", "finite and > a", b));
        }
        let ln_b = ln_gamma(alpha) + ln_gamma(beta) - ln_gamma(alpha + beta);
        Ok(Self {
            alpha,
            beta,
            a,
            b,
            ln_b,
        })
    }
}

impl Marginal for Beta {
    fn name(&self) -> &'static str {
        "beta"
    }
    fn pdf(&self, x: f64) -> f64 {
        if x < self.a || x > self.b {
            return 0.0;
        }
        let t = (x - self.a) / (self.b - self.a);
        ((self.alpha - 1.0) * t.ln() + (self.beta - 1.0) * (1.0 - t).ln() - self.ln_b).exp()
            / (self.b - self.a)
    }
    fn cdf(&self, x: f64) -> f64 {
        inc_beta((x - self.a) / (self.b - self.a), self.alpha, self.beta)
    }
    fn quantile(&self, p: f64) -> f64 {
        self.a + (self.b - self.a) * inc_beta_inv(p, self.alpha, self.beta)
    }
    fn mean(&self) -> f64 {
        self.a + (self.b - self.a) * self.alpha / (self.alpha + self.beta)
    }
    fn std(&self) -> f64 {
        let s = self.alpha + self.beta;
        (self.b - self.a) * (self.alpha * self.beta / (s * s * (s + 1.0))).sqrt()
    }
    fn support(&self) -> (f64, f64) {
        (self.a, self.b)
    }
    fn poly_family(&self) -> Option<PolyFamily> {
        Some(PolyFamily::Jacobi {
            alpha: self.alpha,
            beta: self.beta,
            a: self.a,
            b: self.b,
        })
    }
}
