//! Piecewise multilinear interpolation on an adaptive stochastic mesh (thesis 1.2.2.4b and 4.2:
//! the "stochastic finite elements" refined by the adaptive loop).
//!
//! The parameter box `[lo, hi]` (`d <= 6`) is covered by a regular grid of root cells; each cell
//! can be split into `2^d` children (or along some directions only, see below). On a leaf cell `C` with local coordinates `t in [0, 1]^d`
//!
//! ```text
//! q~(xi) = sum_{c in corners(C)} phi_c(t) q(c),    phi_c(t) = prod_j (c_j ? t_j : 1 - t_j).
//! ```
//!
//! A mesh node is a **run** if it is a corner of every leaf whose closure contains it. Otherwise
//! it is a **hanging node**: it lies inside a face or edge of a coarser leaf `M` and its value is
//! `M`'s interpolant there, `q(p) = sum_c phi^M_c(p) q(c)`, resolved recursively down to runs.
//! This makes `q~` continuous. Hence the weights: `w_k(xi) = sum_c phi_c(t) W_{c,k}` with `W`
//! the resolved node-to-run matrix; the leaf has `2^d` corners, each resolved to runs. On a
//! 2:1-balanced mesh ([`StochasticMesh::refine_balanced`]: adjacent leaves differ by at most one
//! level) the weights involve at most `2^d` runs (tested for d = 2, 3); on strongly unbalanced
//! meshes ([`StochasticMesh::refine`]) a hanging node may resolve through several coarser levels
//! and a point can depend on more runs (up to 6 in 2D and 14 in 3D in the random stress test).
//!
//! **Centred refinement** ([`StochasticMesh::refine_centred`], the thesis's adaptive criteria
//! 4.2.2): a refined cell gets one run, its centre; the other new nodes are interpolated from the
//! cell for good (the thesis's structured stochastic mesh whose extra nodes are "interpolated,
//! not run"), so the surrogate changes only inside the cell, through the centre's hat function.
//! [`StochasticMesh::refine_at_point`] places one run at a dyadic point by splitting the leaves
//! around it with interpolated nodes only (the maximum-error criterion).
//!
//! **Anisotropic refinement** ([`StochasticMesh::refine_directions`]): a leaf is split only
//! along some directions (a mask), into `2^popcount` children, so a response that bends in some
//! parameters only (e.g. `P / E`, curved in `E`, linear in `P`) is refined like a
//! lower-dimensional interpolant. Cells then have a level per direction
//! ([`StochasticMesh::levels`]; [`StochasticMesh::level`] is their maximum) and a cell records the
//! mask it was split along (a child index packs one bit per split direction, in increasing
//! direction order). The runs are the split's centres (midpoint in the split directions, corner
//! values in the others), the other new nodes are interpolated from the cell for good. A centre
//! on the cell's boundary is made a corner of every leaf around it (leaves across that hold it
//! inside a face are split with interpolated nodes only). On a mesh with anisotropic cells two
//! more rules keep the surrogate continuous: an interpolated node inside a face of a leaf takes
//! that leaf's value (it hangs on it), and where the faces of two adjacent leaves cross (each
//! holds a point of their common boundary inside a face that does not contain the other's:
//! possible in 3D and above) the newer leaf is split, with interpolated nodes, until the point is
//! its corner. On meshes refined isotropically only, none of this applies and the results are
//! bit for bit those of the isotropic mesh.
//!
//! Refinement ([`StochasticMesh::refine`]) returns the nodes that became runs (new centre, face
//! and edge points shared with already refined neighbours or on the box boundary, and former
//! hanging nodes freed by the refinement): these need model runs. Runs are never removed and keep
//! their index, so run arrays only grow.
//!
//! The mesh can live on the physical box or on the probability-space cube `[0, 1]^d` (then
//! run the model at `x = T^-1(u)` from [`JointLaw::unit_to_x`](crate::joint::JointLaw::unit_to_x)
//! and evaluate at `u = T(x)`; the faces of the cube map to the bounds of the support, which must
//! then be finite, e.g. truncated normal laws). On the cube every cell's probability is its volume
//! (independent inputs) and `E[q~] = sum_k E[w_k] q_k` with `expected_weights(|_| 1.0, order)`.
//! Integer coordinates: a root cell spans `2^MAX_LEVEL` units, so node keys are exact.
//! Cell ids and run indices are deterministic: replaying the same sequence of refinement calls
//! (`refine`, `refine_centred`, `refine_directions`, ...) on a new mesh reproduces it exactly (a
//! store only needs the box, the root counts and the lists of refined cell ids, with their masks
//! for `refine_directions`).

