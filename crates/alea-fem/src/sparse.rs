//! Symmetric sparse matrices stored as the upper triangle in compressed sparse columns.
//!
//! The pattern is built once from a graph of blocks (mesh nodes, each carrying some dofs);
//! values are then accumulated by [`SymCsc::add`] (binary search in a column) and can be reset
//! and re-assembled on the same pattern, or combined (`K + k M`) value by value.

/// Upper-triangular CSC storage of a symmetric matrix (`row <= col` in every entry).
#[derive(Clone, Debug)]
pub struct SymCsc {
    /// Order of the matrix.
    pub n: usize,
    /// Column pointers (`n + 1`).
    pub col_ptr: Vec<usize>,
    /// Row indices, sorted within each column.
    pub row_idx: Vec<usize>,
    /// Values, aligned with `row_idx`.
    pub values: Vec<f64>,
}

impl SymCsc {
    /// Builds the pattern from, for every dof, the sorted set of dofs it couples to (any order
    /// within; only `row <= col` entries are kept). Values are zero.
    pub fn from_couplings(n: usize, couplings: impl Fn(usize, &mut Vec<usize>)) -> Self {
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        let mut buf = Vec::new();
        for j in 0..n {
            buf.clear();
            couplings(j, &mut buf);
            buf.retain(|&i| i <= j);
            buf.push(j);
            buf.sort_unstable();
            buf.dedup();
            row_idx.extend_from_slice(&buf);
            col_ptr.push(row_idx.len());
        }
        let nnz = row_idx.len();
        SymCsc {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
        }
    }

    /// Position of entry `(i, j)` (`i <= j`) in `values`, if in the pattern.
    #[inline]
    pub fn position(&self, i: usize, j: usize) -> Option<usize> {
        let (i, j) = if i <= j { (i, j) } else { (j, i) };
        let rows = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
        rows.binary_search(&i).ok().map(|p| self.col_ptr[j] + p)
    }

    /// Adds `v` to entry `(i, j)` (either triangle; the upper one is stored).
    ///
    /// # Panics
    /// If the entry is not in the pattern (a programming error in the caller's pattern).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let p = self
            .position(i, j)
            .unwrap_or_else(|| panic!("entry ({i}, {j}) not in the sparse pattern"));
        self.values[p] += v;
    }

    /// Scatters a dense symmetric block `ke` (row-major, `dofs.len()^2`) at `dofs`; entries
    /// with a dof equal to `usize::MAX` (eliminated) are skipped.
    ///
    /// # Panics
    /// If an entry is not in the pattern.
    pub fn add_block(&mut self, dofs: &[usize], ke: &[f64]) {
        let m = dofs.len();
        for (q, &gj) in dofs.iter().enumerate() {
            if gj == usize::MAX {
                continue;
            }
            let start = self.col_ptr[gj];
            let rows = &self.row_idx[start..self.col_ptr[gj + 1]];
            // The dofs of a node are consecutive, so the next row is usually the next entry
            // of the column: try it before a binary search.
            let mut next = usize::MAX;
            for (p, &gi) in dofs.iter().enumerate() {
                if gi == usize::MAX || gi > gj {
                    continue;
                }
                let k = if rows.get(next) == Some(&gi) {
                    next
                } else {
                    rows.binary_search(&gi)
                        .unwrap_or_else(|_| panic!("entry ({gi}, {gj}) not in the sparse pattern"))
                };
                self.values[start + k] += ke[p * m + q];
                next = k + 1;
            }
        }
    }

    /// `y = A x` using both triangles.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for j in 0..self.n {
            for p in self.col_ptr[j]..self.col_ptr[j + 1] {
                let i = self.row_idx[p];
                let v = self.values[p];
                y[i] += v * x[j];
                if i != j {
                    y[j] += v * x[i];
                }
            }
        }
    }

    /// Diagonal entries.
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.n)
            .map(|j| self.values[self.col_ptr[j + 1] - 1])
            .collect()
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
}
