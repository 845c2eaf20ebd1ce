//! Polynomial chaos surrogate (thesis 1.3; Sudret 2008).
//!
//! `q~(xi) = sum_{alpha in A} s_alpha Psi_alpha(xi)` (1.22) with an orthonormal basis
//! (`E[Psi_alpha Psi_beta] = delta`), `card A = P + 1 = (n + p)!/(n! p!)` for total degree `p`.
//! The coefficients are a linear map of the run values, `s = A q`:
//!
//! * **regression** (1.29): `s = (Psi^T Psi)^-1 Psi^T q`, `Psi_ki = Psi_i(xi_k)`, computed by
//!   Householder QR `Psi = Q R`, `A = R^-1 Q^T`. The condition number is estimated by
//!   `max|r_ii| / min|r_ii|` ([`PcSurrogate::condition_estimate`]);
//!   [`PcSurrogate::warnings`] reports ill-conditioning (> 1e8).
//! * **projection** (1.27)-(1.28): `s_alpha = E[q Psi_alpha] ~= sum_k omega_k q_k Psi_alpha(xi_k)`
//!   on a quadrature rule (tensor Gauss or Smolyak).
//!
//! Statistics from the coefficients: `E[q] = s_0`, `Var[q] = sum_{alpha != 0} s_alpha^2`,
//! first-order Sobol' index `S_i = sum_{alpha in A_i} s_alpha^2 / Var` with `A_i` the indices
//! whose only non-zero entry is `i`, total index `S_Ti = sum_{alpha_i > 0} s_alpha^2 / Var`.
//! Leave-one-out error (regression, Blatman & Sudret 2010):
//! `e_LOO = (1/K) sum_k ((q_k - q~(xi_k)) / (1 - h_k))^2 / Var_emp(q)` with `h_k` the diagonal of
//! the hat matrix `Psi A`, without refitting.
//! Corrected LOO (Chapelle et al. 2002, Blatman & Sudret 2011): `e*_LOO = T e_LOO`,
//! `T = K/(K - P) (1 + tr((Psi^T Psi)^-1))`, `tr((Psi^T Psi)^-1) = ||A||_F^2` since
//! `A A^T = R^-1 R^-T` ([`PcSurrogate::corrected_loo_error`]).
//! Sparse PC by least-angle regression: [`PcSurrogate::lars`] / [`PcSurrogate::lars_with`]
//! (hybrid LARS selected by the corrected LOO error, file `lars.rs`).

use super::LinearSurrogate;
use crate::basis::PcBasis;
use crate::error::{Result, UqError, check_len};
use crate::linalg::least_squares_projector;
use crate::quadrature::QuadratureRule;

/// How the coefficients were obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum PcMethod {
    /// Least squares on a design.
    Regression,
    /// Quadrature projection.
    Projection,
}

/// A PC surrogate: basis plus the linear map from run values to coefficients.
#[derive(Debug, Clone)]
pub struct PcSurrogate {
    pub(super) basis: PcBasis,
    /// `P x K` row-major.
    pub(super) a: Vec<f64>,
    pub(super) k: usize,
    pub(super) hat_diag: Option<Vec<f64>>,
    /// Design matrix (`K x P`, regression only), for fitted values in the LOO error.
    pub(super) psi: Option<Vec<f64>>,
    pub(super) cond: f64,
    pub(super) method: PcMethod,
    /// `tr((Psi^T Psi)^-1)` (regression only).
    pub(super) trace_inv_gram: f64,
}

impl PcSurrogate {
    /// Regression on the points `points` (row-major `K x dim`, `K >= P + 1`).
    ///
    /// # Errors
    /// If the sizes are inconsistent or the design matrix is rank deficient.
    pub fn regression(basis: PcBasis, points: &[f64]) -> Result<Self> {
        let d = basis.dim();
        let psi = basis.design_matrix(points)?;
        let k = points.len() / d;
        let proj = least_squares_projector("PC regression", &psi, k, basis.len())?;
        let trace_inv_gram = proj.a.iter().map(|v| v * v).sum();
        Ok(Self {
            basis,
            a: proj.a,
            k,
            hat_diag: Some(proj.hat_diag),
            psi: Some(psi),
            cond: proj.cond_estimate,
            method: PcMethod::Regression,
            trace_inv_gram,
        })
    }

    /// Projection on a quadrature rule whose nodes are the run points.
    ///
    /// # Errors
    /// If the rule's dimension differs from the basis.
    pub fn projection(basis: PcBasis, rule: &QuadratureRule) -> Result<Self> {
        check_len("PC projection", "rule dimension", basis.dim(), rule.dim())?;
        let p = basis.len();
        let k = rule.len();
        let mut a = vec![0.0; p * k];
        let mut psi = vec![0.0; p];
        for q in 0..k {
            basis.eval(rule.node(q), &mut psi)?;
            for i in 0..p {
                a[i * k + q] = rule.weights()[q] * psi[i];
            }
        }
        Ok(Self {
            basis,
            a,
            k,
            hat_diag: None,
            psi: None,
            cond: 1.0,
            method: PcMethod::Projection,
            trace_inv_gram: f64::NAN,
        })
    }