use super::LinearSurrogate;
use crate::error::{Result, UqError, check_len, invalid};
use crate::joint::JointLaw;
use crate::quadrature::QuadratureRule;
use std::collections::HashMap;

mod locate;
mod parent;
mod refine;
mod weights;

pub use parent::ParentLevel;

/// Maximum refinement depth below a root cell.
pub const MAX_LEVEL: u32 = 24;
/// Maximum dimension.
pub const MAX_DIM: usize = 6;

type Key = [u64; MAX_DIM];

/// Index of a cell of the mesh (stable: cells are never removed).
pub type CellId = usize;

/// A node that became a run after a refinement.
#[derive(Debug, Clone, PartialEq)]
pub struct NewRun {
    /// Run index (position in the value arrays).
    pub run: usize,
    /// Coordinates of the point to run.
    pub point: Vec<f64>,
}

#[derive(Debug, Clone)]
struct Cell {
    origin: Key,
    /// Refinement level per direction (0 for root cells): the cell spans
    /// `2^(MAX_LEVEL - levels[j])` units in direction `j`.
    levels: [u32; MAX_DIM],
    /// Maximum of `levels` (the level of an isotropic cell).
    level: u32,
    first_child: Option<usize>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum NodeKind {
    Run(usize),
    /// Hanging, interpolated from this leaf cell (re-classified after every refinement).
    Hanging(usize),
    /// Interpolated for good from this (refined) cell: a node of a centred refinement
    /// ([`StochasticMesh::refine_centred`]) that the thesis fills by interpolation, not by a run.
    Fixed(usize),
}

/// Adaptive piecewise multilinear surrogate on a box.
#[derive(Debug, Clone)]
pub struct StochasticMesh {
    d: usize,
    lo: Vec<f64>,
    hi: Vec<f64>,
    roots: Vec<usize>,
    cells: Vec<Cell>,
    /// First child of each cell (`u32::MAX` for leaves): a compact copy of
    /// `Cell::first_child` for cache-friendly point location.
    child: Vec<u32>,
    /// Directions along which each cell was split (bit j: direction j; 0 for leaves). A child
    /// index packs one bit per split direction, in increasing direction order.
    split_mask: Vec<u8>,
    nodes: HashMap<Key, NodeKind>,
    run_keys: Vec<Key>,
    run_points: Vec<f64>,
    /// Per cell (valid for leaves): range in `terms`.
    leaf_terms: Vec<(u32, u32)>,
    /// `(corner, run, coefficient)` triples.
    terms: Vec<(u8, u32, f64)>,
    num_leaves: usize,
    /// Some cell was split along only some directions: every interpolated node is then
    /// re-classified after a refinement (see [`StochasticMesh::settle`]).
    aniso: bool,
}

impl StochasticMesh {
    /// Mesh of the box `[lo, hi]` with `roots[j]` root cells in direction `j`. The runs are the
    /// `prod_j (roots[j] + 1)` grid nodes, numbered with the first direction fastest.
    ///
    /// # Errors
    /// If `d` is 0 or above 6, the box is empty or a root count is 0 or above 65536.
    pub fn new(lo: &[f64], hi: &[f64], roots: &[usize]) -> Result<Self> {
        let what = "stochastic mesh";
        check_len(what, "hi", lo.len(), hi.len())?;
        check_len(what, "roots", lo.len(), roots.len())?;
        let d = lo.len();
        if d == 0 || d > MAX_DIM {
            return Err(invalid(what, "dimension", "in 1..=6", d as f64));
        }
        for j in 0..d {
            if !lo[j].is_finite() {
                return Err(invalid(what, "lo", "finite", lo[j]));
            }
            if !(hi[j].is_finite() && hi[j] > lo[j]) {
                return Err(invalid(what, "hi", "finite and > lo", hi[j]));
            }
            if roots[j] == 0 || roots[j] > 65536 {
                return Err(invalid(what, "root cells", "in 1..=65536", roots[j] as f64));
            }
        }
        let ncell = roots
            .iter()
            .try_fold(1usize, |acc, &r| acc.checked_mul(r))
            .filter(|&n| n <= 1 << 24);
        if ncell.is_none() {
            return Err(UqError::Invalid {
                what,
                message: format!("too many root cells: {roots:?} (at most 2^24 in total)"),
            });
        }
        let mut m = Self {
            d,
            lo: lo.to_vec(),
            hi: hi.to_vec(),
            roots: roots.to_vec(),
            cells: Vec::new(),
            child: Vec::new(),
            split_mask: Vec::new(),
            nodes: HashMap::new(),
            run_keys: Vec::new(),
            run_points: Vec::new(),
            leaf_terms: Vec::new(),
            terms: Vec::new(),
            num_leaves: 0,
            aniso: false,
        };
        let s = 1u64 << MAX_LEVEL;
        let ncell: usize = roots.iter().product();
        for flat in 0..ncell {
            let mut origin = [0u64; MAX_DIM];
            let mut r = flat;
            for j in 0..d {
                origin[j] = (r % roots[j]) as u64 * s;
                r /= roots[j];
            }
            m.cells.push(Cell {
                origin,
                levels: [0; MAX_DIM],
                level: 0,
                first_child: None,
            });
            m.child.push(u32::MAX);
            m.split_mask.push(0);
        }
        let nnode: usize = roots.iter().map(|r| r + 1).product();
        for flat in 0..nnode {
            let mut key = [0u64; MAX_DIM];
            let mut r = flat;
            for j in 0..d {
                key[j] = (r % (roots[j] + 1)) as u64 * s;
                r /= roots[j] + 1;
            }
            m.add_run(key);
        }
        m.rebuild()?;
        Ok(m)
    }

