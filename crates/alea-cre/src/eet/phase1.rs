//! EET phase 1: traction densities on the element edges (thesis (3.20)-(3.22)).
//!
//! With `phi_i` the FE shape function of node `i` and `Q_E(i) = int_E sigma_h : eps(phi_i) -
//! int_E f phi_i` (a vector: one entry per direction), the prolongation condition (3.21) and the
//! element equilibrium (3.20) give, for every element `E` around node `i` ((3.22)):
//!
//! `sum_{Gamma in dE, i in Gamma} eta_E b_(i,Gamma) = Q_E(i)`,  `b_(i,Gamma) = int_Gamma F_hat phi_i dS`.
//!
//! Node by node this is a small system (one equation per element around the node, one unknown
//! per edge around it, per direction). Unknowns: interior edges, and boundary edges in the
//! directions constrained at all their nodes (the reaction is free there); on the other
//! boundary edges `b` is data: prescribed tractions, interface densities (see
//! [`interface_densities`]) or zero on free edges. The systems are singular (interior nodes) but
//! compatible when `u_h` is the FE solution for these loads: the node's equation sum is its FE
//! equilibrium. Among the solutions we take the one closest (Euclidean) to the projections of the
//! averaged FE tractions `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n phi_i`, the usual
//! minimisation of Ladeveze-Leguillon. A non-zero residual (incompatible data) is reported as
//! the compatibility defect. Directions are taken node by node in the frame of the node's
//! constraints (free directions, then constrained ones), so skew constraints are handled.
//!
//! For quadratic cells (T6/Q8) the same holds with every node of the mesh, vertex or mid-side
//! (the mid-side node's system has one unknown, determined by its FE equilibrium). On each edge
//! the density of degree `p` (1 or 2) is recovered from its `p + 1` projections through the
//! edge mass matrix: `F_a = (2 / L) (2 b_a - b_b)` on a 2-node edge. Everything is per unit
//! thickness.
//!
//! # Curved edges
//! A quadratic edge whose mid node is off the chord is the isoparametric curve `x(s)`,
//! `s in [0, 1]`, with length element `J(s) = |x'(s)|` and normal `n(s)`
//! ([`crate::topology::Edge::point`]); the FE shape functions restricted to it are the edge
//! shape functions `N_k(s)` of the reference parameter. The density is stored **per unit
//! reference length**: with `L` the chord length and `P(s) = sum_k N_k(s) F_k` the stored
//! quadratic polynomial ([`EdgeDensity::lin`]),
//!
//! `F_hat(x(s)) J(s) = L P(s)`, i.e. the traction `F_hat(x(s)) = (L / J(s)) P(s)`
//! ([`EdgeTractions::traction`]).
//!
//! Then `b_k = int_Gamma F_hat N_k dS = L int_0^1 P N_k ds = (M_L F)_k` with the same edge mass
//! matrix `M_L` as a straight edge of length `L`: the node systems (3.22), the recovery of `F`
//! from its projections and the interface densities are unchanged, and the projections hold
//! exactly. Because the isoparametric space reproduces the rigid modes exactly (`sum_i phi_i =
//! 1` and `sum_i phi_i (-y_i, x_i) = (-y, x)` on the curved cell), the prolongation condition
//! makes every cell's force **and moment** resultant of `F_hat` (plus the body force, with the
//! FE load rule) vanish to round-off, as on straight cells. On a straight edge `J = L` and the
//! representation is the usual one. A uniform stress `sigma_0` has the traction `sigma_0 n J /
//! L = sigma_0 (x'_y, -x'_x) / L`, linear in `s`: it is represented exactly. The targets
//! `b_bar` and the prescribed-traction projections are integrated on the curved edge
//! (`n(s)`, `J(s)`; for the latter the FE load vector's rule and facet geometry).

use std::sync::Arc;

use alea_fem::{DofMap, Model, Quadrature, kinematics::point_geometry};
use alea_mesh::Mesh;
use rayon::prelude::*;

