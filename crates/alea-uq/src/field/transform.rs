//! Random fields built on a Karhunen-Loeve expansion: a Gaussian field and its pointwise
//! transforms.
//!
//! With `g(x) = m + sum_k sqrt(lambda_k) phi_k(x) xi_k` the Gaussian field (mean `m`, kernel
//! variance `sigma^2`):
//! * Gaussian: `u(x) = g(x)`;
//! * lognormal: `u(x) = exp(g(x))`; for a target mean `mu_u` and standard deviation `s_u` of
//!   `u`, take `sigma^2 = ln(1 + s_u^2 / mu_u^2)` and `m = ln(mu_u) - sigma^2 / 2`
//!   ([`lognormal_gaussian_parameters`]);
//! * bounded: `u(x) = a + (b - a) Phi((g(x) - m) / sigma)`, values in `(a, b)`, uniform marginals
//!   when the expansion keeps all the variance (the truncated field has a smaller variance, so
//!   its marginals are slightly concentrated towards the middle).

use super::kl::KlExpansion;
use crate::error::{Result, invalid};
use crate::special::norm_cdf;

/// Pointwise map from the Gaussian field to the field used by a model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FieldTransform {
    /// `u = g`.
    Gaussian,
    /// `u = exp(g)`.
    Lognormal,
    /// `u = a + (b - a) Phi((g - m) / sigma)`.
    Bounded {
        /// Lower bound `a`.
        lower: f64,
        /// Upper bound `b > a`.
        upper: f64,
    },
}

/// Mean `m` and variance `sigma^2` of the Gaussian field whose exponential has mean `mean > 0`
/// and standard deviation `std > 0`.
pub fn lognormal_gaussian_parameters(mean: f64, std: f64) -> Result<(f64, f64)> {
    if !(mean.is_finite() && mean > 0.0) {
        return Err(invalid("lognormal field", "mean", "finite and > 0", mean));
    }
    if !(std.is_finite() && std > 0.0) {
        return Err(invalid("lognormal field", "std", "finite and > 0", std));
    }
    let var = (1.0 + (std / mean).powi(2)).ln();
    Ok((mean.ln() - 0.5 * var, var))
}

/// A random field: mean of the Gaussian field, its KL expansion and a pointwise transform.
#[derive(Debug, Clone)]
pub struct RandomField {
    mean: f64,
    std: f64,
    transform: FieldTransform,
    kl: KlExpansion,
}

impl RandomField {
    /// A field `u = T(g)` with `g` of mean `mean` and expansion `kl`; `std` is the kernel's
    /// standard deviation `sigma` (used by the bounded transform).
    pub fn new(mean: f64, std: f64, transform: FieldTransform, kl: KlExpansion) -> Result<Self> {
        if !mean.is_finite() {
            return Err(invalid("random field", "mean", "finite", mean));
        }
        if !(std.is_finite() && std > 0.0) {
            return Err(invalid("random field", "std", "finite and > 0", std));
        }
        if let FieldTransform::Bounded { lower, upper } = transform
            && !(lower.is_finite() && upper.is_finite() && upper > lower)
        {
            return Err(invalid(
                "bounded random field",
                "upper - lower",
                "finite and > 0",
                upper - lower,
            ));
        }
        Ok(Self {
            mean,
            std,
            transform,
            kl,
        })
    }

    /// The KL expansion.
    pub fn kl(&self) -> &KlExpansion {
        &self.kl
    }

    /// Number of KL variables (independent standard normal parameters).
    pub fn num_variables(&self) -> usize {
        self.kl.num_modes()
    }

    /// The transform.
    pub fn transform(&self) -> FieldTransform {
        self.transform
    }

    /// The field at the nodes for KL variables `xi`.
    pub fn at_nodes(&self, xi: &[f64]) -> Result<Vec<f64>> {
        let mut g = vec![0.0; self.kl.mesh().num_nodes()];
        self.kl.realise(self.mean, xi, &mut g)?;
        match self.transform {
            FieldTransform::Gaussian => {}
            FieldTransform::Lognormal => {
                for v in &mut g {
                    *v = v.exp();
                    if !v.is_finite() {
                        return Err(invalid("lognormal random field", "exp(g)", "finite", *v));
                    }
                }
            }
            FieldTransform::Bounded { lower, upper } => {
                for v in &mut g {
                    *v = lower + (upper - lower) * norm_cdf((*v - self.mean) / self.std);
                }
            }
        }
        Ok(g)
    }
}
