//! Marginal (one-dimensional) laws.
//!
//! Every law implements [`Marginal`]: density `pdf`, distribution function `cdf`, its inverse
//! `quantile`, the first two moments and sampling by inversion, `x = quantile(U)`, `U ~ U(0, 1)`.
//! Constructors validate their parameters and return [`UqError`](crate::UqError) naming the law and
//! the field.
//!
//! | law | parameters | orthonormal family |
//! |---|---|---|
//! | [`Uniform`] | `a < b` | Legendre |
//! | [`Normal`] | `mean`, `std > 0` | Hermite |
//! | [`TruncatedNormal`] | `mean`, `std > 0`, `lo < hi` (may be infinite) | generated (Stieltjes) |
//! | [`LogNormal`] | `mu`, `sigma > 0` of `ln X` | generated |
//! | [`Beta`] | `alpha, beta > 0` on `[a, b]` | Jacobi |
//! | [`Gamma`] | shape `k > 0`, scale `theta > 0`, location | Laguerre |
//! | [`Triangular`] | `a <= c <= b`, `a < b` | generated |
//! | [`Tabulated`] | nodes `x_i` and pdf values `f_i >= 0` (piecewise linear) | generated |
//! | [`Empirical`] | data (linearly interpolated empirical cdf) | generated |
//! | [`KdeLaw`] | a [`Kde`](crate::kde::Kde) (Gaussian mixture) | generated |

mod beta;
mod empirical;
mod gamma;
mod lognormal;
mod normal;
mod tabulated;
mod triangular;
mod truncated_normal;
mod uniform;

pub use beta::Beta;
pub use empirical::{Empirical, KdeLaw};
pub use gamma::Gamma;
pub use lognormal::LogNormal;
pub use normal::Normal;
pub use tabulated::Tabulated;
pub use triangular::Triangular;
pub use truncated_normal::TruncatedNormal;
pub use uniform::Uniform;

use rand::RngCore;

/// Classical orthogonal polynomial family attached to a law, with the affine map from the
/// physical variable `x` to the standard variable `t` of the family.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PolyFamily {
    /// Probabilists' Hermite polynomials, `t = (x - mean) / std`, `t ~ N(0, 1)`.
    Hermite {
        /// Mean of the law.
        mean: f64,
        /// Standard deviation of the law.
        std: f64,
    },
    /// Legendre polynomials, `t = (2x - a - b) / (b - a)`, `t ~ U(-1, 1)`.
    Legendre {
        /// Lower bound.
        a: f64,
        /// Upper bound.
        b: f64,
    },
    /// Jacobi polynomials for the weight `(1 - t)^(beta - 1) (1 + t)^(alpha - 1)` on `[-1, 1]`,
    /// `t = (2x - a - b) / (b - a)`.
    Jacobi {
        /// First shape parameter of the beta law.
        alpha: f64,
        /// Second shape parameter of the beta law.
        beta: f64,
        /// Lower bound.
        a: f64,
        /// Upper bound.
        b: f64,
    },
    /// Generalised Laguerre polynomials for the weight `t^(k - 1) exp(-t)`, `t = (x - loc)/scale`.
    Laguerre {
        /// Shape `k` of the gamma law.
        shape: f64,
        /// Scale of the gamma law.
        scale: f64,
        /// Location of the gamma law.
        loc: f64,
    },
}

/// Where the standard normal variable's map to a law saturates when `Phi` rounds to 0 or 1
/// ([`Marginal::quantile_of_normal`]): `Phi(8.2) = 1 - 1.2e-16`.
pub const Z_TAIL: f64 = 8.2;

/// A one-dimensional probability law.
pub trait Marginal: Send + Sync + std::fmt::Debug {
    /// Short name used in messages, e.g. `"truncated normal"`.
    fn name(&self) -> &'static str;
    /// Probability density at `x` (0 outside the support).
    fn pdf(&self, x: f64) -> f64;
    /// Distribution function `P(X <= x)`.
    fn cdf(&self, x: f64) -> f64;
    /// Inverse distribution function on `[0, 1]`; NaN for `p` outside `[0, 1]`.
    fn quantile(&self, p: f64) -> f64;
    /// Expectation.
    fn mean(&self) -> f64;
    /// Standard deviation.
    fn std(&self) -> f64;
    /// Closed support `[lo, hi]` (bounds may be infinite).
    fn support(&self) -> (f64, f64);
    /// Survival function `P(X > x)`; override where `1 - cdf` loses accuracy.
    fn sf(&self, x: f64) -> f64 {
        1.0 - self.cdf(x)
    }
    /// The quantile at `Phi(z)`: the map of a standard normal variable `z` to this law
    /// (`F^-1(Phi(z))`, the isoprobabilistic transform of FORM, SORM and importance sampling).
    /// Beyond `z = 8.29`, `Phi(z)` rounds to 1 and the quantile of a law unbounded above would
    /// be infinite: there it saturates at the quantile of `Phi(+-Z_TAIL)` ([`Z_TAIL`] = 8.2,
    /// probability 1.2e-16 beyond), so the transform is finite and non-decreasing everywhere.
    /// The normal and lognormal laws override it with their exact maps.
    fn quantile_of_normal(&self, z: f64) -> f64 {
        let x = self.quantile(crate::special::norm_cdf(z));
        if x.is_finite() || z.is_nan() {
            return x;
        }
        self.quantile(crate::special::norm_cdf(z.clamp(-Z_TAIL, Z_TAIL)))
    }
    /// Probability of `[a, b]`.
    fn interval_probability(&self, a: f64, b: f64) -> f64 {
        if b <= a {
            0.0
        } else {
            (self.cdf(b) - self.cdf(a)).max(0.0)
        }
    }
    /// One draw by inversion.
    fn sample(&self, rng: &mut dyn RngCore) -> f64 {
        self.quantile(crate::rng::open01(rng))
    }
    /// Classical orthogonal polynomial family, if any (else the basis is generated numerically).
    fn poly_family(&self) -> Option<PolyFamily> {
        None
    }
}
