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
        Gram {
            k,
            aa: Vec::new(),
            ah: Vec::new(),
            hh: cross_gram(&[], h, n).bb,
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
        cross_gram(a, h, n).into_gram()
    }
}

/// The Gram blocks of `a` and `b` (vectors of length `n`), accumulated over blocks of rows in
/// parallel and added in block order (independent of the thread count).
fn cross_gram(a: &[&[f64]], b: &[&[f64]], n: usize) -> CrossGram {
    let (ka, kb) = (a.len(), b.len());
    let mut sum = CrossGram::zeros(ka, kb);
    if n == 0 || ka + kb == 0 {
        return sum;
    }
    let block = (n / 16).max(4096).min(n);
    let starts: Vec<usize> = (0..n).step_by(block).collect();
    let parts: Vec<CrossGram> = starts
        .par_iter()
        .map(|&r0| {
            let r1 = (r0 + block).min(n);
            let m = r1 - r0;
            let gather = |v: &[&[f64]]| -> Vec<f64> {
                let mut buf = Vec::with_capacity(m * v.len());
                for col in v {
                    buf.extend_from_slice(&col[r0..r1]);
                }
                buf
            };
            let mut g = CrossGram::zeros(ka, kb);
            g.add_block(m, &gather(a), &gather(b));
            g
        })
        .collect();
    for p in &parts {
        sum.add(p);
    }
    sum
}

/// The Gram blocks of two families of sample vectors `a_1..a_ka` and `b_1..b_kb` of one
/// length, accumulated over blocks of sample rows (so that neither family need be held whole):
/// `aa = A^T A` (`ka x ka`), `ab = A^T B` (`ka x kb`), `bb = B^T B` (`kb x kb`), dense
/// row-major. [`Gram`] is the case `ka = kb` with the admissible and FE samples; the reference
/// distance of the `reference` module uses a reference solution's runs against a surrogate's.
/// Blocks are multiplied by faer's matmul (sequential); adding them in a fixed order gives
/// results independent of the thread count.
#[derive(Clone, Debug, PartialEq)]
pub struct CrossGram {
    /// Vectors of the first family.
    pub ka: usize,
    /// Vectors of the second family.
    pub kb: usize,
    /// `A^T A`.
    pub aa: Vec<f64>,
    /// `A^T B`.
    pub ab: Vec<f64>,
    /// `B^T B`.
    pub bb: Vec<f64>,
}

impl CrossGram {
    /// All zero.
    pub fn zeros(ka: usize, kb: usize) -> Self {
        CrossGram {
            ka,
            kb,
            aa: vec![0.0; ka * ka],
            ab: vec![0.0; ka * kb],
            bb: vec![0.0; kb * kb],
        }
    }

    /// Adds the products of `m` sample rows: `a` column-major `m x ka` (vector `k`'s rows at
    /// `a[k * m..(k + 1) * m]`), `b` column-major `m x kb`.
    ///
    /// # Panics
    /// If the lengths are not `m * ka` and `m * kb`.
    pub fn add_block(&mut self, m: usize, a: &[f64], b: &[f64]) {
        let (ka, kb) = (self.ka, self.kb);
        assert!(a.len() == m * ka && b.len() == m * kb, "block sizes");
        if m == 0 {
            return;
        }
        let ya = MatRef::from_column_major_slice(a, m, ka);
        let yb = MatRef::from_column_major_slice(b, m, kb);
        let mut out = [Mat::zeros(ka, ka), Mat::zeros(ka, kb), Mat::zeros(kb, kb)];
        for (dst, (l, r)) in out.iter_mut().zip([(ya, ya), (ya, yb), (yb, yb)]) {
            matmul(dst, Accum::Replace, l.transpose(), r, 1.0, Par::Seq);
        }
        for (acc, mat) in [&mut self.aa, &mut self.ab, &mut self.bb]
            .into_iter()
            .zip(&out)
        {
            let cols = mat.ncols();
            for i in 0..mat.nrows() {
                for j in 0..cols {
                    acc[i * cols + j] += mat[(i, j)];
                }
            }
        }
    }

    /// Adds another accumulation of the same families.
    ///
    /// # Panics
    /// If the sizes differ.
    pub fn add(&mut self, other: &CrossGram) {
        assert!(self.ka == other.ka && self.kb == other.kb, "Gram sizes");
        for (s, o) in [
            (&mut self.aa, &other.aa),
            (&mut self.ab, &other.ab),
            (&mut self.bb, &other.bb),
        ] {
            for (x, y) in s.iter_mut().zip(o) {
                *x += y;
            }
        }
    }

    fn into_gram(self) -> Gram {
        Gram {
            k: self.ka,
            aa: self.aa,
            ah: self.ab,
            hh: self.bb,
        }
    }
}

/// `sum_kl x_k y_l M_kl` over sparse vectors.
pub(crate) fn form(m: &[f64], k: usize, x: &[(usize, f64)], y: &[(usize, f64)]) -> f64 {
    let mut s = 0.0;
    for &(i, xi) in x {
        let row = &m[i * k..(i + 1) * k];
        let mut r = 0.0;
        for &(j, yj) in y {
            r += row[j] * yj;
        }
        s += xi * r;
    }
    s
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
