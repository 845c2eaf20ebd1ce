//! Sparse Cholesky factorisation `A = L L^T` of a symmetric positive definite [`SymCsc`], with
//! faer's sparse Cholesky: supernodal for dense factors (3D), simplicial (column by column) for
//! sparse ones (2D substructures), whose triangular solves with several right-hand sides use
//! the row-interleaved kernel of module `simplicial` (bitwise faer's own solve, column by
//! column; `SUPERNODAL_FLOPS_PER_ENTRY` says where the line is and why).
//!
//! The symbolic analysis (fill-reducing ordering + elimination structure) is done once in
//! [`Cholesky::new`]; [`Cholesky::factorize`] computes the numeric factor in a buffer owned by
//! the solver and can be called again with new values on the same pattern (a refactorisation
//! allocates nothing). Ordering: nested dissection by METIS (vendored C library, built by the
//! `metis-sys` crate; no system library) on the graph of dof blocks (mesh nodes), expanded to
//! dofs, or faer's AMD. For 3D meshes METIS is about 3x faster and needs half the memory of AMD.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

use crate::simplicial::SimplicialFactor;
use crate::single::{RefineWork, SingleFactor};
use crate::{FemError, SymCsc};

/// Pivots with `L_jj^2 < SINGULAR_PIVOT_RATIO * A_jj` mean a numerically singular stiffness
/// matrix. Measured: a free rigid-body mode gives 1e-15 (30 dofs) to 1.4e-13 (20k dofs); a sound
/// 200:1 cantilever with a 1000:1 stiffness contrast gives 3e-10, ordinary models 1e-2 or more.
const SINGULAR_PIVOT_RATIO: f64 = 1e-11;

/// Fill-reducing ordering.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordering {
    /// METIS nested dissection on the block graph (default).
    Metis,
    /// faer's approximate minimum degree.
    Amd,
    /// No reordering (tests only).
    Identity,
}

/// [`FactorKind::Auto`] stores a factor in supernodes when its factorisation needs more than
/// this many flops per factor entry (faer's measure, `sum_j (c_j + c_j (c_j + 1) / 2) / sum_j
/// c_j` with `c_j` the entries of column `j` of `L`; faer's own default is 40). Measured
/// (`cargo bench -p alea-fem --bench multi_rhs` and `-p alea-study --bench batch_turbine`, one
/// thread): the 2D turbine's substructures (5 200 - 5 800 dof, Quad8) have 37 - 45 flops per
/// entry, a 5 460-dof Quad8 rectangle 45, a 21 500-dof one 70, a 57 000-dof Hex8 box 728. With
/// the row-interleaved solves of module `simplicial`, a simplicial factor solves 8 right-hand
/// sides at 0.19x (5 460 dof) and 0.23x (21 500 dof) of a single solve per column, against
/// 0.39x / 0.56x (per column: 0.056 against 0.099 ms, 0.37 against 0.77 ms) for faer's
/// supernodal kernels (the 2D turbine's batched iteration: 0.29x of a run alone, against 0.50x
/// with faer's choice of kinds). A single simplicial solve takes 10 % longer at 5 460 dof
/// (0.284 against 0.257 ms) but 25 % longer at 21 500 (1.64 against 1.31 ms), and the
/// factorisation 3.5-4.5x longer: the line sits between them, so that the small 2D factors of
/// substructured models gain the batched solves while larger ones keep faer's single-solve
/// speed. 3D factors are far denser and stay supernodal.
const SUPERNODAL_FLOPS_PER_ENTRY: f64 = 50.0;

/// Storage of the factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FactorKind {
    /// Simplicial up to 50 flops per factor entry of the factorisation, supernodal above (the
    /// default of [`Cholesky::new`]; measurements in the source, `SUPERNODAL_FLOPS_PER_ENTRY`).
    Auto,
    /// Dense blocks of columns with a common pattern (BLAS-3 kernels).
    Supernodal,
    /// One sparse column at a time.
    Simplicial,
}

