//! A Cholesky factor stored in single precision, with the matrix kept in double precision for
//! iterative refinement (issue 38): half the memory of the factor, and triangular solves that
//! read half the bytes. A 3D substructure's solve is bound by memory traffic (its factor has
//! ~500 entries per row), so an `f32` solve takes 0.4 - 0.5x the time of the `f64` one
//! (`cargo bench -p alea-fem --bench multi_rhs`, BENCHMARKS.md).
//!
//! # Equations
//! With `L~` the factor `L` of `A = L L^T` rounded to `f32` and `A~ = L~ L~^T`, mixed-precision
//! iterative refinement (Wilkinson; Higham, *Accuracy and Stability of Numerical Algorithms*,
//! ch. 12) solves `A x = b` by
//!
//! ```text
//! x_0 = 0,   r_k = b - A x_k  (f64),   x_{k+1} = x_k + A~^{-1} r_k  (f32 solve),
//! ```
//!
//! whose error contracts by `delta = |I - A~^{-1} A| ~ c eps_32 kappa(A)` per step, to the
//! level `~ eps_64 kappa(A)` of the `f64` residual. Each correction `A~^{-1} r` is solved on the
//! residual scaled by its largest entry, so `f32`'s range never over- or underflows.
//!
//! * [`SingleFactor::solve`]: refinement until the next correction, predicted from the last
//!   one and its contraction, is below `REFINE_TOL` of the solution, or the corrections stop
//!   shrinking (the `f64` floor), or `MAX_STEPS`;
//! * [`SingleFactor::solve_near`]: **one** step from a nearby solution `x_prev` (the previous
//!   iterate of an outer fixed-point iteration, the LATIN method's linear stage):
//!   `x = x_prev + A~^{-1} (b - A x_prev)`, whose error is `delta |A^{-1} b - x_prev|`. In an
//!   iteration whose right-hand sides converge, the error of step `n` is
//!   `e_n = (I - A~^{-1} A) (u*_n - u*_{n-1} + e_{n-1})`, bounded by `delta / (1 - delta)` times
//!   the largest change `|u*_n - u*_{n-1}|`: it does not accumulate, and it vanishes with the
//!   changes as the iteration converges.
//!
//! A factor is stored in single precision only if the refinement contracts by at most
//! `MAX_RATE` per step on a test solve ([`SingleFactor::new`]); otherwise (`kappa(A)` beyond
//! about 1e5) it stays in double precision.
//!
//! Written here: faer solves with an `f32` factor, but has no refinement driver for a sparse
//! symmetric matrix stored by its upper triangle, nor a one-step variant.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{LltRef, SymbolicCholesky};
use faer::{Conj, MatMut, Par};

use crate::SymCsc;

/// Refinement stops when every column's next correction is predicted below this fraction of
/// its solution.
const REFINE_TOL: f64 = 1e-13;

/// At most this many corrections after the first solve.
const MAX_STEPS: usize = 12;

/// A factor is stored in single precision only if the refinement contracts by at most this
/// factor per step (module doc).
pub(crate) const MAX_RATE: f64 = 1e-2;

/// The upper triangle of `A` in compressed columns with 32-bit indices: 12 bytes an entry.
struct CompactSym {
    col_ptr: Vec<u32>,
    row_idx: Vec<u32>,
    values: Vec<f64>,
}

impl CompactSym {
    /// `None` if `a` has more than `u32::MAX` entries or a column without its diagonal entry
    /// last (the layout of [`SymCsc::from_couplings`]).
    fn new(a: &SymCsc) -> Option<Self> {
        let diagonal_last = (0..a.n)
            .all(|j| a.col_ptr[j + 1] > a.col_ptr[j] && a.row_idx[a.col_ptr[j + 1] - 1] == j);
        if !diagonal_last {
            return None;
        }
        let fits = |v: usize| u32::try_from(v).ok();
        Some(CompactSym {
            col_ptr: a.col_ptr.iter().map(|&p| fits(p)).collect::<Option<_>>()?,
            row_idx: a.row_idx.iter().map(|&i| fits(i)).collect::<Option<_>>()?,
            values: a.values.clone(),
        })
    }