use crate::CreError;
use crate::data::{SideForces, TractionField, VectorField};
use crate::fe::{facet_point, gauss01, hooke, mul3, strain_h, traction_of};
use crate::linalg::{cholesky_solve, least_change};

use super::sides::edge_mass;
pub use super::sides::{EdgeLinear, facet_projections, interface_densities};
use crate::topology::{EdgePoint, Topology};

/// Data part of an edge's density.
#[derive(Clone, Copy, Debug)]
pub struct EdgeData {
    /// Index of the traction field in the domain's load data.
    pub field: usize,
    /// Projector applied to the field (removes directions constrained along the edge).
    pub projector: [[f64; 2]; 2],
}

/// Density on one edge (first-cell orientation: the traction exerted on the edge's first cell).
#[derive(Clone, Debug, Default)]
pub struct EdgeDensity {
    /// Polynomial part: values at the edge's end nodes and mid node (the mid value is unused on
    /// a 2-node edge), interpolated with [`crate::topology::Edge::shape`].
    pub lin: [[f64; 2]; 3],
    /// Prescribed-traction part (possibly non-polynomial).
    pub data: Vec<EdgeData>,
}

/// Result of phase 1.
#[derive(Clone)]
pub struct EdgeTractions {
    /// Mesh edges (shared with the estimator context that built them).
    pub topo: Arc<Topology>,
    /// Density of each edge.
    pub density: Vec<EdgeDensity>,
    /// Prescribed traction fields (indexed by [`EdgeData::field`]).
    pub fields: Vec<TractionField>,
    /// Largest residual of the node systems relative to the largest node load (sum of the
    /// absolute element residuals and data at a node) of the domain: 0 when compatible.
    pub compatibility_defect: f64,
}

impl std::fmt::Debug for EdgeTractions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EdgeTractions")
            .field("edges", &self.density.len())
            .field("compatibility_defect", &self.compatibility_defect)
            .finish()
    }
}

impl EdgeTractions {
    /// Traction on edge `e`'s first cell at parameter `s in [0, 1]` (from `nodes[0]`), physical
    /// point `x` and first-cell outward normal `n` (on a curved edge: `x(s)` and `n(s)` of
    /// [`crate::topology::Edge::point`]; the polynomial part is then scaled by `L / J(s)`, see
    /// the module doc).
    pub fn traction(&self, e: usize, s: f64, x: [f64; 3], n: [f64; 2]) -> [f64; 2] {
        let edge = &self.topo.edges[e];
        let scale = if edge.curved {
            edge.chord() / edge.point(s).jac
        } else {
            1.0
        };
        self.traction_scaled(e, s, x, n, scale)
    }

    /// [`EdgeTractions::traction`] at the edge point `p` of parameter `s` (its `x`, `n` and
    /// `J`).
    pub fn traction_at(&self, e: usize, s: f64, p: &EdgePoint) -> [f64; 2] {
        let edge = &self.topo.edges[e];
        let scale = if edge.curved {
            edge.chord() / p.jac
        } else {
            1.0
        };
        self.traction_scaled(e, s, p.x, p.n, scale)
    }

    /// The polynomial density at `s` (values per unit chord length of the reference
    /// parametrisation: `t J / L`, see the module doc).
    pub fn polynomial(&self, e: usize, s: f64) -> [f64; 2] {
        let d = &self.density[e];
        let sh = self.topo.edges[e].shape(s);
        let mut t = [0.0; 2];
        for k in 0..3 {
            t[0] += sh[k] * d.lin[k][0];
            t[1] += sh[k] * d.lin[k][1];
        }
        t
    }

