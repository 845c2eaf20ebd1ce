//! The interpolant one level coarser than a stochastic mesh: on each leaf `L` with parent cell
//! `P`, the multilinear interpolant over `P` of the mesh's own values at the `2^d` corners of
//! `P`,
//!
//! ```text
//! q~_P(xi) = sum_{c in corners(P)} phi^P_c(xi) q~(c),    xi in L,
//! ```
//!
//! (a root leaf is its own parent). `q~ - q~_P` is the hierarchical surplus of the last
//! refinement of every leaf: it vanishes where `q~` is multilinear over the parent, and its
//! size on a leaf measures what that leaf's refinement changed. The error budget of an
//! adaptive method compares with it, and the goal-oriented adaptive loop refines where it is
//! largest (crate `alea-study`).
//!
//! [`ParentLevel::coarsenable`] merges only the **coarsenable** families, those whose children
//! are all leaves (the coarsening of adaptive mesh refinement: a cell can be un-split only when
//! none of its children is split), and every other leaf stands for itself. On a uniform grid
//! refined once everywhere it is the grid before that refinement; on an adaptive mesh it undoes
//! the last refinement of each region. [`ParentLevel::new`] also replaces a leaf whose sibling
//! was refined further by the parent's interpolant, whose corners then straddle what the
//! sibling resolved (a kink, a contact threshold): measured on a 1D contact threshold (8 runs
//! from 3), its difference from the mesh was 60 - 120x the mesh's true error of the mean and
//! the standard deviation, the coarsenable level's 2 - 5x (the error budget uses the latter).

use super::*;

/// [`StochasticMesh`] one level coarser (a [`LinearSurrogate`] on the same runs).
#[derive(Debug, Clone)]
pub struct ParentLevel {
    mesh: StochasticMesh,
    /// Parent of each cell (`None` for roots).
    parent: Vec<Option<CellId>>,
}

impl ParentLevel {
    /// The coarser interpolant of `mesh`.
    pub fn new(mesh: StochasticMesh) -> Self {
        let mut parent = vec![None; mesh.cells.len()];
        for (c, cell) in mesh.cells.iter().enumerate() {
            if let Some(first) = cell.first_child {
                let n = 1usize << mesh.split_mask[c].count_ones();
                for p in parent.iter_mut().skip(first).take(n) {
                    *p = Some(c);
                }
            }
        }
        ParentLevel { mesh, parent }
    }

    /// The interpolant one level coarser where the mesh can be coarsened: every family whose
    /// children are all leaves is replaced by its parent's interpolant, every other leaf is
    /// kept (its own "parent").
    pub fn coarsenable(mesh: StochasticMesh) -> Self {
        let mut level = Self::new(mesh);
        for c in 0..level.mesh.cells.len() {
            let Some(first) = level.mesh.cells[c].first_child else {
                continue;
            };
            let n = 1usize << level.mesh.split_mask[c].count_ones();
            let all_leaves = (first..first + n).all(|k| level.mesh.cells[k].first_child.is_none());
            if !all_leaves {
                for p in level.parent.iter_mut().skip(first).take(n) {
                    *p = None;
                }
            }
        }
        level
    }

    /// The fine mesh.
    pub fn mesh(&self) -> &StochasticMesh {
        &self.mesh
    }

    /// The cell whose multilinear interpolant stands for leaf `leaf` (its parent, or itself
    /// for a root and, in [`ParentLevel::coarsenable`], for a leaf whose family is not
    /// coarsenable).
    pub fn coarse_cell(&self, leaf: CellId) -> CellId {
        self.parent[leaf].unwrap_or(leaf)
    }
}

impl LinearSurrogate for ParentLevel {
    fn dim(&self) -> usize {
        self.mesh.d
    }

    fn num_runs(&self) -> usize {
        self.mesh.num_runs()
    }

