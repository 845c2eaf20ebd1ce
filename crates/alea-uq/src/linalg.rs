//! Small dense linear algebra written for this crate (no external dependency): Householder QR
//! least squares, Cholesky, and the implicit QL algorithm for symmetric tridiagonal matrices
//! (eigenvalues and first eigenvector components, used by Golub-Welsch).
//!
//! Matrices are row-major `Vec<f64>`; an `m x n` matrix `a` stores entry `(i, j)` at `a[i*n + j]`.

use crate::error::{Result, UqError};

/// Output of [`least_squares_projector`].
#[derive(Debug, Clone)]
pub(crate) struct Projector {
    /// `n x m` matrix `A = (Psi^T Psi)^-1 Psi^T = R^-1 Q1^T`, row-major.
    pub a: Vec<f64>,
    /// Diagonal of the hat matrix `H = Psi A` (leverages), length `m`.
    pub hat_diag: Vec<f64>,
    /// Lower bound of the 2-norm condition number of `Psi`: `max|r_ii| / min|r_ii|`.
    pub cond_estimate: f64,
}

/// Least-squares projector of the `m x n` (m >= n) design matrix `psi` by Householder QR.
///
/// # Errors
/// [`UqError::Singular`] if `m < n` or a pivot of `R` vanishes relative to the largest one.
pub(crate) fn least_squares_projector(
    what: &'static str,
    psi: &[f64],
    m: usize,
    n: usize,
) -> Result<Projector> {
    if m < n {
        return Err(UqError::Invalid {
            what,
            message: format!("needs at least as many points ({m}) as basis functions ({n})"),
        });
    }
    // Column-major copy for cache-friendly Householder sweeps.
    let mut q = vec![0.0; m * n];
    for i in 0..m {
        for j in 0..n {
            q[j * m + i] = psi[i * n + j];
        }
    }
    let mut tau = vec![0.0; n];
    let mut rdiag = vec![0.0; n];
    for k in 0..n {
        let (head, tail) = q.split_at_mut((k + 1) * m);
        let col = &mut head[k * m..];
        let norm = col[k..].iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm == 0.0 {
            return Err(UqError::Singular {
                what,
                pivot: k,
                size: n,
            });
        }
        let alpha = if col[k] > 0.0 { -norm } else { norm };
        // v = x - alpha e_k stored in col[k..], tau = 2 / v^T v
        col[k] -= alpha;
        let vtv: f64 = col[k..].iter().map(|v| v * v).sum();
        tau[k] = 2.0 / vtv;
        rdiag[k] = alpha;
        for j in (k + 1)..n {
            let cj = &mut tail[(j - k - 1) * m..(j - k) * m];
            let dot: f64 = col[k..].iter().zip(&cj[k..]).map(|(a, b)| a * b).sum();
            let s = tau[k] * dot;
            for (c, v) in cj[k..].iter_mut().zip(&col[k..]) {
                *c -= s * v;
            }
        }
    }
    let rmax = rdiag.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let rmin = rdiag.iter().fold(f64::INFINITY, |a, v| a.min(v.abs()));
    for (k, r) in rdiag.iter().enumerate() {
        if r.abs() <= rmax * 1e-13 {
            return Err(UqError::Singular {
                what,
                pivot: k,
                size: n,
            });
        }
    }
    // Q1 (m x n, column-major): apply reflectors to the first n columns of the identity.
    let mut q1 = vec![0.0; m * n];
    for j in 0..n {
        q1[j * m + j] = 1.0;
    }
    for k in (0..n).rev() {
        let v = &q[k * m..(k + 1) * m];
        for j in k..n {
            let cj = &mut q1[j * m..(j + 1) * m];
            let dot: f64 = v[k..].iter().zip(&cj[k..]).map(|(a, b)| a * b).sum();
            let s = tau[k] * dot;
            for (c, vv) in cj[k..].iter_mut().zip(&v[k..]) {
                *c -= s * vv;
            }
        }
    }
    // R strictly upper part lives in q above the diagonal: R(i, j) = q[j*m + i] for i < j.
    // A = R^-1 Q1^T: back substitution, row i of A = (Q1^T row i - sum_{j>i} R_ij A_j) / R_ii.
    let mut a = vec![0.0; n * m];
    for i in (0..n).rev() {
        let (upper, lower) = a.split_at_mut((i + 1) * m);
        let row = &mut upper[i * m..];
        row.copy_from_slice(&q1[i * m..(i + 1) * m]);
        for j in (i + 1)..n {
            let rij = q[j * m + i];
            let aj = &lower[(j - i - 1) * m..(j - i) * m];
            for (r, v) in row.iter_mut().zip(aj) {
                *r -= rij * v;
            }
        }
        let inv = 1.0 / rdiag[i];
        for r in row.iter_mut() {
            *r *= inv;
        }
    }
    let mut hat_diag = vec![0.0; m];
    for j in 0..n {
        for (h, v) in hat_diag.iter_mut().zip(&q1[j * m..(j + 1) * m]) {
            *h += v * v;
        }
    }
    Ok(Projector {
        a,
        hat_diag,
        cond_estimate: rmax / rmin,
    })
}

