//! Anderson acceleration of the LATIN fixed-point map (optional, `LatinOptions::acceleration`).
//!
//! One LATIN iteration maps the local-stage state `x = (W_hat, F_hat)` used by the linear stage
//! to the next local-stage state `f = T(x)`. With the residual `g = f - x` and the differences
//! `dG`, `dF` of the last `m` residuals and images, Anderson's (type II) update is
//! `x_next = f - dF gamma`, `gamma = argmin |g - dG gamma|` (Walker & Ni 2011). On a linear map
//! this is GMRES-like; LATIN with perfect interfaces is linear, and with Coulomb contact it is
//! piecewise linear, so once the contact statuses settle the slow global modes (floating
//! substructures, no coarse problem) are resolved in a few iterations instead of hundreds.
//! The state is packed in the k-weighted norm of the error indicator (`sqrt(m k) W`,
//! `sqrt(m / k) F`), so displacements and forces weigh alike. The normal equations are
//! regularised by `1e-10 max(tr(dG^T dG), |g|^2)`: where the iteration drifts without a fixed
//! point yet (a floating block closing an initial gap moves by the same step every iteration,
//! so `dG` is round-off while `g` is not), a regularisation relative to `dG` alone let `gamma`
//! grow like `|g| / |dG|` and threw the block 1e5 model sizes away (issue 21); relative to
//! `|g|` too, such a step stays a plain one. The caller resets the history
//! when the indicator grows (safeguard); results are always the last true local stage.

use std::collections::VecDeque;

