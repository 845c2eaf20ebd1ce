//! Triangular solves `L L^T x = b` with a simplicial (column-by-column) Cholesky factor of faer,
//! for several right-hand sides at once, stored **row-interleaved**.
//!
//! faer's simplicial solve walks the factor once per group of at most 4 right-hand sides held
//! column by column, so each entry `l_ij` of the factor updates 4 values `n` apart. Here the
//! right-hand sides are copied (with the fill-reducing permutation `x_i = b_{perm(i)}`) into
//! blocks of `W = 8, 4, 2` or `1` columns stored row by row (5 - 7 columns padded with zero
//! columns to 8, 3 to 4: a pass costs about the same for them), `x[i] = [x_i^(1) .. x_i^(W)]`, so
//! each entry of the factor is read once per block and updates `W` contiguous values (one
//! cache line for `W = 8`) in a loop the compiler vectorises (with AVX2 where the processor has
//! it, detected at run time):
//!
//! ```text
//! forward  (j = 0 .. n-1):  x[j] *= 1 / l_jj;   x[i] -= l_ij x[j]   (i > j in column j)
//! backward (j = n-1 .. 0):  x[j] = (x[j] - sum_{i > j} l_ij x[i]) * (1 / l_jj)
//! ```
//!
//! with the sum accumulated from zero in reverse storage order. These are the operations of
//! faer's `solve_lower_triangular_in_place` / `..._transpose_in_place` in the same order, column
//! by column, so every column of the result is bitwise the single-column solve of faer,
//! whatever the number of columns solved with it (test `interleaved_solve_is_bitwise_faer`).

/// A simplicial factor of faer: column pointers, row indices (diagonal first in each column)
/// and values of `L`, with the fill-reducing permutation (`fwd`, `inv`).
pub(crate) struct SimplicialFactor<'a> {
    pub col_ptr: &'a [usize],
    pub row_idx: &'a [usize],
    pub values: &'a [f64],
    pub perm: Option<(&'a [usize], &'a [usize])>,
}

impl SimplicialFactor<'_> {
    /// Solves `A x = b` in place for the `ncols` columns of `rhs` (column-major, `n x ncols`);
    /// `buf` is scratch.
    pub fn solve(&self, rhs: &mut [f64], n: usize, ncols: usize, buf: &mut Vec<f64>) {
        let mut c0 = 0;
        while c0 < ncols {
            // Blocks of 8, the rest in one block padded with zero columns (one pass over the
            // factor costs about the same for 5 or 8 columns, less than two passes).
            let (w, real) = match ncols - c0 {
                r if r >= 8 => (8, 8),
                r if r >= 5 => (8, r),
                r if r >= 3 => (4, r),
                r => (r, r),
            };
            let block = &mut rhs[c0 * n..(c0 + real) * n];
            match w {
                8 => self.solve_block::<8>(block, n, buf),
                4 => self.solve_block::<4>(block, n, buf),
                2 => self.solve_block::<2>(block, n, buf),
                _ => self.solve_block::<1>(block, n, buf),
            }
            c0 += real;
        }
    }

    /// The solve of the (at most `W`) columns of `block` (column-major) through a
    /// row-interleaved copy of `W` columns (zeros beyond them), with AVX2 where the processor
    /// has it.
    fn solve_block<const W: usize>(&self, block: &mut [f64], n: usize, buf: &mut Vec<f64>) {
        #[cfg(target_arch = "x86_64")]
        if W >= 4 && std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2 (checked just above).
            unsafe { self.solve_block_avx2::<W>(block, n, buf) };
            return;
        }
        self.solve_block_generic::<W>(block, n, buf);
    }

    /// [`SimplicialFactor::solve_block_generic`] compiled with AVX2 (4 doubles per operation;
    /// the same operations in the same order, no fused multiply-add, so the same bits).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_block_avx2<const W: usize>(&self, block: &mut [f64], n: usize, buf: &mut Vec<f64>) {
        self.solve_block_generic::<W>(block, n, buf);
    }

    #[inline(always)]
    fn solve_block_generic<const W: usize>(&self, block: &mut [f64], n: usize, buf: &mut Vec<f64>) {
        let real = block.len() / n.max(1);
        debug_assert!(real <= W);
        buf.clear();
        buf.resize(n * W, 0.0);
        let (x, _) = buf.as_chunks_mut::<W>();
        match self.perm {
            Some((fwd, _)) => {
                for (i, xi) in x.iter_mut().enumerate() {
                    for (c, v) in xi[..real].iter_mut().enumerate() {
                        *v = block[c * n + fwd[i]];
                    }
                }
            }
            None => {
                for (i, xi) in x.iter_mut().enumerate() {
                    for (c, v) in xi[..real].iter_mut().enumerate() {
                        *v = block[c * n + i];
                    }
                }
            }
        }
        let (cp, ri, lv) = (self.col_ptr, self.row_idx, self.values);
        for j in 0..n {
            let (p0, p1) = (cp[j], cp[j + 1]);
            debug_assert_eq!(ri[p0], j, "diagonal first");
            let d = lv[p0].recip();
            let mut xj = x[j];
            for v in xj.iter_mut() {
                *v *= d;
            }
            x[j] = xj;
            for (&i, &l) in ri[p0 + 1..p1].iter().zip(&lv[p0 + 1..p1]) {
                let xi = &mut x[i];
                for c in 0..W {
                    xi[c] -= l * xj[c];
                }
            }
        }
        for j in (0..n).rev() {
            let (p0, p1) = (cp[j], cp[j + 1]);
            let mut acc = [0.0; W];
            for (&i, &l) in ri[p0 + 1..p1].iter().zip(&lv[p0 + 1..p1]).rev() {
                let xi = &x[i];
                for c in 0..W {
                    acc[c] += l * xi[c];
                }
            }
            let d = lv[p0].recip();
            let xj = &mut x[j];
            for c in 0..W {
                xj[c] = (xj[c] - acc[c]) * d;
            }
        }
        match self.perm {
            Some((_, inv)) => {
                for c in 0..real {
                    for (i, v) in block[c * n..(c + 1) * n].iter_mut().enumerate() {
                        *v = x[inv[i]][c];
                    }
                }
            }
            None => {
                for c in 0..real {
                    for (i, v) in block[c * n..(c + 1) * n].iter_mut().enumerate() {
                        *v = x[i][c];
                    }
                }
            }
        }
    }
}
