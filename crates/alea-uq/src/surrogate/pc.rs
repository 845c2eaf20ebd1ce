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
//! Sparse PC by least-angle regression: [`PcSurrogate::lars`] (hybrid LARS with LOO selection).

use super::LinearSurrogate;
use crate::basis::PcBasis;
use crate::error::{Result, UqError, check_len};
use crate::linalg::least_squares_projector;
use crate::quadrature::QuadratureRule;

/// How the coefficients were obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PcMethod {
    /// Least squares on a design.
    Regression,
    /// Quadrature projection.
    Projection,
}

/// A PC surrogate: basis plus the linear map from run values to coefficients.
#[derive(Debug, Clone)]
pub struct PcSurrogate {
    basis: PcBasis,
    /// `P x K` row-major.
    a: Vec<f64>,
    k: usize,
    hat_diag: Option<Vec<f64>>,
    /// Design matrix (`K x P`, regression only), for fitted values in the LOO error.
    psi: Option<Vec<f64>>,
    cond: f64,
    method: PcMethod,
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
        Ok(Self {
            basis,
            a: proj.a,
            k,
            hat_diag: Some(proj.hat_diag),
            psi: Some(psi),
            cond: proj.cond_estimate,
            method: PcMethod::Regression,
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
        })
    }

    /// Sparse PC by hybrid least-angle regression (Blatman & Sudret 2011): LARS orders the
    /// candidate basis functions of `basis` on the data `values`; for each step an OLS fit on the
    /// active set is scored by its LOO error and the best set is kept (at most `K - 1` terms).
    /// The returned surrogate is a regression on the selected basis, hence still linear in the
    /// data for this selection.
    ///
    /// # Errors
    /// As [`PcSurrogate::regression`].
    pub fn lars(basis: PcBasis, points: &[f64], values: &[f64]) -> Result<Self> {
        let psi = basis.design_matrix(points)?;
        let k = points.len() / basis.dim();
        check_len("PC LARS", "values", k, values.len())?;
        let order = lars_path(&psi, values, k, basis.len());
        let mut best: Option<(f64, Self)> = None;
        let mut active: Vec<usize> = vec![0];
        let mut steps = vec![active.clone()];
        for &j in &order {
            if j != 0 && !active.contains(&j) && active.len() + 1 < k {
                active.push(j);
                steps.push(active.clone());
            }
        }
        for s in steps {
            let mut keep = s.clone();
            keep.sort_unstable();
            let sub = basis.subset(&keep);
            if let Ok(sur) = Self::regression(sub, points) {
                let e = sur.loo_error(values)?;
                if best.as_ref().is_none_or(|(b, _)| e < *b) {
                    best = Some((e, sur));
                }
            }
        }
        best.map(|b| b.1).ok_or(UqError::Singular {
            what: "PC LARS",
            pivot: 0,
            size: basis.len(),
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
    /// `Var[q~] = sum_{alpha != 0} s_alpha^2`.
    pub fn variance(&self) -> f64 {
        self.basis
            .indices()
            .iter()
            .zip(&self.coeffs)
            .filter(|(a, _)| a.iter().any(|&v| v != 0))
            .map(|(_, c)| c * c)
            .sum()
    }
    /// First-order Sobol' indices `S_i`.
    pub fn sobol_first(&self) -> Vec<f64> {
        let v = self.variance();
        (0..self.basis.dim())
            .map(|i| {
                self.basis
                    .indices()
                    .iter()
                    .zip(&self.coeffs)
                    .filter(|(a, _)| {
                        a[i] > 0 && a.iter().enumerate().all(|(j, &x)| j == i || x == 0)
                    })
                    .map(|(_, c)| c * c)
                    .sum::<f64>()
                    / v
            })
            .collect()
    }
    /// Total Sobol' indices `S_Ti`.
    pub fn sobol_total(&self) -> Vec<f64> {
        let v = self.variance();
        (0..self.basis.dim())
            .map(|i| {
                self.basis
                    .indices()
                    .iter()
                    .zip(&self.coeffs)
                    .filter(|(a, _)| a[i] > 0)
                    .map(|(_, c)| c * c)
                    .sum::<f64>()
                    / v
            })
            .collect()
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

/// Order in which LARS activates the columns `1..p` of the `k x p` matrix `psi` (column 0, the
/// constant, is handled by centring). Efron et al. 2004, equiangular steps.
fn lars_path(psi: &[f64], y: &[f64], k: usize, p: usize) -> Vec<usize> {
    let ym = y.iter().sum::<f64>() / k as f64;
    let r0: Vec<f64> = y.iter().map(|v| v - ym).collect();
    // Centred, normalised columns (column-major).
    let mut x = vec![0.0; k * p];
    let mut usable = vec![false; p];
    for j in 1..p {
        let m = (0..k).map(|i| psi[i * p + j]).sum::<f64>() / k as f64;
        let col: Vec<f64> = (0..k).map(|i| psi[i * p + j] - m).collect();
        let n = col.iter().map(|v| v * v).sum::<f64>().sqrt();
        if n > 1e-12 {
            usable[j] = true;
            for i in 0..k {
                x[j * k + i] = col[i] / n;
            }
        }
    }
    let col = |j: usize| &x[j * k..(j + 1) * k];
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>();
    let mut mu = vec![0.0; k];
    let mut active: Vec<usize> = Vec::new();
    let max_steps = (p - 1).min(k.saturating_sub(2));
    while active.len() < max_steps {
        let r: Vec<f64> = r0.iter().zip(&mu).map(|(a, b)| a - b).collect();
        let c: Vec<f64> = (0..p)
            .map(|j| if usable[j] { dot(col(j), &r) } else { 0.0 })
            .collect();
        let next = (1..p)
            .filter(|j| usable[*j] && !active.contains(j))
            .max_by(|&a, &b| c[a].abs().total_cmp(&c[b].abs()));
        let Some(jn) = next else { break };
        if active.is_empty() || c[jn].abs() > 0.0 {
            active.push(jn);
        }
        let cmax = c[jn].abs();
        if cmax < 1e-14 {
            break;
        }
        let na = active.len();
        let s: Vec<f64> = active.iter().map(|&j| c[j].signum()).collect();
        let mut g = vec![0.0; na * na];
        for a in 0..na {
            for b in 0..na {
                g[a * na + b] = s[a] * s[b] * dot(col(active[a]), col(active[b]));
            }
        }
        let Ok(l) = crate::linalg::cholesky("LARS", &g, na) else {
            break;
        };
        // Solve G w = 1.
        let mut z = vec![0.0; na];
        for i in 0..na {
            let mut v = 1.0;
            for t in 0..i {
                v -= l[i * na + t] * z[t];
            }
            z[i] = v / l[i * na + i];
        }
        let mut w = vec![0.0; na];
        for i in (0..na).rev() {
            let mut v = z[i];
            for t in (i + 1)..na {
                v -= l[t * na + i] * w[t];
            }
            w[i] = v / l[i * na + i];
        }
        let aa = 1.0 / w.iter().sum::<f64>().sqrt();
        let mut u = vec![0.0; k];
        for (t, &j) in active.iter().enumerate() {
            for (ui, xi) in u.iter_mut().zip(col(j)) {
                *ui += aa * w[t] * s[t] * xi;
            }
        }
        let mut gamma = cmax / aa;
        for j in 1..p {
            if !usable[j] || active.contains(&j) {
                continue;
            }
            let aj = dot(col(j), &u);
            for cand in [(cmax - c[j]) / (aa - aj), (cmax + c[j]) / (aa + aj)] {
                if cand > 1e-14 && cand < gamma {
                    gamma = cand;
                }
            }
        }
        for (m, ui) in mu.iter_mut().zip(&u) {
            *m += gamma * ui;
        }
    }
    active
}
