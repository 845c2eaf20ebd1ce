//! Whether a design determines a least-squares surrogate: its information matrix.
//!
//! For a basis `psi(x) = (psi_1(x) .. psi_P(x))` evaluated at the `n` points of a design, the
//! regression matrix is `Psi_ki = psi_i(x_k)` (`n x P`) and the normalised information matrix
//! `M = Psi^T Psi / n` (for an orthonormal basis and points drawn from its law, `M -> I` as
//! `n -> inf`). The least-squares coefficients `s = (Psi^T Psi)^-1 Psi^T q` exist when `M` has
//! full rank, and an error `dq` in the run values moves them by up to
//! `|ds| <= sqrt(kappa / (n lambda_max)) |dq|`, `kappa = lambda_max / lambda_min` the condition
//! number of `M` (the same as that of `Psi^T Psi`, the square of that of `Psi`).
//!
//! [`information`] computes:
//! * the **rank** test: Cholesky `M = L L^T` without pivoting; the first `k` with
//!   `l_kk^2 <= 1e-12 M_kk` is a term whose values at the points are (numerically) a combination
//!   of those of the terms before it - [`UqError::Singular`] with `pivot = k`;
//! * `lambda_max` by the power iteration on `M` and `lambda_min` by inverse iteration (solves
//!   with `L`), from a fixed start vector, each until its Rayleigh quotient changes by less than
//!   `1e-10` relative (at most 1000 iterations). Both quotients lie in `[lambda_min, lambda_max]`,
//!   so [`Information::condition`] never exceeds `kappa` and converges to it.

use crate::error::{Result, UqError};
use crate::linalg::cholesky;

/// The information matrix of a design for a basis, reduced to what decides well-posedness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Information {
    /// Number of points `n`.
    pub points: usize,
    /// Number of basis functions `P`.
    pub terms: usize,
    /// Smallest eigenvalue of `M = Psi^T Psi / n`.
    pub lambda_min: f64,
    /// Largest eigenvalue of `M`.
    pub lambda_max: f64,
}

impl Information {
    /// Condition number `lambda_max / lambda_min` of `M` (equally of `Psi^T Psi`).
    pub fn condition(&self) -> f64 {
        self.lambda_max / self.lambda_min
    }
}

/// The information matrix of the row-major `n x terms` regression matrix `psi` (module doc).
///
/// # Errors
/// [`UqError::Invalid`] if `psi` does not hold `n` rows of `terms` values with
/// `n >= terms >= 1`; [`UqError::Singular`] (`pivot`: the first dependent term, `size`: `terms`)
/// if `M` is rank deficient.
pub fn information(psi: &[f64], n: usize, terms: usize) -> Result<Information> {
    if psi.len() != n * terms || terms == 0 || n < terms {
        return Err(UqError::Invalid {
            what: "information matrix",
            message: format!(
                "{} values do not form {n} >= {terms} rows of {terms} terms",
                psi.len()
            ),
        });
    }
    let m = gram(psi, n, terms);
    let l = cholesky("information matrix", &m, terms)?;
    for k in 0..terms {
        if l[k * terms + k].powi(2) <= 1e-12 * m[k * terms + k] {
            return Err(UqError::Singular {
                what: "information matrix",
                pivot: k,
                size: terms,
            });
        }
    }
    let lambda_max = rayleigh_limit(terms, |v, out| sym_mul(&m, terms, v, out));
    let lambda_min = rayleigh_limit(terms, |v, out| chol_solve(&l, terms, v, out));
    Ok(Information {
        points: n,
        terms,
        lambda_min: 1.0 / lambda_min,
        lambda_max,
    })
}

/// `Psi^T Psi / n`, row-major `terms x terms`.
fn gram(psi: &[f64], n: usize, terms: usize) -> Vec<f64> {
    let mut m = vec![0.0; terms * terms];
    for r in psi.chunks_exact(terms) {
        for i in 0..terms {
            for j in i..terms {
                m[i * terms + j] += r[i] * r[j];
            }
        }
    }
    for i in 0..terms {
        for j in i..terms {
            m[i * terms + j] /= n as f64;
            m[j * terms + i] = m[i * terms + j];
        }
    }
    m
}

fn sym_mul(m: &[f64], n: usize, v: &[f64], out: &mut [f64]) {
    for (i, o) in out.iter_mut().enumerate() {
        *o = m[i * n..(i + 1) * n]
            .iter()
            .zip(v)
            .map(|(a, b)| a * b)
            .sum();
    }
}

