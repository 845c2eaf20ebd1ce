//! Gamma law: `f(x) = t^(k-1) exp(-t) / (Gamma(k) theta)`, `t = (x - loc)/theta`;
//! `E[X] = loc + k theta`, `Var[X] = k theta^2`. `k = 1` is the exponential law.

use super::{Marginal, PolyFamily};
use crate::error::{Result, invalid};
use crate::special::{inc_gamma_p, ln_gamma, quantile_ends, safeguarded_newton};

/// Gamma law with shape `k`, scale `theta` and location `loc`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gamma {
    k: f64,
    theta: f64,
    loc: f64,
    ln_gk: f64,
}

impl Gamma {
    /// # Errors
    /// If `k <= 0`, `theta <= 0` or `loc` is not finite.
    pub fn new(k: f64, theta: f64, loc: f64) -> Result<Self> {
        if !(k.is_finite() && k > 0.0) {
            return Err(invalid("gamma", "shape", "> 0", k));
        }
        if !(theta.is_finite() && theta > 0.0) {
            return Err(invalid("gamma", "scale", "> 0", theta));
        }
        if !loc.is_finite() {
            return Err(invalid("gamma", "loc", "finite", loc));
        }
        Ok(Self {
            k,
            theta,
            loc,
            ln_gk: ln_gamma(k),
        })
    }
}

impl Marginal for Gamma {
    fn name(&self) -> &'static str {
        "gamma"
    }
    fn pdf(&self, x: f64) -> f64 {
        let t = (x - self.loc) / self.theta;
        if t < 0.0 || (t == 0.0 && self.k != 1.0) {
            return if t == 0.0 && self.k < 1.0 {
                f64::INFINITY
            } else {
                0.0
            };
        }
        ((self.k - 1.0) * t.ln() - t - self.ln_gk).exp() / self.theta
    }
    fn cdf(&self, x: f64) -> f64 {
        inc_gamma_p(self.k, (x - self.loc) / self.theta)
    }
    fn quantile(&self, p: f64) -> f64 {
        if let Some(q) = quantile_ends(p, self.loc, f64::INFINITY) {
            return q;
        }
        // Bracket [0, hi] in the standard variable.
        let mut hi = self.k + 10.0 * self.k.sqrt() + 10.0;
        while inc_gamma_p(self.k, hi) < p {
            hi *= 2.0;
        }
        let k = self.k;
        let ln_gk = self.ln_gk;
        let t = safeguarded_newton(
            p,
            0.0,
            hi,
            k.min(hi),
            |t| inc_gamma_p(k, t),
            |t| {
                if t > 0.0 {
                    ((k - 1.0) * t.ln() - t - ln_gk).exp()
                } else {
                    0.0
                }
            },
        );
        self.loc + self.theta * t
    }
    fn mean(&self) -> f64 {
        self.loc + self.k * self.theta
    }
    fn std(&self) -> f64 {
        self.k.sqrt() * self.theta
    }
    fn support(&self) -> (f64, f64) {
        (self.loc, f64::INFINITY)
    }
    fn poly_family(&self) -> Option<PolyFamily> {
        Some(PolyFamily::Laguerre {
            shape: self.k,
            scale: self.theta,
            loc: self.loc,
        })
    }
}
