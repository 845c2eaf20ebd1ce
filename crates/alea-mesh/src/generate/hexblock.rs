//! Multi-block structured hexahedral meshes (3D) of straight-edged (trilinear) blocks, with
//! geometric grading.
//!
//! A [`HexBlock`] is a hexahedron given by its eight corners in the `Hex8` node order (VTK):
//! `c0 c1 c2 c3` the bottom face, `c4..c7` the top face, `c(i+4)` above `c(i)`. Block
//! coordinates `(s, t, w) in [0, 1]^3` run from `c0` towards `c1` (s), `c3` (t) and `c4` (w); the
//! point of block coordinates `(s, t, w)` is the trilinear interpolation
//!
//! ```text
//! X(s, t, w) = sum_k N_k(s, t, w) c_k,   N_0 = (1-s)(1-t)(1-w), N_1 = s(1-t)(1-w),
//!              N_2 = s t (1-w), N_3 = (1-s) t (1-w), N_4..N_7 the same with w for (1-w).
//! ```
//! Each block is divided into `n[0] x n[1] x n[2]` cells; along each direction the node
//! parameters follow a geometric progression whose ratio of last to first cell size is
//! `grading[d]` (1 = uniform; the first cell touches the face `s = 0`, `t = 0` or `w = 0`), the
//! same progression as the 2D [`crate::generate::multiblock`]. Blocks whose corners are
//! left-handed (for instance the mirror image of a right-handed block) get their cells
//! re-ordered so that every cell is right-handed; a cell whose Jacobian is not positive at
//! its centre or at a corner after that means the block folds, and is an error.
//!
//! Nodes of different blocks closer than `1e-9` times the model size are merged, so blocks that
//! share a face with the same cell counts and node positions (gradings reversed when the face is
//! traversed in the opposite direction) give a conforming mesh. A face met by more than two
//! cells is an error. Blocks that meet with different subdivisions leave hanging nodes that are
//! **not** detected: give shared faces matching subdivisions. Parts that must stay un-merged
//! along an interface (contact) are generated separately.
//!
//! Groups: a block's cells join the cell group `HexBlock::cell_group` (if set); a face tagged
//! with a name (faces `0..6` = `s = 0`, `s = 1`, `t = 0`, `t = 1`, `w = 0`, `w = 1`) gives a
//! facet group of that name (the cells' faces on it, outward) and a node group with its nodes.

use std::collections::HashMap;

use super::multiblock::distribution;
use crate::{CellType, Facet, Mesh, MeshError};

/// One straight-edged hexahedral block. See the module documentation for the conventions.
#[derive(Clone, Debug)]
pub struct HexBlock {
    /// Corners in the `Hex8` node order.
    pub corners: [[f64; 3]; 8],
    /// Number of cells along s, t and w.
    pub n: [usize; 3],
    /// Ratio of the last to the first cell size along s, t and w.
    pub grading: [f64; 3],
    /// Cell group the block's cells join.
    pub cell_group: Option<String>,
    /// Facet (and node) group of each face `s = 0`, `s = 1`, `t = 0`, `t = 1`, `w = 0`, `w = 1`.
    pub face_groups: [Option<String>; 6],
}

impl HexBlock {
    /// A block with uniform spacing and no groups.
    pub fn new(corners: [[f64; 3]; 8], n: [usize; 3]) -> Self {
        HexBlock {
            corners,
            n,
            grading: [1.0; 3],
            cell_group: None,
            face_groups: Default::default(),
        }
    }

    /// The axis-aligned box `[lo, hi]` as a block (s, t, w along x, y, z).
    pub fn cuboid(lo: [f64; 3], hi: [f64; 3], n: [usize; 3]) -> Self {
        let c = |i: usize, j: usize, k: usize| {
            [
                if i == 0 { lo[0] } else { hi[0] },
                if j == 0 { lo[1] } else { hi[1] },
                if k == 0 { lo[2] } else { hi[2] },
            ]
        };
        Self::new(
            [
                c(0, 0, 0),
                c(1, 0, 0),
                c(1, 1, 0),
                c(0, 1, 0),
                c(0, 0, 1),
                c(1, 0, 1),
                c(1, 1, 1),
                c(0, 1, 1),
            ],
            n,
        )
    }

