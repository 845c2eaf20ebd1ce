//! Uniform law on `[a, b]`: `f(x) = 1/(b - a)`, mean `(a + b)/2`, variance `(b - a)^2 / 12`.

use super::{Marginal, PolyFamily};
use crate::error::{Result, invalid};

/// Uniform law on `[a, b]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uniform {
    a: f64,
    b: f64,
}

impl Uniform {
    /// # Errors
    /// If a bound is not finite or `a >= b`.
    pub fn new(a: f64, b: f64) -> Result<Self> {
        if !a.is_finite() {
            return Err(invalid("uniform", "a", "finite", a));
        }
        if !(b.is_finite() && b > a) {
            return Err(invalid("uniform", "b", "finite and > a", b));
        }
        Ok(Self { a, b })
    }
}

impl Marginal for Uniform {
    fn name(&self) -> &'static str {
        "uniform"
    }
    fn pdf(&self, x: f64) -> f64 {
        if x >= self.a && x <= self.b {
            1.0 / (self.b - self.a)
        } else {
            0.0
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        ((x - self.a) / (self.b - self.a)).clamp(0.0, 1.0)
    }
    fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        self.a + p * (self.b - self.a)
    }
    fn mean(&self) -> f64 {
        0.5 * (self.a + self.b)
    }
    fn std(&self) -> f64 {
        (self.b - self.a) / 12f64.sqrt()
    }
    fn support(&self) -> (f64, f64) {
        (self.a, self.b)
    }
    fn poly_family(&self) -> Option<PolyFamily> {
        Some(PolyFamily::Legendre {
            a: self.a,
            b: self.b,
        })
    }
}
