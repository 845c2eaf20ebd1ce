//! EET phase 1 with everything that does not depend on the run computed once per domain
//! (multiresolution estimator, [`crate::DomainEstimator`]).
//!
//! Phase 1 ([`super::phase1`]) is linear in the run's data once the mesh, the constraints and the
//! reference materials are fixed. With a Young's factor `alpha` (`D = alpha D0`), cached:
//!
//! - per cell the FE stiffness `K0_e` (packed), so that `Q_E(i) = alpha (K0_e u_e)_i / t -
//!   int f phi_i`; for an affine body force the moments `int phi_i`, `int x phi_i`,
//!   `int y phi_i` (on the FE load rule, computed on first use), a general one is integrated
//!   on that rule as in the direct path;
//! - per edge and adjacent cell the operator that maps `u_e` to the cell's FE traction
//!   projections `int (sigma_h n) phi_k` on the edge (times the averaging share), so that
//!   `b_bar = alpha sum_cells B_bar u_e`;
//! - per node and direction the system's matrix `A` and the operator `P = A^T (A A^T)^+` of the
//!   least-change solution, so that `y = y_bar + P (c - A y_bar)`.
//!
//! Prescribed tractions and interface sides (boundary edges, run-dependent functions and forces)
//! are handled as in the direct path ([`super::phase1::EdgeLoads`]).

use std::sync::{Arc, OnceLock};

use alea_fem::{DofMap, Model, Quadrature, kinematics::point_geometry};
use rayon::prelude::*;

use super::phase1::{EdgeLoads, EdgeTractions, NodeFrame, NodeSystem, node_frames};
use crate::CreError;
use crate::data::{AffineBody, SideForces, TractionField, VectorField};
use crate::fe::{facet_point, gauss01, hooke, mul3, traction_of};
use crate::linalg::least_change_operator;
use crate::topology::Topology;

/// Index of the packed lower triangle entry `(i, j)`, `j <= i`.
#[inline]
fn tri(i: usize, j: usize) -> usize {
    i * (i + 1) / 2 + j
}

/// A node system with its least-change operator.
#[derive(Clone, Debug)]
struct CachedSystem {
    sys: NodeSystem,
    /// `P = A^T (A A^T)^+` (`unknowns x rows`).
    p: Vec<f64>,
}

/// The systems of one node: `dirs[d]` indexes `systems` (both directions share one system
/// when they have the same unknowns).
#[derive(Clone, Debug)]
struct NodeCache {
    systems: Vec<CachedSystem>,
    dirs: [u8; 2],
}

/// Phase-1 cache of one 2D domain.
#[derive(Debug)]
pub(crate) struct Phase1Cache {
    /// Constraint frame of each node.
    pub frames: Vec<NodeFrame>,
    /// Offset of each cell's first node in node-indexed per-cell arrays (`num_cells + 1`).
    cell_nodes: Vec<usize>,
    /// Packed FE stiffness of each cell (thickness included), from `stiffness_offsets[c]`.
    stiffness: Vec<f64>,
    stiffness_offsets: Vec<usize>,
    /// Per edge, per adjacent cell: `(slots x 2) x 2 nn` operator (row-major), from
    /// `bbar_offsets[e]`, cells in the edge's order.
    bbar: Vec<f64>,
    bbar_offsets: Vec<usize>,
    nodes: Vec<Option<NodeCache>>,
    /// Affine body moments per cell node (`[int N, int x N, int y N]`), on first use.
    body: OnceLock<Vec<[f64; 3]>>,
}

/// Number of projection slots of an edge (ends, and the mid node of a quadratic edge).
fn slots(topo: &Topology, e: usize) -> usize {
    2 + topo.edges[e].mid.is_some() as usize
}

