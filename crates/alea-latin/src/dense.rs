//! Small dense linear systems `A x = b` (`m x m`, row-major, `m` up to a few tens): Gaussian
//! elimination with partial pivoting, the first row of largest magnitude in the column as the
//! pivot. Used by the Anderson acceleration's normal equations and by alea-study's
//! moving-least-squares warm-start weights; a dense factorisation crate would cost more than it
//! saves at these sizes.

/// Solves `a x = b` in place (`a` is `m x m`, row-major, overwritten by its triangular factor,
/// `b` by the reduced right-hand side). `None` when a pivot's magnitude is at most
/// `pivot_floor` (0.0: only an exactly singular column), or the solution is not finite.
pub fn solve_pivoted(a: &mut [f64], b: &mut [f64], m: usize, pivot_floor: f64) -> Option<Vec<f64>> {
    for c in 0..m {
        let p = (c..m).max_by(|&r, &s| {
            a[r * m + c]
                .abs()
                .total_cmp(&a[s * m + c].abs())
                .then(s.cmp(&r))
        })?;
        if a[p * m + c].abs() <= pivot_floor {
            return None;
        }
        if p != c {
            for k in 0..m {
                a.swap(p * m + k, c * m + k);
            }
            b.swap(p, c);
        }
        for r in c + 1..m {
            let l = a[r * m + c] / a[c * m + c];
            for k in c..m {
                a[r * m + k] -= l * a[c * m + k];
            }
            b[r] -= l * b[c];
        }
    }
    let mut x = vec![0.0; m];
    for r in (0..m).rev() {
        let s: f64 = (r + 1..m).map(|k| a[r * m + k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r * m + r];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Makes faer's dense kernels that take their parallelism from the global setting (`llt`,
/// `self_adjoint_eigen` on `Mat`: the coarse problem, the equilibrium check, the 3D
/// equilibrated tractions) run sequentially. By default faer splits them over every rayon
/// thread, and the blocked sums then round differently with the thread count; alea
/// parallelises over runs instead, so that the same inputs give the same bits whatever
/// `--threads` is. Called once by the programs (the `alea` binary, the Python module).
pub fn use_sequential_dense_kernels() {
    faer::set_global_parallelism(faer::Par::Seq);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A system that needs a row swap, solved exactly; a singular one refused.
    #[test]
    fn solves_with_pivoting_and_refuses_singular_systems() {
        let mut a = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 2.0, 0.0, 3.0];
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|r| (0..3).map(|c| a[r * 3 + c] * x[c]).sum())
            .collect();
        let got = solve_pivoted(&mut a, &mut b, 3, 0.0).unwrap();
        for (g, e) in got.iter().zip(x) {
            assert!((g - e).abs() < 1e-14, "{got:?}");
        }
        let mut s = vec![1.0, 2.0, 2.0, 4.0];
        let mut bs = vec![1.0, 2.0];
        assert!(solve_pivoted(&mut s, &mut bs, 2, 1e-12).is_none());
    }
}