/// A symbolic + numeric sparse Cholesky factorisation.
pub struct Cholesky {
    n: usize,
    /// Shared by the factorisations of the same pattern ([`Cholesky::same_pattern`]).
    symbolic: std::sync::Arc<SymbolicCholesky<usize>>,
    /// The factor's values in double precision (empty when stored in single precision).
    l_values: Vec<f64>,
    /// The factor in single precision ([`Cholesky::store_single`]).
    single: Option<SingleFactor>,
    factorized: bool,
    stack: MemBuffer,
    /// Row-interleaved block of the simplicial solves of [`Cholesky::solve_in_place`].
    rows: Vec<f64>,
}

impl std::fmt::Debug for Cholesky {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cholesky")
            .field("n", &self.n)
            .field("len_l", &self.symbolic.len_val())
            .field("single", &self.single.is_some())
            .finish()
    }
}

/// METIS nested-dissection ordering of the block graph; returns `(perm_fwd, perm_inv)` on dofs.
/// The CSR arrays `(xadj, adjncy)` METIS reads, from adjacency lists (sorted and
/// deduplicated here; no self loops).
pub(crate) fn metis_graph(mut adj: Vec<Vec<i32>>) -> (Vec<i32>, Vec<i32>) {
    let mut xadj = Vec::with_capacity(adj.len() + 1);
    let mut adjncy = Vec::new();
    xadj.push(0i32);
    for l in adj.iter_mut() {
        l.sort_unstable();
        l.dedup();
        adjncy.extend_from_slice(l);
        xadj.push(adjncy.len() as i32);
    }
    (xadj, adjncy)
}

/// METIS keeps its random-number state in process globals: one call at a time (module
/// [`crate::partition`] too).
pub(crate) static METIS_LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn metis_order(a: &SymCsc, block_of_dof: &[usize]) -> Result<(Vec<usize>, Vec<usize>), FemError> {
    let n = a.n;
    let nb = block_of_dof.iter().map(|&b| b + 1).max().unwrap_or(0);
    let mut adj: Vec<Vec<i32>> = vec![Vec::new(); nb];
    for j in 0..n {
        for p in a.col_ptr[j]..a.col_ptr[j + 1] {
            let (bi, bj) = (block_of_dof[a.row_idx[p]], block_of_dof[j]);
            if bi != bj {
                adj[bi].push(bj as i32);
                adj[bj].push(bi as i32);
            }
        }
    }
    let (mut xadj, mut adjncy) = metis_graph(adj);
    let mut perm = vec![0i32; nb];
    let mut iperm = vec![0i32; nb];
    if nb > 1 {
        let mut nvtxs = nb as i32;
        let mut options = [0i32; metis_sys::METIS_NOPTIONS as usize];
        // SAFETY: METIS reads nvtxs/xadj/adjncy (valid CSR graph without self loops, sizes as
        // declared) and writes nb entries to perm and iperm; options is METIS_NOPTIONS long.
        // METIS keeps its random-number state in process globals: concurrent calls (several
        // substructures set up in parallel) would interleave it and give orderings, hence
        // rounding, that change from one run to the next. One call at a time; each call seeds
        // the generator itself, so the ordering is then reproducible.
        let _guard = METIS_LOCK.lock().unwrap_or_else(|e| e.into_inner());
        let status = unsafe {
            metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
            metis_sys::METIS_NodeND(
                &mut nvtxs,
                xadj.as_mut_ptr(),
                adjncy.as_mut_ptr(),
                std::ptr::null_mut(),
                options.as_mut_ptr(),
                perm.as_mut_ptr(),
                iperm.as_mut_ptr(),
            )
        };
        if status != metis_sys::rstatus_et_METIS_OK {
            return Err(FemError::Solver(format!(
                "METIS_NodeND failed with status {status}"
            )));
        }
    }
    // perm[new_block] = old_block. Expand to dofs in block order.
    let mut dofs_of_block: Vec<Vec<usize>> = vec![Vec::new(); nb];
    for (d, &b) in block_of_dof.iter().enumerate() {
        dofs_of_block[b].push(d);
    }
    let mut fwd = Vec::with_capacity(n);
    for &b in &perm {
        fwd.extend_from_slice(&dofs_of_block[b as usize]);
    }
    let mut inv = vec![0usize; n];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    Ok((fwd, inv))
}

