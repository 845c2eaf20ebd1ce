//! The node systems of phase 1 (thesis (3.22)): for node `i` and direction `r` of its frame,
//!
//! `sum_{Gamma in dE, i in Gamma} eta_(E,Gamma) b_(i,Gamma) . r = Q_E(i) . r` for every cell `E`
//! around `i`, `b_(i,Gamma) = int_Gamma F_hat phi_i dS`,
//!
//! one row per cell around the node, one unknown per side around it whose projection is not
//! data (interior sides, and boundary sides in a direction constrained at all their nodes); the
//! known projections move to the right-hand side. The systems are singular (interior nodes) but
//! compatible when `u_h` is the FE solution for the loads; among the solutions we take the one
//! closest to the averaged FE traction projections `b_bar` in the norm
//! `sum_Gamma (b - b_bar)^2 / |Gamma|` (Ladeveze-Leguillon), through the weighted unknowns
//! `x = sqrt(|Gamma|) y` and [`least_change`]. The residual, relative to the node's data, is
//! the compatibility defect.

use alea_mesh::Mesh;
use rayon::prelude::*;

use super::frames::constrained_on_side;
use super::topology::SideTopology;
use super::vector::{Frame, dot};
use crate::linalg::least_change;

/// The system (3.22) of one node in one direction of its frame; the matrix holds
/// `eta sqrt(|Gamma|)` (weighted unknowns).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NodeSystem {
    /// Rows: `(cell, local index of the node in the cell)`.
    pub rows: Vec<(u32, u32)>,
    /// Unknown projections `(side, slot of the node on the side)`.
    pub unknown: Vec<(u32, u32)>,
    /// `sqrt(|Gamma|)` of each unknown side.
    pub sqrt_len: Vec<f64>,
    /// Weighted matrix (`rows x unknowns`, row-major).
    pub a: Vec<f64>,
    /// Known projections entering the rows: `(row, side, slot, eta)`.
    pub known: Vec<(u32, u32, u32, f64)>,
    /// Every side around the node with the node's slot (scale of the known data).
    pub around: Vec<(u32, u32)>,
}

/// Right-hand side `Q_E(i) . r - sum_known eta b_known . r` of a node system into `rhs`, and the
/// scale of the node's data `(sum |Q_E(i) . r|, sum_around |b_known . r|)`: `row_loads` are the
/// `Q_E(i)` of the rows, `known` the `(row, side, slot, eta)` of the known projections, `around`
/// the `(side, slot)` of every side around the node.
pub(crate) fn node_rhs<B: AsRef<[[f64; D]]>, const D: usize>(
    r: [f64; D],
    row_loads: impl Iterator<Item = [f64; D]>,
    known: impl Iterator<Item = (usize, usize, usize, f64)>,
    around: impl Iterator<Item = (usize, usize)>,
    b_known: &[B],
    rhs: &mut Vec<f64>,
) -> (f64, f64) {
    rhs.clear();
    let mut scale = 0.0;
    for q in row_loads {
        let v = dot(q, r);
        scale += v.abs();
        rhs.push(v);
    }
    for (row, s, slot, eta) in known {
        rhs[row] -= eta * dot(b_known[s].as_ref()[slot], r);
    }
    let known_scale: f64 = around
        .map(|(s, slot)| dot(b_known[s].as_ref()[slot], r).abs())
        .sum();
    (scale, known_scale)
}

impl NodeSystem {
    /// The system of node `i` in direction `d` of its frame (`None` for a node without cell).
    /// The directions of a node have the same rows; they differ only where `d` is a constrained
    /// direction (boundary sides become unknown).
    pub fn new<T: SideTopology<D>, const D: usize>(
        mesh: &Mesh,
        topo: &T,
        frames: &[Frame<D>],
        i: usize,
        d: usize,
    ) -> Option<NodeSystem> {
        let cells = topo.node_cells(i);
        if cells.is_empty() {
            return None;
        }
        let sides = topo.node_sides(i);
        let frame = &frames[i];
        let slot = |s: usize| topo.slot(s, i).unwrap_or(0);
        let r = frame.0[d];
        let is_constrained_dir = d >= frame.1;
        let unknown: Vec<usize> = sides
            .iter()
            .copied()
            .filter(|&s| {
                !topo.is_boundary(s)
                    || (is_constrained_dir && constrained_on_side(topo, frames, s, r))
            })
            .collect();
        let m = cells.len();
        let nu = unknown.len();
        let sqrt_len: Vec<f64> = unknown
            .iter()
            .map(|&s| topo.measure(mesh, s).sqrt())
            .collect();
        let mut a = vec![0.0; m * nu];
        let mut rows = Vec::with_capacity(m);
        let mut known = Vec::new();
        for (row, &c) in cells.iter().enumerate() {
            let a_loc = mesh
                .cell_nodes(c)
                .iter()
                .position(|&nd| nd == i)
                .unwrap_or(0);
            rows.push((c as u32, a_loc as u32));
            for &(s, eta) in topo.cell_sides(c) {
                if topo.slot(s, i).is_none() {
                    continue;
                }
                if let Some(col) = unknown.iter().position(|&u| u == s) {
                    a[row * nu + col] += eta;
                } else {
                    known.push((row as u32, s as u32, slot(s) as u32, eta));
                }
            }
        }
        for row in 0..m {
            for col in 0..nu {
                a[row * nu + col] *= sqrt_len[col];
            }
        }
        Some(NodeSystem {
            rows,
            unknown: unknown
                .iter()
                .map(|&s| (s as u32, slot(s) as u32))
                .collect(),
            sqrt_len,
            a,
            known,
            around: sides.iter().map(|&s| (s as u32, slot(s) as u32)).collect(),
        })
    }