    /// Sets the gradings along s, t and w (ratio last / first cell size).
    pub fn grading(mut self, g: [f64; 3]) -> Self {
        self.grading = g;
        self
    }

    /// Sets the cell group.
    pub fn group(mut self, name: &str) -> Self {
        self.cell_group = Some(name.to_string());
        self
    }

    /// Tags face `k` (0..6: `s = 0`, `s = 1`, `t = 0`, `t = 1`, `w = 0`, `w = 1`) with a
    /// facet/node group name.
    ///
    /// # Panics
    /// If `k >= 6`.
    pub fn face_group(mut self, k: usize, name: &str) -> Self {
        self.face_groups[k] = Some(name.to_string());
        self
    }

    /// The block with every corner mapped by `f` (a reflection gives a left-handed block,
    /// which the generator re-orients).
    pub fn mapped(&self, f: impl Fn([f64; 3]) -> [f64; 3]) -> Self {
        let mut b = self.clone();
        b.corners = self.corners.map(f);
        b
    }

    fn point(&self, s: f64, t: f64, w: f64) -> [f64; 3] {
        let n = [
            (1.0 - s) * (1.0 - t) * (1.0 - w),
            s * (1.0 - t) * (1.0 - w),
            s * t * (1.0 - w),
            (1.0 - s) * t * (1.0 - w),
            (1.0 - s) * (1.0 - t) * w,
            s * (1.0 - t) * w,
            s * t * w,
            (1.0 - s) * t * w,
        ];
        let mut x = [0.0; 3];
        for (k, c) in self.corners.iter().enumerate() {
            for d in 0..3 {
                x[d] += n[k] * c[d];
            }
        }
        x
    }
}

/// Signed volume factor `(b - a) . ((c - a) x (d - a))`.
fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// Jacobian signs of a `Hex8` at its eight corners and centre (tetrahedra at each corner).
fn hex_positive(x: &[[f64; 3]; 8]) -> bool {
    // Corner k: its three neighbours along the local edges, in right-handed order.
    const NB: [[usize; 3]; 8] = [
        [1, 3, 4],
        [2, 0, 5],
        [3, 1, 6],
        [0, 2, 7],
        [7, 5, 0],
        [4, 6, 1],
        [5, 7, 2],
        [6, 4, 3],
    ];
    let corners = (0..8).all(|k| triple(x[k], x[NB[k][0]], x[NB[k][1]], x[NB[k][2]]) > 0.0);
    // Centre: the mean edge vectors.
    let avg = |a: [usize; 4], b: [usize; 4]| {
        let mut v = [0.0; 3];
        for i in 0..4 {
            for d in 0..3 {
                v[d] += 0.25 * (x[b[i]][d] - x[a[i]][d]);
            }
        }
        v
    };
    let es = avg([0, 3, 4, 7], [1, 2, 5, 6]);
    let et = avg([0, 1, 4, 5], [3, 2, 7, 6]);
    let ew = avg([0, 1, 2, 3], [4, 5, 6, 7]);
    let centre = triple([0.0; 3], es, et, ew);
    corners && centre > 0.0
}

/// Merges points closer than `tol` (spatial hashing on cells of size `4 tol`).
struct NodeMerger {
    cell: f64,
    tol: f64,
    grid: HashMap<[i64; 3], Vec<usize>>,
}

impl NodeMerger {
    fn key(&self, x: [f64; 3]) -> [i64; 3] {
        x.map(|v| (v / self.cell).floor() as i64)
    }

    fn node(&mut self, mesh: &mut Mesh, x: [f64; 3]) -> usize {
        let k = self.key(x);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &i in list {
                            let y = mesh.coords[i];
                            let d2 = (0..3).map(|d| (x[d] - y[d]).powi(2)).sum::<f64>();
                            if d2 <= self.tol * self.tol {
                                return i;
                            }
                        }
                    }
                }
            }
        }
        let i = mesh.add_node(x);
        self.grid.entry(k).or_default().push(i);
        i
    }
}