impl Phase1Cache {
    /// Builds the cache of `model` (reference materials) under `dofs`.
    pub fn new(model: &Model, dofs: &DofMap, topo: &Topology) -> Result<Self, CreError> {
        let mesh = &model.mesh;
        let nn = mesh.num_nodes();
        let ncell = mesh.num_cells();
        let frames = node_frames(dofs, nn);
        let mut cell_nodes = Vec::with_capacity(ncell + 1);
        cell_nodes.push(0);
        for c in 0..ncell {
            cell_nodes.push(cell_nodes[c] + mesh.cell_nodes(c).len());
        }
        let per_cell: Vec<Vec<f64>> = (0..ncell)
            .into_par_iter()
            .map(|c| -> Result<Vec<f64>, CreError> {
                let mut ke = Vec::new();
                alea_fem::assembly::element_stiffness(model, c, &mut ke)?;
                let m = 2 * mesh.cell_nodes(c).len();
                let mut packed = Vec::with_capacity(m * (m + 1) / 2);
                for i in 0..m {
                    packed.extend_from_slice(&ke[i * m..i * m + i + 1]);
                }
                Ok(packed)
            })
            .collect::<Result<_, _>>()?;
        let mut stiffness_offsets = Vec::with_capacity(ncell + 1);
        stiffness_offsets.push(0);
        for k in &per_cell {
            stiffness_offsets.push(stiffness_offsets.last().copied().unwrap_or(0) + k.len());
        }
        let stiffness = per_cell.concat();

        let rule = gauss01(4);
        let per_edge: Vec<Vec<f64>> = topo
            .edges
            .par_iter()
            .enumerate()
            .map(|(e, edge)| -> Result<Vec<f64>, CreError> {
                let (n, len, _) = topo.geometry(mesh, e);
                let share = 1.0 / edge.cells.len() as f64;
                let ns = slots(topo, e);
                let mut out = Vec::new();
                for (k, &(c, l)) in edge.cells.iter().enumerate() {
                    let kind = mesh.cell_type(c);
                    let coords = model.cell_coords(c);
                    let m = 2 * coords.len();
                    let d = hooke(model.material(c)?, model.analysis);
                    let mut op = vec![0.0; 2 * ns * m];
                    for &(s, w) in &rule {
                        let s_cell = if k == 0 { s } else { 1.0 - s };
                        let g = point_geometry(kind, &coords, facet_point(kind, l, s_cell));
                        let sh = edge.shape(s);
                        for a in 0..coords.len() {
                            let [gx, gy, _] = g.grad[a];
                            for (j, eps) in [[gx, 0.0, gy], [0.0, gy, gx]].iter().enumerate() {
                                let t = traction_of(&mul3(&d, eps), n);
                                for kk in 0..ns {
                                    for c2 in 0..2 {
                                        op[(2 * kk + c2) * m + 2 * a + j] +=
                                            share * w * len * sh[kk] * t[c2];
                                    }
                                }
                            }
                        }
                    }
                    out.extend_from_slice(&op);
                }
                Ok(out)
            })
            .collect::<Result<_, _>>()?;
        let mut bbar_offsets = Vec::with_capacity(per_edge.len() + 1);
        bbar_offsets.push(0);
        for b in &per_edge {
            bbar_offsets.push(bbar_offsets.last().copied().unwrap_or(0) + b.len());
        }
        let bbar = per_edge.concat();

        let nodes: Vec<Option<NodeCache>> = (0..nn)
            .into_par_iter()
            .map(|i| {
                let s0 = NodeSystem::new(mesh, topo, &frames, i, 0)?;
                let s1 = NodeSystem::new(mesh, topo, &frames, i, 1)?;
                let cached = |sys: NodeSystem| {
                    let p = least_change_operator(&sys.a, sys.num_rows(), sys.num_unknowns());
                    CachedSystem { sys, p }
                };
                Some(if s0 == s1 {
                    NodeCache {
                        systems: vec![cached(s0)],
                        dirs: [0, 0],
                    }
                } else {
                    NodeCache {
                        systems: vec![cached(s0), cached(s1)],
                        dirs: [0, 1],
                    }
                })
            })
            .collect();
        Ok(Phase1Cache {
            frames,
            cell_nodes,
            stiffness,
            stiffness_offsets,
            bbar,
            bbar_offsets,
            nodes,
            body: OnceLock::new(),
        })
    }

