//! Post-processing of a displacement field: strains and stresses at quadrature points and at
//! nodes (recovered by averaging the values each adjacent cell gives at the node), von Mises,
//! internal and reaction forces, strain energy `1/2 int sigma : eps dV`.

use rayon::prelude::*;

use crate::kinematics::point_geometry;
use crate::reference::MAX_NODES;
use crate::reference::node_coords;
use crate::{FemError, Model, Quadrature, von_mises};

fn cell_strain_at(model: &Model, c: usize, u: &[f64], xi: [f64; 3]) -> ([f64; 6], f64, [f64; 3]) {
    let kind = model.mesh.cell_type(c);
    let dim = model.mesh.dim;
    let nodes = model.mesh.cell_nodes(c);
    let mut coords = [[0.0; 3]; MAX_NODES];
    for (x, &n) in coords.iter_mut().zip(nodes) {
        *x = model.mesh.coords[n];
    }
    let g = point_geometry(kind, &coords[..nodes.len()], xi);
    // `eps = B u_e` with the rows of `kinematics::strain_operator` (engineering shears), summed
    // node by node and component by component in the order of the product `B u_e`, without
    // forming `B` (no allocation per evaluation: this runs for every node of every cell of
    // every run's stress recovery).
    let mut eps = [0.0; 6];
    for (a, &n) in nodes.iter().enumerate() {
        let [gx, gy, gz] = g.grad[a];
        if dim == 2 {
            let (ux, uy) = (u[n * 2], u[n * 2 + 1]);
            eps[0] += gx * ux;
            eps[2] += gy * ux;
            eps[1] += gy * uy;
            eps[2] += gx * uy;
        } else {
            let (ux, uy, uz) = (u[n * 3], u[n * 3 + 1], u[n * 3 + 2]);
            eps[0] += gx * ux;
            eps[4] += gz * ux;
            eps[5] += gy * ux;
            eps[1] += gy * uy;
            eps[3] += gz * uy;
            eps[5] += gx * uy;
            eps[2] += gz * uz;
            eps[3] += gy * uz;
            eps[4] += gx * uz;
        }
    }
    (eps, g.det, g.x)
}

/// Stress `[xx, yy, zz, yz, xz, xy]` of cell `c` at reference point `xi`.
pub fn stress_at(model: &Model, c: usize, u: &[f64], xi: [f64; 3]) -> Result<[f64; 6], FemError> {
    let (eps, _, _) = cell_strain_at(model, c, u, xi);
    let nv = model.analysis.n_voigt();
    Ok(model.material(c)?.stress(model.analysis, &eps[..nv]))
}

/// A stress `[xx, yy, zz, yz, xz, xy]` at a physical point.
pub type PointStress = ([f64; 3], [f64; 6]);

/// Stresses at the stiffness quadrature points of every cell: `(point, stress)` lists.
pub fn gauss_stresses(model: &Model, u: &[f64]) -> Result<Vec<Vec<PointStress>>, FemError> {
    (0..model.mesh.num_cells())
        .into_par_iter()
        .map(|c| {
            let q = Quadrature::stiffness(model.mesh.cell_type(c));
            let mat = model.material(c)?;
            let nv = model.analysis.n_voigt();
            Ok(q.points
                .iter()
                .map(|&xi| {
                    let (eps, _, x) = cell_strain_at(model, c, u, xi);
                    (x, mat.stress(model.analysis, &eps[..nv]))
                })
                .collect())
        })
        .collect()
}

/// Nodal stresses recovered by averaging, over the cells of each node, the stress each cell
/// gives at that node. Nodes in no cell get zero.
pub fn nodal_stresses(model: &Model, u: &[f64]) -> Result<Vec<[f64; 6]>, FemError> {
    let n = model.mesh.num_nodes();
    // Each cell's stress at each of its nodes, in cell order (one flat list: no allocation
    // per cell).
    let per_node_of_cell: Vec<[f64; 6]> = (0..model.mesh.num_cells())
        .into_par_iter()
        .flat_map_iter(|c| {
            let refs = node_coords(model.mesh.cell_type(c));
            (0..refs.len()).map(move |a| stress_at(model, c, u, refs[a]))
        })
        .collect::<Result<_, _>>()?;
    let mut acc = vec![[0.0; 6]; n];
    let mut count = vec![0u32; n];
    let mut at = per_node_of_cell.iter();
    for c in 0..model.mesh.num_cells() {
        for &node in model.mesh.cell_nodes(c) {
            let s = at.next().ok_or_else(|| {
                FemError::Setup("nodal stresses: a cell with more nodes than its type".into())
            })?;
            for k in 0..6 {
                acc[node][k] += s[k];
            }
            count[node] += 1;
        }
    }
    for (s, &k) in acc.iter_mut().zip(&count) {
        if k > 0 {
            for v in s.iter_mut() {
                *v /= k as f64;
            }
        }
    }
    Ok(acc)
}

/// Von Mises stress of each entry.
pub fn von_mises_of(stresses: &[[f64; 6]]) -> Vec<f64> {
    stresses.iter().map(von_mises).collect()
}

/// Internal forces `f_int = sum_e K_e u_e` (full node-major vector). Reactions are
/// `f_int - f_ext` on constrained nodes.
pub fn internal_forces(model: &Model, u: &[f64]) -> Result<Vec<f64>, FemError> {
    let dim = model.mesh.dim;
    let mut f = vec![0.0; u.len()];
    let mut ke = Vec::new();
    for c in 0..model.mesh.num_cells() {
        crate::assembly::element_stiffness(model, c, &mut ke)?;
        let nodes = model.mesh.cell_nodes(c);
        let m = nodes.len() * dim;
        for (a, &na) in nodes.iter().enumerate() {
            for ca in 0..dim {
                let r = a * dim + ca;
                let mut s = 0.0;
                for (b, &nb) in nodes.iter().enumerate() {
                    for cb in 0..dim {
                        s += ke[r * m + b * dim + cb] * u[nb * dim + cb];
                    }
                }
                f[na * dim + ca] += s;
            }
        }
    }
    Ok(f)
}

/// Strain energy `1/2 int sigma : eps dV` (times thickness in 2D).
pub fn strain_energy(model: &Model, u: &[f64]) -> Result<f64, FemError> {
    let th = model.analysis.thickness();
    let per: Vec<f64> = (0..model.mesh.num_cells())
        .into_par_iter()
        .map(|c| {
            let kind = model.mesh.cell_type(c);
            let mat = model.material(c)?;
            let q = Quadrature::stiffness(kind);
            let mut e = 0.0;
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let (eps, det, _) = cell_strain_at(model, c, u, *xi);
                let nv = model.analysis.n_voigt();
                let s = mat.stress(model.analysis, &eps[..nv]);
                let dot = if nv == 3 {
                    s[0] * eps[0] + s[1] * eps[1] + s[5] * eps[2]
                } else {
                    (0..6).map(|k| s[k] * eps[k]).sum()
                };
                e += 0.5 * w * det * th * dot;
            }
            Ok(e)
        })
        .collect::<Result<_, FemError>>()?;
    Ok(per.iter().sum())
}
