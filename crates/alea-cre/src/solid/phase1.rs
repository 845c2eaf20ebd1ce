//! EET phase 1 in 3D: traction densities on the element faces (thesis (3.20)-(3.22), with faces
//! in place of edges).
//!
//! With `phi_i` the FE shape function of node `i` and `Q_E(i) = int_E sigma_h : eps(phi_i) -
//! int_E f phi_i` (a vector: one entry per direction), the prolongation condition (3.21) and the
//! element equilibrium (3.20) give, for every element `E` around node `i` ((3.22)):
//!
//! `sum_{Gamma face of E, i in Gamma} eta_(E,Gamma) b_(i,Gamma) = Q_E(i)`,
//! `b_(i,Gamma) = int_Gamma F_hat phi_i dS`.
//!
//! Node by node this is a small system per direction: one equation per element around the
//! node, one unknown per face around it (interior faces; boundary faces in the directions
//! constrained at all their nodes, where the reaction is free). On the other boundary faces
//! `b` is data: prescribed tractions (integrated with the rule of `alea_fem::Loads::traction`, so
//! that the node systems are compatible to round-off), interface densities
//! ([`super::sides::interface_densities`]) or zero on free faces. Among the solutions we take
//! the one closest to the projections of the averaged FE tractions
//! `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n phi_i`, in the norm
//! `sum_Gamma (b - b_bar)^2 / |Gamma|` (Ladeveze-Leguillon's minimisation, weighted by the face
//! areas as the 2D code weights by edge lengths). The systems are singular (interior nodes:
//! every column holds `+1` and `-1`) but compatible when `u_h` is the FE solution for these
//! loads; a non-zero residual is reported as the compatibility defect. Directions are taken
//! node by node in the frame of the node's constraints (free directions first), so skew
//! constraints are handled.
//!
//! For Tet10 the same holds for every node, vertex or mid-edge (a mid-edge node's system has
//! the elements and faces around its edge). On each face the density of the face's degree
//! (linear on Tri3, bilinear on Quad4, quadratic on Tri6) is recovered from its projections
//! through the face mass matrix: `M F = b`, `M_ab = int_Gamma N_a N_b dS`.

use alea_fem::{DofMap, Model, Quadrature, kinematics::point_geometry};
use rayon::prelude::*;

use super::sides::{fe_traction, interface_densities};
use super::topology::{FaceTopology, face_mass};
use crate::CreError;
use crate::data::{SideForces, TractionField, VectorField};
use crate::linalg::{cholesky_solve, least_change};

/// Data part of a face's density.
#[derive(Clone, Copy, Debug)]
pub struct FaceData {
    /// Index of the traction field in the domain's load data.
    pub field: usize,
    /// Projector applied to the field (removes directions constrained on the whole face).
    pub projector: [[f64; 3]; 3],
}

/// Density on one face (first-cell orientation: the traction exerted on the face's first cell).
#[derive(Clone, Debug, Default)]
pub struct FaceDensity {
    /// Polynomial part: values at the face's nodes, interpolated with the face's shape functions.
    pub values: Vec<[f64; 3]>,
    /// Prescribed-traction part (possibly non-polynomial).
    pub data: Vec<FaceData>,
}

/// Result of phase 1 in 3D.
#[derive(Clone)]
pub struct FaceTractions {
    /// Mesh faces.
    pub topo: FaceTopology,
    /// Density of each face.
    pub density: Vec<FaceDensity>,
    /// Prescribed traction fields (indexed by [`FaceData::field`]).
    pub fields: Vec<TractionField>,
    /// Largest residual of the node systems relative to the largest node load (sum of the
    /// absolute element residuals and data at a node): 0 when compatible.
    pub compatibility_defect: f64,
}

impl std::fmt::Debug for FaceTractions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FaceTractions")
            .field("faces", &self.density.len())
            .field("compatibility_defect", &self.compatibility_defect)
            .finish()
    }
}

impl FaceTractions {
    /// Traction on face `f`'s first cell at a face point with face shape values `shape`,
    /// physical point `x` and first-cell outward normal `n`.
    pub fn traction(&self, f: usize, shape: &[f64], x: [f64; 3], n: [f64; 3]) -> [f64; 3] {
        let d = &self.density[f];
        let mut t = [0.0; 3];
        for (a, v) in d.values.iter().enumerate() {
            for c in 0..3 {
                t[c] += shape[a] * v[c];
            }
        }
        for fd in &d.data {
            let v = (self.fields[fd.field])(x, n);
            let p = fd.projector;
            for c in 0..3 {
                t[c] += p[c][0] * v[0] + p[c][1] * v[1] + p[c][2] * v[2];
            }
        }
        t
    }
}

