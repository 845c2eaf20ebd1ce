//! Small dense linear algebra: Cholesky factor and solve, and the least-norm solution of small (possibly
//! singular) systems through a symmetric eigendecomposition (cyclic Jacobi, [`alea_uq::eigen`]).

use alea_uq::eigen::{JacobiStop, jacobi_sweeps};

/// Solves `a x = b` in place for a symmetric positive definite row-major `n x n` matrix `a`
/// (overwritten by its Cholesky factor). Returns `false` if `a` is not positive definite.
pub fn cholesky_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d > 0.0) || !d.is_finite() {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[k * n + i] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    true
}

/// Lower Cholesky factor of a symmetric positive definite `n x n` row-major matrix.
pub fn cholesky_factor(d: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let s: f64 = (0..j).map(|k| l[i * n + k] * l[j * n + k]).sum();
            if i == j {
                let v = d[i * n + i] - s;
                if !(v > 0.0) {
                    return None;
                }
                l[i * n + i] = v.sqrt();
            } else {
                l[i * n + j] = (d[i * n + j] - s) / l[j * n + j];
            }
        }
    }
    Some(l)
}

/// Eigen-decomposition of a symmetric row-major `n x n` matrix by cyclic Jacobi rotations:
/// returns `(eigenvalues, eigenvectors)` with eigenvector `k` in column `k` (row-major `v`).
pub fn sym_eigen(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut a = a.to_vec();
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    let stop = JacobiStop {
        max_sweeps: 60,
        // |a_pq| < the smallest subnormal: only an exact zero is skipped.
        skip_below: f64::from_bits(1),
        converged: |a: &[f64]| {
            let mut off = 0.0;
            let mut diag = 0.0;
            for i in 0..n {
                diag += a[i * n + i] * a[i * n + i];
                for j in i + 1..n {
                    off += a[i * n + j] * a[i * n + j];
                }
            }
            off <= 1e-30 * diag || off == 0.0
        },
    };
    jacobi_sweeps(&mut a, Some(&mut v), n, &stop);
    ((0..n).map(|i| a[i * n + i]).collect(), v)
}

/// Eigen-decomposition `(lambda, V)` of `A A^T` (`A` row-major `m x n`, [`sym_eigen`]) and
/// which eigenvalues the pseudo-inverse keeps (positive and above `1e-11` of the largest).
fn gram_eigen(a: &[f64], m: usize, n: usize) -> (Vec<f64>, Vec<f64>, Vec<bool>) {
    let mut aat = vec![0.0; m * m];
    for i in 0..m {
        for j in 0..m {
            aat[i * m + j] = (0..n).map(|k| a[i * n + k] * a[j * n + k]).sum();
        }
    }
    let (lam, v) = sym_eigen(&aat, m);
    let lmax = lam.iter().fold(0.0f64, |s, &l| s.max(l.abs()));
    let kept = lam.iter().map(|&l| l > 1e-11 * lmax && l > 0.0).collect();
    (lam, v, kept)
}

/// Least-change solution of the underdetermined (possibly singular) system `A x = c`
/// (`m x n`, row-major): `x = x_bar + A^T lambda` with `lambda = (A A^T)^+ (c - A x_bar)`, i.e.
/// the `x` closest to `x_bar` among the least-squares solutions. Returns `(x, |A x - c|)`.
pub fn least_change(a: &[f64], m: usize, n: usize, c: &[f64], x_bar: &[f64]) -> (Vec<f64>, f64) {
    let mut r: Vec<f64> = (0..m)
        .map(|i| c[i] - (0..n).map(|j| a[i * n + j] * x_bar[j]).sum::<f64>())
        .collect();
    let (lam, v, kept) = gram_eigen(a, m, n);
    let mut mult = vec![0.0; m];
    for k in 0..m {
        if kept[k] {
            let proj: f64 = (0..m).map(|i| v[i * m + k] * r[i]).sum::<f64>() / lam[k];
            for i in 0..m {
                mult[i] += proj * v[i * m + k];
            }
        }
    }
    let mut x = x_bar.to_vec();
    for j in 0..n {
        x[j] += (0..m).map(|i| a[i * n + j] * mult[i]).sum::<f64>();
    }
    for i in 0..m {
        r[i] = c[i] - (0..n).map(|j| a[i * n + j] * x[j]).sum::<f64>();
    }
    let res = r.iter().map(|v| v * v).sum::<f64>().sqrt();
    (x, res)
}

/// The operator `P = A^T (A A^T)^+` (`n x m`, row-major) of [`least_change`]: its solution is
/// `x = x_bar + P (c - A x_bar)` (same eigenvalue cut-off), so a system whose matrix does not
/// change is solved for any `c` and `x_bar` by two small products.
pub fn least_change_operator(a: &[f64], m: usize, n: usize) -> Vec<f64> {
    let (lam, v, kept) = gram_eigen(a, m, n);
    // (A A^T)^+ = sum_k v_k v_k^T / lambda_k over the kept eigenvalues.
    let mut pinv = vec![0.0; m * m];
    for k in 0..m {
        if kept[k] {
            for i in 0..m {
                for j in 0..m {
                    pinv[i * m + j] += v[i * m + k] * v[j * m + k] / lam[k];
                }
            }
        }
    }
    let mut p = vec![0.0; n * m];
    for j in 0..n {
        for i in 0..m {
            p[j * m + i] = (0..m).map(|k| a[k * n + j] * pinv[k * m + i]).sum();
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_and_least_change() {
        let mut a = vec![4.0, 1.0, 1.0, 3.0];
        let mut b = vec![1.0, 2.0];
        assert!(cholesky_solve(&mut a, &mut b, 2));
        assert!((4.0 * b[0] + b[1] - 1.0).abs() < 1e-14);
        assert!((b[0] + 3.0 * b[1] - 2.0).abs() < 1e-14);
        // Interior-node-like system: 3 elements around a node, 3 edges (cyclic), singular but
        // compatible (rhs sums to zero).
        let a = vec![1.0, -1.0, 0.0, 0.0, 1.0, -1.0, -1.0, 0.0, 1.0];
        let c = vec![1.0, 2.0, -3.0];
        let (x, res) = least_change(&a, 3, 3, &c, &[5.0, 5.0, 5.0]);
        assert!(res < 1e-12);
        // The minimal change keeps the mean of x at 5.
        assert!(((x[0] + x[1] + x[2]) / 3.0 - 5.0).abs() < 1e-12);
        // Incompatible rhs: residual reported.
        let (_, res) = least_change(&a, 3, 3, &[1.0, 1.0, 1.0], &[0.0; 3]);
        assert!((res - 3f64.sqrt()).abs() < 1e-12);
        // The cached operator gives the same solution.
        let p = least_change_operator(&a, 3, 3);
        let x_bar = [5.0, 4.0, -1.0];
        let (x, _) = least_change(&a, 3, 3, &c, &x_bar);
        for j in 0..3 {
            let r: Vec<f64> = (0..3)
                .map(|i| c[i] - (0..3).map(|k| a[i * 3 + k] * x_bar[k]).sum::<f64>())
                .collect();
            let xj = x_bar[j] + (0..3).map(|i| p[j * 3 + i] * r[i]).sum::<f64>();
            assert!((xj - x[j]).abs() < 1e-12);
        }
    }
}
