//! EET phase 1 with everything that does not depend on the run computed once per domain
//! (multiresolution estimator, [`crate::DomainEstimator`]).
//!
//! Phase 1 ([`super::phase1`]) is linear in the run's data once the mesh, the constraints and the
//! reference materials are fixed. With a Young's factor `alpha` (`D = alpha D0`), cached:
//!
//! - per node and direction the system's matrix `A` and the operator `P = A^T (A A^T)^+` of the
//!   least-change solution, so that `y = y_bar + P (c - A y_bar)` (the direct path's cost: an
//!   eigendecomposition per node and direction);
//! - per cell type the reference shape-function gradients at the points of the FE stiffness
//!   rule and at the edge points of the traction projections: the element residuals
//!   `Q_E(i) = alpha int B_i^T D0 B u_e - int f phi_i` and the averaged FE traction projections
//!   `b_bar = alpha sum_cells int (D0 B u_e) n phi_k` are evaluated per run from them (a
//!   Jacobian per point; storing `K0_e` and the projection operators instead would cost
//!   ~1.3 KB per Q4 cell for ~0.5 us per cell saved);
//! - for an affine body force the moments `int phi_i`, `int x phi_i`, `int y phi_i` (on the FE
//!   load rule, computed on first use); a general one is integrated on that rule as in the
//!   direct path.
//!
//! - the edge mass matrices (recovery of the densities from their projections).
//!
//! Prescribed tractions and interface sides (boundary edges, run-dependent functions and forces)
//! are handled as in the direct path (`crate::kernel::loads::SideLoads`).

use std::sync::{Arc, OnceLock};

use alea_fem::reference::{MAX_NODES, shape};
use alea_fem::{DofMap, Model, Quadrature, kinematics::point_geometry};
use alea_mesh::CellType;
use rayon::prelude::*;

use super::phase1::{EdgeTractions, edge_density};
use super::projections::add_prescribed_tractions;
use crate::CreError;
use crate::data::{AffineBody, SideForces, TractionField, VectorField};
use crate::fe::{facet_point, gauss01, hooke, mul3, traction_of};
use crate::kernel::family::CellFamily;
use crate::kernel::frames::node_frames;
use crate::kernel::loads::SideLoads;
use crate::kernel::node_system::{NodeSolution, NodeSystem, gather_node_solutions, node_rhs};
use crate::kernel::phase1::{add_interface_sides, add_recovered};
use crate::kernel::vector::Frame;
use crate::linalg::least_change_operator;
use crate::topology::{EdgePoint, Topology};

/// Reference shape-function gradients of one cell type at the points of the FE stiffness rule
/// (with their weights) and, per local facet, at the 4 Gauss points of the traction
/// projections (in the facet's own direction).
#[derive(Clone, Debug)]
struct KindTable {
    stiffness: Vec<(f64, Vec<[f64; 2]>)>,
    facets: Vec<Vec<Vec<[f64; 2]>>>,
}

impl KindTable {
    fn new(kind: CellType, edge_rule: &[(f64, f64)]) -> Self {
        let nn = kind.num_nodes();
        let grads = |xi: [f64; 3]| -> Vec<[f64; 2]> {
            let mut n = [0.0; MAX_NODES];
            let mut dn = [[0.0; 3]; MAX_NODES];
            shape(kind, xi, &mut n, &mut dn);
            dn[..nn].iter().map(|d| [d[0], d[1]]).collect()
        };
        let rule = Quadrature::stiffness(kind);
        KindTable {
            stiffness: rule
                .points
                .iter()
                .zip(&rule.weights)
                .map(|(xi, w)| (*w, grads(*xi)))
                .collect(),
            facets: (0..kind.facets().len())
                .map(|l| {
                    edge_rule
                        .iter()
                        .map(|&(s, _)| grads(facet_point(kind, l, s)))
                        .collect()
                })
                .collect(),
        }
    }
}

