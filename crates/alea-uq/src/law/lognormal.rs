//! Log-normal law: `ln X ~ N(mu, sigma^2)`; `E[X] = exp(mu + sigma^2/2)`,
//! `Var[X] = (exp(sigma^2) - 1) exp(2 mu + sigma^2)`.

use super::Marginal;
use crate::error::{Result, invalid};
use crate::special::{norm_cdf, norm_pdf, norm_quantile, norm_sf};

/// Log-normal law with log-mean `mu` and log-std `sigma`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogNormal {
    mu: f64,
    sigma: f64,
}

impl LogNormal {
    /// # Errors
    /// If `mu` is not finite or `sigma <= 0`.
    pub fn new(mu: f64, sigma: f64) -> Result<Self> {
        if !mu.is_finite() {
            return Err(invalid("lognormal", "mu", "finite", mu));
        }
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(invalid("lognormal", "sigma", "> 0", sigma));
        }
        Ok(Self { mu, sigma })
    }

    /// The log-normal law with the given mean and standard deviation of `X`.
    ///
    /// # Errors
    /// If `mean <= 0` or `std <= 0`.
    pub fn from_mean_std(mean: f64, std: f64) -> Result<Self> {
        if !(mean.is_finite() && mean > 0.0) {
            return Err(invalid("lognormal", "mean", "> 0", mean));
        }
        if !(std.is_finite() && std > 0.0) {
            return Err(invalid("lognormal", "std", "> 0", std));
        }
        let s2 = (1.0 + (std / mean).powi(2)).ln();
        Self::new(mean.ln() - 0.5 * s2, s2.sqrt())
    }
}

impl Marginal for LogNormal {
    fn name(&self) -> &'static str {
        "lognormal"
    }
    fn pdf(&self, x: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else {
            norm_pdf((x.ln() - self.mu) / self.sigma) / (self.sigma * x)
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else {
            norm_cdf((x.ln() - self.mu) / self.sigma)
        }
    }
    fn sf(&self, x: f64) -> f64 {
        if x <= 0.0 {
            1.0
        } else {
            norm_sf((x.ln() - self.mu) / self.sigma)
        }
    }
    fn quantile_of_normal(&self, z: f64) -> f64 {
        (self.mu + self.sigma * z).exp()
    }
    fn quantile(&self, p: f64) -> f64 {
        (self.mu + self.sigma * norm_quantile(p)).exp()
    }
    fn mean(&self) -> f64 {
        (self.mu + 0.5 * self.sigma * self.sigma).exp()
    }
    fn std(&self) -> f64 {
        let s2 = self.sigma * self.sigma;
        ((s2.exp() - 1.0) * (2.0 * self.mu + s2).exp()).sqrt()
    }
    fn support(&self) -> (f64, f64) {
        (0.0, f64::INFINITY)
    }
}
