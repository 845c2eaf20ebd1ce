//! Multi-block mapped quadrilateral meshes (2D) with transfinite (Coons) interpolation.
//!
//! A [`Block`] is a curvilinear quadrilateral given by its four corners `c0 c1 c2 c3` and four
//! edges `e_k` from corner `k` to corner `k + 1 (mod 4)`, each a [`Curve`] parametrised by
//! `u in [0, 1]` from its start corner to its end corner. Block coordinates `(s, t) in [0, 1]^2`
//! run along `e0` (s, from `c0` to `c1`) and along `e1` (t, from `c1` to `c2`):
//!
//! ```text
//!        c3 <------ e2 ------- c2          bottom B(s) = e0(s)       right R(t) = e1(t)
//!        |                      ^          top    T(s) = e2(1 - s)   left  L(t) = e3(1 - t)
//!    e3  |     t ^              |  e1
//!        v       |--> s         |
//!        c0 ------- e0 ------> c1
//! ```
//! The point of block coordinates `(s, t)` is the Coons patch (bilinearly blended transfinite
//! interpolation)
//!
//! ```text
//! X(s,t) = (1-t) B(s) + t T(s) + (1-s) L(t) + s R(t)
//!        - [ (1-s)(1-t) c0 + s(1-t) c1 + s t c2 + (1-s) t c3 ]
//! ```
//! which reproduces the four edges exactly. Each block is divided into `n[0] x n[1]` cells along
//! s and t; the node parameters follow a geometric progression whose ratio of last to first cell
//! size is `grading[d]` (1 = uniform; in s the first cell touches `e3`, in t it touches `e0`).
//! Quadratic cells (`Quad8`, `Tri6`) get their mid-side nodes at the parametric mid-points mapped
//! by X, so they lie on curved edges. Triangles split each quad `(a, b, c, d)` along the diagonal
//! a-c into `(a, b, c)` and `(a, c, d)`.
//!
//! Blocks whose corners are given clockwise are re-ordered (counter-clockwise cells are produced
//! in all cases); a cell with a non-positive Jacobian after that means the mapping folds, and is an
//! error. Corners closer than `1e-9` times the size of the model are merged. Two blocks share an
//! edge when its two end corners coincide and its curves' mid-points coincide; the shared edge must
//! then have the same number of cells in both blocks and the same node positions (gradings
//! mirrored if the edge is traversed in opposite directions), and the two blocks must lie on
//! opposite sides of it (no overlap, at most two blocks per edge), otherwise [`multiblock`]
//! returns [`MeshError::Invalid`](crate::MeshError::Invalid). Nodes are merged along shared edges, so the mesh is conforming;
//! distinct nodes at the same position after that (an edge met twice with different curves or
//! parametrisations) are reported as an error. Parts that must stay un-merged along an interface
//! (contact) are generated separately and joined with [`Mesh::append`](crate::Mesh::append).
//!
//! Groups: a block's cells join the cell group `Block::cell_group` (if set); an edge tagged with a
//! name gives a facet group of that name (the edge's cell facets, outward from the block) and a
//! node group with the same name holding the edge's nodes.

mod assemble;
mod block;
mod curve;
mod mapping;

pub use assemble::multiblock;
pub use block::{Block, Curve, CurveFn};
pub(crate) use curve::Prepared;
pub(crate) use mapping::distribution;