    /// Bytes held by the cache (affine-body moments included once computed).
    pub fn bytes(&self) -> usize {
        let sys: usize = self
            .nodes
            .iter()
            .flatten()
            .map(|n| {
                std::mem::size_of::<NodeCache>()
                    + n.systems
                        .iter()
                        .map(|c| {
                            let s = &c.sys;
                            std::mem::size_of::<CachedSystem>()
                                + 8 * (s.rows.len()
                                    + s.unknown.len()
                                    + s.sqrt_len.len()
                                    + s.a.len()
                                    + s.around.len()
                                    + c.p.len())
                                + 24 * s.known.len()
                        })
                        .sum::<usize>()
            })
            .sum();
        8 * (self.cell_nodes.len()
            + self.stiffness.len()
            + self.stiffness_offsets.len()
            + self.bbar.len()
            + self.bbar_offsets.len()
            + self.nodes.len())
            + std::mem::size_of_val(&self.frames[..])
            + sys
            + self.body.get().map_or(0, |b| 24 * b.len())
    }

    fn body_moments(&self, model: &Model) -> &[[f64; 3]] {
        self.body.get_or_init(|| {
            let mesh = &model.mesh;
            (0..mesh.num_cells())
                .into_par_iter()
                .map(|c| {
                    let kind = mesh.cell_type(c);
                    let coords = model.cell_coords(c);
                    let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
                    let mut mom = vec![[0.0; 3]; coords.len()];
                    for (xi, w) in rule.points.iter().zip(&rule.weights) {
                        let g = point_geometry(kind, &coords, *xi);
                        for (a, ma) in mom.iter_mut().enumerate() {
                            let wn = w * g.det * g.n[a];
                            ma[0] += wn;
                            ma[1] += wn * g.x[0];
                            ma[2] += wn * g.x[1];
                        }
                    }
                    mom
                })
                .collect::<Vec<_>>()
                .concat()
        })
    }

