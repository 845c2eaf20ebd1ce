//! Rare-event probabilities `P_f = P(g(X) <= 0)` for a model or a surrogate given as a
//! closure, in the independent standard normal space `u` of the joint law
//! (`x = T^-1(u)`, [`JointLaw::standard_normal_to_x`]; Nataf for the Gaussian copula,
//! `Phi` + Rosenblatt otherwise), `G(u) = g(T^-1(u))`.
//!
//! * [`form`]: first-order reliability method, design point `u* = argmin |u|` on `G(u) = 0` by
//!   the improved HL-RF iteration (Zhang & Der Kiureghian 1997, Armijo line search on
//!   `m(u) = |u|^2/2 + c |G(u)|`), `beta = |u*|`, `P_f ~ Phi(-beta)` (exact for a limit state
//!   linear in `u`);
//! * [`sorm`]: second order at the design point, principal curvatures `kappa_i` of the limit
//!   state from a finite-difference Hessian, Breitung (1984)
//!   `P_f ~ Phi(-beta) prod_i (1 + beta kappa_i)^-1/2` and Tvedt's (1990) three-term formula;
//! * [`importance_sampling`]: Monte Carlo with the density `N(u*, I)` centred at the design
//!   point, weights `phi(u)/phi(u - u*) = exp(-u.u* + |u*|^2/2)`, drawn in batches until a
//!   target coefficient of variation;
//! * [`subset_simulation`]: Au & Beck (2001) with intermediate thresholds at the `p0`
//!   quantile and conditional sampling by the preconditioned Crank-Nicolson random walk
//!   (`u' = rho u + sqrt(1 - rho^2) xi`, accepted if it stays in the current failure domain;
//!   it leaves `N(0, I)` invariant, Papaioannou et al. 2015), coefficient of variation from the
//!   chain correlations (Au & Beck, eq. (29)-(30));
//! * [`form_from_starts`]: FORM from several starting points ([`axis_starts`]: the median and
//!   `+-3` on every axis), every distinct design point, and a warning when several are close;
//! * [`propose_runs`]: goal-oriented placement of new runs of a linear surrogate near its limit state.
//!
//! Every estimate carries its interval: importance sampling the CLT interval
//! `P ± z sd / sqrt(N)`; subset simulation the log-normal interval
//! `P exp(± z delta)` with `delta` its coefficient of variation. FORM and SORM are asymptotic
//! approximations without a statistical interval: their error is the model's curvature, which
//! [`SormResult`] exposes. [`mc_equivalent_draws`] gives the Monte Carlo sample size
//! `(1 - P)/(P delta^2)` that would reach the same coefficient of variation.

mod form;
mod importance;
mod multistart;
mod refine;
mod subset;

pub use form::{FormOptions, FormResult, SormResult, breitung_tvedt, form, sorm, sorm_at};
pub use importance::{ImportanceOptions, importance_sampling};
pub use multistart::{MultiStart, axis_starts, form_from_starts};
pub use refine::{Proposal, RefineOptions, propose_runs};
pub use subset::{SubsetOptions, subset_simulation};

use crate::joint::JointLaw;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A boxed limit-state function of the physical variables.
type LimitFn<'a> = Box<dyn Fn(&[f64]) -> f64 + Sync + 'a>;

/// A limit state `g(x) <= 0` (failure) under a joint law, evaluated in the standard normal
/// space and counting its evaluations.
pub struct LimitState<'a> {
    law: &'a dyn JointLaw,
    g: LimitFn<'a>,
    calls: AtomicUsize,
}

impl std::fmt::Debug for LimitState<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LimitState")
            .field("dim", &self.law.dim())
            .field("calls", &self.calls())
            .finish()
    }
}

impl<'a> LimitState<'a> {
    /// Failure when `g(x) <= 0`.
    pub fn new(law: &'a dyn JointLaw, g: impl Fn(&[f64]) -> f64 + Sync + 'a) -> Self {
        Self {
            law,
            g: Box::new(g),
            calls: AtomicUsize::new(0),
        }
    }
    /// Failure when `q(x) > threshold` (`g = threshold - q`), the exceedance of a quantity of
    /// interest, e.g. `q = |x| surrogate.eval(x, &values)`.
    pub fn exceedance(
        law: &'a dyn JointLaw,
        q: impl Fn(&[f64]) -> f64 + Sync + 'a,
        threshold: f64,
    ) -> Self {
        Self::new(law, move |x| threshold - q(x))
    }
    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.law.dim()
    }
    /// The joint law.
    pub fn law(&self) -> &dyn JointLaw {
        self.law
    }
    /// `g(x)` in the physical space (counted).
    pub fn eval_x(&self, x: &[f64]) -> f64 {
        self.calls.fetch_add(1, Ordering::Relaxed);
        (self.g)(x)
    }
    /// `G(u) = g(T^-1(u))` (counted). A `NaN` never counts as a failure (`NaN <= 0` is
    /// false); FORM rejects non-finite values with an error.
    pub fn eval_u(&self, u: &[f64]) -> f64 {
        let mut buf = [0.0; 16];
        let mut heap;
        let x: &mut [f64] = if u.len() <= 16 {
            &mut buf[..u.len()]
        } else {
            heap = vec![0.0; u.len()];
            &mut heap
        };
        self.law.standard_normal_to_x(u, x);
        self.eval_x(x)
    }
    /// Number of evaluations of `g` so far.
    pub fn calls(&self) -> usize {
        self.calls.load(Ordering::Relaxed)
    }
}

/// A probability estimate with its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Estimated failure probability.
    pub p: f64,
    /// Lower bound of the confidence interval.
    pub lower: f64,
    /// Upper bound of the confidence interval.
    pub upper: f64,
    /// Coefficient of variation of the estimator.
    pub cov: f64,
    /// Evaluations of the limit state used.
    pub evaluations: usize,
    /// Confidence level of the interval.
    pub level: f64,
}

impl Estimate {
    /// Monte Carlo draws that would reach the same coefficient of variation at this `p`.
    pub fn mc_equivalent_draws(&self) -> f64 {
        mc_equivalent_draws(self.p, self.cov)
    }
}

/// Crude Monte Carlo sample size reaching coefficient of variation `cov` for probability `p`:
/// `N = (1 - p) / (p cov^2)`.
pub fn mc_equivalent_draws(p: f64, cov: f64) -> f64 {
    (1.0 - p) / (p * cov * cov)
}
