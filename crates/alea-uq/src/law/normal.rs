//! Normal law `N(mean, std^2)`: `f(x) = phi((x - mean)/std)/std`, `F(x) = Phi((x - mean)/std)`.

use super::{Marginal, PolyFamily};
use crate::error::{Result, invalid};
use crate::special::{norm_cdf, norm_pdf, norm_quantile, norm_sf};

/// Normal (Gaussian) law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normal {
    mean: f64,
    std: f64,
}

impl Normal {
    /// # Errors
    /// If `mean` is not finite or `std <= 0`.
    pub fn new(mean: f64, std: f64) -> Result<Self> {
        if !mean.is_finite() {
            return Err(invalid("normal", "mean", "finite", mean));
        }
        if !(std.is_finite() && std > 0.0) {
            return Err(invalid("normal", "std", "> 0", std));
        }
        Ok(Self { mean, std })
    }

    /// The standard normal law `N(0, 1)`.
    pub fn standard() -> Self {
        Self {
            mean: 0.0,
            std: 1.0,
        }
    }
}

impl Marginal for Normal {
    fn name(&self) -> &'static str {
        "normal"
    }
    fn pdf(&self, x: f64) -> f64 {
        norm_pdf((x - self.mean) / self.std) / self.std
    }
    fn cdf(&self, x: f64) -> f64 {
        norm_cdf((x - self.mean) / self.std)
    }
    fn sf(&self, x: f64) -> f64 {
        norm_sf((x - self.mean) / self.std)
    }
    fn quantile(&self, p: f64) -> f64 {
        self.mean + self.std * norm_quantile(p)
    }
    fn quantile_of_normal(&self, z: f64) -> f64 {
        self.mean + self.std * z
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
    fn poly_family(&self) -> Option<PolyFamily> {
        Some(PolyFamily::Hermite {
            mean: self.mean,
            std: self.std,
        })
    }
}
