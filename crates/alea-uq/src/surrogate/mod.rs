//! Surrogates that are linear in the run data.
//!
//! A surrogate built on `K` runs at points `xi_k` with values `q_k` evaluates as
//!
//! ```text
//! q~(xi) = sum_{k=1}^{K} w_k(xi) q_k                                   (thesis (1.22))
//! ```
//!
//! The weights `w_k(xi)` depend only on the design and the basis, never on the values, so the
//! same weights interpolate a scalar quantity of interest, a whole field (each run's field array
//! multiplied by its weight) or the admissible fields of an error estimator.
//!
//! * [`PcSurrogate`]: polynomial chaos; regression `s = (Psi^T Psi)^-1 Psi^T S` (1.29) gives
//!   `w(xi) = psi(xi)^T (Psi^T Psi)^-1 Psi^T`, projection (1.27)-(1.28) gives
//!   `w_k(xi) = omega_k psi(xi)^T psi(xi_k)`.
//! * [`MonomialSurface`]: standard polynomial response surface (monomials, least squares).
//! * [`StochasticMesh`]: piecewise multilinear interpolation on an adaptive mesh of the
//!   parameter box (the thesis's stochastic finite elements), with hanging nodes.

mod lars;
mod monomial;
mod multilinear;
mod pc;
mod saved;

pub use lars::{LARS_MAXIMUM_ERROR, LARS_SMALL_BASIS, LarsOptions, LarsReport};
pub use monomial::MonomialSurface;
pub use multilinear::{CellId, MAX_DIM, MAX_LEVEL, NewRun, ParentLevel, StochasticMesh};
pub use pc::corrected_loo_factor;
pub use pc::{PcExpansion, PcMethod, PcSurrogate};
pub use saved::RunData;

/// A surrogate `q~(xi) = sum_k w_k(xi) q_k` over `num_runs()` runs.
///
/// # Panics
/// `eval` and `eval_field` index the value arrays by run: they panic if `values` holds fewer than
/// `num_runs()` entries (rows); `xi` must have `dim()` entries.
pub trait LinearSurrogate: Send + Sync {
    /// Number of parameters.
    fn dim(&self) -> usize;
    /// Number of runs `K` (length of the value arrays).
    fn num_runs(&self) -> usize;
    /// Non-zero weights at `xi`: clears `w` and pushes `(run index, w_k(xi))` pairs, each run
    /// at most once.
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>);
    /// `sum_k w_k(xi) values[k]` for one scalar per run.
    fn eval(&self, xi: &[f64], values: &[f64]) -> f64 {
        let mut w = Vec::new();
        self.weights(xi, &mut w);
        w.iter().map(|&(k, wk)| wk * values[k]).sum()
    }
    /// Interpolate fields: `values` is row-major `num_runs() x out.len()` (run `k`'s field is
    /// `values[k * m .. (k + 1) * m]`), `out = sum_k w_k(xi) field_k`.
    fn eval_field(&self, xi: &[f64], values: &[f64], out: &mut [f64]) {
        let m = out.len();
        out.fill(0.0);
        let mut w = Vec::new();
        self.weights(xi, &mut w);
        for &(k, wk) in &w {
            for (o, v) in out.iter_mut().zip(&values[k * m..(k + 1) * m]) {
                *o += wk * v;
            }
        }
    }
}