    fn traction_scaled(&self, e: usize, s: f64, x: [f64; 3], n: [f64; 2], scale: f64) -> [f64; 2] {
        let d = &self.density[e];
        let p = self.polynomial(e, s);
        let mut t = [scale * p[0], scale * p[1]];
        for ed in &d.data {
            let v = (self.fields[ed.field])(x, [n[0], n[1], 0.0]);
            let p = ed.projector;
            t[0] += p[0][0] * v[0] + p[0][1] * v[1];
            t[1] += p[1][0] * v[0] + p[1][1] * v[1];
        }
        t
    }
}

/// Inputs of phase 1 for one domain.
pub struct Phase1Input<'a> {
    /// Model (materials already scaled).
    pub model: &'a Model,
    /// Constraints of the domain.
    pub dofs: &'a DofMap,
    /// FE displacement, node-major.
    pub u: &'a [f64],
    /// Body force.
    pub body: Option<&'a VectorField>,
    /// Prescribed tractions by facet group.
    pub tractions: &'a [(String, TractionField)],
    /// Discrete interface forces by side.
    pub sides: &'a [SideForces],
}

pub use super::sides::NodeFrame;

/// Per node: orthonormal frame (rows) and the number of free directions (the rest are
/// constrained).
pub(crate) fn node_frames(dofs: &DofMap, nn: usize) -> Vec<NodeFrame> {
    let mut scratch = vec![0.0; dofs.num_free()];
    (0..nn)
        .map(|n| {
            if dofs.is_free_node(n) {
                return ([[1.0, 0.0], [0.0, 1.0]], 2);
            }
            let r = dofs.node_dofs(n);
            let nf = r.len();
            let mut free = [[0.0; 2]; 2];
            for c in 0..2 {
                let mut v = [0.0; 3];
                v[c] = 1.0;
                dofs.add_node_force(n, &v, &mut scratch);
                for (i, g) in r.clone().enumerate() {
                    free[i][c] = scratch[g];
                    scratch[g] = 0.0;
                }
            }
            match nf {
                0 => ([[1.0, 0.0], [0.0, 1.0]], 0),
                1 => {
                    let t = free[0];
                    ([t, [-t[1], t[0]]], 1)
                }
                _ => ([[1.0, 0.0], [0.0, 1.0]], 2),
            }
        })
        .collect()
}

/// True if direction `d` is constrained at a node with frame `f`.
fn constrained(f: &([[f64; 2]; 2], usize), d: [f64; 2]) -> bool {
    let free_part: f64 = (0..f.1)
        .map(|k| (f.0[k][0] * d[0] + f.0[k][1] * d[1]).powi(2))
        .sum();
    free_part < 1e-12
}

/// Projector `P = I - sum q q^T` of a boundary edge over the directions `q` constrained at all
/// its nodes (the traction there is a reaction, not data).
pub(crate) fn edge_projector(topo: &Topology, frames: &[NodeFrame], e: usize) -> [[f64; 2]; 2] {
    let a = topo.edges[e].nodes[0];
    let mut p = [[1.0, 0.0], [0.0, 1.0]];
    let fa = &frames[a];
    for k in fa.1..2 {
        let q = fa.0[k];
        if topo.edges[e]
            .all_nodes()
            .all(|nd| constrained(&frames[nd], q))
        {
            for i in 0..2 {
                for j in 0..2 {
                    p[i][j] -= q[i] * q[j];
                }
            }
        }
    }
    p
}

/// Known edge projections `b_known[e][slot]` (per unit thickness) and the densities being built.
pub(crate) struct EdgeLoads {
    /// Density of each edge (polynomial part and prescribed-traction data).
    pub density: Vec<EdgeDensity>,
    /// Known projections on boundary edges (prescribed tractions, interface densities).
    pub b_known: Vec<[[f64; 2]; 3]>,
}

impl EdgeLoads {
    /// No load on `ne` edges.
    pub fn new(ne: usize) -> Self {
        EdgeLoads {
            density: vec![EdgeDensity::default(); ne],
            b_known: vec![[[0.0; 2]; 3]; ne],
        }
    }

