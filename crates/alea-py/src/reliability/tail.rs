//! The law of a reliability analysis, with its transform from the standard normal space kept
//! finite in the far upper tail.
//!
//! `alea_uq`'s laws map `u` to `x` through `x_i = F_i^-1(Phi(z_i))`. Beyond `z = 8.29`,
//! `Phi(z)` rounds to 1 and the quantile of an unbounded marginal is infinite; importance
//! sampling around a design point at `beta ~ 4.5` draws such points (about 1 in 10^4 draws),
//! so the model would be called at `x = inf`. Here a coordinate the transform sends to `+-inf`
//! is replaced by its marginal's quantile at `Phi(+-8.2)` (probability 1.2e-16 beyond it),
//! i.e. the transform saturates there; every finite coordinate is left as it is, so the
//! result is unchanged wherever the law's own transform is finite.

use std::sync::Arc;

use alea_uq::joint::JointLaw;
use alea_uq::law::Marginal;
use alea_uq::special::norm_cdf;

/// Largest `|z|` whose `Phi(z)` is below 1 with a margin (`Phi(8.2) = 1 - 1.2e-16`).
const Z_MAX: f64 = 8.2;

/// A joint law whose `standard_normal_to_x` never returns an infinite coordinate.
#[derive(Debug)]
pub struct TailSafe {
    inner: Arc<dyn JointLaw>,
    lo: Vec<f64>,
    hi: Vec<f64>,
}

impl TailSafe {
    /// Wraps `inner`, whose marginals are `marginals`.
    pub fn new(inner: Arc<dyn JointLaw>, marginals: &[Arc<dyn Marginal>]) -> Self {
        let lo = marginals
            .iter()
            .map(|m| m.quantile(norm_cdf(-Z_MAX)))
            .collect();
        let hi = marginals
            .iter()
            .map(|m| m.quantile(norm_cdf(Z_MAX)))
            .collect();
        Self { inner, lo, hi }
    }
}

impl JointLaw for TailSafe {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn pdf(&self, x: &[f64]) -> f64 {
        self.inner.pdf(x)
    }
    fn x_to_unit(&self, x: &[f64], u: &mut [f64]) {
        self.inner.x_to_unit(x, u);
    }
    fn unit_to_x(&self, u: &[f64], x: &mut [f64]) {
        self.inner.unit_to_x(u, x);
    }
    fn x_to_standard_normal(&self, x: &[f64], y: &mut [f64]) {
        self.inner.x_to_standard_normal(x, y);
    }
    fn standard_normal_to_x(&self, y: &[f64], x: &mut [f64]) {
        self.inner.standard_normal_to_x(y, x);
        for ((v, &lo), &hi) in x.iter_mut().zip(&self.lo).zip(&self.hi) {
            if *v == f64::INFINITY {
                *v = hi;
            } else if *v == f64::NEG_INFINITY {
                *v = lo;
            }
        }
    }
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        self.inner.bounds()
    }
    fn is_independent(&self) -> bool {
        self.inner.is_independent()
    }
    fn box_probability(&self, lo: &[f64], hi: &[f64]) -> f64 {
        self.inner.box_probability(lo, hi)
    }
}