    /// Weights of `q~_P(xi)`: the fine weights at the parent's corners, combined with the
    /// parent's hat functions (each run once; empty outside the box).
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let d = self.mesh.d;
        let Some(leaf) = self.mesh.locate(xi) else {
            return;
        };
        let p = self.coarse_cell(leaf);
        let (lo, hi) = self.mesh.cell_bounds(p);
        let mut t = [0.0; MAX_DIM];
        for j in 0..d {
            t[j] = ((xi[j] - lo[j]) / (hi[j] - lo[j])).clamp(0.0, 1.0);
        }
        let mut phi = [0.0; 1 << MAX_DIM];
        self.mesh.corner_phi(&t[..d], &mut phi);
        let mut corner = vec![0.0; d];
        let mut wc = Vec::new();
        for (c, &ph) in phi.iter().enumerate().take(1 << d) {
            if ph == 0.0 {
                continue;
            }
            for j in 0..d {
                corner[j] = if (c >> j) & 1 == 1 { hi[j] } else { lo[j] };
            }
            self.mesh.weights(&corner, &mut wc);
            for &(k, wk) in &wc {
                match w.iter_mut().find(|(r, _)| *r == k) {
                    Some(e) => e.1 += ph * wk,
                    None => w.push((k, ph * wk)),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One level coarser than the start mesh (the box's corners and centre) is the box's
    /// multilinear interpolant of its corners: exact for multilinear responses, and differs
    /// from the fine mesh by the centre's surplus times the centre's hat function.
    #[test]
    fn parent_level_of_the_start_mesh_is_the_corner_interpolant() {
        let mut mesh = StochasticMesh::new(&[0.0, -1.0], &[2.0, 1.0], &[1, 1]).unwrap();
        mesh.refine_centred(&[0]).unwrap();
        assert_eq!(mesh.num_runs(), 5);
        let f = |x: &[f64]| 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[0] * x[1] + 3.0 * x[0] * x[0];
        let values: Vec<f64> = (0..5).map(|k| f(mesh.run_point(k))).collect();
        let bilinear = |x: &[f64]| {
            // Corner interpolant of f on [0, 2] x [-1, 1].
            let (s, u) = (x[0] / 2.0, (x[1] + 1.0) / 2.0);
            let c = |a: f64, b: f64| f(&[a, b]);
            (1.0 - s) * (1.0 - u) * c(0.0, -1.0)
                + s * (1.0 - u) * c(2.0, -1.0)
                + (1.0 - s) * u * c(0.0, 1.0)
                + s * u * c(2.0, 1.0)
        };
        let coarse = ParentLevel::new(mesh.clone());
        let surplus = values[4] - bilinear(&[1.0, 0.0]);
        assert!(surplus.abs() > 1.0);
        for &(x, y) in &[(0.3, -0.7), (1.0, 0.0), (1.9, 0.9), (0.5, 0.5)] {
            let xi = [x, y];
            let got = coarse.eval(&xi, &values);
            assert!((got - bilinear(&xi)).abs() < 1e-12, "{xi:?}: {got}");
            // Fine minus coarse: the centre's surplus times its hat function.
            let hat = (1.0 - (x - 1.0).abs()) * (1.0 - y.abs());
            let diff = mesh.interpolate(&xi, &values) - got;
            assert!((diff - surplus * hat).abs() < 1e-12, "{xi:?}: {diff}");
        }
    }

    /// Coarsenable families only: on a mesh whose first child was refined again, that child's
    /// family is merged (the surrogate there is the child's corner interpolant) and the
    /// root's family is not (the other three children keep the fine interpolant), where
    /// [`ParentLevel::new`] replaces those three by the root's corner interpolant.
    #[test]
    fn coarsenable_level_merges_only_families_of_leaves() {
        let mut mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 1.0], &[1, 1]).unwrap();
        mesh.refine_centred(&[0]).unwrap();
        let first = mesh.cells[0].first_child.unwrap();
        // The child at the origin (index 0 in the family: no direction bit set).
        mesh.refine_centred(&[first]).unwrap();
        let f = |x: &[f64]| (3.0 * x[0]).sin() + x[1] * x[1] + 0.5 * x[0] * x[1];
        let values: Vec<f64> = (0..mesh.num_runs()).map(|k| f(mesh.run_point(k))).collect();
        let coarsenable = ParentLevel::coarsenable(mesh.clone());
        let full = ParentLevel::new(mesh.clone());
        // The corner interpolant of the mesh's values over a cell.
        let corner_interp = |lo: [f64; 2], hi: [f64; 2], x: &[f64]| {
            let s = (x[0] - lo[0]) / (hi[0] - lo[0]);
            let u = (x[1] - lo[1]) / (hi[1] - lo[1]);
            let c = |a: f64, b: f64| mesh.interpolate(&[a, b], &values);
            (1.0 - s) * (1.0 - u) * c(lo[0], lo[1])
                + s * (1.0 - u) * c(hi[0], lo[1])
                + (1.0 - s) * u * c(lo[0], hi[1])
                + s * u * c(hi[0], hi[1])
        };
        for &(x, y) in &[(0.1, 0.2), (0.3, 0.4), (0.7, 0.2), (0.2, 0.8), (0.9, 0.6)] {
            let xi = [x, y];
            let fine = mesh.interpolate(&xi, &values);
            let got = coarsenable.eval(&xi, &values);
            let whole = full.eval(&xi, &values);
            if x < 0.5 && y < 0.5 {
                let want = corner_interp([0.0, 0.0], [0.5, 0.5], &xi);
                assert!((got - want).abs() < 1e-12, "{xi:?}: {got} vs {want}");
                assert!((got - fine).abs() > 1e-6, "{xi:?}: merged family unchanged");
            } else {
                assert!((got - fine).abs() < 1e-12, "{xi:?}: {got} vs {fine}");
                let root = corner_interp([0.0, 0.0], [1.0, 1.0], &xi);
                assert!((whole - root).abs() < 1e-12, "{xi:?}: {whole} vs {root}");
                assert!((whole - fine).abs() > 1e-6, "{xi:?}");
            }
        }
    }
}