    /// Adds the prescribed tractions (projected on the unconstrained directions) as data
    /// densities and their projections, integrated with the rule of `alea_fem::Loads::traction`
    /// so that they are those of the FE load vector.
    pub fn add_tractions(
        &mut self,
        mesh: &Mesh,
        topo: &Topology,
        frames: &[NodeFrame],
        tractions: &[(String, TractionField)],
    ) -> Result<(), CreError> {
        for (fi, (group, field)) in tractions.iter().enumerate() {
            for f in mesh.facet_group(group)? {
                let e = topo.find(f.nodes[0], f.nodes[1]).ok_or_else(|| {
                    CreError::Invalid(format!(
                        "facet {:?} of '{group}' is not a mesh edge",
                        f.nodes
                    ))
                })?;
                if !topo.edges[e].is_boundary() {
                    return Err(CreError::Invalid(format!(
                        "traction group '{group}' contains the interior edge {:?}",
                        f.nodes
                    )));
                }
                let projector = edge_projector(topo, frames, e);
                self.density[e].data.push(EdgeData {
                    field: fi,
                    projector,
                });
                let edge = &topo.edges[e];
                let line_rule = Quadrature::for_cell(
                    alea_mesh::CellType::Line2,
                    2 * (1 + edge.mid.is_some() as usize) + 2,
                );
                for (xi, w) in line_rule.points.iter().zip(&line_rule.weights) {
                    let s = 0.5 * (xi[0] + 1.0);
                    // The FE load vector's facet geometry (isoparametric: curved edges too).
                    let EdgePoint { x, n, jac } = edge.point(s);
                    let v = field(x, [n[0], n[1], 0.0]);
                    let pv = [
                        projector[0][0] * v[0] + projector[0][1] * v[1],
                        projector[1][0] * v[0] + projector[1][1] * v[1],
                    ];
                    let dl = 0.5 * w * jac;
                    let sh = edge.shape(s);
                    for k in 0..3 {
                        for c in 0..2 {
                            self.b_known[e][k][c] += dl * sh[k] * pv[c];
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Adds the interface sides' densities ([`interface_densities`], split targets `b_bar`) as
    /// known polynomial densities of their boundary edges.
    #[allow(clippy::too_many_arguments)]
    pub fn add_sides(
        &mut self,
        mesh: &Mesh,
        topo: &Topology,
        frames: &[NodeFrame],
        sides: &[SideForces],
        thickness: f64,
        b_bar: &[[[f64; 2]; 3]],
    ) -> Result<(), CreError> {
        for side in sides {
            for (e, t) in interface_densities(mesh, topo, side, thickness, b_bar, Some(frames))? {
                if !topo.edges[e].is_boundary() {
                    return Err(CreError::Invalid(format!(
                        "interface side '{}' contains an interior edge",
                        side.group
                    )));
                }
                let p = edge_projector(topo, frames, e);
                let (_, len, _) = topo.geometry(mesh, e);
                let m = edge_mass(topo.edges[e].mid.is_some(), len);
                let mut pt = [[0.0; 2]; 3];
                for k in 0..3 {
                    pt[k] = [
                        p[0][0] * t[k][0] + p[0][1] * t[k][1],
                        p[1][0] * t[k][0] + p[1][1] * t[k][1],
                    ];
                }
                for k in 0..3 {
                    for c in 0..2 {
                        self.density[e].lin[k][c] += pt[k][c];
                        self.b_known[e][k][c] += (0..3).map(|j| m[k][j] * pt[j][c]).sum::<f64>();
                    }
                }
            }
        }
        Ok(())
    }

    /// Adds the densities of the node systems' solutions: each edge's degree-`p` density
    /// recovered from its projections `b_unknown[e][slot]` through the edge mass matrix.
    pub fn add_unknown(
        &mut self,
        mesh: &Mesh,
        topo: &Topology,
        b_unknown: &[[[f64; 2]; 3]],
    ) -> Result<(), CreError> {
        for (e, bu) in b_unknown.iter().enumerate() {
            let (_, len, _) = topo.geometry(mesh, e);
            if topo.edges[e].mid.is_some() {
                let m = edge_mass(true, len);
                for c in 0..2 {
                    let mut a: Vec<f64> = m.iter().flatten().copied().collect();
                    let mut b = vec![bu[0][c], bu[1][c], bu[2][c]];
                    if !cholesky_solve(&mut a, &mut b, 3) {
                        return Err(CreError::Invalid(format!("degenerate edge {e}")));
                    }
                    for k in 0..3 {
                        self.density[e].lin[k][c] += b[k];
                    }
                }
            } else {
                for c in 0..2 {
                    self.density[e].lin[0][c] += 2.0 / len * (2.0 * bu[0][c] - bu[1][c]);
                    self.density[e].lin[1][c] += 2.0 / len * (2.0 * bu[1][c] - bu[0][c]);
                }
            }
        }
        Ok(())
    }
}

/// The system (3.22) of one node in one direction `r` of its frame: one row per cell around the
/// node, one unknown per edge around it whose projection is not data (interior edges, and
/// boundary edges in a direction constrained at all their nodes). The unknowns are weighted,
/// `x = sqrt(L) y` (the Ladeveze-Leguillon minimisation `sum (x - x_bar)^2 / L`), so the
/// matrix holds `eta sqrt(L)`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NodeSystem {
    /// Rows: `(cell, local index of the node in the cell)`.
    pub rows: Vec<(u32, u32)>,
    /// Unknown projections `(edge, slot of the node on the edge)`.
    pub unknown: Vec<(u32, u32)>,
    /// `sqrt(L)` of each unknown edge.
    pub sqrt_len: Vec<f64>,
    /// Weighted matrix (`rows x unknowns`, row-major).
    pub a: Vec<f64>,
    /// Known projections entering the rows: `(row, edge, slot, eta)`.
    pub known: Vec<(u32, u32, u32, f64)>,
    /// Every edge around the node with the node's slot (scale of the known data).
    pub around: Vec<(u32, u32)>,
}

impl NodeSystem {
    /// The system of node `i` in direction `d` of its frame (`None` for a node without cell).
    /// Both directions of a node have the same rows; they differ only where `d` is a constrained
    /// direction (boundary edges become unknown).
    pub fn new(
        mesh: &Mesh,
        topo: &Topology,
        frames: &[NodeFrame],
        i: usize,
        d: usize,
    ) -> Option<NodeSystem> {
        let cells = &topo.node_cells[i];
        if cells.is_empty() {
            return None;
        }
        let edges = &topo.node_edges[i];
        let frame = &frames[i];
        let slot = |e: usize| topo.edges[e].slot(i).unwrap_or(0);
        let r = frame.0[d];
        let is_constrained_dir = d >= frame.1;
        let unknown: Vec<usize> = edges
            .iter()
            .copied()
            .filter(|&e| {
                let ed = &topo.edges[e];
                !ed.is_boundary()
                    || (is_constrained_dir && ed.all_nodes().all(|nd| constrained(&frames[nd], r)))
            })
            .collect();
        let m = cells.len();
        let nu = unknown.len();
        let sqrt_len: Vec<f64> = unknown
            .iter()
            .map(|&e| topo.geometry(mesh, e).1.sqrt())
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
            for &(e, eta) in &topo.cell_edges[c] {
                if topo.edges[e].slot(i).is_none() {
                    continue;
                }
                if let Some(col) = unknown.iter().position(|&u| u == e) {
                    a[row * nu + col] += eta;
                } else {
                    known.push((row as u32, e as u32, slot(e) as u32, eta));
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
                .map(|&e| (e as u32, slot(e) as u32))
                .collect(),
            sqrt_len,
            a,
            known,
            around: edges.iter().map(|&e| (e as u32, slot(e) as u32)).collect(),
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

    /// Right-hand side `Q_E(i) . r - sum_known eta b_known . r` into `rhs`, and the scale of the
    /// node's data `(sum |Q_E(i) . r|, sum_around |b_known . r|)`. `q(cell, local node)` is the
    /// element residual, `r` the system's direction.
    pub fn rhs(
        &self,
        r: [f64; 2],
        q: impl Fn(usize, usize) -> [f64; 2],
        b_known: &[[[f64; 2]; 3]],
        rhs: &mut Vec<f64>,
    ) -> (f64, f64) {
        rhs.clear();
        let mut scale = 0.0;
        for &(c, a_loc) in &self.rows {
            let qv = q(c as usize, a_loc as usize);
            let v = qv[0] * r[0] + qv[1] * r[1];
            scale += v.abs();
            rhs.push(v);
        }
        for &(row, e, slot, eta) in &self.known {
            let bk = b_known[e as usize][slot as usize];
            rhs[row as usize] -= eta * (bk[0] * r[0] + bk[1] * r[1]);
        }
        let known_scale: f64 = self
            .around
            .iter()
            .map(|&(e, slot)| {
                let bk = b_known[e as usize][slot as usize];
                (bk[0] * r[0] + bk[1] * r[1]).abs()
            })
            .sum();
        (scale, known_scale)
    }

    /// Weighted targets `y_bar = (b_bar . r) / sqrt(L)` of the unknowns into `y_bar`.
    pub fn targets(&self, r: [f64; 2], b_bar: &[[[f64; 2]; 3]], y_bar: &mut Vec<f64>) {
        y_bar.clear();
        for (&(e, slot), s) in self.unknown.iter().zip(&self.sqrt_len) {
            let bb = b_bar[e as usize][slot as usize];
            y_bar.push((bb[0] * r[0] + bb[1] * r[1]) / s);
        }
    }
}

/// Runs phase 1 on one domain.
pub fn phase1(inp: &Phase1Input) -> Result<EdgeTractions, CreError> {
    let model = inp.model;
    let mesh = &model.mesh;
    if mesh.dim != 2 {
        return Err(CreError::Invalid("the EET estimator is 2D only".into()));
    }
    let nn = mesh.num_nodes();
    if inp.u.len() != 2 * nn {
        return Err(CreError::Invalid(format!(
            "displacement of length {} for {nn} nodes",
            inp.u.len()
        )));
    }
    let topo = Topology::new(mesh)?;
    let th = model.analysis.thickness();
    let frames = node_frames(inp.dofs, nn);
    let ne = topo.edges.len();
    let mut loads = EdgeLoads::new(ne);
    loads.add_tractions(mesh, &topo, &frames, inp.tractions)?;
    // Element residuals Q_E(i) (per unit thickness) and FE stresses along the edges.
    let ncell = mesh.num_cells();
    let q_res: Vec<Vec<[f64; 2]>> = (0..ncell)
        .into_par_iter()
        .map(|c| -> Result<Vec<[f64; 2]>, CreError> {
            let mut ke = Vec::new();
            let kind = mesh.cell_type(c);
            let nodes = mesh.cell_nodes(c);
            let coords = model.cell_coords(c);
            alea_fem::assembly::element_stiffness(model, c, &mut ke)?;
            let m = nodes.len() * 2;
            let ue: Vec<f64> = nodes
                .iter()
                .flat_map(|&n| [inp.u[2 * n], inp.u[2 * n + 1]])
                .collect();
            let mut q = vec![[0.0; 2]; nodes.len()];
            for a in 0..nodes.len() {
                for ca in 0..2 {
                    let r = a * 2 + ca;
                    q[a][ca] = (0..m).map(|j| ke[r * m + j] * ue[j]).sum::<f64>() / th;
                }
            }
            if let Some(body) = inp.body {
                let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
                for (xi, w) in rule.points.iter().zip(&rule.weights) {
                    let g = point_geometry(kind, &coords, *xi);
                    let b = body(g.x);
                    for a in 0..nodes.len() {
                        for ca in 0..2 {
                            q[a][ca] -= w * g.det * g.n[a] * b[ca];
                        }
                    }
                }
            }
            Ok(q)
        })
        .collect::<Result<_, _>>()?;
    // b_bar: averaged FE traction projections, per edge and edge node (first orientation).
    let rule = gauss01(4);
    let b_bar: Vec<[[f64; 2]; 3]> = topo
        .edges
        .par_iter()
        .map(|edge| -> Result<[[f64; 2]; 3], CreError> {
            let mut bb = [[0.0; 2]; 3];
            let pts: Vec<EdgePoint> = rule.iter().map(|&(s, _)| edge.point(s)).collect();
            let share = 1.0 / edge.cells.len() as f64;
            for (k, &(c, l)) in edge.cells.iter().enumerate() {
                let kind = mesh.cell_type(c);
                let coords = model.cell_coords(c);
                let nodes = mesh.cell_nodes(c);
                let ue: Vec<f64> = nodes
                    .iter()
                    .flat_map(|&nd| [inp.u[2 * nd], inp.u[2 * nd + 1]])
                    .collect();
                let d = hooke(model.material(c)?, model.analysis);
                for (&(s, w), p) in rule.iter().zip(&pts) {
                    // The second cell runs along the edge in the opposite direction.
                    let s_cell = if k == 0 { s } else { 1.0 - s };
                    let (eps, _) = strain_h(kind, &coords, &ue, facet_point(kind, l, s_cell));
                    let t = traction_of(&mul3(&d, &eps), p.n);
                    let sh = edge.shape(s);
                    for kk in 0..3 {
                        for c2 in 0..2 {
                            bb[kk][c2] += share * w * p.jac * sh[kk] * t[c2];
                        }
                    }
                }
            }
            Ok(bb)
        })
        .collect::<Result<_, _>>()?;

    // Interface sides (after b_bar, which they use as the minimisation target).
    loads.add_sides(mesh, &topo, &frames, inp.sides, th, &b_bar)?;

    // Node systems.
    type NodeOut = (Vec<(usize, usize, [f64; 2])>, f64, f64);
    let per_node: Vec<NodeOut> = (0..nn)
        .into_par_iter()
        .map(|i| {
            let mut out: Vec<(usize, usize, [f64; 2])> = Vec::new();
            let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
            let (mut rhs, mut y_bar) = (Vec::new(), Vec::new());
            for d in 0..2 {
                let Some(sys) = NodeSystem::new(mesh, &topo, &frames, i, d) else {
                    break;
                };
                let r = frames[i].0[d];
                let (scale, known_scale) = sys.rhs(r, |c, a| q_res[c][a], &loads.b_known, &mut rhs);
                sys.targets(r, &b_bar, &mut y_bar);
                let (m, nu) = (sys.num_rows(), sys.num_unknowns());
                let (mut x, res) = least_change(&sys.a, m, nu, &rhs, &y_bar);
                for (v, s) in x.iter_mut().zip(&sys.sqrt_len) {
                    *v *= s;
                }
                max_res = max_res.max(res);
                max_scale = max_scale.max(scale + known_scale);
                for (col, &(e, slot)) in sys.unknown.iter().enumerate() {
                    out.push((e as usize, slot as usize, [x[col] * r[0], x[col] * r[1]]));
                }
            }
            (out, max_res, max_scale)
        })
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
    loads.add_unknown(mesh, &topo, &b_unknown)?;
    Ok(EdgeTractions {
        topo: Arc::new(topo),
        density: loads.density,
        fields: inp.tractions.iter().map(|t| t.1.clone()).collect(),
        compatibility_defect: if max_scale > 0.0 {
            max_res / max_scale
        } else {
            0.0
        },
    })
}