    /// Phase 1 for a run: `model` with its reference materials, `alpha` the Young's factor,
    /// `u` the FE displacement (node-major).
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &self,
        model: &Model,
        topo: &Arc<Topology>,
        u: &[f64],
        alpha: f64,
        body: Option<&VectorField>,
        affine: Option<&AffineBody>,
        tractions: &[(String, TractionField)],
        sides: &[SideForces],
    ) -> Result<EdgeTractions, CreError> {
        let mesh = &model.mesh;
        let th = model.analysis.thickness();
        let ne = topo.edges.len();
        let mut loads = EdgeLoads::new(ne);
        loads.add_tractions(mesh, topo, &self.frames, tractions)?;
        let affine_moments = affine.map(|_| self.body_moments(model));
        // Element residuals Q_E(i) per unit thickness, by cell node.
        let q_res: Vec<Vec<[f64; 2]>> = (0..mesh.num_cells())
            .into_par_iter()
            .map(|c| {
                let nodes = mesh.cell_nodes(c);
                let m = 2 * nodes.len();
                let k = &self.stiffness[self.stiffness_offsets[c]..self.stiffness_offsets[c + 1]];
                let mut ue = [0.0; 16];
                for (a, &nd) in nodes.iter().enumerate() {
                    ue[2 * a] = u[2 * nd];
                    ue[2 * a + 1] = u[2 * nd + 1];
                }
                let mut ku = [0.0; 16];
                for i in 0..m {
                    let row = &k[tri(i, 0)..tri(i, 0) + i + 1];
                    let mut s = row[i] * ue[i];
                    for j in 0..i {
                        s += row[j] * ue[j];
                        ku[j] += row[j] * ue[i];
                    }
                    ku[i] += s;
                }
                let scale = alpha / th;
                let mut q: Vec<[f64; 2]> = (0..nodes.len())
                    .map(|a| [scale * ku[2 * a], scale * ku[2 * a + 1]])
                    .collect();
                if let (Some(b), Some(mom)) = (affine, affine_moments) {
                    let mom = &mom[self.cell_nodes[c]..self.cell_nodes[c + 1]];
                    for (qa, ma) in q.iter_mut().zip(mom) {
                        for (ca, qc) in qa.iter_mut().enumerate() {
                            *qc -= b.constant[ca] * ma[0]
                                + b.gradient[ca][0] * ma[1]
                                + b.gradient[ca][1] * ma[2];
                        }
                    }
                } else if let Some(body) = body {
                    let kind = mesh.cell_type(c);
                    let coords = model.cell_coords(c);
                    let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
                    for (xi, w) in rule.points.iter().zip(&rule.weights) {
                        let g = point_geometry(kind, &coords, *xi);
                        let b = body(g.x);
                        for (a, qa) in q.iter_mut().enumerate() {
                            for ca in 0..2 {
                                qa[ca] -= w * g.det * g.n[a] * b[ca];
                            }
                        }
                    }
                }
                q
            })
            .collect();
        // b_bar.
        let b_bar: Vec<[[f64; 2]; 3]> = topo
            .edges
            .par_iter()
            .enumerate()
            .map(|(e, edge)| {
                let ns = slots(topo, e);
                let mut bb = [[0.0; 2]; 3];
                let mut off = self.bbar_offsets[e];
                for &(c, _) in &edge.cells {
                    let nodes = mesh.cell_nodes(c);
                    let m = 2 * nodes.len();
                    let op = &self.bbar[off..off + 2 * ns * m];
                    off += 2 * ns * m;
                    for kk in 0..ns {
                        for c2 in 0..2 {
                            let row = &op[(2 * kk + c2) * m..(2 * kk + c2 + 1) * m];
                            let mut s = 0.0;
                            for (a, &nd) in nodes.iter().enumerate() {
                                s += row[2 * a] * u[2 * nd] + row[2 * a + 1] * u[2 * nd + 1];
                            }
                            bb[kk][c2] += alpha * s;
                        }
                    }
                }
                bb
            })
            .collect();
        loads.add_sides(mesh, topo, &self.frames, sides, th, &b_bar)?;
        // Node systems.
        type NodeOut = (Vec<(usize, usize, [f64; 2])>, f64, f64);
        let per_node: Vec<NodeOut> = self
            .nodes
            .par_iter()
            .enumerate()
            .map_init(
                || (Vec::new(), Vec::new(), Vec::new(), Vec::new()),
                |(rhs, y_bar, t, y), (i, nc)| {
                    let mut out = Vec::new();
                    let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
                    let Some(nc) = nc else {
                        return (out, 0.0, 0.0);
                    };
                    for d in 0..2 {
                        let cs = &nc.systems[nc.dirs[d] as usize];
                        let sys = &cs.sys;
                        let r = self.frames[i].0[d];
                        let (scale, known_scale) =
                            sys.rhs(r, |c, a| q_res[c][a], &loads.b_known, rhs);
                        sys.targets(r, &b_bar, y_bar);
                        let (m, nu) = (sys.num_rows(), sys.num_unknowns());
                        // t = c - A y_bar; y = y_bar + P t; residual c - A y.
                        t.clear();
                        t.extend((0..m).map(|row| {
                            rhs[row]
                                - (0..nu)
                                    .map(|col| sys.a[row * nu + col] * y_bar[col])
                                    .sum::<f64>()
                        }));
                        y.clear();
                        y.extend((0..nu).map(|col| {
                            y_bar[col] + (0..m).map(|row| cs.p[col * m + row] * t[row]).sum::<f64>()
                        }));
                        let res = (0..m)
                            .map(|row| {
                                let v = rhs[row]
                                    - (0..nu)
                                        .map(|col| sys.a[row * nu + col] * y[col])
                                        .sum::<f64>();
                                v * v
                            })
                            .sum::<f64>()
                            .sqrt();
                        max_res = max_res.max(res);
                        max_scale = max_scale.max(scale + known_scale);
                        for (col, &(e, slot)) in sys.unknown.iter().enumerate() {
                            let x = y[col] * sys.sqrt_len[col];
                            out.push((e as usize, slot as usize, [x * r[0], x * r[1]]));
                        }
                    }
                    (out, max_res, max_scale)
                },
            )
            .collect();
        let mut b_unknown = vec![[[0.0; 2]; 3]; ne];
        let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
        for (out, res, scale) in per_node {
            max_res = max_res.max(res);
            max_scale = max_scale.max(scale);
            for (e, slot, v) in out {
                b_unknown[e][slot][0] += v[0];
                b_unknown[e][slot][1] += v[1];
            }
        }
        loads.add_unknown(mesh, topo, &b_unknown)?;
        Ok(EdgeTractions {
            topo: topo.clone(),
            density: loads.density,
            fields: tractions.iter().map(|t| t.1.clone()).collect(),
            compatibility_defect: if max_scale > 0.0 {
                max_res / max_scale
            } else {
                0.0
            },
        })
    }
}