/// Inputs of phase 1 for one 3D domain.
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

pub use super::sides::NodeFrame3;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// A unit vector orthogonal to the unit vector `t`.
fn orthogonal(t: [f64; 3]) -> [f64; 3] {
    let k = (0..3)
        .min_by(|&a, &b| t[a].abs().total_cmp(&t[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    unit(cross(t, e))
}

/// Per node: orthonormal frame and number of free directions.
pub(crate) fn node_frames(dofs: &DofMap, nn: usize) -> Vec<NodeFrame3> {
    let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut scratch = vec![0.0; dofs.num_free()];
    (0..nn)
        .map(|n| {
            if dofs.is_free_node(n) {
                return (id, 3);
            }
            let r = dofs.node_dofs(n);
            let nf = r.len();
            let mut free = [[0.0; 3]; 3];
            for c in 0..3 {
                let mut v = [0.0; 3];
                v[c] = 1.0;
                dofs.add_node_force(n, &v, &mut scratch);
                for (i, g) in r.clone().enumerate() {
                    free[i][c] = scratch[g];
                    scratch[g] = 0.0;
                }
            }
            match nf {
                0 => (id, 0),
                1 => {
                    let t = unit(free[0]);
                    let o = orthogonal(t);
                    ([t, o, cross(t, o)], 1)
                }
                2 => {
                    let (t1, t2) = (unit(free[0]), unit(free[1]));
                    ([t1, t2, unit(cross(t1, t2))], 2)
                }
                _ => (id, 3),
            }
        })
        .collect()
}

/// True if direction `d` is constrained at a node with frame `f`.
pub(crate) fn constrained(f: &NodeFrame3, d: [f64; 3]) -> bool {
    let free_part: f64 = (0..f.1).map(|k| dot(f.0[k], d).powi(2)).sum();
    free_part < 1e-12
}

/// Projector `I - sum q q^T` over the directions constrained at every node of face `f`.
fn face_projector(topo: &FaceTopology, frames: &[NodeFrame3], f: usize) -> [[f64; 3]; 3] {
    let face = &topo.faces[f];
    let fa = &frames[face.nodes[0]];
    let mut p = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for k in fa.1..3 {
        let q = fa.0[k];
        if face.nodes.iter().all(|&nd| constrained(&frames[nd], q)) {
            for i in 0..3 {
                for j in 0..3 {
                    p[i][j] -= q[i] * q[j];
                }
            }
        }
    }
    p
}

fn apply(p: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| p[i][0] * v[0] + p[i][1] * v[1] + p[i][2] * v[2])
}

/// Runs phase 1 on one 3D domain.
pub fn phase1(inp: &Phase1Input) -> Result<FaceTractions, CreError> {
    let model = inp.model;
    let mesh = &model.mesh;
    if mesh.dim != 3 {
        return Err(CreError::Invalid(
            "the 3D EET phase 1 needs a 3D mesh".into(),
        ));
    }
    let nn = mesh.num_nodes();
    if inp.u.len() != 3 * nn {
        return Err(CreError::Invalid(format!(
            "displacement of length {} for {nn} nodes",
            inp.u.len()
        )));
    }
    let topo = FaceTopology::new(mesh)?;
    let frames = node_frames(inp.dofs, nn);
    let nf = topo.faces.len();
    let mut density: Vec<FaceDensity> = topo
        .faces
        .iter()
        .map(|f| FaceDensity {
            values: vec![[0.0; 3]; f.nodes.len()],
            data: Vec::new(),
        })
        .collect();
    // Known projections b on boundary faces: b_known[f][slot] (vector).
    let mut b_known: Vec<Vec<[f64; 3]>> = topo
        .faces
        .iter()
        .map(|f| vec![[0.0; 3]; f.nodes.len()])
        .collect();
    for (fi, (group, field)) in inp.tractions.iter().enumerate() {
        // The facets as `Loads::traction` sees them (outward, in the cell's local order).
        for bf in mesh.attach_facets(mesh.facet_group(group)?, None)? {
            let fnodes = &bf.facet.nodes;
            let f = topo
                .find(&fnodes[..bf.facet.kind.num_corners()])
                .ok_or_else(|| {
                    CreError::Invalid(format!("facet {fnodes:?} of '{group}' is not a mesh face"))
                })?;
            let face = &topo.faces[f];
            if !face.is_boundary() {
                return Err(CreError::Invalid(format!(
                    "traction group '{group}' contains the interior face {fnodes:?}"
                )));
            }
            let projector = face_projector(&topo, &frames, f);
            density[f].data.push(FaceData {
                field: fi,
                projector,
            });
            let coords: Vec<[f64; 3]> = fnodes.iter().map(|&n| mesh.coords[n]).collect();
            let kind = bf.facet.kind;
            let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
            for (rs, w) in rule.points.iter().zip(&rule.weights) {
                let g = alea_fem::kinematics::facet_geometry(kind, &coords, *rs);
                let v = apply(&projector, field(g.x, g.normal));
                for (a, &node) in fnodes.iter().enumerate() {
                    let slot = face.slot(node).unwrap_or(0);
                    for c in 0..3 {
                        b_known[f][slot][c] += w * g.jac * g.n[a] * v[c];
                    }
                }
            }
        }
    }
    // Element residuals Q_E(i).
    let ncell = mesh.num_cells();
    let q_res: Vec<Vec<[f64; 3]>> = (0..ncell)
        .into_par_iter()
        .map(|c| -> Result<Vec<[f64; 3]>, CreError> {
            let mut ke = Vec::new();
            let kind = mesh.cell_type(c);
            let nodes = mesh.cell_nodes(c);
            let coords = model.cell_coords(c);
            alea_fem::assembly::element_stiffness(model, c, &mut ke)?;
            let m = nodes.len() * 3;
            let ue: Vec<f64> = nodes
                .iter()
                .flat_map(|&n| [inp.u[3 * n], inp.u[3 * n + 1], inp.u[3 * n + 2]])
                .collect();
            let mut q = vec![[0.0; 3]; nodes.len()];
            for a in 0..nodes.len() {
                for ca in 0..3 {
                    let r = a * 3 + ca;
                    q[a][ca] = (0..m).map(|j| ke[r * m + j] * ue[j]).sum::<f64>();
                }
            }
            if let Some(body) = inp.body {
                let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
                for (xi, w) in rule.points.iter().zip(&rule.weights) {
                    let g = point_geometry(kind, &coords, *xi);
                    let b = body(g.x);
                    for a in 0..nodes.len() {
                        for ca in 0..3 {
                            q[a][ca] -= w * g.det * g.n[a] * b[ca];
                        }
                    }
                }
            }
            Ok(q)
        })
        .collect::<Result<_, _>>()?;
    // b_bar: averaged FE traction projections, per face and face node (first orientation).
    let b_bar: Vec<Vec<[f64; 3]>> = topo
        .faces
        .par_iter()
        .map(|face| -> Result<Vec<[f64; 3]>, CreError> {
            let mut bb = vec![[0.0; 3]; face.nodes.len()];
            let share = 1.0 / face.cells.len() as f64;
            let rule = Quadrature::for_cell(face.kind, 2 * face.kind.order() + 3);
            for (rs, w) in rule.points.iter().zip(&rule.weights) {
                let g = face.geometry(mesh, *rs);
                for k in 0..face.cells.len() {
                    let xi = face.cell_point(mesh, k, *rs);
                    let t = fe_traction(model, face.cells[k].0, inp.u, xi, g.normal)?;
                    for (a, b) in bb.iter_mut().enumerate() {
                        for c in 0..3 {
                            b[c] += share * w * g.jac * g.n[a] * t[c];
                        }
                    }
                }
            }
            Ok(bb)
        })
        .collect::<Result<_, _>>()?;
    let masses: Vec<Vec<f64>> = topo.faces.iter().map(|f| face_mass(mesh, f)).collect();

    // Interface sides (after b_bar, which they use as the minimisation target).
    for side in inp.sides {
        for (f, t) in interface_densities(mesh, &topo, side, &b_bar, Some(&frames))? {
            if !topo.faces[f].is_boundary() {
                return Err(CreError::Invalid(format!(
                    "interface side '{}' contains an interior face",
                    side.group
                )));
            }
            let p = face_projector(&topo, &frames, f);
            let nfn = t.len();
            let pt: Vec<[f64; 3]> = t.iter().map(|v| apply(&p, *v)).collect();
            let m = &masses[f];
            for a in 0..nfn {
                for c in 0..3 {
                    density[f].values[a][c] += pt[a][c];
                    b_known[f][a][c] += (0..nfn).map(|b| m[a * nfn + b] * pt[b][c]).sum::<f64>();
                }
            }
        }
    }

    // Node systems.
    type NodeOut = (Vec<(usize, usize, [f64; 3])>, f64, f64);
    let per_node: Vec<NodeOut> = (0..nn)
        .into_par_iter()
        .map(|i| {
            let mut out: Vec<(usize, usize, [f64; 3])> = Vec::new();
            let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
            let cells = &topo.node_cells[i];
            if cells.is_empty() {
                return (out, 0.0, 0.0);
            }
            let faces = &topo.node_faces[i];
            let frame = &frames[i];
            let slot = |f: usize| topo.faces[f].slot(i).unwrap_or(0);
            for d in 0..3 {
                let r = frame.0[d];
                let is_constrained_dir = d >= frame.1;
                let unknown: Vec<usize> = faces
                    .iter()
                    .copied()
                    .filter(|&f| {
                        let face = &topo.faces[f];
                        !face.is_boundary()
                            || (is_constrained_dir
                                && face.nodes.iter().all(|&nd| constrained(&frames[nd], r)))
                    })
                    .collect();
                let m = cells.len();
                let nu = unknown.len();
                let mut a = vec![0.0; m * nu];
                let mut rhs = vec![0.0; m];
                let mut scale = 0.0;
                for (row, &c) in cells.iter().enumerate() {
                    let a_loc = mesh
                        .cell_nodes(c)
                        .iter()
                        .position(|&nd| nd == i)
                        .unwrap_or(0);
                    rhs[row] = dot(q_res[c][a_loc], r);
                    scale += rhs[row].abs();
                    for &(f, eta) in &topo.cell_faces[c] {
                        if topo.faces[f].slot(i).is_none() {
                            continue;
                        }
                        if let Some(col) = unknown.iter().position(|&u| u == f) {
                            a[row * nu + col] += eta;
                        } else {
                            rhs[row] -= eta * dot(b_known[f][slot(f)], r);
                        }
                    }
                }
                let sq: Vec<f64> = unknown.iter().map(|&f| topo.faces[f].area.sqrt()).collect();
                for row in 0..m {
                    for col in 0..nu {
                        a[row * nu + col] *= sq[col];
                    }
                }
                let y_bar: Vec<f64> = unknown
                    .iter()
                    .zip(&sq)
                    .map(|(&f, s)| dot(b_bar[f][slot(f)], r) / s)
                    .collect();
                let (mut x, res) = least_change(&a, m, nu, &rhs, &y_bar);
                for (v, s) in x.iter_mut().zip(&sq) {
                    *v *= s;
                }
                let known_scale: f64 = faces
                    .iter()
                    .map(|&f| dot(b_known[f][slot(f)], r).abs())
                    .sum();
                max_res = max_res.max(res);
                max_scale = max_scale.max(scale + known_scale);
                for (col, &f) in unknown.iter().enumerate() {
                    out.push((f, slot(f), [x[col] * r[0], x[col] * r[1], x[col] * r[2]]));
                }
            }
            (out, max_res, max_scale)
        })
        .collect();
    let mut b_unknown: Vec<Vec<[f64; 3]>> = topo
        .faces
        .iter()
        .map(|f| vec![[0.0; 3]; f.nodes.len()])
        .collect();
    let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
    for (out, res, scale) in per_node {
        max_res = max_res.max(res);
        max_scale = max_scale.max(scale);
        for (f, slot, v) in out {
            for c in 0..3 {
                b_unknown[f][slot][c] += v[c];
            }
        }
    }
    for f in 0..nf {
        let nfn = topo.faces[f].nodes.len();
        if b_unknown[f].iter().all(|v| *v == [0.0; 3]) {
            continue;
        }
        for c in 0..3 {
            let mut a = masses[f].clone();
            let mut b: Vec<f64> = b_unknown[f].iter().map(|v| v[c]).collect();
            if !cholesky_solve(&mut a, &mut b, nfn) {
                return Err(CreError::Invalid(format!("degenerate face {f}")));
            }
            for k in 0..nfn {
                density[f].values[k][c] += b[k];
            }
        }
    }
    Ok(FaceTractions {
        topo,
        density,
        fields: inp.tractions.iter().map(|t| t.1.clone()).collect(),
        compatibility_defect: if max_scale > 0.0 {
            max_res / max_scale
        } else {
            0.0
        },
    })
}
