//! Standard polynomial response surface (thesis 1.3): monomials of total degree `<= p`,
//! `q~(x) = sum_alpha c_alpha prod_i t_i^alpha_i`, fitted by least squares, `c = (M^T M)^-1 M^T q`.
//! For conditioning the monomials are taken in the scaled variables `t_i = (x_i - m_i)/h_i`, with
//! `m_i`, `h_i` the centre and half-width of the design's bounding box.

use super::LinearSurrogate;
use crate::basis::MultiIndexSet;
use crate::error::{Result, UqError, check_len};
use crate::linalg::least_squares_projector;

/// Least-squares monomial response surface.
#[derive(Debug, Clone)]
pub struct MonomialSurface {
    set: MultiIndexSet,
    centre: Vec<f64>,
    half: Vec<f64>,
    /// `P x K` row-major projector.
    a: Vec<f64>,
    k: usize,
    cond: f64,
    /// Leverages (diagonal of the hat matrix).
    hat_diag: Vec<f64>,
    /// `tr((M^T M)^-1)`.
    trace_inv_gram: f64,
    /// Design matrix `K x P` (row-major), for the fitted values.
    design: Vec<f64>,
}

impl MonomialSurface {
    /// Fit the total-degree-`degree` monomial basis in `dim` variables on `points` (`K x dim`).
    ///
    /// # Errors
    /// If sizes are inconsistent or the system is rank deficient (too few / degenerate points).
    pub fn fit(dim: usize, degree: usize, points: &[f64]) -> Result<Self> {
        let set = MultiIndexSet::total_degree(dim, degree)?;
        if !points.len().is_multiple_of(dim) || points.is_empty() {
            return Err(UqError::Invalid {
                what: "monomial response surface",
                message: format!("points length {} is not a multiple of {dim}", points.len()),
            });
        }
        let k = points.len() / dim;
        let mut centre = vec![0.0; dim];
        let mut half = vec![0.0; dim];
        for j in 0..dim {
            let (lo, hi) = points
                .chunks_exact(dim)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                    (a.min(x[j]), b.max(x[j]))
                });
            centre[j] = 0.5 * (lo + hi);
            half[j] = if hi > lo { 0.5 * (hi - lo) } else { 1.0 };
        }
        let mut s = Self {
            set,
            centre,
            half,
            a: Vec::new(),
            k,
            cond: 1.0,
            hat_diag: Vec::new(),
            trace_inv_gram: 0.0,
            design: Vec::new(),
        };
        let p = s.set.len();
        let mut m = vec![0.0; k * p];
        for i in 0..k {
            s.monomials(&points[i * dim..(i + 1) * dim], &mut m[i * p..(i + 1) * p]);
        }
        let proj = least_squares_projector("monomial response surface", &m, k, p)?;
        s.trace_inv_gram = proj.a.iter().map(|v| v * v).sum();
        s.a = proj.a;
        s.cond = proj.cond_estimate;
        s.hat_diag = proj.hat_diag;
        s.design = m;
        Ok(s)
    }

    fn monomials(&self, x: &[f64], out: &mut [f64]) {
        for (o, a) in out.iter_mut().zip(self.set.iter()) {
            let mut v = 1.0;
            for (j, &aj) in a.iter().enumerate() {
                v *= ((x[j] - self.centre[j]) / self.half[j]).powi(aj as i32);
            }
            *o = v;
        }
    }

    /// Lower bound of the condition number of the scaled design matrix.
    pub fn condition_estimate(&self) -> f64 {
        self.cond
    }
    /// Multi-indices of the monomials.
    pub fn indices(&self) -> &MultiIndexSet {
        &self.set
    }

    /// Coefficients in the scaled variables.
    ///
    /// # Errors
    /// If `values.len() != num_runs()`.
    pub fn coefficients(&self, values: &[f64]) -> Result<Vec<f64>> {
        check_len("monomial response surface", "values", self.k, values.len())?;
        Ok(self
            .a
            .chunks_exact(self.k)
            .map(|r| r.iter().zip(values).map(|(a, b)| a * b).sum())
            .collect())
    }

    /// Normalised leave-one-out error `(1/K) sum ((q_k - q~(x_k)) / (1 - h_k))^2 / Var(q)`
    /// from the hat matrix (no refit), and the corrected one `T(P, K) e_LOO`
    /// ([`crate::surrogate::corrected_loo_factor`]).
    ///
    /// # Errors
    /// If `values.len() != num_runs()`, fewer than 2 runs, or a leverage is 1.
    pub fn loo_errors(&self, values: &[f64]) -> Result<(f64, f64)> {
        let what = "monomial response surface";
        check_len(what, "values", self.k, values.len())?;
        let p = self.set.len();
        let c = self.coefficients(values)?;
        let mean = values.iter().sum::<f64>() / self.k as f64;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (self.k as f64 - 1.0);
        let mut s = 0.0;
        for (k, (&h, &q)) in self.hat_diag.iter().zip(values).enumerate() {
            let d = 1.0 - h;
            if !(d > 1e-12) {
                return Err(UqError::Invalid {
                    what,
                    message: format!("run {k} has leverage 1: leave-one-out undefined"),
                });
            }
            let fitted: f64 = self.design[k * p..(k + 1) * p]
                .iter()
                .zip(&c)
                .map(|(a, b)| a * b)
                .sum();
            s += ((q - fitted) / d).powi(2);
        }
        let plain = s / self.k as f64 / var;
        Ok((
            plain,
            plain * super::corrected_loo_factor(self.k, p, self.trace_inv_gram),
        ))
    }

    /// Evaluate from coefficients (as returned by [`MonomialSurface::coefficients`]).
    pub fn eval_coefficients(&self, xi: &[f64], coeffs: &[f64]) -> f64 {
        let mut m = vec![0.0; self.set.len()];
        self.monomials(xi, &mut m);
        m.iter().zip(coeffs).map(|(a, b)| a * b).sum()
    }
}

impl LinearSurrogate for MonomialSurface {
    fn dim(&self) -> usize {
        self.set.dim()
    }
    fn num_runs(&self) -> usize {
        self.k
    }
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let mut m = vec![0.0; self.set.len()];
        self.monomials(xi, &mut m);
        let mut dense = vec![0.0; self.k];
        for (mi, row) in m.iter().zip(self.a.chunks_exact(self.k)) {
            for (d, a) in dense.iter_mut().zip(row) {
                *d += mi * a;
            }
        }
        w.extend(dense.into_iter().enumerate());
    }
}