    pub(super) fn add_run(&mut self, key: Key) -> usize {
        let k = self.run_keys.len();
        self.run_keys.push(key);
        let p = self.key_point(&key);
        self.run_points.extend_from_slice(&p);
        self.nodes.insert(key, NodeKind::Run(k));
        k
    }

    pub(super) fn key_point(&self, key: &Key) -> Vec<f64> {
        (0..self.d)
            .map(|j| {
                let span = (self.roots[j] as u64) << MAX_LEVEL;
                if key[j] == span {
                    self.hi[j]
                } else {
                    self.lo[j] + (self.hi[j] - self.lo[j]) * key[j] as f64 / span as f64
                }
            })
            .collect()
    }

    /// Size of cell `c` in direction `j`, in key units.
    pub(super) fn size(&self, c: usize, j: usize) -> u64 {
        1u64 << (MAX_LEVEL - self.cells[c].levels[j])
    }

    /// The corner of cell `c` opposite to its origin.
    pub(super) fn far_corner(&self, c: usize) -> Key {
        let mut hi = self.cells[c].origin;
        for (j, v) in hi.iter_mut().enumerate().take(self.d) {
            *v += self.size(c, j);
        }
        hi
    }

    /// `mask` with only the directions of this mesh: `0 < mask < 2^d`.
    pub(super) fn full_mask(&self) -> u8 {
        ((1usize << self.d) - 1) as u8
    }

    /// Splits leaf `c` along the directions of `mask` into `2^popcount(mask)` children (child
    /// index: one bit per split direction, in increasing direction order). Returns the first
    /// child. No node is created.
    pub(super) fn split_cell(&mut self, c: CellId, mask: u8) -> usize {
        let d = self.d;
        let o = self.cells[c].origin;
        let dirs: Vec<usize> = (0..d).filter(|&j| (mask >> j) & 1 == 1).collect();
        let mut levels = self.cells[c].levels;
        for &j in &dirs {
            levels[j] += 1;
        }
        let level = levels[..d].iter().copied().max().unwrap_or(0);
        let first = self.cells.len();
        for child in 0..(1usize << dirs.len()) {
            let mut origin = o;
            for (b, &j) in dirs.iter().enumerate() {
                if (child >> b) & 1 == 1 {
                    origin[j] += self.size(c, j) / 2;
                }
            }
            self.cells.push(Cell {
                origin,
                levels,
                level,
                first_child: None,
            });
            self.child.push(u32::MAX);
            self.split_mask.push(0);
        }
        self.cells[c].first_child = Some(first);
        self.child[c] = first as u32;
        self.split_mask[c] = mask;
        first
    }