    /// `r_c -= A x_c` for the columns `x[c]` of `x` (`r`: as many columns of `n`, holding `b`
    /// on entry, the residual on exit): one pass over `A` per group of up to 4 columns.
    fn subtract_product(&self, x: &[&[f64]], r: &mut [f64], n: usize) {
        for (xs, rs) in x.chunks(4).zip(r.chunks_mut(4 * n)) {
            match xs.len() {
                1 => self.subtract_group::<1>([xs[0]], rs, n),
                2 => self.subtract_group::<2>([xs[0], xs[1]], rs, n),
                3 => self.subtract_group::<3>([xs[0], xs[1], xs[2]], rs, n),
                _ => self.subtract_group::<4>([xs[0], xs[1], xs[2], xs[3]], rs, n),
            }
        }
    }

    /// `r_c -= A x_c` for `W` columns. Rows are sorted in each column of the upper triangle,
    /// so the diagonal is the column's last entry.
    fn subtract_group<const W: usize>(&self, x: [&[f64]; W], r: &mut [f64], n: usize) {
        for j in 0..n {
            let (p0, p1) = (self.col_ptr[j] as usize, self.col_ptr[j + 1] as usize);
            if p0 == p1 {
                continue;
            }
            let xj: [f64; W] = std::array::from_fn(|c| x[c][j]);
            let mut rj = [0.0; W];
            for p in p0..p1 - 1 {
                let i = self.row_idx[p] as usize;
                let v = self.values[p];
                for c in 0..W {
                    r[c * n + i] -= v * xj[c];
                    rj[c] += v * x[c][i];
                }
            }
            let d = self.values[p1 - 1];
            for c in 0..W {
                r[c * n + j] -= rj[c] + d * xj[c];
            }
        }
    }

    fn bytes(&self) -> usize {
        4 * (self.col_ptr.len() + self.row_idx.len()) + 8 * self.values.len()
    }
}

/// Work space of the refinement, grown on demand (kept in [`crate::SolveScratch`]).
#[derive(Default)]
pub(crate) struct RefineWork {
    correction: Vec<f32>,
    b: Vec<f64>,
    r: Vec<f64>,
}

/// The factor of [`crate::Cholesky`] in single precision with `A` for the refinement.
pub(crate) struct SingleFactor {
    values: Vec<f32>,
    matrix: CompactSym,
    /// Contraction per refinement step measured on the test solve.
    rate: f64,
}

impl SingleFactor {
    /// The factor `l_values` (of `a`, with `symbolic`) rounded to `f32`, if its refinement
    /// contracts by at most [`MAX_RATE`] on a test solve with a known solution; `None`
    /// otherwise (or if `a` is empty or has more than `u32::MAX` entries).
    pub(crate) fn new(
        symbolic: &SymbolicCholesky<usize>,
        l_values: &[f64],
        a: &SymCsc,
        stack: &mut MemBuffer,
    ) -> Option<Self> {
        let n = a.n;
        if n == 0 {
            return None;
        }
        let single = SingleFactor {
            values: l_values.iter().map(|&v| v as f32).collect(),
            matrix: CompactSym::new(a)?,
            rate: 0.0,
        };
        // A smooth and a rough component, so that both ends of the spectrum are excited.
        let x_true: Vec<f64> = (0..n)
            .map(|i| 1.0 + 0.5 * ((i * 7919) % 1013) as f64 / 1013.0)
            .collect();
        let mut b = vec![0.0; n];
        a.mul_vec(&x_true, &mut b);
        let mut work = RefineWork::default();
        let mut x = b.clone();
        let corrections = single.solve(symbolic, &mut x, n, 1, stack, &mut work);
        // The first correction's size is the initial error, `delta |x|` (module doc).
        let rate = corrections.first().copied().unwrap_or(0.0);
        let scale = x_true.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = x
            .iter()
            .zip(&x_true)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        (rate <= MAX_RATE && err <= 1e-8 * scale).then_some(SingleFactor { rate, ..single })
    }

    /// Contraction per refinement step measured at construction.
    pub(crate) fn rate(&self) -> f64 {
        self.rate
    }

    /// Bytes of the factor and the kept matrix.
    pub(crate) fn bytes(&self) -> usize {
        4 * self.values.len() + self.matrix.bytes()
    }