impl Cholesky {
    /// Symbolic analysis of the pattern of `a`. `block_of_dof[d]` groups dofs that share a
    /// mesh node (used by the METIS ordering; pass `None` to treat each dof as its own block).
    pub fn new(
        a: &SymCsc,
        ordering: Ordering,
        block_of_dof: Option<&[usize]>,
    ) -> Result<Self, FemError> {
        Self::with_kind(a, ordering, block_of_dof, FactorKind::Auto)
    }

    /// [`Cholesky::new`] with the factor's storage chosen.
    pub fn with_kind(
        a: &SymCsc,
        ordering: Ordering,
        block_of_dof: Option<&[usize]>,
        kind: FactorKind,
    ) -> Result<Self, FemError> {
        let n = a.n;
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &a.col_ptr, None, &a.row_idx);
        let perm_store;
        let ord = match ordering {
            Ordering::Amd => SymmetricOrdering::Amd,
            Ordering::Identity => SymmetricOrdering::Identity,
            Ordering::Metis => {
                let identity: Vec<usize>;
                let blocks = match block_of_dof {
                    Some(b) => b,
                    None => {
                        identity = (0..n).collect();
                        &identity
                    }
                };
                perm_store = metis_order(a, blocks)?;
                SymmetricOrdering::Custom(PermRef::new_checked(&perm_store.0, &perm_store.1, n))
            }
        };
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: match kind {
                // faer compares the flops per entry with 40 times its threshold.
                FactorKind::Auto => SupernodalThreshold(SUPERNODAL_FLOPS_PER_ENTRY / 40.0),
                FactorKind::Supernodal => SupernodalThreshold::FORCE_SUPERNODAL,
                FactorKind::Simplicial => SupernodalThreshold::FORCE_SIMPLICIAL,
            },
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(sym, Side::Upper, ord, params)
            .map_err(|e| FemError::Solver(format!("symbolic Cholesky failed: {e:?}")))?;
        let l_values = vec![0.0; symbolic.len_val()];
        let req = symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Ok(Cholesky {
            n,
            symbolic: std::sync::Arc::new(symbolic),
            l_values,
            single: None,
            factorized: false,
            stack: MemBuffer::new(req),
            rows: Vec::new(),
        })
    }

    /// A factorisation with this one's ordering and symbolic analysis, not yet factorised: for
    /// a matrix of the same pattern with other values ([`Cholesky::factorize`]), without
    /// ordering it again.
    pub fn same_pattern(&self) -> Cholesky {
        let req = self
            .symbolic
            .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
            .or(self.symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
        Cholesky {
            n: self.n,
            symbolic: self.symbolic.clone(),
            l_values: vec![0.0; self.symbolic.len_val()],
            single: None,
            factorized: false,
            stack: MemBuffer::new(req),
            rows: Vec::new(),
        }
    }

    /// Order of the matrix.
    pub fn n(&self) -> usize {
        self.n
    }

    /// True if the factor is stored in supernodes ([`FactorKind`]).
    pub fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
    }

    /// Number of stored entries of `L`.
    pub fn nnz_factor(&self) -> usize {
        self.symbolic.len_val()
    }

    /// True if the factor is stored in single precision ([`Cholesky::store_single`]).
    pub fn is_single(&self) -> bool {
        self.single.is_some()
    }

    /// Bytes of the factor's values (and, in single precision, of the matrix kept for the
    /// refinement).
    pub fn factor_bytes(&self) -> usize {
        match &self.single {
            Some(s) => s.bytes(),
            None => 8 * self.l_values.len(),
        }
    }

    /// Contraction per step of the single-precision refinement (module `single`),
    /// measured when the factor was stored so; `None` in double precision.
    pub fn refinement_rate(&self) -> Option<f64> {
        self.single.as_ref().map(SingleFactor::rate)
    }

    /// Stores the factor (of `a`, factorised) in single precision with `a` kept for the
    /// iterative refinement of every solve (module `single`): the solves of
    /// [`Cholesky::solve_with`] keep full accuracy, [`Cholesky::solve_near`] makes one step.
    /// Returns `false`, keeping double precision, when the refinement would contract by more
    /// than 1e-2 per step (`kappa(A)` beyond about 1e5) or `a` is too large for 32-bit indices.
    ///
    /// # Panics
    /// If not factorised or `a` is not the factorised matrix's size.
    pub fn store_single(&mut self, a: &SymCsc) -> bool {
        assert!(
            self.factorized,
            "store_single before a successful factorisation"
        );
        assert_eq!(a.n, self.n, "matrix size changed");
        if self.single.is_some() {
            return true;
        }
        let req = self.symbolic.solve_in_place_scratch::<f32>(1, Par::Seq);
        let mut stack = MemBuffer::new(req);
        match SingleFactor::new(&self.symbolic, &self.l_values, a, &mut stack) {
            Some(single) => {
                self.single = Some(single);
                self.l_values = Vec::new();
                true
            }
            None => false,
        }
    }

    /// Numeric factorisation of `a` (same pattern as at construction).
    ///
    /// # Errors
    /// [`FemError::NotPositiveDefinite`] if a pivot is not positive, or so small
    /// (`L_jj^2 < 1e-11 A_jj`) that the matrix is singular to working precision (e.g. a floating
    /// body: a rigid-body mode not removed by constraints).
    pub fn factorize(&mut self, a: &SymCsc) -> Result<(), FemError> {
        assert_eq!(a.n, self.n, "matrix size changed");
        let sym =
            SymbolicSparseColMatRef::new_checked(self.n, self.n, &a.col_ptr, None, &a.row_idx);
        let mat = SparseColMatRef::new(sym, &a.values);
        self.factorized = false;
        self.single = None;
        self.l_values.resize(self.symbolic.len_val(), 0.0);
        self.symbolic
            .factorize_numeric_llt(
                &mut self.l_values,
                mat,
                Side::Upper,
                LltRegularization::default(),
                Par::Seq,
                MemStack::new(&mut self.stack),
                Default::default(),
            )
            .map_err(|_| FemError::NotPositiveDefinite)?;
        // A rigid-body mode left free by the constraints makes A singular, but round-off
        // usually leaves a tiny *positive* pivot, so faer succeeds; catch it here.
        if self.min_pivot_ratio(a) < SINGULAR_PIVOT_RATIO {
            return Err(FemError::NotPositiveDefinite);
        }
        self.factorized = true;
        Ok(())
    }

    /// Smallest `L_jj^2 / A_jj` over the columns of the (permuted) factor: the fraction of a
    /// dof's own stiffness left after eliminating the dofs before it. About 1e-16 for a singular
    /// matrix (a free rigid-body mode), far larger for any constrained structure.
    fn min_pivot_ratio(&self, a: &SymCsc) -> f64 {
        let diag = a.diagonal();
        let fwd: Option<&[usize]> = self.symbolic.perm().map(|p| p.arrays().0);
        let ratio = |j: usize, l: f64| l * l / diag[fwd.map_or(j, |f| f[j])];
        let mut min = f64::INFINITY;
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(sym) => {
                let llt = SupernodalLltRef::<usize, f64>::new(sym, &self.l_values);
                for s in 0..sym.n_supernodes() {
                    let node = llt.supernode(s);
                    let v = node.val();
                    for c in 0..v.ncols() {
                        min = min.min(ratio(node.start() + c, v[(c, c)]));
                    }
                }
            }
            SymbolicCholeskyRaw::Simplicial(sym) => {
                let (cp, ri) = (sym.col_ptr(), sym.row_idx());
                for j in 0..self.n {
                    if let Some(p) = (cp[j]..cp[j + 1]).find(|&p| ri[p] == j) {
                        min = min.min(ratio(j, self.l_values[p]));
                    }
                }
            }
        }
        min
    }

    /// Solves `A x = b` in place for the columns of `rhs` (column-major, `n x ncols`).
    ///
    /// # Panics
    /// If not factorised, or if `rhs.len()` is not a multiple of `n`.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let stack = std::mem::replace(&mut self.stack, MemBuffer::new(StackReq::EMPTY));
        let mut scratch = SolveScratch {
            stack,
            rows: std::mem::take(&mut self.rows),
            refine: RefineWork::default(),
        };
        self.solve_with(rhs, &mut scratch);
        self.stack = scratch.stack;
        self.rows = scratch.rows;
    }
}

