//! Stationary covariance models of a random field.
//!
//! With the (anisotropic) scaled distance `r = sqrt(sum_d ((x_d - y_d) / l_d)^2)`, variance
//! `sigma^2` and correlation lengths `l_d`, the kernels are
//!
//! * squared-exponential: `k(r) = sigma^2 exp(-r^2 / 2)`;
//! * exponential (Matern nu = 1/2): `k(r) = sigma^2 exp(-r)`;
//! * Matern nu = 3/2: `k(r) = sigma^2 (1 + sqrt(3) r) exp(-sqrt(3) r)`;
//! * Matern nu = 5/2: `k(r) = sigma^2 (1 + sqrt(5) r + 5 r^2 / 3) exp(-sqrt(5) r)`.
//!
//! These are the closed forms of OpenTURNS's `SquaredExponential`, `ExponentialModel` and
//! `MaternModel` with the same scale parameters, so a length here is a length there.

use crate::error::{Result, UqError, invalid};

/// Shape of a stationary covariance kernel (a function of the scaled distance `r`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelShape {
    /// `exp(-r^2 / 2)`.
    SquaredExponential,
    /// `exp(-r)`, the Matern kernel with nu = 1/2.
    Exponential,
    /// Matern nu = 3/2: `(1 + sqrt(3) r) exp(-sqrt(3) r)`.
    Matern32,
    /// Matern nu = 5/2: `(1 + sqrt(5) r + 5 r^2 / 3) exp(-sqrt(5) r)`.
    Matern52,
}

impl KernelShape {
    /// The correlation `rho(r)` at scaled distance `r >= 0` (`rho(0) = 1`).
    pub fn correlation(self, r: f64) -> f64 {
        match self {
            KernelShape::SquaredExponential => (-0.5 * r * r).exp(),
            KernelShape::Exponential => (-r).exp(),
            KernelShape::Matern32 => {
                let s = 3f64.sqrt() * r;
                (1.0 + s) * (-s).exp()
            }
            KernelShape::Matern52 => {
                let s = 5f64.sqrt() * r;
                (1.0 + s + s * s / 3.0) * (-s).exp()
            }
        }
    }

    /// The Matern kernel of smoothness `nu` in closed form: nu = 1/2, 3/2 or 5/2 (the squared
    /// exponential is the limit nu -> infinity, use [`KernelShape::SquaredExponential`]).
    pub fn matern(nu: f64) -> Result<Self> {
        if nu == 0.5 {
            Ok(KernelShape::Exponential)
        } else if nu == 1.5 {
            Ok(KernelShape::Matern32)
        } else if nu == 2.5 {
            Ok(KernelShape::Matern52)
        } else {
            Err(invalid("Matern covariance", "nu", "0.5, 1.5 or 2.5", nu))
        }
    }
}

/// A stationary covariance `k(x, y) = sigma^2 rho(r(x, y))` over points of dimension up to 3.
#[derive(Debug, Clone, PartialEq)]
pub struct Covariance {
    shape: KernelShape,
    variance: f64,
    inv_lengths: [f64; 3],
}

impl Covariance {
    /// Isotropic covariance with the given variance `sigma^2 > 0` and correlation length `l > 0`.
    pub fn new(shape: KernelShape, variance: f64, length: f64) -> Result<Self> {
        Self::anisotropic(shape, variance, &[length, length, length])
    }

    /// Anisotropic covariance: one correlation length per coordinate (1 to 3 of them; missing
    /// coordinates take the last length given).
    pub fn anisotropic(shape: KernelShape, variance: f64, lengths: &[f64]) -> Result<Self> {
        if !(variance.is_finite() && variance > 0.0) {
            return Err(invalid(
                "covariance",
                "variance",
                "finite and > 0",
                variance,
            ));
        }
        if lengths.is_empty() || lengths.len() > 3 {
            return Err(UqError::Invalid {
                what: "covariance",
                message: format!("1 to 3 correlation lengths expected, got {}", lengths.len()),
            });
        }
        let mut inv_lengths = [0.0; 3];
        for (d, il) in inv_lengths.iter_mut().enumerate() {
            let l = lengths[d.min(lengths.len() - 1)];
            if !(l.is_finite() && l > 0.0) {
                return Err(invalid(
                    "covariance",
                    "correlation length",
                    "finite and > 0",
                    l,
                ));
            }
            *il = 1.0 / l;
        }
        Ok(Self {
            shape,
            variance,
            inv_lengths,
        })
    }

    /// Kernel shape.
    pub fn shape(&self) -> KernelShape {
        self.shape
    }

    /// Point variance `sigma^2 = k(x, x)`.
    pub fn variance(&self) -> f64 {
        self.variance
    }

    /// Correlation lengths per coordinate.
    pub fn lengths(&self) -> [f64; 3] {
        self.inv_lengths.map(|il| 1.0 / il)
    }

    /// Scaled distance `r(x, y)`.
    #[inline]
    pub fn scaled_distance(&self, x: &[f64; 3], y: &[f64; 3]) -> f64 {
        let mut r2 = 0.0;
        for d in 0..3 {
            let t = (x[d] - y[d]) * self.inv_lengths[d];
            r2 += t * t;
        }
        r2.sqrt()
    }

    /// `k(x, y)`.
    #[inline]
    pub fn eval(&self, x: &[f64; 3], y: &[f64; 3]) -> f64 {
        self.variance * self.shape.correlation(self.scaled_distance(x, y))
    }
}