    /// One refinement step from `previous` (one slice per column):
    /// `rhs <- previous + A~^{-1} (rhs - A previous)`.
    pub(crate) fn solve_near(
        &self,
        symbolic: &SymbolicCholesky<usize>,
        rhs: &mut [f64],
        previous: &[&[f64]],
        n: usize,
        stack: &mut MemBuffer,
        work: &mut RefineWork,
    ) {
        self.matrix.subtract_product(previous, rhs, n);
        self.correct(
            symbolic,
            rhs,
            n,
            previous.len(),
            stack,
            &mut work.correction,
        );
        for (r, x) in rhs.chunks_exact_mut(n).zip(previous) {
            for (ri, xi) in r.iter_mut().zip(*x) {
                *ri += xi;
            }
        }
    }

    /// `A x = b` for the columns of `x` (holding `b` on entry) to full accuracy by the
    /// refinement loop (module doc); returns the largest relative correction of each step.
    pub(crate) fn solve(
        &self,
        symbolic: &SymbolicCholesky<usize>,
        x: &mut [f64],
        n: usize,
        ncols: usize,
        stack: &mut MemBuffer,
        work: &mut RefineWork,
    ) -> Vec<f64> {
        let RefineWork { correction, b, r } = work;
        b.clear();
        b.extend_from_slice(x);
        self.correct(symbolic, x, n, ncols, stack, correction);
        r.resize(x.len(), 0.0);
        let mut sizes = Vec::new();
        // The relative size of each column's last correction (the first solve: 1).
        let mut previous = vec![1.0; ncols];
        for _ in 0..MAX_STEPS {
            r.copy_from_slice(b);
            let columns: Vec<&[f64]> = x.chunks_exact(n).collect();
            self.matrix.subtract_product(&columns, r, n);
            self.correct(symbolic, r, n, ncols, stack, correction);
            let mut done = true;
            let mut largest = 0.0f64;
            for c in 0..ncols {
                let (xc, dc) = (&mut x[c * n..(c + 1) * n], &r[c * n..(c + 1) * n]);
                let size = dc.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (xi, di) in xc.iter_mut().zip(dc) {
                    *xi += di;
                }
                let scale = xc.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let relative = if scale > 0.0 { size / scale } else { 0.0 };
                largest = largest.max(relative);
                // Done when the next correction, shrunk by this step's contraction, would be
                // below the tolerance, or at the level of the f64 residual (no longer
                // shrinking).
                let contraction = relative / previous[c];
                if relative * contraction > REFINE_TOL && contraction < 0.5 {
                    done = false;
                }
                previous[c] = relative;
            }
            sizes.push(largest);
            if done {
                break;
            }
        }
        sizes
    }

    /// `v <- A~^{-1} v` column by column scaled into `f32` and back.
    fn correct(
        &self,
        symbolic: &SymbolicCholesky<usize>,
        v: &mut [f64],
        n: usize,
        ncols: usize,
        stack: &mut MemBuffer,
        buf: &mut Vec<f32>,
    ) {
        buf.resize(n * ncols, 0.0);
        let mut scales = Vec::with_capacity(ncols);
        for (vc, bc) in v.chunks_exact(n).zip(buf.chunks_exact_mut(n)) {
            let s = vc.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let inv = if s > 0.0 { 1.0 / s } else { 0.0 };
            for (b, x) in bc.iter_mut().zip(vc) {
                *b = (x * inv) as f32;
            }
            scales.push(s);
        }
        let req = symbolic.solve_in_place_scratch::<f32>(ncols, Par::Seq);
        if req.size_bytes() > stack.len() {
            *stack = MemBuffer::new(req);
        }
        let llt = LltRef::<usize, f32>::new(symbolic, &self.values);
        let mat = MatMut::from_column_major_slice_mut(buf, n, ncols);
        llt.solve_in_place_with_conj(Conj::No, mat, Par::Seq, MemStack::new(stack));
        for ((vc, bc), s) in v.chunks_exact_mut(n).zip(buf.chunks_exact(n)).zip(scales) {
            for (x, b) in vc.iter_mut().zip(bc) {
                *x = f64::from(*b) * s;
            }
        }
    }
}