/// Scratch memory for [`Cholesky::solve_with`]: one per thread, so that one factorisation can
/// serve concurrent solves (faer's stack for supernodal solves, the row-interleaved block of a
/// simplicial one, the work space of a single-precision factor's refinement).
pub struct SolveScratch {
    stack: MemBuffer,
    rows: Vec<f64>,
    refine: RefineWork,
}

impl std::fmt::Debug for SolveScratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SolveScratch")
            .field("bytes", &self.stack.len())
            .finish()
    }
}

impl Cholesky {
    /// Scratch for solves with up to `ncols` right-hand sides.
    pub fn solve_scratch(&self, ncols: usize) -> SolveScratch {
        let req = match self.single {
            Some(_) => self
                .symbolic
                .solve_in_place_scratch::<f32>(ncols.max(1), Par::Seq),
            None => self
                .symbolic
                .solve_in_place_scratch::<f64>(ncols.max(1), Par::Seq),
        };
        SolveScratch {
            stack: MemBuffer::new(req),
            rows: Vec::new(),
            refine: RefineWork::default(),
        }
    }

    /// Solves `A x = b` in place like [`Cholesky::solve_in_place`], through a shared reference
    /// and caller-owned scratch (from [`Cholesky::solve_scratch`] with at least as many
    /// columns).
    ///
    /// # Panics
    /// If not factorised, or if `rhs.len()` is not a multiple of `n`.
    pub fn solve_with(&self, rhs: &mut [f64], scratch: &mut SolveScratch) {
        assert!(self.factorized, "solve before a successful factorisation");
        assert_eq!(rhs.len() % self.n.max(1), 0);
        let ncols = rhs.len() / self.n.max(1);
        if let Some(single) = &self.single {
            let SolveScratch { stack, refine, .. } = scratch;
            single.solve(&self.symbolic, rhs, self.n, ncols, stack, refine);
            return;
        }
        if let SymbolicCholeskyRaw::Simplicial(sym) = self.symbolic.raw() {
            let fwd = self.symbolic.perm().map(|p| p.arrays());
            let factor = SimplicialFactor {
                col_ptr: sym.col_ptr(),
                row_idx: sym.row_idx(),
                values: &self.l_values,
                perm: fwd,
            };
            factor.solve(rhs, self.n, ncols, &mut scratch.rows);
            return;
        }
        let req = self.symbolic.solve_in_place_scratch::<f64>(ncols, Par::Seq);
        if req.size_bytes() > scratch.stack.len() {
            scratch.stack = MemBuffer::new(req);
        }
        let llt = LltRef::new(&self.symbolic, &self.l_values);
        let mat = MatMut::from_column_major_slice_mut(rhs, self.n, ncols);
        llt.solve_in_place_with_conj(Conj::No, mat, Par::Seq, MemStack::new(&mut scratch.stack));
    }

