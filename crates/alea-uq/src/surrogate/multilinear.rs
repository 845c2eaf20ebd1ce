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

    fn add_run(&mut self, key: Key) -> usize {
        let k = self.run_keys.len();
        self.run_keys.push(key);
        let p = self.key_point(&key);
        self.run_points.extend_from_slice(&p);
        self.nodes.insert(key, NodeKind::Run(k));
        k
    }

    fn key_point(&self, key: &Key) -> Vec<f64> {
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
    fn size(&self, c: usize, j: usize) -> u64 {
        1u64 << (MAX_LEVEL - self.cells[c].levels[j])
    }

    /// The corner of cell `c` opposite to its origin.
    fn far_corner(&self, c: usize) -> Key {
        let mut hi = self.cells[c].origin;
        for (j, v) in hi.iter_mut().enumerate().take(self.d) {
            *v += self.size(c, j);
        }
        hi
    }

    /// `mask` with only the directions of this mesh: `0 < mask < 2^d`.
    fn full_mask(&self) -> u8 {
        ((1usize << self.d) - 1) as u8
    }

    /// Splits leaf `c` along the directions of `mask` into `2^popcount(mask)` children (child
    /// index: one bit per split direction, in increasing direction order). Returns the first
    /// child. No node is created.
    fn split_cell(&mut self, c: CellId, mask: u8) -> usize {
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
    fn split_grid(&self, c: CellId, mask: u8) -> Vec<(Key, bool, bool)> {
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

    /// Leaf containing `xi` and the local coordinates of `xi` in it (`None` outside the box).
    pub fn locate_local(&self, xi: &[f64], t: &mut [f64]) -> Option<CellId> {
        let d = self.d;
        let mut root = 0usize;
        let mut stride = 1usize;
        for j in 0..d {
            let x = xi[j];
            if !(x >= self.lo[j] && x <= self.hi[j]) {
                return None;
            }
            let s = (x - self.lo[j]) / (self.hi[j] - self.lo[j]) * self.roots[j] as f64;
            let r = (s.floor() as usize).min(self.roots[j] - 1);
            t[j] = (s - r as f64).clamp(0.0, 1.0);
            root += r * stride;
            stride *= self.roots[j];
        }
        let mut c = root;
        loop {
            let first = self.child[c];
            if first == u32::MAX {
                break;
            }
            let first = first as usize;
            let mask = self.split_mask[c];
            let mut child = 0usize;
            let mut b = 0;
            for (j, tj) in t.iter_mut().enumerate().take(d) {
                if (mask >> j) & 1 == 1 {
                    if *tj >= 0.5 {
                        child |= 1 << b;
                        *tj = 2.0 * *tj - 1.0;
                    } else {
                        *tj *= 2.0;
                    }
                    b += 1;
                }
            }
            c = first + child;
        }
        Some(c)
    }

    /// Leaf cell containing `xi` (`None` outside the box).
    pub fn locate(&self, xi: &[f64]) -> Option<CellId> {
        let mut t = [0.0; MAX_DIM];
        self.locate_local(xi, &mut t[..self.d])
    }

    /// Leaf containing the neighbourhood of integer point `p` in the orthant `signs` (bit j set:
    /// positive direction), or `None` outside the box.
    fn locate_key(&self, p: &Key, signs: usize) -> Option<usize> {
        let s = 1u64 << MAX_LEVEL;
        let mut root = 0usize;
        let mut stride = 1usize;
        for j in 0..self.d {
            let r = if (signs >> j) & 1 == 1 {
                p[j] / s
            } else {
                if p[j] == 0 {
                    return None;
                }
                (p[j] - 1) / s
            };
            if r >= self.roots[j] as u64 {
                return None;
            }
            root += r as usize * stride;
            stride *= self.roots[j];
        }
        let mut c = root;
        while let Some(first) = self.cells[c].first_child {
            let mask = self.split_mask[c];
            let o = self.cells[c].origin;
            let mut child = 0usize;
            let mut b = 0;
            for j in 0..self.d {
                if (mask >> j) & 1 == 0 {
                    continue;
                }
                let half = self.size(c, j) / 2;
                let off = p[j] - o[j];
                let up = if (signs >> j) & 1 == 1 {
                    off >= half
                } else {
                    off > half
                };
                if up {
                    child |= 1 << b;
                }
                b += 1;
            }
            c = first + child;
        }
        Some(c)
    }

    fn is_corner(&self, c: usize, p: &Key) -> bool {
        let o = self.cells[c].origin;
        (0..self.d).all(|j| p[j] == o[j] || p[j] == o[j] + self.size(c, j))
    }

    /// Extent of the face of cell `c` through `p` (in its closure): the cell's size in the
    /// directions where `p` is strictly inside it, 0 in the others.
    fn extent(&self, c: usize, p: &Key) -> Key {
        let o = self.cells[c].origin;
        let mut e = [0u64; MAX_DIM];
        for j in 0..self.d {
            let s = self.size(c, j);
            if p[j] != o[j] && p[j] != o[j] + s {
                e[j] = s;
            }
        }
        e
    }

    /// `true` if leaf `c` is a better master than `b` for `p`: its face through `p` contains
    /// `b`'s (componentwise larger extent; for isotropic cells: coarser), or, when neither
    /// contains the other, it has the larger total extent.
    fn better_master(&self, c: usize, b: usize, p: &Key) -> bool {
        let (ec, eb) = (self.extent(c, p), self.extent(b, p));
        let ge = (0..self.d).all(|j| ec[j] >= eb[j]);
        let le = (0..self.d).all(|j| ec[j] <= eb[j]);
        if ge || le {
            ge && !le
        } else {
            ec.iter().sum::<u64>() > eb.iter().sum::<u64>()
        }
    }

    /// Classify node `p`: `None` if it is a corner of every leaf around it, else the coarsest
    /// leaf that contains it without having it as a corner (the one whose face through `p`
    /// contains the others').
    fn master_of(&self, p: &Key) -> Option<usize> {
        let mut best: Option<usize> = None;
        for signs in 0..(1usize << self.d) {
            if let Some(c) = self.locate_key(p, signs)
                && !self.is_corner(c, p)
                && best.is_none_or(|b| self.better_master(c, b, p))
            {
                best = Some(c);
            }
        }
        best
    }

    /// Split the given leaf cells into `2^d` children each. Returns the nodes that became runs,
    /// in increasing run index.
    ///
    /// # Errors
    /// If a cell is not a leaf or is already at [`MAX_LEVEL`].
    pub fn refine(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let full = self.full_mask();
        let mut todo: Vec<CellId> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for &c in &todo {
            if !self.is_leaf(c) {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf"),
                });
            }
            if self.cells[c].level >= MAX_LEVEL {
                return Err(invalid(
                    "stochastic mesh",
                    "cell level",
                    "below the maximum",
                    self.cells[c].level as f64,
                ));
            }
        }
        for &c in &todo {
            // New nodes: o + half * m, m in {0, 1, 2}^d (placeholder kind, classified below).
            let grid = self.split_grid(c, full);
            self.split_cell(c, full);
            for (key, _, _) in grid {
                self.nodes
                    .entry(key)
                    .or_insert(NodeKind::Hanging(usize::MAX));
            }
        }
        // Anisotropic meshes: split (interpolated) where faces cross (see `crossings`).
        let mut split = todo.clone();
        self.resolve_crossings(&mut split)?;
        // Reclassify every non-run node; nodes with no master become runs.
        let mut pending: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, k)| matches!(k, NodeKind::Hanging(_)))
            .map(|(key, _)| *key)
            .collect();
        pending.sort_unstable();
        let mut new_runs = Vec::new();
        for key in pending {
            match self.master_of(&key) {
                Some(mc) => {
                    self.nodes.insert(key, NodeKind::Hanging(mc));
                }
                None => {
                    let run = self.add_run(key);
                    new_runs.push(NewRun {
                        run,
                        point: self.run_point(run).to_vec(),
                    });
                }
            }
        }
        if self.aniso {
            self.classify_interpolated(&split)?;
        }
        self.rebuild()?;
        Ok(new_runs)
    }

    /// Splits leaf `c` along the directions of `mask` and classifies the nodes of the split
    /// ([`StochasticMesh::split_grid`]): if `centre_runs`, the centres are left as they are and
    /// returned (the caller makes them runs); every other node that is neither a corner of `c`,
    /// a run nor already interpolated for good is interpolated from `c` for good.
    fn split_interpolated(&mut self, c: CellId, mask: u8, centre_runs: bool) -> Result<Vec<Key>> {
        if !self.is_leaf(c) {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("cell {c} is not a leaf"),
            });
        }
        let d = self.d;
        if mask == 0 || (mask as usize) >> d != 0 {
            return Err(invalid(
                "stochastic mesh",
                "split mask",
                "a non-empty set of directions of the mesh",
                mask as f64,
            ));
        }
        if let Some(j) =
            (0..d).find(|&j| (mask >> j) & 1 == 1 && self.cells[c].levels[j] >= MAX_LEVEL)
        {
            return Err(invalid(
                "stochastic mesh",
                "cell level",
                "below the maximum",
                self.cells[c].levels[j] as f64,
            ));
        }
        let grid = self.split_grid(c, mask);
        self.split_cell(c, mask);
        self.aniso |= mask != self.full_mask();
        let mut centres = Vec::new();
        for (key, centre, corner) in grid {
            if centre && centre_runs {
                centres.push(key);
            } else if !corner {
                match self.nodes.get(&key) {
                    Some(NodeKind::Run(_)) | Some(NodeKind::Fixed(_)) => {}
                    _ => {
                        self.nodes.insert(key, NodeKind::Fixed(c));
                    }
                }
            }
        }
        Ok(centres)
    }

    /// Leaves whose interior meets the open box `(lo, hi)` (key units), appended to `out`.
    fn leaves_in(&self, lo: &Key, hi: &Key, out: &mut Vec<usize>) {
        let d = self.d;
        let s = 1u64 << MAX_LEVEL;
        let mut rlo = [0usize; MAX_DIM];
        let mut rhi = [0usize; MAX_DIM];
        for j in 0..d {
            if hi[j] <= lo[j] {
                return;
            }
            rlo[j] = (lo[j] / s) as usize;
            rhi[j] = (((hi[j] - 1) / s) as usize).min(self.roots[j] - 1);
            if rlo[j] > rhi[j] {
                return;
            }
        }
        let mut stack = Vec::new();
        let mut idx = rlo;
        'roots: loop {
            let mut root = 0usize;
            let mut stride = 1usize;
            for j in 0..d {
                root += idx[j] * stride;
                stride *= self.roots[j];
            }
            stack.push(root);
            for j in 0..d {
                idx[j] += 1;
                if idx[j] <= rhi[j] {
                    continue 'roots;
                }
                idx[j] = rlo[j];
            }
            break;
        }
        while let Some(c) = stack.pop() {
            let o = self.cells[c].origin;
            if !(0..d).all(|j| o[j] < hi[j] && o[j] + self.size(c, j) > lo[j]) {
                continue;
            }
            match self.cells[c].first_child {
                None => out.push(c),
                Some(first) => {
                    let n = 1usize << self.split_mask[c].count_ones();
                    stack.extend((first..first + n).rev());
                }
            }
        }
    }

    /// Points where two adjacent leaves hold a point of their common boundary inside faces that
    /// do not contain one another (possible with anisotropic cells when the leaves share a
    /// region of dimension 2 or more: a face in 3D, also a 2D region in 4D): no node value can
    /// match both interpolants there. Returns, per leaf to split (the newer of the two), the
    /// directions in which its face through the point exceeds the other's, so that splitting
    /// along them makes the point its corner (sorted by leaf, deterministic).
    /// Only pairs with a leaf of `from` are examined.
    fn crossings(&self, from: &[usize]) -> Vec<(usize, u8)> {
        let d = self.d;
        let mut out: Vec<(usize, u8)> = Vec::new();
        let mut across = Vec::new();
        for &a in from {
            let oa = self.cells[a].origin;
            let fa = self.far_corner(a);
            // The regions around `a`: per direction below (0), along (1) or above (2) it.
            'patterns: for pattern in 0..3usize.pow(d as u32) {
                let mut side = [0usize; MAX_DIM];
                let mut r = pattern;
                for v in side.iter_mut().take(d) {
                    *v = r % 3;
                    r /= 3;
                }
                let along = side[..d].iter().filter(|&&v| v == 1).count();
                if along < 2 || along == d {
                    continue;
                }
                let (mut lo, mut hi) = (oa, fa);
                for i in 0..d {
                    let span = (self.roots[i] as u64) << MAX_LEVEL;
                    match side[i] {
                        0 if oa[i] == 0 => continue 'patterns,
                        0 => (lo[i], hi[i]) = (oa[i] - 1, oa[i]),
                        2 if fa[i] == span => continue 'patterns,
                        2 => (lo[i], hi[i]) = (fa[i], fa[i] + 1),
                        _ => {}
                    }
                }
                across.clear();
                self.leaves_in(&lo, &hi, &mut across);
                for &b in &across {
                    let ob = self.cells[b].origin;
                    let fb = self.far_corner(b);
                    for corner in 0..(1usize << d) {
                        if (0..d).any(|i| side[i] != 1 && (corner >> i) & 1 == 1) {
                            continue;
                        }
                        let mut q = [0u64; MAX_DIM];
                        for i in 0..d {
                            q[i] = match side[i] {
                                0 => oa[i],
                                2 => fa[i],
                                _ if (corner >> i) & 1 == 1 => fa[i].min(fb[i]),
                                _ => oa[i].max(ob[i]),
                            };
                        }
                        let (ea, eb) = (self.extent(a, &q), self.extent(b, &q));
                        let ge = (0..d).all(|i| ea[i] >= eb[i]);
                        let le = (0..d).all(|i| ea[i] <= eb[i]);
                        if ge || le {
                            continue;
                        }
                        let (l, el, eo) = if b > a { (b, eb, ea) } else { (a, ea, eb) };
                        let mask = (0..d)
                            .filter(|&i| el[i] > eo[i])
                            .fold(0u8, |m, i| m | (1 << i));
                        match out.iter_mut().find(|e| e.0 == l) {
                            Some(e) => e.1 |= mask,
                            None => out.push((l, mask)),
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// The leaves below (or equal to) the given cells, in increasing id order.
    fn leaves_below(&self, cells: &[CellId]) -> Vec<CellId> {
        let mut out = Vec::new();
        let mut stack: Vec<CellId> = cells.to_vec();
        while let Some(c) = stack.pop() {
            match self.cells[c].first_child {
                None => out.push(c),
                Some(first) => {
                    stack.extend(first..first + (1usize << self.split_mask[c].count_ones()))
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Splits leaves (interpolated nodes only) until no [`StochasticMesh::crossings`] remain;
    /// the split cells are appended to `split`.
    fn resolve_crossings(&mut self, split: &mut Vec<CellId>) -> Result<()> {
        if !self.aniso {
            return Ok(());
        }
        // A crossing involves a leaf made by the splits: look from those only.
        let mut from = self.leaves_below(split);
        loop {
            let todo = self.crossings(&from);
            if todo.is_empty() {
                return Ok(());
            }
            let cells: Vec<CellId> = todo.iter().map(|e| e.0).collect();
            for (l, mask) in todo {
                self.split_interpolated(l, mask, false)?;
                split.push(l);
            }
            from = self.leaves_below(&cells);
        }
    }

    /// Re-classifies the hanging nodes after splits and rebuilds the weights. A hanging node
    /// left without a leaf master lies on a split cell: it is interpolated from it for good.
    ///
    /// On a mesh with anisotropic splits, the interpolated-for-good nodes are re-classified as
    /// well: a node inside a face of a leaf must take that leaf's value for the surrogate to be
    /// continuous (on isotropic meshes this holds by construction), so it hangs on the leaf;
    /// a hanging node whose master leaf was split is interpolated from that cell for good (its
    /// value is unchanged).
    fn settle(&mut self, split: &[CellId]) -> Result<()> {
        let mut split = split.to_vec();
        self.resolve_crossings(&mut split)?;
        self.classify_interpolated(&split)?;
        self.rebuild()
    }

    fn classify_interpolated(&mut self, split: &[CellId]) -> Result<()> {
        let aniso = self.aniso;
        let mut pending: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, k)| match k {
                NodeKind::Hanging(_) => true,
                NodeKind::Fixed(_) => aniso,
                NodeKind::Run(_) => false,
            })
            .map(|(key, _)| *key)
            .collect();
        pending.sort_unstable();
        for key in pending {
            let old = self.nodes[&key];
            let kind = match self.master_of(&key) {
                Some(mc) => NodeKind::Hanging(mc),
                None if aniso && matches!(old, NodeKind::Fixed(_)) => old,
                None if aniso
                    && matches!(old, NodeKind::Hanging(m) if m < self.cells.len() && !self.is_leaf(m)) =>
                {
                    let NodeKind::Hanging(m) = old else {
                        unreachable!()
                    };
                    NodeKind::Fixed(m)
                }
                None => {
                    let owner = split.iter().copied().find(|&c| {
                        let o = self.cells[c].origin;
                        (0..self.d).all(|j| key[j] >= o[j] && key[j] <= o[j] + self.size(c, j))
                    });
                    match owner {
                        Some(c) => NodeKind::Fixed(c),
                        None => {
                            return Err(UqError::Invalid {
                                what: "stochastic mesh",
                                message: "internal error: a hanging node lost its master".into(),
                            });
                        }
                    }
                }
            };
            self.nodes.insert(key, kind);
        }
        Ok(())
    }

    /// Refines leaf cells **at their centres** (the thesis's improved criterion, 4.2.2.2, and
    /// the structured stochastic mesh of 4.2.1 b): each cell is split into `2^d` children, its
    /// centre becomes a run, and every other new node is interpolated from the cell (not run).
    /// The surrogate is unchanged outside the cells and, inside, changes only through the
    /// centres' values; it stays continuous. Returns one new run per cell, in cell order.
    ///
    /// # Errors
    /// If a cell is not a leaf or is already at [`MAX_LEVEL`].
    pub fn refine_centred(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let mut todo: Vec<CellId> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for &c in &todo {
            if !self.is_leaf(c) || self.cells[c].level >= MAX_LEVEL {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf below the maximum level"),
                });
            }
        }
        let full = self.full_mask();
        let mut new_runs = Vec::with_capacity(todo.len());
        for &c in &todo {
            for key in self.split_interpolated(c, full, true)? {
                let run = self.add_run(key);
                new_runs.push(NewRun {
                    run,
                    point: self.run_point(run).to_vec(),
                });
            }
        }
        self.settle(&todo)?;
        Ok(new_runs)
    }

    /// Splits each leaf `cell` only along the directions whose bit is set in `mask` (bit j:
    /// direction j; `mask != 0`, only bits below `d`) into `2^popcount(mask)` children, and
    /// makes runs of the **centres** of the split: the new nodes at the cell's midpoint in every
    /// split direction and at a corner value in every other direction (`2^(d - popcount)` of
    /// them; the midpoint of the cell when the mask is full). Every other new node is
    /// interpolated from the cell for good (as [`StochasticMesh::refine_centred`], which this is
    /// with a full mask: same runs, same order, same weights).
    ///
    /// A centre on a face of the cell must be a corner of every leaf around it to be a run (else
    /// the surrogate would jump there): a leaf across that holds it inside a face is split
    /// first, with interpolated nodes only, along the directions in which it holds it inside,
    /// until it is a corner (as [`StochasticMesh::refine_at_point`] does). A centre that is
    /// already a run (shared with a neighbour split the same way) is not returned again; one that
    /// was interpolated becomes a run. On a mesh with anisotropic cells, interpolated nodes inside
    /// a face of a leaf hang on it and crossing faces are split (see the module documentation),
    /// so the surrogate can also change on the leaves next to the refined cells: it stays
    /// continuous.
    ///
    /// Returns the nodes that became runs, in increasing run index.
    ///
    /// # Errors
    /// If a cell is not a leaf, is listed twice with different masks, a mask is empty or has a
    /// bit at or above `d`, or the cell is already at [`MAX_LEVEL`] in a split direction. The
    /// mesh is unchanged then.
    pub fn refine_directions(&mut self, cells: &[(CellId, u32)]) -> Result<Vec<NewRun>> {
        let d = self.d;
        let mut todo: Vec<(CellId, u32)> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for (i, &(c, mask)) in todo.iter().enumerate() {
            if !self.is_leaf(c) {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf"),
                });
            }
            if i > 0 && todo[i - 1].0 == c {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is listed with two masks"),
                });
            }
            if mask == 0 || mask >> d != 0 {
                return Err(invalid(
                    "stochastic mesh",
                    "split mask",
                    "a non-empty set of directions of the mesh",
                    mask as f64,
                ));
            }
            if let Some(j) =
                (0..d).find(|&j| (mask >> j) & 1 == 1 && self.cells[c].levels[j] >= MAX_LEVEL)
            {
                return Err(invalid(
                    "stochastic mesh",
                    "cell level",
                    "below the maximum",
                    self.cells[c].levels[j] as f64,
                ));
            }
        }
        let mut split: Vec<CellId> = Vec::with_capacity(todo.len());
        let mut centres = Vec::new();
        for &(c, mask) in &todo {
            centres.extend(self.split_interpolated(c, mask as u8, true)?);
            split.push(c);
        }
        let mut new_runs = Vec::with_capacity(centres.len());
        for key in centres {
            if matches!(self.nodes.get(&key), Some(NodeKind::Run(_))) {
                continue;
            }
            // Split the leaves that hold the centre inside a face until it is their corner.
            while let Some(l) = (0..(1usize << d))
                .filter_map(|signs| self.locate_key(&key, signs))
                .find(|&l| !self.is_corner(l, &key))
            {
                let o = self.cells[l].origin;
                let mut mask = 0u8;
                for j in 0..d {
                    if key[j] != o[j] && key[j] != o[j] + self.size(l, j) {
                        mask |= 1 << j;
                    }
                }
                self.split_interpolated(l, mask, false)?;
                split.push(l);
            }
            let run = self.add_run(key);
            new_runs.push(NewRun {
                run,
                point: self.run_point(run).to_vec(),
            });
        }
        self.settle(&split)?;
        Ok(new_runs)
    }

    /// One new run at `xi` (the thesis's maximum-error criterion, 4.2.2.1): the leaves around
    /// `xi` are split, with interpolated nodes only, until `xi` is the centre of a leaf, which
    /// is then refined at its centre. `xi` must be a dyadic point strictly inside a leaf, such
    /// as those of [`StochasticMesh::sub_cell_centres`].
    ///
    /// # Errors
    /// If `xi` is outside the box, not a dyadic point of the mesh, or already a node.
    pub fn refine_at_point(&mut self, xi: &[f64]) -> Result<NewRun> {
        let d = self.d;
        if xi.len() != d {
            return Err(invalid(
                "stochastic mesh",
                "point dimension",
                "the mesh's",
                xi.len() as f64,
            ));
        }
        let mut key = [0u64; MAX_DIM];
        for j in 0..d {
            let span = ((self.roots[j] as u64) << MAX_LEVEL) as f64;
            let t = (xi[j] - self.lo[j]) / (self.hi[j] - self.lo[j]) * span;
            if !(t > 0.0 && t < span) {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "strictly inside the box",
                    xi[j],
                ));
            }
            key[j] = t.round() as u64;
            if (t - key[j] as f64).abs() > 1e-6 {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "a dyadic point of the mesh",
                    xi[j],
                ));
            }
        }
        if self.nodes.contains_key(&key) {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is already a node of the mesh"),
            });
        }
        let mut split = Vec::new();
        let mut runs = Vec::new();
        loop {
            let p = self.key_point(&key);
            let c = self.locate(&p).ok_or_else(|| UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is outside the mesh"),
            })?;
            let o = self.cells[c].origin;
            let half: Vec<u64> = (0..d).map(|j| self.size(c, j) / 2).collect();
            let is_centre = (0..d).all(|j| key[j] == o[j] + half[j]);
            if half.contains(&0) {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "a dyadic point of the mesh",
                    xi[0],
                ));
            }
            split.push(c);
            let full = self.full_mask();
            for centre in self.split_interpolated(c, full, is_centre)? {
                let run = self.add_run(centre);
                runs.push(NewRun {
                    run,
                    point: self.run_point(run).to_vec(),
                });
            }
            if is_centre {
                break;
            }
            if (0..d).any(|j| key[j] == o[j] + half[j]) {
                // On a split plane but not the centre: never a leaf centre below.
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!(
                        "{xi:?} lies on a face of the refined cells, not a cell centre"
                    ),
                });
            }
        }
        self.settle(&split)?;
        runs.pop().ok_or_else(|| UqError::Invalid {
            what: "stochastic mesh",
            message: "internal error: no run created".into(),
        })
    }

    /// Every node that is not a run (interpolated for good by a centred refinement, or hanging
    /// on a coarser leaf), in increasing key order (deterministic), with the coarsest leaf that
    /// holds it without having it as a corner: `None` when [`StochasticMesh::promote`] can make
    /// it a run now, else the leaf to refine first (its value follows that leaf's interpolant,
    /// which a run there would break).
    pub fn interpolated_nodes(&self) -> Vec<(Vec<f64>, Option<CellId>)> {
        let mut keys: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, kind)| !matches!(kind, NodeKind::Run(_)))
            .map(|(key, _)| *key)
            .collect();
        keys.sort_unstable();
        keys.iter()
            .map(|k| (self.key_point(k), self.master_of(k)))
            .collect()
    }

    /// Makes the interpolated node at `xi` (one of [`StochasticMesh::interpolated_nodes`]
    /// without a leaf to refine first) a run: the maximum-error criterion's new run where the
    /// density peaks on a node whose value a centred refinement froze. The surrogate changes
    /// only on the leaves around it (and wherever an interpolated value resolves through it); it
    /// stays continuous.
    ///
    /// # Errors
    /// If `xi` is not such a node.
    pub fn promote(&mut self, xi: &[f64]) -> Result<NewRun> {
        let d = self.d;
        let mut key = [0u64; MAX_DIM];
        for j in 0..d.min(xi.len()) {
            let span = ((self.roots[j] as u64) << MAX_LEVEL) as f64;
            let t = (xi[j] - self.lo[j]) / (self.hi[j] - self.lo[j]) * span;
            if !(t >= 0.0 && t <= span) {
                return Err(invalid("stochastic mesh", "point", "inside the box", xi[j]));
            }
            key[j] = t.round() as u64;
        }
        let ok = xi.len() == d
            && matches!(
                self.nodes.get(&key),
                Some(NodeKind::Fixed(_) | NodeKind::Hanging(_))
            )
            && self.master_of(&key).is_none()
            && (0..d).all(|j| {
                (self.key_point(&key)[j] - xi[j]).abs() <= 1e-9 * (self.hi[j] - self.lo[j])
            });
        if !ok {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is not an interpolated node that can become a run"),
            });
        }
        let run = self.add_run(key);
        self.rebuild()?;
        Ok(NewRun {
            run,
            point: self.run_point(run).to_vec(),
        })
    }

    /// Centres of the `2^(d depth)` sub-cells of `cell` at relative depth `depth` (the candidate
    /// points of the maximum-error criterion), row-major `n x d`.
    ///
    /// # Errors
    /// If the sub-cells would be deeper than [`MAX_LEVEL`] or more than 2^20.
    pub fn sub_cell_centres(&self, cell: CellId, depth: u32) -> Result<Vec<f64>> {
        let d = self.d;
        if self.cells[cell].level + depth + 1 > MAX_LEVEL || (d as u32) * depth > 20 {
            return Err(invalid(
                "stochastic mesh",
                "sub-cell depth",
                "within the maximum level and 2^20 points",
                depth as f64,
            ));
        }
        let o = self.cells[cell].origin;
        let step: Vec<u64> = (0..d).map(|j| self.size(cell, j) >> depth).collect();
        let n = 1usize << depth;
        let mut out = Vec::with_capacity(n.pow(d as u32) * d);
        let mut idx = [0usize; MAX_DIM];
        for _ in 0..n.pow(d as u32) {
            let mut key = o;
            for j in 0..d {
                key[j] += step[j] / 2 + idx[j] as u64 * step[j];
            }
            out.extend(self.key_point(&key));
            for v in idx.iter_mut().take(d) {
                *v += 1;
                if *v < n {
                    break;
                }
                *v = 0;
            }
        }
        Ok(out)
    }

    /// Leaf cells adjacent to `cell` (sharing a face, an edge or a corner).
    pub fn neighbours(&self, cell: CellId) -> Vec<CellId> {
        let d = self.d;
        let o = self.cells[cell].origin;
        let mut out = Vec::new();
        let mut delta = [-1i32; MAX_DIM];
        for _ in 0..3usize.pow(d as u32) {
            // delta in {-1, 0, 1}^d, enumerated as base-3 digits.
            if delta[..d].iter().any(|&v| v != 0) {
                // A probe point strictly inside the neighbouring region, in units where a
                // cell of this size spans 4 sub-units (sizes are powers of two >= 1).
                let mut ok = true;
                let mut key = [0u64; MAX_DIM];
                for j in 0..d {
                    let span = (self.roots[j] as u64) << MAX_LEVEL;
                    let v = match delta[j] {
                        -1 => o[j].checked_sub(1),
                        0 => Some(o[j] + self.size(cell, j) / 2),
                        _ => Some(o[j] + self.size(cell, j)),
                    };
                    match v {
                        Some(v) if v < span => key[j] = v,
                        _ => ok = false,
                    }
                }
                if ok
                    && let Some(c) = self.locate_key(&key, (1usize << d) - 1)
                    && !out.contains(&c)
                {
                    out.push(c);
                }
            }
            for v in delta.iter_mut().take(d) {
                *v += 1;
                if *v <= 1 {
                    break;
                }
                *v = -1;
            }
        }
        out
    }

    /// As [`StochasticMesh::refine`], but also refines coarser neighbours as needed so that
    /// adjacent leaves differ by at most one level (2:1 balance, if the mesh was balanced).
    ///
    /// # Errors
    /// As [`StochasticMesh::refine`].
    pub fn refine_balanced(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let mut set: Vec<CellId> = cells.to_vec();
        let mut i = 0;
        while i < set.len() {
            let c = set[i];
            if self.is_leaf(c) {
                let level = self.cells[c].level;
                for n in self.neighbours(c) {
                    if self.cells[n].level < level && !set.contains(&n) {
                        set.push(n);
                    }
                }
            }
            i += 1;
        }
        self.refine(&set)
    }

    /// Refine every leaf once.
    ///
    /// # Errors
    /// As [`StochasticMesh::refine`].
    pub fn refine_all(&mut self) -> Result<Vec<NewRun>> {
        let leaves = self.leaves();
        self.refine(&leaves)
    }

    /// Resolve the weights of every node on runs and cache, per leaf, `(corner, run, coef)`.
    fn rebuild(&mut self) -> Result<()> {
        let mut memo: HashMap<Key, Vec<(usize, f64)>> = HashMap::new();
        let d = self.d;
        let mut leaf_terms = vec![(0u32, 0u32); self.cells.len()];
        let mut terms = Vec::new();
        let mut nl = 0;
        for c in 0..self.cells.len() {
            if self.cells[c].first_child.is_some() {
                continue;
            }
            nl += 1;
            let start = terms.len() as u32;
            let o = self.cells[c].origin;
            for corner in 0..(1usize << d) {
                let mut key = o;
                for j in 0..d {
                    if (corner >> j) & 1 == 1 {
                        key[j] += self.size(c, j);
                    }
                }
                let w = self.resolve(&key, &mut memo, 0)?;
                for &(run, coef) in &w {
                    terms.push((corner as u8, run as u32, coef));
                }
            }
            leaf_terms[c] = (start, terms.len() as u32);
        }
        self.leaf_terms = leaf_terms;
        self.terms = terms;
        self.num_leaves = nl;
        Ok(())
    }

    fn resolve(
        &self,
        key: &Key,
        memo: &mut HashMap<Key, Vec<(usize, f64)>>,
        depth: u32,
    ) -> Result<Vec<(usize, f64)>> {
        if let Some(v) = memo.get(key) {
            return Ok(v.clone());
        }
        let kind = self
            .nodes
            .get(key)
            .copied()
            .ok_or_else(|| UqError::Invalid {
                what: "stochastic mesh",
                message: "internal error: missing node".into(),
            })?;
        let out = match kind {
            NodeKind::Run(k) => vec![(k, 1.0)],
            NodeKind::Hanging(m) | NodeKind::Fixed(m) => {
                // A guard against cycles: a chain of interpolated nodes has at most a few steps
                // per level and direction.
                if depth > (MAX_LEVEL + 2) * self.d as u32 || m == usize::MAX {
                    return Err(UqError::Invalid {
                        what: "stochastic mesh",
                        message: "internal error: unresolved hanging node".into(),
                    });
                }
                let o = self.cells[m].origin;
                let mut acc: Vec<(usize, f64)> = Vec::new();
                for corner in 0..(1usize << self.d) {
                    let mut phi = 1.0;
                    let mut ck = o;
                    for j in 0..self.d {
                        let t = (key[j] - o[j]) as f64 / self.size(m, j) as f64;
                        if (corner >> j) & 1 == 1 {
                            phi *= t;
                            ck[j] += self.size(m, j);
                        } else {
                            phi *= 1.0 - t;
                        }
                    }
                    if phi == 0.0 {
                        continue;
                    }
                    for (run, w) in self.resolve(&ck, memo, depth + 1)? {
                        match acc.iter_mut().find(|e| e.0 == run) {
                            Some(e) => e.1 += phi * w,
                            None => acc.push((run, phi * w)),
                        }
                    }
                }
                acc
            }
        };
        memo.insert(*key, out.clone());
        Ok(out)
    }

    /// Fast evaluation (no allocation): `sum_k w_k(xi) values[k]`; `NaN` outside the box.
    ///
    /// # Panics
    /// If `values.len() < num_runs()` or `xi.len() < dim()`.
    #[inline]
    pub fn interpolate(&self, xi: &[f64], values: &[f64]) -> f64 {
        let mut t = [0.0; MAX_DIM];
        let Some(c) = self.locate_local(xi, &mut t[..self.d]) else {
            return f64::NAN;
        };
        let mut phi = [0.0; 1 << MAX_DIM];
        self.corner_phi(&t, &mut phi);
        let (a, b) = self.leaf_terms[c];
        self.terms[a as usize..b as usize]
            .iter()
            .map(|&(corner, run, coef)| phi[corner as usize] * coef * values[run as usize])
            .sum()
    }

    #[inline]
    fn corner_phi(&self, t: &[f64], phi: &mut [f64; 1 << MAX_DIM]) {
        phi[0] = 1.0;
        let mut n = 1;
        for &tj in t.iter().take(self.d) {
            for c in 0..n {
                phi[c + n] = phi[c] * tj;
                phi[c] *= 1.0 - tj;
            }
            n *= 2;
        }
    }

    /// Probability of each leaf cell under `law` (`(cell, P(xi in cell))`, leaves in id order).
    pub fn cell_probabilities(&self, law: &dyn JointLaw) -> Vec<(CellId, f64)> {
        self.leaves()
            .into_iter()
            .map(|c| {
                let (a, b) = self.cell_bounds(c);
                (c, law.box_probability(&a, &b))
            })
            .collect()
    }

    /// Integral of `f` over each leaf cell with an `order`-point tensor Gauss-Legendre rule
    /// (`(cell, int_cell f)`), e.g. `f = error density * pdf` for the refinement criterion.
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn integrate_cells(
        &self,
        f: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<(CellId, f64)>> {
        use rayon::prelude::*;
        self.leaves()
            .into_par_iter()
            .map(|c| {
                let (a, b) = self.cell_bounds(c);
                Ok((
                    c,
                    QuadratureRule::gauss_legendre_box(&a, &b, order)?.integrate(&f),
                ))
            })
            .collect()
    }

    /// Expected weights `E[w_k(xi)] = int w_k(x) f(x) dx` under a density `pdf` on the box, by
    /// an `order`-point Gauss-Legendre rule per leaf, so that `E[q~] = sum_k E[w_k] q_k`.
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn expected_weights(
        &self,
        pdf: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<f64>> {
        let mut out = vec![0.0; self.num_runs()];
        let mut w = Vec::new();
        for c in self.leaves() {
            let (a, b) = self.cell_bounds(c);
            let r = QuadratureRule::gauss_legendre_box(&a, &b, order)?;
            for q in 0..r.len() {
                let x = r.node(q);
                let f = r.weights()[q] * pdf(x);
                if f == 0.0 {
                    continue;
                }
                self.cell_weights(c, x, &mut w);
                for &(k, wk) in &w {
                    out[k] += f * wk;
                }
            }
        }
        Ok(out)
    }

    /// Second moments of the weights, `M_kl = E[w_k(xi) w_l(xi)] = int w_k w_l f dx`, under a
    /// density `pdf` on the box (`order`-point Gauss-Legendre per leaf; `order = 2` is exact for
    /// a piecewise-constant density). Returned sparse, as `(k, l, M_kl)` with `k <= l`, sorted.
    /// Then `E[q~^2] = sum_kl M_kl q_k q_l` and, for a field or an energy with Gram matrix
    /// `G_kl = <u_k, u_l>`, `E[||u~||^2] = sum_kl M_kl G_kl` (counting `k != l` twice).
    ///
    /// # Errors
    /// If `order == 0`.
    pub fn weight_second_moments(
        &self,
        pdf: impl Fn(&[f64]) -> f64 + Sync,
        order: usize,
    ) -> Result<Vec<(usize, usize, f64)>> {
        let mut acc: HashMap<(usize, usize), f64> = HashMap::new();
        let mut w = Vec::new();
        for c in self.leaves() {
            let (a, b) = self.cell_bounds(c);
            let r = QuadratureRule::gauss_legendre_box(&a, &b, order)?;
            for q in 0..r.len() {
                let x = r.node(q);
                let f = r.weights()[q] * pdf(x);
                if f == 0.0 {
                    continue;
                }
                self.cell_weights(c, x, &mut w);
                for &(k, wk) in &w {
                    for &(l, wl) in &w {
                        if k <= l {
                            *acc.entry((k, l)).or_insert(0.0) += f * wk * wl;
                        }
                    }
                }
            }
        }
        let mut out: Vec<(usize, usize, f64)> =
            acc.into_iter().map(|((k, l), v)| (k, l, v)).collect();
        out.sort_unstable_by_key(|e| (e.0, e.1));
        Ok(out)
    }

    fn cell_weights(&self, c: CellId, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        w.clear();
        let o = self.cells[c].origin;
        let mut t = [0.0; MAX_DIM];
        let hi = self.far_corner(c);
        let (pl, ph) = (self.key_point(&o), self.key_point(&hi));
        for j in 0..self.d {
            t[j] = ((xi[j] - pl[j]) / (ph[j] - pl[j])).clamp(0.0, 1.0);
        }
        let mut phi = [0.0; 1 << MAX_DIM];
        self.corner_phi(&t[..self.d], &mut phi);
        let (a, b) = self.leaf_terms[c];
        for &(corner, run, coef) in &self.terms[a as usize..b as usize] {
            let v = phi[corner as usize] * coef;
            if v == 0.0 {
                continue;
            }
            match w.iter_mut().find(|e| e.0 == run as usize) {
                Some(e) => e.1 += v,
                None => w.push((run as usize, v)),
            }
        }
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
