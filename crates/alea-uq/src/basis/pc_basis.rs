//! Tensor-product orthonormal basis `Psi_alpha(x) = prod_i p^(i)_{alpha_i}(x_i)` of a polynomial
//! chaos (thesis (1.22)) for independent inputs: `E[Psi_alpha Psi_beta] = delta_alpha,beta`.

use super::{MultiIndexSet, OrthoPoly};
use crate::error::{Result, check_len};
use crate::law::Marginal;
use std::sync::Arc;

/// Orthonormal polynomial chaos basis.
#[derive(Debug, Clone)]
pub struct PcBasis {
    polys: Vec<OrthoPoly>,
    set: MultiIndexSet,
    /// `max_degree(j) + 1` per variable.
    npow: Vec<usize>,
}

impl PcBasis {
    /// Basis of the multi-index `set` for independent `marginals` (one per variable).
    ///
    /// # Errors
    /// If the numbers of variables differ or polynomial generation fails.
    pub fn new(marginals: &[Arc<dyn Marginal>], set: MultiIndexSet) -> Result<Self> {
        check_len("PC basis", "marginals", set.dim(), marginals.len())?;
        let npow: Vec<usize> = (0..set.dim()).map(|j| set.max_degree(j) + 1).collect();
        let polys = marginals
            .iter()
            .zip(&npow)
            .map(|(m, &n)| OrthoPoly::for_marginal(m.as_ref(), n - 1))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self { polys, set, npow })
    }

    /// Rebuild a basis from its one-dimensional polynomials and multi-indices (as saved).
    ///
    /// # Errors
    /// If the numbers of variables differ or a polynomial's recurrence is shorter than the
    /// degrees used.
    pub fn from_parts(polys: Vec<OrthoPoly>, set: MultiIndexSet) -> Result<Self> {
        check_len("PC basis", "polynomials", set.dim(), polys.len())?;
        let npow: Vec<usize> = (0..set.dim()).map(|j| set.max_degree(j) + 1).collect();
        for (j, (p, &n)) in polys.iter().zip(&npow).enumerate() {
            if p.max_degree() + 1 < n {
                return Err(crate::UqError::Invalid {
                    what: "PC basis",
                    message: format!(
                        "polynomial {j} has degree {} but the indices need {}",
                        p.max_degree(),
                        n - 1
                    ),
                });
            }
        }
        Ok(Self { polys, set, npow })
    }

    /// Total-degree basis of degree `p`.
    ///
    /// # Errors
    /// As [`PcBasis::new`].
    pub fn total_degree(marginals: &[Arc<dyn Marginal>], p: usize) -> Result<Self> {
        Self::new(marginals, MultiIndexSet::total_degree(marginals.len(), p)?)
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.set.dim()
    }
    /// Number of basis functions `P + 1`.
    pub fn len(&self) -> usize {
        self.set.len()
    }
    /// `true` if the basis is empty.
    pub fn is_empty(&self) -> bool {
        self.set.is_empty()
    }
    /// The multi-index set.
    pub fn indices(&self) -> &MultiIndexSet {
        &self.set
    }
    /// The one-dimensional polynomials.
    pub fn polys(&self) -> &[OrthoPoly] {
        &self.polys
    }
    /// A basis on a subset of the indices (positions `keep`).
    pub fn subset(&self, keep: &[usize]) -> Self {
        Self {
            polys: self.polys.clone(),
            set: self.set.subset(keep),
            npow: self.npow.clone(),
        }
    }

    /// Values `Psi_alpha(x)` for all `alpha` into `out` (length `len()`).
    ///
    /// # Errors
    /// If `x` or `out` has the wrong length.
    pub fn eval(&self, x: &[f64], out: &mut [f64]) -> Result<()> {
        check_len("PC basis", "x", self.dim(), x.len())?;
        check_len("PC basis", "out", self.len(), out.len())?;
        let stride = self.npow.iter().copied().max().unwrap_or(1);
        let mut table = [0.0f64; 256];
        let mut heap;
        let tab: &mut [f64] = if stride * self.dim() <= 256 {
            &mut table[..stride * self.dim()]
        } else {
            heap = vec![0.0; stride * self.dim()];
            &mut heap
        };
        for j in 0..self.dim() {
            self.polys[j].eval_all(x[j], &mut tab[j * stride..j * stride + self.npow[j]]);
        }
        for (o, a) in out.iter_mut().zip(self.set.iter()) {
            let mut v = 1.0;
            for (j, &aj) in a.iter().enumerate() {
                v *= tab[j * stride + aj as usize];
            }
            *o = v;
        }
        Ok(())
    }

    /// Row-major `n x len()` matrix `Psi_ij = Psi_j(x_i)` of the points `points` (`n x dim`).
    ///
    /// # Errors
    /// If `points.len()` is not a multiple of `dim`.
    pub fn design_matrix(&self, points: &[f64]) -> Result<Vec<f64>> {
        let d = self.dim();
        if !points.len().is_multiple_of(d) {
            return Err(crate::UqError::Invalid {
                what: "PC basis",
                message: format!("points length {} is not a multiple of {d}", points.len()),
            });
        }
        let n = points.len() / d;
        let p = self.len();
        let mut psi = vec![0.0; n * p];
        for i in 0..n {
            self.eval(&points[i * d..(i + 1) * d], &mut psi[i * p..(i + 1) * p])?;
        }
        Ok(psi)
    }
}
