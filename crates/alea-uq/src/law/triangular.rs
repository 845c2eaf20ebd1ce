//! Triangular law on `[a, b]` with mode `c`: `E[X] = (a + b + c)/3`,
//! `Var[X] = (a^2 + b^2 + c^2 - ab - ac - bc)/18`.

use super::Marginal;
use crate::error::{Result, invalid};

/// Triangular law `(a, c, b)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangular {
    a: f64,
    c: f64,
    b: f64,
}

impl Triangular {
    /// Lower bound `a`, mode `c`, upper bound `b`.
    ///
    /// # Errors
    /// Unless `a <= c <= b` and `a < b` (all finite).
    pub fn new(a: f64, c: f64, b: f64) -> Result<Self> {
        if !a.is_finite() {
            return Err(invalid("triangular", "a", "finite", a));
        }
        if !(b.is_finite() && b > a) {
            return Err(invalid("triangular", "b", "finite and > a", b));
        }
        if !(c >= a && c <= b) {
            return Err(invalid("triangular", "mode", "in [a, b]", c));
        }
        Ok(Self { a, c, b })
    }
}

impl Marginal for Triangular {
    fn name(&self) -> &'static str {
        "triangular"
    }
    fn pdf(&self, x: f64) -> f64 {
        let (a, b, c) = (self.a, self.b, self.c);
        if x < a || x > b {
            0.0
        } else if x < c {
            2.0 * (x - a) / ((b - a) * (c - a))
        } else if x > c {
            2.0 * (b - x) / ((b - a) * (b - c))
        } else {
            2.0 / (b - a)
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        let (a, b, c) = (self.a, self.b, self.c);
        if x <= a {
            0.0
        } else if x >= b {
            1.0
        } else if x <= c {
            (x - a) * (x - a) / ((b - a) * (c - a))
        } else {
            1.0 - (b - x) * (b - x) / ((b - a) * (b - c))
        }
    }
    fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        let (a, b, c) = (self.a, self.b, self.c);
        let pc = (c - a) / (b - a);
        if p <= pc {
            a + (p * (b - a) * (c - a)).sqrt()
        } else {
            b - ((1.0 - p) * (b - a) * (b - c)).sqrt()
        }
    }
    fn mean(&self) -> f64 {
        (self.a + self.b + self.c) / 3.0
    }
    fn std(&self) -> f64 {
        let (a, b, c) = (self.a, self.b, self.c);
        ((a * a + b * b + c * c - a * b - a * c - b * c) / 18.0).sqrt()
    }
    fn support(&self) -> (f64, f64) {
        (self.a, self.b)
    }
}