/// Builds a conforming `Hex8` mesh from blocks.
///
/// # Errors
/// [`MeshError::Invalid`] for an empty block list, zero cell counts, non-positive or non-finite
/// gradings, non-finite corners, a folded block (non-positive Jacobian) or a face shared by more
/// than two cells.
pub fn multiblock_hex(blocks: &[HexBlock]) -> Result<Mesh, MeshError> {
    if blocks.is_empty() {
        return Err(MeshError::Invalid("multiblock_hex() needs blocks".into()));
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (bi, b) in blocks.iter().enumerate() {
        if b.n.contains(&0) {
            return Err(MeshError::Invalid(format!(
                "block {bi}: cell counts must be >= 1, got {:?}",
                b.n
            )));
        }
        if b.grading.iter().any(|g| !(g.is_finite() && *g > 0.0)) {
            return Err(MeshError::Invalid(format!(
                "block {bi}: gradings must be positive and finite, got {:?}",
                b.grading
            )));
        }
        for c in &b.corners {
            if c.iter().any(|v| !v.is_finite()) {
                return Err(MeshError::Invalid(format!(
                    "block {bi}: non-finite corner {c:?}"
                )));
            }
            for d in 0..3 {
                lo[d] = lo[d].min(c[d]);
                hi[d] = hi[d].max(c[d]);
            }
        }
    }
    let size = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    if !(size > 0.0) {
        return Err(MeshError::Invalid("the blocks have zero extent".into()));
    }
    let tol = 1e-9 * size;
    let mut merger = NodeMerger {
        cell: 4.0 * tol,
        tol,
        grid: HashMap::new(),
    };
    let mut mesh = Mesh::new(3);
    let mut groups: Vec<(String, Vec<Facet>, Vec<usize>)> = Vec::new();
    for (bi, b) in blocks.iter().enumerate() {
        let ds: Vec<Vec<f64>> = (0..3).map(|d| distribution(b.n[d], b.grading[d])).collect();
        let [ns, nt, nw] = b.n;
        let mut ids = vec![0usize; (ns + 1) * (nt + 1) * (nw + 1)];
        let at = |i: usize, j: usize, k: usize| (k * (nt + 1) + j) * (ns + 1) + i;
        for k in 0..=nw {
            for j in 0..=nt {
                for i in 0..=ns {
                    let x = b.point(ds[0][i], ds[1][j], ds[2][k]);
                    ids[at(i, j, k)] = merger.node(&mut mesh, x);
                }
            }
        }
        let left_handed = {
            let x: [[f64; 3]; 8] = std::array::from_fn(|k| b.corners[k]);
            !hex_positive(&x)
        };
        let first_cell = mesh.num_cells();
        // Cell (i, j, k) -> its global index, for the face groups.
        let mut cell_of = vec![0usize; ns * nt * nw];
        for k in 0..nw {
            for j in 0..nt {
                for i in 0..ns {
                    let mut nodes = [
                        ids[at(i, j, k)],
                        ids[at(i + 1, j, k)],
                        ids[at(i + 1, j + 1, k)],
                        ids[at(i, j + 1, k)],
                        ids[at(i, j, k + 1)],
                        ids[at(i + 1, j, k + 1)],
                        ids[at(i + 1, j + 1, k + 1)],
                        ids[at(i, j + 1, k + 1)],
                    ];
                    if left_handed {
                        nodes = [
                            nodes[4], nodes[5], nodes[6], nodes[7], nodes[0], nodes[1], nodes[2],
                            nodes[3],
                        ];
                    }
                    let x: [[f64; 3]; 8] = std::array::from_fn(|q| mesh.coords[nodes[q]]);
                    if !hex_positive(&x) {
                        return Err(MeshError::Invalid(format!(
                            "block {bi}: cell ({i}, {j}, {k}) has a non-positive Jacobian (the block folds or is degenerate)"
                        )));
                    }
                    cell_of[(k * nt + j) * ns + i] = mesh.add_cell(CellType::Hex8, &nodes);
                }
            }
        }
        if let Some(g) = &b.cell_group {
            mesh.add_cells_to_group(g, first_cell..mesh.num_cells());
        }
        for (face, name) in b.face_groups.iter().enumerate() {
            let Some(name) = name else { continue };
            let (axis, side) = (face / 2, face % 2);
            let mut facets = Vec::new();
            let mut nodes = Vec::new();
            for k in 0..nw {
                for j in 0..nt {
                    for i in 0..ns {
                        let idx = [i, j, k];
                        let last = [ns - 1, nt - 1, nw - 1];
                        if idx[axis] != if side == 0 { 0 } else { last[axis] } {
                            continue;
                        }
                        let c = cell_of[(k * nt + j) * ns + i];
                        // The four nodes of the cell on the block face.
                        let mut on: Vec<usize> = Vec::with_capacity(4);
                        for dk in 0..2 {
                            for dj in 0..2 {
                                for di in 0..2 {
                                    let d = [di, dj, dk];
                                    if d[axis] == side {
                                        on.push(ids[at(i + di, j + dj, k + dk)]);
                                    }
                                }
                            }
                        }
                        on.sort_unstable();
                        let cn = mesh.cell_nodes(c);
                        let facet = CellType::Hex8
                            .facets()
                            .iter()
                            .map(|(_, loc)| loc.iter().map(|&q| cn[q]).collect::<Vec<_>>())
                            .find(|f| {
                                let mut s = f.clone();
                                s.sort_unstable();
                                s == on
                            })
                            .ok_or_else(|| {
                                MeshError::Invalid(format!(
                                    "block {bi}: face {face} of cell ({i}, {j}, {k}) collapsed (merged nodes)"
                                ))
                            })?;
                        nodes.extend_from_slice(&facet);
                        facets.push(Facet {
                            kind: CellType::Quad4,
                            nodes: facet,
                        });
                    }
                }
            }
            match groups.iter_mut().find(|g| &g.0 == name) {
                Some(g) => {
                    g.1.extend(facets);
                    g.2.extend(nodes);
                }
                None => groups.push((name.clone(), facets, nodes)),
            }
        }
    }
    // Conformity: no face shared by more than two cells.
    let mut count: HashMap<Vec<usize>, usize> = HashMap::new();
    for (_, kind, nodes) in mesh.cells() {
        for (fk, loc) in kind.facets() {
            let f = Facet {
                kind: *fk,
                nodes: loc.iter().map(|&q| nodes[q]).collect(),
            };
            let e = count.entry(f.key()).or_insert(0);
            *e += 1;
            if *e > 2 {
                return Err(MeshError::Invalid(format!(
                    "face with nodes {:?} is shared by more than two cells (overlapping blocks)",
                    f.nodes
                )));
            }
        }
    }
    for (name, facets, nodes) in groups {
        mesh.add_facets_to_group(&name, facets);
        mesh.add_nodes_to_group(&name, nodes);
    }
    mesh.validate()?;
    Ok(mesh)
}

/// Ratio of the last to the first cell size of `m` cells spanning `len` whose first cell is
/// `h` (geometric progression, solved by bisection).
///
/// # Errors
/// [`MeshError::Invalid`] if `len <= m h` (the cells could not grow) or the data are not
/// positive and finite.
pub fn grading_for_first_cell(len: f64, h: f64, m: usize) -> Result<f64, MeshError> {
    if !(len.is_finite() && h.is_finite() && len > 0.0 && h > 0.0) || m == 0 {
        return Err(MeshError::Invalid(format!(
            "grading: need positive length, first cell and count, got {len}, {h}, {m}"
        )));
    }
    if m == 1 || len <= m as f64 * h {
        return Err(MeshError::Invalid(format!(
            "grading: {m} cells growing from {h} cannot span only {len} (need m >= 2 and len > m h)"
        )));
    }
    Ok(first_cell_grading(len, h, m))
}

/// [`grading_for_first_cell`] without its checks, for callers that made them: the ratio of the
/// last to the first cell size of `m` cells spanning `len > m h` whose first cell is `h > 0`
/// (1 for one cell).
pub fn first_cell_grading(len: f64, h: f64, m: usize) -> f64 {
    let mi = m as i32;
    // sum_{i<m} h r^i = len  <=>  h (r^m - 1) / (r - 1) = len; bisection on r > 1.
    let total = |r: f64| h * (r.powi(mi) - 1.0) / (r - 1.0);
    let (mut lo, mut hi) = (1.0 + 1e-12, 2.0f64);
    while total(hi) < len {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let r = 0.5 * (lo + hi);
        if total(r) < len {
            lo = r;
        } else {
            hi = r;
        }
    }
    (0.5 * (lo + hi)).powi(mi - 1)
}

/// Blocks of the octant `[0, l] x [0, l] x [-l, 0]` refined toward the origin, for point
/// contacts (a sphere on a flat at the origin, with quarter symmetry): a uniform cube
/// `[0, a]^2 x [-a, 0]` of `n^3` cells (size `h = a / n`) and three frusta joining its faces
/// `x = a`, `y = a`, `z = -a` to the box faces `x = l`, `y = l`, `z = -l`, each with `n x n`
/// cells across and `m` cells outward, graded so that the first one is `h`:
///
/// ```text
///    z = 0  +--contact--+-------free------+        (section y = 0)
///           |   cube    |     .           |
///           |  n^3, h   |  +x frustum     |  far_x
///   z = -a  +-----------+                 |
///           |   -z    .   .               |
///           | frustum       .             |
///   z = -l  +----------far_z--------------+
///          x=0          a                 l
/// ```
/// The frustum of `+x` is `{x >= a, y <= x, -z <= x}` (and likewise), so cells stay
/// about as wide as deep all the way out. Face groups: `"contact"` (the cube's face on
/// `z = 0`), `"free"` (the rest of `z = 0`), `"sym_x"` (`x = 0`), `"sym_y"` (`y = 0`),
/// `"far_x"`, `"far_y"`, `"far_z"` (the faces `x = l`, `y = l`, `z = -l`); cell group
/// `"body"`. Mirror the blocks ([`HexBlock::mapped`]) for other octants, then build with
/// [`multiblock_hex`].
///
/// # Errors
/// [`MeshError::Invalid`] unless `0 < a < l`, `n >= 1`, `m >= 2` and `l - a > m a / n`.
pub fn corner_refined_blocks(
    a: f64,
    l: f64,
    n: usize,
    m: usize,
) -> Result<Vec<HexBlock>, MeshError> {
    if !(a > 0.0 && l > a && l.is_finite()) || n == 0 {
        return Err(MeshError::Invalid(format!(
            "corner_refined_blocks: need 0 < a < l and n >= 1, got a = {a}, l = {l}, n = {n}"
        )));
    }
    let g = grading_for_first_cell(l - a, a / n as f64, m)?;
    let core = HexBlock::cuboid([0.0, 0.0, -a], [a, a, 0.0], [n, n, n])
        .group("body")
        .face_group(0, "sym_x")
        .face_group(2, "sym_y")
        .face_group(5, "contact");
    let plus_x = HexBlock::new(
        [
            [a, 0.0, -a],
            [l, 0.0, -l],
            [l, l, -l],
            [a, a, -a],
            [a, 0.0, 0.0],
            [l, 0.0, 0.0],
            [l, l, 0.0],
            [a, a, 0.0],
        ],
        [m, n, n],
    )
    .grading([g, 1.0, 1.0])
    .group("body")
    .face_group(1, "far_x")
    .face_group(2, "sym_y")
    .face_group(5, "free");
    let plus_y = HexBlock::new(
        [
            [0.0, a, -a],
            [a, a, -a],
            [l, l, -l],
            [0.0, l, -l],
            [0.0, a, 0.0],
            [a, a, 0.0],
            [l, l, 0.0],
            [0.0, l, 0.0],
        ],
        [n, m, n],
    )
    .grading([1.0, g, 1.0])
    .group("body")
    .face_group(0, "sym_x")
    .face_group(3, "far_y")
    .face_group(5, "free");
    let minus_z = HexBlock::new(
        [
            [0.0, 0.0, -l],
            [l, 0.0, -l],
            [l, l, -l],
            [0.0, l, -l],
            [0.0, 0.0, -a],
            [a, 0.0, -a],
            [a, a, -a],
            [0.0, a, -a],
        ],
        [n, n, m],
    )
    .grading([1.0, 1.0, 1.0 / g])
    .group("body")
    .face_group(0, "sym_x")
    .face_group(2, "sym_y")
    .face_group(4, "far_z");
    Ok(vec![core, plus_x, plus_y, minus_z])
}