    /// The basis.
    pub fn basis(&self) -> &PcBasis {
        &self.basis
    }
    /// Regression or projection.
    pub fn method(&self) -> PcMethod {
        self.method
    }
    /// Lower bound of the condition number of the design matrix (1 for projection).
    pub fn condition_estimate(&self) -> f64 {
        self.cond
    }
    /// Human-readable warnings (ill-conditioning, few points per coefficient).
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        if self.cond > 1e8 {
            w.push(format!(
                "PC regression: design matrix is ill-conditioned (condition >= {:.1e})",
                self.cond
            ));
        }
        if self.method == PcMethod::Regression && self.k < 2 * self.basis.len() {
            w.push(format!(
                "PC regression: {} points for {} coefficients (at least twice as many advised)",
                self.k,
                self.basis.len()
            ));
        }
        w
    }

    /// Coefficients `s = A q`.
    ///
    /// # Errors
    /// If `values.len() != num_runs()`.
    pub fn coefficients(&self, values: &[f64]) -> Result<Vec<f64>> {
        check_len("PC surrogate", "values", self.k, values.len())?;
        Ok(self
            .a
            .chunks_exact(self.k)
            .map(|row| row.iter().zip(values).map(|(a, v)| a * v).sum())
            .collect())
    }

    /// Expansion (coefficients and statistics) for the given run values.
    ///
    /// # Errors
    /// If `values.len() != num_runs()`.
    pub fn expansion(&self, values: &[f64]) -> Result<PcExpansion> {
        Ok(PcExpansion {
            basis: self.basis.clone(),
            coeffs: self.coefficients(values)?,
        })
    }

    /// Expected weights `E[w_k] = A_0k` (orthonormality: only the constant term has a non-zero
    /// mean), so that `E[q~] = sum_k E[w_k] q_k`.
    pub fn expected_weights(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.k];
        for (a, row) in self.basis.indices().iter().zip(self.a.chunks_exact(self.k)) {
            if a.iter().all(|&v| v == 0) {
                for (o, r) in out.iter_mut().zip(row) {
                    *o += r;
                }
            }
        }
        out
    }

    /// Second moments of the weights, `M_kl = E[w_k w_l] = sum_alpha A_alpha,k A_alpha,l`,
    /// dense row-major `K x K`: `E[q~^2] = q^T M q`.
    pub fn weight_second_moments(&self) -> Vec<f64> {
        let k = self.k;
        let mut m = vec![0.0; k * k];
        for row in self.a.chunks_exact(k) {
            for i in 0..k {
                let ri = row[i];
                if ri == 0.0 {
                    continue;
                }
                for (mv, rj) in m[i * k..(i + 1) * k].iter_mut().zip(row) {
                    *mv += ri * rj;
                }
            }
        }
        m
    }

    /// Normalised leave-one-out error `e_LOO` (regression only).
    ///
    /// # Errors
    /// If `values.len() != num_runs()` or the surrogate was built by projection.
    pub fn loo_error(&self, values: &[f64]) -> Result<f64> {
        let (Some(h), Some(psi)) = (&self.hat_diag, &self.psi) else {
            return Err(UqError::Invalid {
                what: "PC surrogate",
                message: "leave-one-out error needs a regression surrogate".into(),
            });
        };
        let c = self.coefficients(values)?;
        let p = c.len();
        let mean = values.iter().sum::<f64>() / self.k as f64;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (self.k as f64 - 1.0);
        let mut s = 0.0;
        for i in 0..self.k {
            let fitted: f64 = psi[i * p..(i + 1) * p]
                .iter()
                .zip(&c)
                .map(|(a, b)| a * b)
                .sum();
            let r = (values[i] - fitted) / (1.0 - h[i]);
            s += r * r;
        }
        Ok(s / self.k as f64 / var)
    }

    /// Corrected leave-one-out error `T(P, K) e_LOO` (regression only), the error to report for
    /// a fit whose basis was chosen on the same data.
    ///
    /// # Errors
    /// As [`PcSurrogate::loo_error`].
    pub fn corrected_loo_error(&self, values: &[f64]) -> Result<f64> {
        let e = self.loo_error(values)?;
        Ok(e * corrected_loo_factor(self.k, self.basis.len(), self.trace_inv_gram))
    }
}

impl LinearSurrogate for PcSurrogate {
    fn dim(&self) -> usize {
        self.basis.dim()
    }
    fn num_runs(&self) -> usize {
        self.k
    }
    /// Dense weights `w(xi) = psi(xi)^T A` (all `K` runs).
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let mut psi = vec![0.0; self.basis.len()];
        if self.basis.eval(xi, &mut psi).is_err() {
            return;
        }
        let mut dense = vec![0.0; self.k];
        for (pi, row) in psi.iter().zip(self.a.chunks_exact(self.k)) {
            for (d, a) in dense.iter_mut().zip(row) {
                *d += pi * a;
            }
        }
        w.extend(dense.into_iter().enumerate());
    }
}

/// Coefficients of a PC expansion and the statistics they give.
#[derive(Debug, Clone)]
pub struct PcExpansion {
    basis: PcBasis,
    coeffs: Vec<f64>,
}