/// `out = (L L^T)^-1 v`.
fn chol_solve(l: &[f64], n: usize, v: &[f64], out: &mut [f64]) {
    for i in 0..n {
        let s: f64 = (0..i).map(|k| l[i * n + k] * out[k]).sum();
        out[i] = (v[i] - s) / l[i * n + i];
    }
    for i in (0..n).rev() {
        let s: f64 = ((i + 1)..n).map(|k| l[k * n + i] * out[k]).sum();
        out[i] = (out[i] - s) / l[i * n + i];
    }
}

/// Largest eigenvalue of the symmetric positive operator `apply` by the power iteration: the
/// Rayleigh quotient once it has settled.
fn rayleigh_limit(n: usize, apply: impl Fn(&[f64], &mut [f64])) -> f64 {
    // A fixed start with components of both signs and unequal sizes.
    let mut v: Vec<f64> = (0..n).map(|i| (1.3 * i as f64 + 0.7).sin() + 1.5).collect();
    let mut w = vec![0.0; n];
    let mut quotient = 0.0;
    for _ in 0..1000 {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter_mut().for_each(|x| *x /= norm);
        apply(&v, &mut w);
        let next: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
        let settled = (next - quotient).abs() <= 1e-10 * next.abs();
        quotient = next;
        std::mem::swap(&mut v, &mut w);
        if settled {
            break;
        }
    }
    quotient
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eigen::{JacobiStop, jacobi_sweeps};

    fn jacobi_extremes(psi: &[f64], n: usize, terms: usize) -> (f64, f64) {
        let mut m = gram(psi, n, terms);
        let stop = JacobiStop {
            max_sweeps: 100,
            skip_below: 0.0,
            converged: |a: &[f64]| {
                let off: f64 = (0..terms)
                    .flat_map(|i| (0..terms).filter(move |&j| j != i).map(move |j| (i, j)))
                    .map(|(i, j)| a[i * terms + j].powi(2))
                    .sum();
                off < 1e-30
            },
        };
        jacobi_sweeps(&mut m, None, terms, &stop);
        let diag: Vec<f64> = (0..terms).map(|i| m[i * terms + i]).collect();
        (
            diag.iter().copied().fold(f64::INFINITY, f64::min),
            diag.iter().copied().fold(0.0, f64::max),
        )
    }

    #[test]
    fn extremes_match_jacobi_eigenvalues() {
        // Monomials 1, x, x^2, x^3 on 9 points of [0, 2]: ill-conditioned but full rank.
        let xs: Vec<f64> = (0..9).map(|k| 0.25 * k as f64).collect();
        let psi: Vec<f64> = xs
            .iter()
            .flat_map(|&x| [1.0, x, x * x, x * x * x])
            .collect();
        let info = information(&psi, 9, 4).unwrap();
        let (lo, hi) = jacobi_extremes(&psi, 9, 4);
        assert!((info.lambda_min / lo - 1.0).abs() < 1e-6, "{info:?} {lo}");
        assert!((info.lambda_max / hi - 1.0).abs() < 1e-6, "{info:?} {hi}");
        assert!(info.condition() > 1e3);
    }

    #[test]
    fn orthonormal_design_has_identity_information() {
        // Legendre 1, sqrt(3) x on the two Gauss points +-1/sqrt(3): Psi^T Psi / 2 = I.
        let a = 1.0 / 3f64.sqrt();
        let psi = [1.0, -3f64.sqrt() * a, 1.0, 3f64.sqrt() * a];
        let info = information(&psi, 2, 2).unwrap();
        assert!((info.condition() - 1.0).abs() < 1e-12, "{info:?}");
    }

    #[test]
    fn dependent_term_is_named() {
        // 1, x, x^2 with x taking two values only: x^2 = 3x - 2 on {1, 2}: term 2.
        let psi: Vec<f64> = [1.0, 2.0, 1.0, 2.0]
            .iter()
            .flat_map(|&x: &f64| [1.0, x, x * x])
            .collect();
        let e = information(&psi, 4, 3).unwrap_err();
        assert!(
            matches!(
                e,
                UqError::Singular {
                    pivot: 2,
                    size: 3,
                    ..
                }
            ),
            "{e}"
        );
        assert!(information(&psi[..6], 2, 3).is_err());
    }
}
