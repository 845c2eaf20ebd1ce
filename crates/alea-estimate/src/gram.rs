//! Gram matrices of the runs' stress samples, per substructure:
//! `A_kl = y(sigma_hat_k) . y(sigma_hat_l)`, `B_kl = y(sigma_hat_k) . y(sigma_h,l)`,
//! `C_kl = y(sigma_h,k) . y(sigma_h,l)` (crate doc). With them every substructure term at any
//! parameter point is a quadratic form in the `K` weights, whatever the size of the mesh.
//!
//! Computed as `Y^T Y` products (faer's matmul) on blocks of sample rows, in parallel over the
//! blocks with a sequential product inside each and the partial sums added in block order, so
//! the result does not depend on the thread count.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};
use rayon::prelude::*;

/// The three Gram matrices of one substructure, dense row-major `K x K` (only `C` for a
/// substructure with FE samples only: [`Gram::fe_only`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Gram {
    /// Number of runs.
    pub k: usize,
    /// `A_kl = a_k . a_l` (admissible with admissible; empty without admissible samples).
    pub aa: Vec<f64>,
    /// `B_kl = a_k . h_l` (admissible with FE; not symmetric; empty without admissible
    /// samples).
    pub ah: Vec<f64>,
    /// `C_kl = h_k . h_l` (FE with FE).
    pub hh: Vec<f64>,
}

impl Gram {
    /// `C` alone, for a substructure with FE samples `h[k]` only (no admissible stress): `aa`
    /// and `ah` are left empty.
    ///
    /// # Panics
    /// If the vectors do not all have the same length.
    pub fn fe_only(h: &[&[f64]]) -> Self {
        let k = h.len();
        let n = h.first().map_or(0, |v| v.len());
        assert!(
            h.iter().all(|v| v.len() == n),
            "sample vectors of one length"
        );
        let hh = if k == 0 || n == 0 {
            vec![0.0; k * k]
        } else {
            products(h, h, n, k, false)[2].clone()
        };
        Gram {
            k,
            aa: Vec::new(),
            ah: Vec::new(),
            hh,
        }
    }

    /// True when `A` and `B` are present (the runs gave admissible samples).
    pub fn has_admissible(&self) -> bool {
        self.aa.len() == self.k * self.k && self.ah.len() == self.k * self.k
    }

    /// The Gram matrices of sample vectors `a[k]` (admissible) and `h[k]` (FE), all of one
    /// length.
    ///
    /// # Panics
    /// If the vectors do not all have the same length or the slices differ in length.
    pub fn new(a: &[&[f64]], h: &[&[f64]]) -> Self {
        let k = a.len();
        assert_eq!(h.len(), k, "as many FE as admissible sample vectors");
        let n = a.first().map_or(0, |v| v.len());
        assert!(
            a.iter().chain(h).all(|v| v.len() == n),
            "sample vectors of one length"
        );
        if k == 0 || n == 0 {
            return Gram {
                k,
                aa: vec![0.0; k * k],
                ah: vec![0.0; k * k],
                hh: vec![0.0; k * k],
            };
        }
        let [aa, ah, hh] = products(a, h, n, k, true);
        Gram { k, aa, ah, hh }
    }
}

/// `[A, B, C]` (row-major `K x K`) of `a` and `h` (`K` vectors of length `n > 0`); with
/// `all = false` only `C` is computed (the others are left zero).
fn products(a: &[&[f64]], h: &[&[f64]], n: usize, k: usize, all: bool) -> [Vec<f64>; 3] {
    let block = (n / 16).max(4096).min(n);
    let starts: Vec<usize> = (0..n).step_by(block).collect();
    let parts: Vec<[Mat<f64>; 3]> = starts
        .par_iter()
        .map(|&r0| {
            let r1 = (r0 + block).min(n);
            let m = r1 - r0;
            let gather = |v: &[&[f64]]| -> Vec<f64> {
                let mut buf = Vec::with_capacity(m * k);
                for col in v {
                    buf.extend_from_slice(&col[r0..r1]);
                }
                buf
            };
            let bh = gather(h);
            let ba = if all { gather(a) } else { Vec::new() };
            let yh = MatRef::from_column_major_slice(&bh, m, k);
            let mut out = [Mat::zeros(k, k), Mat::zeros(k, k), Mat::zeros(k, k)];
            if all {
                let ya = MatRef::from_column_major_slice(&ba, m, k);
                for (dst, (l, r)) in out.iter_mut().zip([(ya, ya), (ya, yh)]) {
                    matmul(dst, Accum::Replace, l.transpose(), r, 1.0, Par::Seq);
                }
            }
            matmul(
                &mut out[2],
                Accum::Replace,
                yh.transpose(),
                yh,
                1.0,
                Par::Seq,
            );
            out
        })
        .collect();
    let mut sum = [vec![0.0; k * k], vec![0.0; k * k], vec![0.0; k * k]];
    for p in &parts {
        for (s, m) in sum.iter_mut().zip(p) {
            for i in 0..k {
                for j in 0..k {
                    s[i * k + j] += m[(i, j)];
                }
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gram_matches_plain_dot_products() {
        // Lengths across the block size (several blocks, a partial last one).
        for n in [7usize, 4096 * 3 + 17] {
            let k = 5;
            let a: Vec<Vec<f64>> = (0..k)
                .map(|r| {
                    (0..n)
                        .map(|i| ((i * 7 + r * 13) % 11) as f64 - 5.0)
                        .collect()
                })
                .collect();
            let h: Vec<Vec<f64>> = (0..k)
                .map(|r| (0..n).map(|i| ((i * 3 + r * 5) % 7) as f64 * 0.5).collect())
                .collect();
            let ar: Vec<&[f64]> = a.iter().map(|v| v.as_slice()).collect();
            let hr: Vec<&[f64]> = h.iter().map(|v| v.as_slice()).collect();
            let g = Gram::new(&ar, &hr);
            let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
            for i in 0..k {
                for j in 0..k {
                    assert_eq!(g.aa[i * k + j], dot(&a[i], &a[j]));
                    assert_eq!(g.ah[i * k + j], dot(&a[i], &h[j]));
                    assert_eq!(g.hh[i * k + j], dot(&h[i], &h[j]));
                }
            }
        }
    }
}