impl PcExpansion {
    /// Build from a basis and coefficients.
    ///
    /// # Errors
    /// If the lengths differ.
    pub fn new(basis: PcBasis, coeffs: Vec<f64>) -> Result<Self> {
        check_len("PC expansion", "coefficients", basis.len(), coeffs.len())?;
        Ok(Self { basis, coeffs })
    }
    /// Coefficients `s_alpha` in the order of the basis.
    pub fn coefficients(&self) -> &[f64] {
        &self.coeffs
    }
    /// The basis.
    pub fn basis(&self) -> &PcBasis {
        &self.basis
    }
    /// `E[q~] = s_0` (the constant term, wherever it sits in the basis).
    pub fn mean(&self) -> f64 {
        self.basis
            .indices()
            .iter()
            .zip(&self.coeffs)
            .filter(|(a, _)| a.iter().all(|&v| v == 0))
            .map(|(_, c)| c)
            .sum()
    }
    /// `sum s_alpha^2` over the multi-indices `alpha` that `keep` accepts.
    fn squares_where(&self, keep: impl Fn(&[u16]) -> bool) -> f64 {
        self.basis
            .indices()
            .iter()
            .zip(&self.coeffs)
            .filter(|(a, _)| keep(a))
            .map(|(_, c)| c * c)
            .sum()
    }
    /// `Var[q~] = sum_{alpha != 0} s_alpha^2`.
    pub fn variance(&self) -> f64 {
        self.squares_where(|a| a.iter().any(|&v| v != 0))
    }
    /// First-order Sobol' indices `S_i`.
    pub fn sobol_first(&self) -> Vec<f64> {
        let v = self.variance();
        (0..self.basis.dim())
            .map(|i| {
                self.squares_where(|a| {
                    a[i] > 0 && a.iter().enumerate().all(|(j, &x)| j == i || x == 0)
                }) / v
            })
            .collect()
    }
    /// Total Sobol' indices `S_Ti`.
    pub fn sobol_total(&self) -> Vec<f64> {
        let v = self.variance();
        (0..self.basis.dim())
            .map(|i| self.squares_where(|a| a[i] > 0) / v)
            .collect()
    }
    /// Sobol' index of the exact group of variables `vars` (interaction index):
    /// `S_u = sum_{alpha : supp(alpha) = u} s_alpha^2 / Var`, e.g. `sobol_index(&[0, 2])` is
    /// `S_13`. The indices of all groups sum to 1.
    pub fn sobol_index(&self, vars: &[usize]) -> f64 {
        let v = self.variance();
        let inside = self.group_mask(vars);
        if vars.is_empty() || vars.iter().any(|&i| i >= inside.len()) {
            return 0.0;
        }
        self.squares_where(|a| a.iter().enumerate().all(|(j, &x)| (x > 0) == inside[j])) / v
    }
    /// Closed Sobol' index of the group `vars`: `sum` of the indices of all its non-empty
    /// subgroups (`S_u^clo = sum_{alpha != 0 : supp(alpha) in u} s_alpha^2 / Var`).
    pub fn sobol_closed(&self, vars: &[usize]) -> f64 {
        let v = self.variance();
        let inside = self.group_mask(vars);
        self.squares_where(|a| {
            a.iter().any(|&x| x > 0) && a.iter().enumerate().all(|(j, &x)| x == 0 || inside[j])
        }) / v
    }
    /// `inside[j]`: variable `j` is in the group `vars` (out-of-range entries ignored).
    fn group_mask(&self, vars: &[usize]) -> Vec<bool> {
        let d = self.basis.dim();
        let mut inside = vec![false; d];
        for &i in vars {
            if i < d {
                inside[i] = true;
            }
        }
        inside
    }
    /// Second-order interaction indices `S_ij` (symmetric `d x d`, row-major, zero diagonal).
    pub fn sobol_second_order(&self) -> Vec<f64> {
        let d = self.basis.dim();
        let mut out = vec![0.0; d * d];
        for i in 0..d {
            for j in (i + 1)..d {
                let s = self.sobol_index(&[i, j]);
                out[i * d + j] = s;
                out[j * d + i] = s;
            }
        }
        out
    }
    /// Value of the expansion at `xi` (`NaN` if `xi` has the wrong length).
    pub fn eval(&self, xi: &[f64]) -> f64 {
        let mut psi = vec![0.0; self.basis.len()];
        if self.basis.eval(xi, &mut psi).is_err() {
            return f64::NAN;
        }
        psi.iter().zip(&self.coeffs).map(|(a, b)| a * b).sum()
    }
}

/// Chapelle / Blatman-Sudret correction `T(P, K) = K/(K - P) (1 + tr((Psi^T Psi)^-1))` of the
/// LOO error of a least-squares fit with `p` terms on `k` points (infinite for `p >= k`).
pub fn corrected_loo_factor(k: usize, p: usize, trace_inv_gram: f64) -> f64 {
    if p >= k {
        return f64::INFINITY;
    }
    k as f64 / (k - p) as f64 * (1.0 + trace_inv_gram)
}
