//! Symmetric eigenproblems by cyclic Jacobi rotations, the one implementation used by FORM/SORM
//! curvatures here and by the least-change pseudo-inverses of alea-cre.
//!
//! For a symmetric row-major `n x n` matrix `A`, the rotation in the plane `(p, q)` with
//! `theta = (a_qq - a_pp) / (2 a_pq)`, `t = sgn(theta) / (|theta| + sqrt(theta^2 + 1))` (`t = 1`
//! for `theta = 0`), `c = 1 / sqrt(t^2 + 1)`, `s = t c` zeroes `a_pq`: `A <- J^T A J` and, when the
//! eigenvectors are wanted, `V <- V J`. Sweeps visit every `p < q` in order until the caller's
//! convergence test on `A` holds or the sweep budget is spent; the diagonal of `A` then holds the
//! eigenvalues and column `k` of `V` the eigenvector of `a_kk`.

/// When to stop the cyclic Jacobi sweeps and which off-diagonal entries to leave alone.
pub struct JacobiStop<F: Fn(&[f64]) -> bool> {
    /// Largest number of sweeps.
    pub max_sweeps: usize,
    /// An entry `a_pq` with `|a_pq| < skip_below` is not rotated.
    pub skip_below: f64,
    /// Test on the current matrix, made before each sweep: `true` ends the iteration.
    pub converged: F,
}

/// Diagonalises the symmetric row-major `n x n` matrix `a` in place by cyclic Jacobi sweeps,
/// accumulating the rotations into `vectors` (row-major `n x n`, start from the identity) if given.
pub fn jacobi_sweeps<F: Fn(&[f64]) -> bool>(
    a: &mut [f64],
    mut vectors: Option<&mut [f64]>,
    n: usize,
    stop: &JacobiStop<F>,
) {
    for _sweep in 0..stop.max_sweeps {
        if (stop.converged)(a) {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq.abs() < stop.skip_below {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k * n + p], a[k * n + q]);
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p * n + k], a[q * n + k]);
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
                if let Some(v) = vectors.as_deref_mut() {
                    for k in 0..n {
                        let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                        v[k * n + p] = c * vkp - s * vkq;
                        v[k * n + q] = s * vkp + c * vkq;
                    }
                }
            }
        }
    }
}