/// FE strain `[e_xx, e_yy, g_xy]`, physical gradients and Jacobian determinant at a point with
/// reference gradients `dn` (the operations of `alea_fem::kinematics::point_geometry`).
#[inline]
fn strain_at(
    dn: &[[f64; 2]],
    coords: &[[f64; 3]],
    ue: &[f64],
    grad: &mut [[f64; 2]; MAX_NODES],
) -> ([f64; 3], f64) {
    let mut j = [[0.0; 2]; 2];
    for (d, x) in dn.iter().zip(coords) {
        for k in 0..2 {
            for l in 0..2 {
                j[k][l] += d[k] * x[l];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut e = [0.0; 3];
    for (a, d) in dn.iter().enumerate() {
        let gx = inv[0][0] * d[0] + inv[0][1] * d[1];
        let gy = inv[1][0] * d[0] + inv[1][1] * d[1];
        grad[a] = [gx, gy];
        let (ux, uy) = (ue[2 * a], ue[2 * a + 1]);
        e[0] += gx * ux;
        e[1] += gy * uy;
        e[2] += gy * ux + gx * uy;
    }
    (e, det)
}

/// The displacements `u` (node-major) of the nodes `nodes` of a cell, without allocation.
#[inline]
fn cell_dofs(u: &[f64], nodes: &[usize]) -> [f64; 2 * MAX_NODES] {
    let mut ue = [0.0; 2 * MAX_NODES];
    for (a, &nd) in nodes.iter().enumerate() {
        ue[2 * a] = u[2 * nd];
        ue[2 * a + 1] = u[2 * nd + 1];
    }
    ue
}

/// One node system: the unknowns and the least-change data in the shared pools.
#[derive(Clone, Copy, Debug)]
struct FlatSystem {
    /// Rows (cells around the node) and unknowns.
    m: u16,
    nu: u16,
    /// Offset of the unknowns `(edge, slot)` in `unknowns`.
    unknowns: u32,
    /// Offset of `[sqrt(L) (nu), A (m x nu), P (nu x m)]` in `values`.
    values: u32,
    /// Offset and number of the known projections in `known`.
    known: u32,
    nknown: u16,
}

/// Phase-1 cache of one 2D domain.
#[derive(Debug)]
pub(crate) struct Phase1Cache {
    /// Constraint frame of each node.
    pub frames: Vec<Frame<2>>,
    /// Mass matrix of each edge.
    masses: Vec<Vec<f64>>,
    /// Offset of each cell's first node in node-indexed per-cell arrays (`num_cells + 1`).
    cell_nodes: Vec<usize>,
    /// Shape tables by cell type (`CellType as usize`).
    tables: Vec<Option<KindTable>>,
    /// Edge rule of the traction projections.
    edge_rule: Vec<(f64, f64)>,
    /// Per node: its systems of directions 0 and 1 (`u32::MAX`: none), indices in `systems`.
    node_systems: Vec<[u32; 2]>,
    systems: Vec<FlatSystem>,
    unknowns: Vec<(u32, u32)>,
    values: Vec<f64>,
    /// Known projections `(row, edge, slot, eta)`.
    known: Vec<(u16, u32, u16, f64)>,
    /// Affine body moments per cell node (`[int N, int x N, int y N]`), on first use.
    body: OnceLock<Vec<[f64; 3]>>,
}

impl Phase1Cache {
    /// Builds the cache of `model` (reference materials) under `dofs`.
    pub fn new(model: &Model, dofs: &DofMap, topo: &Topology) -> Result<Self, CreError> {
        let mesh = &model.mesh;
        let nn = mesh.num_nodes();
        let ncell = mesh.num_cells();
        let frames = node_frames::<Topology, 2>(dofs, nn);
        let masses = (0..topo.edges.len())
            .map(|e| topo.side_mass(mesh, e))
            .collect();
        let mut cell_nodes = Vec::with_capacity(ncell + 1);
        cell_nodes.push(0);
        for c in 0..ncell {
            cell_nodes.push(cell_nodes[c] + mesh.cell_nodes(c).len());
        }
        let edge_rule = gauss01(4);
        let mut tables: Vec<Option<KindTable>> = Vec::new();
        for c in 0..ncell {
            let kind = mesh.cell_type(c);
            let i = kind as usize;
            if tables.len() <= i {
                tables.resize(i + 1, None);
            }
            if tables[i].is_none() {
                tables[i] = Some(KindTable::new(kind, &edge_rule));
            }
        }
        // Node systems and their least-change operators.
        let per_node: Vec<Vec<(NodeSystem, Vec<f64>)>> = (0..nn)
            .into_par_iter()
            .map(|i| {
                let mut out = Vec::new();
                let Some(s0) = NodeSystem::new(mesh, topo, &frames, i, 0) else {
                    return out;
                };
                let s1 = NodeSystem::new(mesh, topo, &frames, i, 1);
                for sys in std::iter::once(s0.clone()).chain(s1.filter(|s1| *s1 != s0)) {
                    let p = least_change_operator(&sys.a, sys.num_rows(), sys.num_unknowns());
                    out.push((sys, p));
                }
                out
            })
            .collect();
        let mut node_systems = Vec::with_capacity(nn);
        let mut systems = Vec::new();
        let mut unknowns = Vec::new();
        let mut values = Vec::new();
        let mut known = Vec::new();
        let too_big = || CreError::Invalid("node system too large for the estimator cache".into());
        for list in per_node {
            let first = systems.len() as u32;
            let mut dirs = [u32::MAX; 2];
            if !list.is_empty() {
                dirs = [first, first + (list.len() as u32 - 1)];
            }
            for (sys, p) in list {
                systems.push(FlatSystem {
                    m: u16::try_from(sys.num_rows()).map_err(|_| too_big())?,
                    nu: u16::try_from(sys.num_unknowns()).map_err(|_| too_big())?,
                    unknowns: u32::try_from(unknowns.len()).map_err(|_| too_big())?,
                    values: u32::try_from(values.len()).map_err(|_| too_big())?,
                    known: u32::try_from(known.len()).map_err(|_| too_big())?,
                    nknown: u16::try_from(sys.known.len()).map_err(|_| too_big())?,
                });
                unknowns.extend_from_slice(&sys.unknown);
                values.extend_from_slice(&sys.sqrt_len);
                values.extend_from_slice(&sys.a);
                values.extend_from_slice(&p);
                for &(row, e, slot, eta) in &sys.known {
                    known.push((row as u16, e, slot as u16, eta));
                }
            }
            node_systems.push(dirs);
        }
        u32::try_from(values.len()).map_err(|_| too_big())?;
        Ok(Phase1Cache {
            frames,
            masses,
            cell_nodes,
            tables,
            edge_rule,
            node_systems,
            systems,
            unknowns,
            values,
            known,
            body: OnceLock::new(),
        })
    }

    /// Bytes held by the cache (affine-body moments included once computed).
    pub fn bytes(&self) -> usize {
        let tables: usize = self
            .tables
            .iter()
            .flatten()
            .map(|t| {
                t.stiffness
                    .iter()
                    .map(|s| 16 * s.1.len() + 32)
                    .sum::<usize>()
                    + t.facets
                        .iter()
                        .flatten()
                        .map(|g| 16 * g.len() + 24)
                        .sum::<usize>()
            })
            .sum();
        8 * self.cell_nodes.len()
            + std::mem::size_of_val(&self.frames[..])
            + self.masses.iter().map(|m| 24 + 8 * m.len()).sum::<usize>()
            + std::mem::size_of_val(&self.node_systems[..])
            + std::mem::size_of_val(&self.systems[..])
            + std::mem::size_of_val(&self.unknowns[..])
            + 8 * self.values.len()
            + std::mem::size_of_val(&self.known[..])
            + tables
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

    fn table(&self, kind: CellType) -> &KindTable {
        self.tables[kind as usize]
            .as_ref()
            .expect("a shape table for every cell type of the mesh")
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
        let mut loads = SideLoads::new(topo.zero_values());
        add_prescribed_tractions(mesh, topo, &self.frames, tractions, &mut loads)?;
        let affine_moments = affine.map(|_| self.body_moments(model));
        // Element residuals Q_E(i) per unit thickness, by cell node.
        let q_res: Vec<Vec<[f64; 2]>> = (0..mesh.num_cells())
            .into_par_iter()
            .map(|c| -> Result<Vec<[f64; 2]>, CreError> {
                let nodes = mesh.cell_nodes(c);
                let kind = mesh.cell_type(c);
                let coords = model.cell_coords(c);
                let ue = cell_dofs(u, nodes);
                let d = hooke(model.material(c)?, model.analysis);
                let mut q = vec![[0.0; 2]; nodes.len()];
                let mut grad = [[0.0; 2]; MAX_NODES];
                for (w, dn) in &self.table(kind).stiffness {
                    let (e, det) = strain_at(dn, &coords, &ue, &mut grad);
                    let sg = mul3(&d, &e);
                    let f = alpha * w * det;
                    for (qa, g) in q.iter_mut().zip(&grad) {
                        qa[0] += f * (g[0] * sg[0] + g[1] * sg[2]);
                        qa[1] += f * (g[1] * sg[1] + g[0] * sg[2]);
                    }
                }
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
                Ok(q)
            })
            .collect::<Result<_, _>>()?;
        // b_bar: averaged FE traction projections (the second cell runs along the edge in the
        // opposite direction: point k of its facet is point n - 1 - k of the edge).
        let np = self.edge_rule.len();
        let b_bar: Vec<[[f64; 2]; 3]> = topo
            .edges
            .par_iter()
            .map(|edge| -> Result<[[f64; 2]; 3], CreError> {
                let pts: Vec<EdgePoint> =
                    self.edge_rule.iter().map(|&(s, _)| edge.point(s)).collect();
                let share = 1.0 / edge.cells.len() as f64;
                let mut bb = [[0.0; 2]; 3];
                let mut grad = [[0.0; 2]; MAX_NODES];
                for (k, &(c, l)) in edge.cells.iter().enumerate() {
                    let kind = mesh.cell_type(c);
                    let nodes = mesh.cell_nodes(c);
                    let coords = model.cell_coords(c);
                    let ue = cell_dofs(u, nodes);
                    let d = hooke(model.material(c)?, model.analysis);
                    let d = d.map(|row| row.map(|v| alpha * v));
                    let facet = &self.table(kind).facets[l];
                    for (p, &(s, w)) in self.edge_rule.iter().enumerate() {
                        let dn = &facet[if k == 0 { p } else { np - 1 - p }];
                        let (eps, _) = strain_at(dn, &coords, &ue, &mut grad);
                        let t = traction_of(&mul3(&d, &eps), pts[p].n);
                        let sh = edge.shape(s);
                        let wl = share * w * pts[p].jac;
                        for kk in 0..3 {
                            for c2 in 0..2 {
                                bb[kk][c2] += wl * sh[kk] * t[c2];
                            }
                        }
                    }
                }
                Ok(bb)
            })
            .collect::<Result<_, _>>()?;
        add_interface_sides(
            mesh,
            &**topo,
            &self.frames,
            sides,
            th,
            &b_bar,
            &self.masses,
            &mut loads,
        )?;
        // Node systems.
        let per_node: Vec<NodeSolution<2>> = self
            .node_systems
            .par_iter()
            .enumerate()
            .map_init(
                || (Vec::new(), Vec::new(), Vec::new(), Vec::new()),
                |(rhs, y_bar, t, y), (i, dirs)| {
                    let mut out = Vec::new();
                    let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
                    if dirs[0] == u32::MAX {
                        return (out, 0.0, 0.0);
                    }
                    for (d, &sid) in dirs.iter().enumerate() {
                        let sys = &self.systems[sid as usize];
                        let (m, nu) = (sys.m as usize, sys.nu as usize);
                        let r = self.frames[i].0[d];
                        let unknown = &self.unknowns[sys.unknowns as usize..][..nu];
                        let vals = &self.values[sys.values as usize..][..nu + 2 * m * nu];
                        let (sqrt_len, rest) = vals.split_at(nu);
                        let (a, p) = rest.split_at(m * nu);
                        let known = &self.known[sys.known as usize..][..sys.nknown as usize];
                        let (scale, known_scale) = node_rhs(
                            r,
                            topo.node_cells[i].iter().map(|&c| {
                                let nodes = mesh.cell_nodes(c);
                                q_res[c][nodes.iter().position(|&nd| nd == i).unwrap_or(0)]
                            }),
                            known.iter().map(|&(row, e, slot, eta)| {
                                (row as usize, e as usize, slot as usize, eta)
                            }),
                            topo.node_edges[i]
                                .iter()
                                .map(|&e| (e, topo.edges[e].slot(i).unwrap_or(0))),
                            &loads.b_known,
                            rhs,
                        );
                        y_bar.clear();
                        for (&(e, slot), sq) in unknown.iter().zip(sqrt_len) {
                            let bb = b_bar[e as usize][slot as usize];
                            y_bar.push((bb[0] * r[0] + bb[1] * r[1]) / sq);
                        }
                        // t = c - A y_bar; y = y_bar + P t; residual c - A y.
                        t.clear();
                        t.extend((0..m).map(|row| {
                            rhs[row]
                                - (0..nu)
                                    .map(|col| a[row * nu + col] * y_bar[col])
                                    .sum::<f64>()
                        }));
                        y.clear();
                        y.extend((0..nu).map(|col| {
                            y_bar[col] + (0..m).map(|row| p[col * m + row] * t[row]).sum::<f64>()
                        }));
                        let res = (0..m)
                            .map(|row| {
                                let v = rhs[row]
                                    - (0..nu).map(|col| a[row * nu + col] * y[col]).sum::<f64>();
                                v * v
                            })
                            .sum::<f64>()
                            .sqrt();
                        max_res = max_res.max(res);
                        max_scale = max_scale.max(scale + known_scale);
                        for (col, &(e, slot)) in unknown.iter().enumerate() {
                            let x = y[col] * sqrt_len[col];
                            out.push((e as usize, slot as usize, [x * r[0], x * r[1]]));
                        }
                    }
                    (out, max_res, max_scale)
                },
            )
            .collect();
        let mut b_unknown = topo.zero_values();
        let compatibility_defect = gather_node_solutions(per_node, &mut b_unknown);
        add_recovered(mesh, &**topo, &self.masses, &b_unknown, &mut loads.values)?;
        Ok(EdgeTractions::from_parts(
            topo.clone(),
            loads.values,
            loads.data,
            tractions,
            compatibility_defect,
            edge_density,
        ))
    }
}