    /// Number of rows.
    pub fn num_rows(&self) -> usize {
        self.rows.len()
    }

    /// Number of unknowns.
    pub fn num_unknowns(&self) -> usize {
        self.unknown.len()
    }

    /// [`node_rhs`] of this system: `q(cell, local node)` is the element residual `Q_E(i)`.
    pub fn rhs<B: AsRef<[[f64; D]]>, const D: usize>(
        &self,
        r: [f64; D],
        q: impl Fn(usize, usize) -> [f64; D],
        b_known: &[B],
        rhs: &mut Vec<f64>,
    ) -> (f64, f64) {
        node_rhs(
            r,
            self.rows.iter().map(|&(c, a)| q(c as usize, a as usize)),
            self.known
                .iter()
                .map(|&(row, s, slot, eta)| (row as usize, s as usize, slot as usize, eta)),
            self.around
                .iter()
                .map(|&(s, slot)| (s as usize, slot as usize)),
            b_known,
            rhs,
        )
    }

    /// Weighted targets `y_bar = (b_bar . r) / sqrt(|Gamma|)` of the unknowns into `y_bar`.
    pub fn targets<B: AsRef<[[f64; D]]>, const D: usize>(
        &self,
        r: [f64; D],
        b_bar: &[B],
        y_bar: &mut Vec<f64>,
    ) {
        y_bar.clear();
        for (&(s, slot), sq) in self.unknown.iter().zip(&self.sqrt_len) {
            y_bar.push(dot(b_bar[s as usize].as_ref()[slot as usize], r) / sq);
        }
    }
}

/// The projections found at one node: `(side, slot, b)`, its largest residual and data scale.
pub(crate) type NodeSolution<const D: usize> = (Vec<(usize, usize, [f64; D])>, f64, f64);

/// Solves the systems of every node (every direction of its frame) with the element residuals
/// `q_res[cell][local node]`, the known projections and the targets.
pub(crate) fn solve_node_systems<T: SideTopology<D>, B, const D: usize>(
    mesh: &Mesh,
    topo: &T,
    frames: &[Frame<D>],
    q_res: &[Vec<[f64; D]>],
    b_known: &[B],
    b_bar: &[B],
) -> Vec<NodeSolution<D>>
where
    B: AsRef<[[f64; D]]> + Sync,
{
    (0..mesh.num_nodes())
        .into_par_iter()
        .map(|i| {
            let mut out = Vec::new();
            let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
            let (mut rhs, mut y_bar) = (Vec::new(), Vec::new());
            for d in 0..D {
                let Some(sys) = NodeSystem::new(mesh, topo, frames, i, d) else {
                    break;
                };
                let r = frames[i].0[d];
                let (scale, known_scale) = sys.rhs(r, |c, a| q_res[c][a], b_known, &mut rhs);
                sys.targets(r, b_bar, &mut y_bar);
                let (m, nu) = (sys.num_rows(), sys.num_unknowns());
                let (mut x, res) = least_change(&sys.a, m, nu, &rhs, &y_bar);
                for (v, s) in x.iter_mut().zip(&sys.sqrt_len) {
                    *v *= s;
                }
                max_res = max_res.max(res);
                max_scale = max_scale.max(scale + known_scale);
                for (col, &(s, slot)) in sys.unknown.iter().enumerate() {
                    out.push((s as usize, slot as usize, r.map(|v| x[col] * v)));
                }
            }
            (out, max_res, max_scale)
        })
        .collect()
}

/// Adds the node solutions to the unknown projections `b_unknown[side][slot]` (in node order)
/// and returns the compatibility defect: the largest residual relative to the largest data
/// scale (0 without data).
pub(crate) fn gather_node_solutions<B: AsMut<[[f64; D]]>, const D: usize>(
    per_node: Vec<NodeSolution<D>>,
    b_unknown: &mut [B],
) -> f64 {
    let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
    for (out, res, scale) in per_node {
        max_res = max_res.max(res);
        max_scale = max_scale.max(scale);
        for (s, slot, v) in out {
            let b = &mut b_unknown[s].as_mut()[slot];
            for c in 0..D {
                b[c] += v[c];
            }
        }
    }
    if max_scale > 0.0 {
        max_res / max_scale
    } else {
        0.0
    }
}