    /// Solves `A x = b` for the columns of `rhs` (in place) knowing a nearby solution of each,
    /// `previous[c]`, for an outer iteration that converges: in double precision the solve of
    /// [`Cholesky::solve_with`], in single precision **one** refinement step from `previous`,
    /// `x = previous + A~^{-1} (b - A previous)`, whose error is about
    /// [`Cholesky::refinement_rate`] times `|x - previous|` (module `single`).
    ///
    /// # Panics
    /// If not factorised, or if `rhs` is not `previous.len()` columns of `n`, or a previous
    /// solution is not of length `n`.
    pub fn solve_near(&self, rhs: &mut [f64], previous: &[&[f64]], scratch: &mut SolveScratch) {
        let Some(single) = &self.single else {
            return self.solve_with(rhs, scratch);
        };
        assert!(self.factorized, "solve before a successful factorisation");
        assert_eq!(
            rhs.len(),
            self.n * previous.len(),
            "one previous solution per column"
        );
        assert!(
            previous.iter().all(|p| p.len() == self.n),
            "previous solution of another size"
        );
        let SolveScratch { stack, refine, .. } = scratch;
        single.solve_near(&self.symbolic, rhs, previous, self.n, stack, refine);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2D 5-point Laplacian on an `m x m` grid plus a varying diagonal (SPD).
    fn grid_matrix(m: usize) -> SymCsc {
        let n = m * m;
        let mut a = SymCsc::from_couplings(n, |j, rows| {
            let (x, y) = (j % m, j / m);
            if x > 0 {
                rows.push(j - 1);
            }
            if y > 0 {
                rows.push(j - m);
            }
            rows.push(j);
        });
        for j in 0..n {
            let (x, y) = (j % m, j / m);
            a.add(j, j, 4.0 + 0.01 * (j % 7) as f64);
            if x > 0 {
                a.add(j - 1, j, -1.0);
            }
            if y > 0 {
                a.add(j - m, j, -1.0);
            }
        }
        a
    }

    /// faer's own solve of the factor (the reference of the interleaved one).
    fn faer_solve(c: &mut Cholesky, rhs: &mut [f64]) {
        let ncols = rhs.len() / c.n;
        let req = c.symbolic.solve_in_place_scratch::<f64>(ncols, Par::Seq);
        let mut stack = MemBuffer::new(req);
        let llt = LltRef::new(&c.symbolic, &c.l_values);
        let mat = MatMut::from_column_major_slice_mut(rhs, c.n, ncols);
        llt.solve_in_place_with_conj(Conj::No, mat, Par::Seq, MemStack::new(&mut stack));
    }

    #[test]
    fn interleaved_solve_is_bitwise_faer() {
        let a = grid_matrix(23);
        let n = a.n;
        for ordering in [Ordering::Metis, Ordering::Amd, Ordering::Identity] {
            let mut c = Cholesky::with_kind(&a, ordering, None, FactorKind::Simplicial).unwrap();
            c.factorize(&a).unwrap();
            assert!(!c.is_supernodal());
            for ncols in [1usize, 2, 3, 5, 8, 11, 16] {
                let b: Vec<f64> = (0..n * ncols)
                    .map(|i| ((i * 7919) % 1013) as f64 / 1013.0 - 0.4)
                    .collect();
                let mut ours = b.clone();
                c.solve_in_place(&mut ours);
                let mut theirs = b.clone();
                faer_solve(&mut c, &mut theirs);
                assert!(
                    ours.iter()
                        .zip(&theirs)
                        .all(|(x, y)| x.to_bits() == y.to_bits()),
                    "{ordering:?}, {ncols} columns"
                );
                // And every column is the single-column solve.
                for j in 0..ncols {
                    let mut one = b[j * n..(j + 1) * n].to_vec();
                    c.solve_with(&mut one, &mut c.solve_scratch(1));
                    assert_eq!(one, ours[j * n..(j + 1) * n].to_vec());
                }
                // A solve, not a copy: the residual is at round-off.
                let mut ax = vec![0.0; n];
                a.mul_vec(&ours[..n], &mut ax);
                let r: f64 = ax.iter().zip(&b[..n]).map(|(p, q)| (p - q).powi(2)).sum();
                assert!(r.sqrt() < 1e-12 * (n as f64).sqrt());
            }
        }
    }

    #[test]
    fn supernodal_and_simplicial_agree() {
        let a = grid_matrix(30);
        let b: Vec<f64> = (0..a.n * 3).map(|i| (i % 17) as f64 - 8.0).collect();
        let mut x = Vec::new();
        for kind in [FactorKind::Simplicial, FactorKind::Supernodal] {
            let mut c = Cholesky::with_kind(&a, Ordering::Metis, None, kind).unwrap();
            c.factorize(&a).unwrap();
            assert_eq!(c.is_supernodal(), kind == FactorKind::Supernodal);
            let mut y = b.clone();
            c.solve_in_place(&mut y);
            x.push(y);
        }
        let d = x[0]
            .iter()
            .zip(&x[1])
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        let s = x[0].iter().map(|p| p.abs()).fold(0.0, f64::max);
        assert!(d < 1e-12 * s, "{d} vs {s}");
    }
}