/// Cholesky factor `L` (row-major, lower) of a symmetric positive definite `n x n` matrix.
///
/// # Errors
/// [`UqError::Singular`] at the first non-positive pivot.
pub(crate) fn cholesky(what: &'static str, a: &[f64], n: usize) -> Result<Vec<f64>> {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            if i == j {
                if !(s > 0.0) {
                    return Err(UqError::Singular {
                        what,
                        pivot: i,
                        size: n,
                    });
                }
                l[i * n + i] = s.sqrt();
            } else {
                l[i * n + j] = s / l[j * n + j];
            }
        }
    }
    Ok(l)
}

/// Eigenvalues `d` and first components `z0` of the orthonormal eigenvectors of the symmetric
/// tridiagonal matrix with diagonal `d` and sub-diagonal `e[1..n]` (`e[0]` ignored), by the
/// implicit QL algorithm with Wilkinson-type shifts. Sorted by increasing eigenvalue.
pub(crate) fn tridiagonal_eigen(mut d: Vec<f64>, mut e: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let n = d.len();
    let mut z = vec![0.0; n];
    if n == 0 {
        return (d, z);
    }
    z[0] = 1.0;
    for i in 1..n {
        e[i - 1] = e[i];
    }
    e[n - 1] = 0.0;
    for l in 0..n {
        let mut iter = 0;
        loop {
            let mut m = l;
            while m + 1 < n {
                let dd = d[m].abs() + d[m + 1].abs();
                if e[m].abs() <= f64::EPSILON * dd {
                    break;
                }
                m += 1;
            }
            if m == l {
                break;
            }
            iter += 1;
            if iter > 100 {
                break;
            }
            let mut g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let mut r = g.hypot(1.0);
            g = d[m] - d[l] + e[l] / (g + r.copysign(g));
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut i = m;
            let mut underflow = false;
            while i > l {
                i -= 1;
                let f = s * e[i];
                let b = c * e[i];
                r = f.hypot(g);
                e[i + 1] = r;
                if r == 0.0 {
                    d[i + 1] -= p;
                    e[m] = 0.0;
                    underflow = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
                let zf = z[i + 1];
                z[i + 1] = s * z[i] + c * zf;
                z[i] = c * z[i] - s * zf;
            }
            if underflow {
                continue;
            }
            d[l] -= p;
            e[l] = g;
            e[m] = 0.0;
        }
    }
    let mut idx: Vec<usize> = (0..n).collect();
    idx.sort_by(|&a, &b| d[a].total_cmp(&d[b]));
    (
        idx.iter().map(|&i| d[i]).collect(),
        idx.iter().map(|&i| z[i]).collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projector_solves_least_squares() {
        // Fit y = 1 + 2x exactly on 5 points; hat diag sums to n = 2.
        let xs = [0.0, 0.5, 1.0, 1.5, 3.0];
        let psi: Vec<f64> = xs.iter().flat_map(|&x| [1.0, x]).collect();
        let p = least_squares_projector("test", &psi, 5, 2).unwrap();
        let y: Vec<f64> = xs.iter().map(|x| 1.0 + 2.0 * x).collect();
        let c0: f64 = (0..5).map(|k| p.a[k] * y[k]).sum();
        let c1: f64 = (0..5).map(|k| p.a[5 + k] * y[k]).sum();
        assert!((c0 - 1.0).abs() < 1e-13 && (c1 - 2.0).abs() < 1e-13);
        assert!((p.hat_diag.iter().sum::<f64>() - 2.0).abs() < 1e-13);
    }

    #[test]
    fn tridiagonal_eigen_matches_closed_form() {
        // Tridiag(-1, 2, -1) of size n: eigenvalues 2 - 2 cos(k pi/(n+1)).
        let n = 7;
        let (d, z) = tridiagonal_eigen(vec![2.0; n], vec![-1.0; n]);
        for (k, v) in d.iter().enumerate() {
            let exact = 2.0 - 2.0 * ((k + 1) as f64 * std::f64::consts::PI / (n + 1) as f64).cos();
            assert!((v - exact).abs() < 1e-13);
        }
        assert!((z.iter().map(|v| v * v).sum::<f64>() - 1.0).abs() < 1e-13);
    }
}