    /// The nodes of a split of leaf `c` along `mask`, before it is split: `(key, centre,
    /// corner)` for the grid with the cell's corners and midpoints in the split directions and
    /// its corners in the others (first direction fastest). `centre`: midpoint in every split
    /// direction; `corner`: a corner of `c`.
    pub(super) fn split_grid(&self, c: CellId, mask: u8) -> Vec<(Key, bool, bool)> {
        let d = self.d;
        let o = self.cells[c].origin;
        let mut out = Vec::new();
        let mut m = [0u64; MAX_DIM];
        for _ in 0..3usize.pow(d as u32) {
            let ok = (0..d).all(|j| m[j] != 1 || (mask >> j) & 1 == 1);
            if ok {
                let mut key = o;
                for j in 0..d {
                    key[j] += m[j] * (self.size(c, j) / 2);
                    if m[j] == 2 {
                        // Exact also for a cell of size 1 in a direction that is not split.
                        key[j] = o[j] + self.size(c, j);
                    }
                }
                let centre = (0..d).all(|j| (mask >> j) & 1 == 0 || m[j] == 1);
                let corner = m[..d].iter().all(|&v| v != 1);
                out.push((key, centre, corner));
            }
            for mj in m.iter_mut().take(d) {
                *mj += 1;
                if *mj < 3 {
                    break;
                }
                *mj = 0;
            }
        }
        out
    }

    /// Number of parameters.
    pub fn dim(&self) -> usize {
        self.d
    }
    /// Number of runs.
    pub fn num_runs(&self) -> usize {
        self.run_keys.len()
    }
    /// Points of all runs, row-major `num_runs() x dim`.
    pub fn run_points(&self) -> &[f64] {
        &self.run_points
    }
    /// Point of run `k`.
    pub fn run_point(&self, k: usize) -> &[f64] {
        &self.run_points[k * self.d..(k + 1) * self.d]
    }
    /// Number of leaf cells.
    pub fn num_leaves(&self) -> usize {
        self.num_leaves
    }
    /// Number of interpolated nodes (hanging nodes and the interpolated nodes of centred
    /// refinements).
    pub fn num_hanging(&self) -> usize {
        self.nodes
            .values()
            .filter(|k| matches!(k, NodeKind::Hanging(_) | NodeKind::Fixed(_)))
            .count()
    }
    /// Leaf cells, in increasing id order.
    pub fn leaves(&self) -> Vec<CellId> {
        (0..self.cells.len())
            .filter(|&c| self.cells[c].first_child.is_none())
            .collect()
    }
    /// `true` if `cell` exists and is a leaf.
    pub fn is_leaf(&self, cell: CellId) -> bool {
        cell < self.cells.len() && self.cells[cell].first_child.is_none()
    }
    /// Refinement level of a cell (0 for root cells): the maximum of its levels per direction
    /// ([`StochasticMesh::levels`]), so the number of halvings of an isotropic cell.
    pub fn level(&self, cell: CellId) -> u32 {
        self.cells[cell].level
    }
    /// Refinement level of a cell in each direction (the cell spans `2^-levels[j]` root cells in
    /// direction `j`).
    pub fn levels(&self, cell: CellId) -> Vec<u32> {
        self.cells[cell].levels[..self.d].to_vec()
    }
    /// Bounds `(lo, hi)` of a cell.
    ///
    /// # Panics
    /// If `cell` is not a cell id of this mesh (as for [`StochasticMesh::level`],
    /// [`StochasticMesh::cell_centre`] and [`StochasticMesh::neighbours`]).
    pub fn cell_bounds(&self, cell: CellId) -> (Vec<f64>, Vec<f64>) {
        let o = self.cells[cell].origin;
        let hi = self.far_corner(cell);
        (self.key_point(&o), self.key_point(&hi))
    }
    /// Centre of a cell.
    pub fn cell_centre(&self, cell: CellId) -> Vec<f64> {
        let (a, b) = self.cell_bounds(cell);
        a.iter().zip(&b).map(|(x, y)| 0.5 * (x + y)).collect()
    }
}

impl LinearSurrogate for StochasticMesh {
    fn dim(&self) -> usize {
        self.d
    }
    fn num_runs(&self) -> usize {
        self.run_keys.len()
    }
    /// Sparse weights (empty outside the box).
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        if let Some(c) = self.locate(xi) {
            self.cell_weights(c, xi, w);
        }
    }
    fn eval(&self, xi: &[f64], values: &[f64]) -> f64 {
        self.interpolate(xi, values)
    }
}