/// Anderson mixing history.
#[derive(Debug)]
pub(crate) struct Anderson {
    depth: usize,
    prev: Option<(Vec<f64>, Vec<f64>)>,
    dg: VecDeque<Vec<f64>>,
    df: VecDeque<Vec<f64>>,
    /// `gram[i][j] = dG_i . dG_j` for `j <= i` (rows follow `dg`): each step computes only the
    /// new difference's row, with the same dot products, so the same bits.
    gram: VecDeque<Vec<f64>>,
    /// Buffers of the state's size no longer in use (differences that left the history, a
    /// forgotten previous residual), reused by the next steps instead of allocating.
    spare: Vec<Vec<f64>>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl Anderson {
    pub(crate) fn new(depth: usize) -> Self {
        Anderson {
            depth,
            prev: None,
            dg: VecDeque::new(),
            df: VecDeque::new(),
            gram: VecDeque::new(),
            spare: Vec::new(),
        }
    }

    /// Forgets the history (next step is a plain fixed-point step).
    pub(crate) fn reset(&mut self) {
        if let Some((g, f)) = self.prev.take() {
            self.spare.extend([g, f]);
        }
        self.spare
            .extend(self.dg.drain(..).chain(self.df.drain(..)));
        self.gram.clear();
    }

    /// A buffer holding `values`.
    fn buffer(&mut self, values: impl Iterator<Item = f64>) -> Vec<f64> {
        let mut v = self.spare.pop().unwrap_or_default();
        v.clear();
        v.extend(values);
        v
    }

    /// Given the input `x` of the last iteration and its image `f`, returns the next input.
    pub(crate) fn step(&mut self, x: &[f64], f: &[f64]) -> Vec<f64> {
        let g = self.buffer(f.iter().zip(x).map(|(a, b)| a - b));
        if let Some((mut dg, mut df)) = self.prev.take() {
            // The previous residual and image become the differences, in place.
            for (d, a) in dg.iter_mut().zip(&g) {
                *d = a - *d;
            }
            for (d, a) in df.iter_mut().zip(f) {
                *d = a - *d;
            }
            self.dg.push_back(dg);
            self.df.push_back(df);
            if self.dg.len() > self.depth {
                let old = [self.dg.pop_front(), self.df.pop_front()];
                self.spare.extend(old.into_iter().flatten());
                self.gram.pop_front();
                for row in self.gram.iter_mut() {
                    row.remove(0);
                }
            }
            let last = &self.dg[self.dg.len() - 1];
            let row: Vec<f64> = self.dg.iter().map(|d| dot(last, d)).collect();
            self.gram.push_back(row);
        }
        let f_kept = self.buffer(f.iter().copied());
        self.prev = Some((g, f_kept));
        let Some((g, _)) = self.prev.as_ref() else {
            return f.to_vec();
        };
        let m = self.dg.len();
        let mut next = f.to_vec();
        if m == 0 {
            return next;
        }
        // Normal equations (dG^T dG + eps I) gamma = dG^T g, solved by Gaussian elimination
        // with partial pivoting (m <= depth, small).
        let mut a = vec![0.0; m * m];
        let mut b = vec![0.0; m];
        for i in 0..m {
            for j in 0..=i {
                let v = self.gram[i][j];
                a[i * m + j] = v;
                a[j * m + i] = v;
            }
            b[i] = dot(&self.dg[i], g);
        }
        let trace: f64 = (0..m).map(|i| a[i * m + i]).sum();
        if !(trace > 0.0 && trace.is_finite()) {
            self.reset();
            return next;
        }
        let reg = 1e-10 * trace.max(dot(g, g));
        for i in 0..m {
            a[i * m + i] += reg;
        }
        let Some(gamma) = crate::dense::solve_pivoted(&mut a, &mut b, m, 0.0) else {
            self.reset();
            return next;
        };
        for (j, gj) in gamma.iter().enumerate() {
            for (n, d) in next.iter_mut().zip(&self.df[j]) {
                *n -= gj * d;
            }
        }
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The update recomputed from scratch each step (every Gram entry anew), as before the
    /// Gram rows were kept: the kept rows must give the same bits.
    fn reference_step(dg: &[Vec<f64>], df: &[Vec<f64>], g: &[f64], f: &[f64]) -> Vec<f64> {
        let m = dg.len();
        let mut next = f.to_vec();
        if m == 0 {
            return next;
        }
        let mut a = vec![0.0; m * m];
        let mut b = vec![0.0; m];
        for i in 0..m {
            for j in 0..=i {
                let v = dot(&dg[i], &dg[j]);
                a[i * m + j] = v;
                a[j * m + i] = v;
            }
            b[i] = dot(&dg[i], g);
        }
        let trace: f64 = (0..m).map(|i| a[i * m + i]).sum();
        let reg = 1e-10 * trace.max(dot(g, g));
        for i in 0..m {
            a[i * m + i] += reg;
        }
        let gamma = crate::dense::solve_pivoted(&mut a, &mut b, m, 0.0).unwrap();
        for (j, gj) in gamma.iter().enumerate() {
            for (n, d) in next.iter_mut().zip(&df[j]) {
                *n -= gj * d;
            }
        }
        next
    }

    #[test]
    fn kept_gram_rows_give_the_recomputed_update_and_solve_a_linear_map() {
        // x -> T x = M x + c, contractive and non-symmetric, n = 40.
        let n = 40;
        let mat = |i: usize, j: usize| {
            if i == j {
                0.9 - 0.01 * i as f64
            } else {
                0.02 * (((i * 31 + j * 17) % 11) as f64 - 5.0) / 5.0
            }
        };
        let c: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let map = |x: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| c[i] + (0..n).map(|j| mat(i, j) * x[j]).sum::<f64>())
                .collect()
        };
        let depth = 4;
        let mut and = Anderson::new(depth);
        let (mut dg, mut df): (Vec<Vec<f64>>, Vec<Vec<f64>>) = (Vec::new(), Vec::new());
        let mut prev: Option<(Vec<f64>, Vec<f64>)> = None;
        let mut x = vec![0.0; n];
        for _ in 0..40 {
            let f = map(&x);
            let g: Vec<f64> = f.iter().zip(&x).map(|(a, b)| a - b).collect();
            if let Some((g0, f0)) = prev.take() {
                dg.push(g.iter().zip(&g0).map(|(a, b)| a - b).collect());
                df.push(f.iter().zip(&f0).map(|(a, b)| a - b).collect());
                if dg.len() > depth {
                    dg.remove(0);
                    df.remove(0);
                }
            }
            prev = Some((g.clone(), f.clone()));
            let expected = reference_step(&dg, &df, &g, &f);
            let next = and.step(&x, &f);
            assert!(
                next.iter()
                    .zip(&expected)
                    .all(|(p, q)| p.to_bits() == q.to_bits())
            );
            x = next;
        }
        // And it accelerates: after 40 steps its fixed-point residual is far below that of 40
        // plain steps (contraction about 0.9 per step).
        let residual = |x: &[f64]| -> f64 {
            map(x)
                .iter()
                .zip(x)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        let mut plain = vec![0.0; n];
        for _ in 0..40 {
            plain = map(&plain);
        }
        let (r, r_plain) = (residual(&x), residual(&plain));
        assert!(r < 1e-8 && r < 1e-5 * r_plain, "{r} vs plain {r_plain}");
    }
}
