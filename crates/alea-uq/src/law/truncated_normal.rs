//! Truncated normal law: `N(mu, sigma^2)` conditioned on `[lo, hi]` (the thesis's law).
//!
//! With `alpha = (lo - mu)/sigma`, `beta = (hi - mu)/sigma`, `Z = Phi(beta) - Phi(alpha)`:
//! `f(x) = phi((x - mu)/sigma) / (sigma Z)` on `[lo, hi]`,
//! `E[X] = mu + sigma (phi(alpha) - phi(beta)) / Z`,
//! `Var[X] = sigma^2 [1 + (alpha phi(alpha) - beta phi(beta))/Z - ((phi(alpha) - phi(beta))/Z)^2]`.
//! When the interval lies in the upper tail (`alpha > 0`) the cdf and quantile are computed from
//! survival functions to keep full relative accuracy.

use super::Marginal;
use crate::error::{Result, UqError, invalid};
use crate::special::{norm_cdf, norm_pdf, norm_quantile, norm_sf};

/// Normal law `N(mu, sigma^2)` truncated to `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruncatedNormal {
    mu: f64,
    sigma: f64,
    lo: f64,
    hi: f64,
    alpha: f64,
    beta: f64,
    /// Mass of the interval under the parent normal.
    z: f64,
    /// Work in the upper tail (survival functions).
    upper: bool,
}

impl TruncatedNormal {
    /// `mu`, `sigma` are the parameters of the parent normal; `lo`/`hi` may be infinite.
    ///
    /// # Errors
    /// If `sigma <= 0`, `lo >= hi` or the interval has (numerically) zero mass.
    pub fn new(mu: f64, sigma: f64, lo: f64, hi: f64) -> Result<Self> {
        let what = "truncated normal";
        if !mu.is_finite() {
            return Err(invalid(what, "mean", "finite", mu));
        }
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(invalid(what, "std", "> 0", sigma));
        }
        if lo.is_nan() || lo == f64::INFINITY {
            return Err(invalid(what, "lo", "< +inf", lo));
        }
        if hi.is_nan() || hi <= lo {
            return Err(invalid(what, "hi", "> lo", hi));
        }
        let alpha = (lo - mu) / sigma;
        let beta = (hi - mu) / sigma;
        let upper = alpha > 0.0;
        let z = if upper {
            norm_sf(alpha) - norm_sf(beta)
        } else {
            norm_cdf(beta) - norm_cdf(alpha)
        };
        if !(z > 1e-300) {
            return Err(UqError::Invalid {
                what,
                message: format!("empty truncation: [{lo}, {hi}] has zero probability"),
            });
        }
        Ok(Self {
            mu,
            sigma,
            lo,
            hi,
            alpha,
            beta,
            z,
            upper,
        })
    }

    fn phi_at(t: f64) -> f64 {
        if t.is_finite() { norm_pdf(t) } else { 0.0 }
    }
    fn t_phi_at(t: f64) -> f64 {
        if t.is_finite() { t * norm_pdf(t) } else { 0.0 }
    }
}

impl Marginal for TruncatedNormal {
    fn name(&self) -> &'static str {
        "truncated normal"
    }
    fn pdf(&self, x: f64) -> f64 {
        if x < self.lo || x > self.hi {
            0.0
        } else {
            norm_pdf((x - self.mu) / self.sigma) / (self.sigma * self.z)
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        if x <= self.lo {
            return 0.0;
        }
        if x >= self.hi {
            return 1.0;
        }
        let t = (x - self.mu) / self.sigma;
        let v = if self.upper {
            (norm_sf(self.alpha) - norm_sf(t)) / self.z
        } else {
            (norm_cdf(t) - norm_cdf(self.alpha)) / self.z
        };
        v.clamp(0.0, 1.0)
    }
    fn quantile(&self, p: f64) -> f64 {
        if !(0.0..=1.0).contains(&p) {
            return f64::NAN;
        }
        let t = if self.upper {
            // sf(t) = sf(alpha) - p Z
            -norm_quantile((norm_sf(self.alpha) - p * self.z).clamp(0.0, 1.0))
        } else {
            norm_quantile((norm_cdf(self.alpha) + p * self.z).clamp(0.0, 1.0))
        };
        (self.mu + self.sigma * t).clamp(self.lo, self.hi)
    }
    fn mean(&self) -> f64 {
        self.mu + self.sigma * (Self::phi_at(self.alpha) - Self::phi_at(self.beta)) / self.z
    }
    fn std(&self) -> f64 {
        let d = (Self::phi_at(self.alpha) - Self::phi_at(self.beta)) / self.z;
        let v = 1.0 + (Self::t_phi_at(self.alpha) - Self::t_phi_at(self.beta)) / self.z - d * d;
        self.sigma * v.max(0.0).sqrt()
    }
    fn support(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }
}
