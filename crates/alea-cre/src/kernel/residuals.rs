//! The element residuals of phase 1: `Q_E(i) = int_E sigma_h : eps(phi_i) dV - int_E f phi_i dV`
//! (a vector, one entry per direction), the right-hand sides of the node systems (3.22), from
//! the FE element stiffness (`Q_E = K_E u_E - f_E`, the body force on the FE load rule). In 2D
//! they are per unit thickness.

use alea_fem::{Model, Quadrature, kinematics::point_geometry};
use rayon::prelude::*;

use crate::CreError;
use crate::data::VectorField;
use crate::fe::cell_values;

/// `Q_E(i)` of every cell `E` and local node `i` of `model` (`D` components per node) for the
/// FE displacement `u` (node-major) and the body force `body`, divided by `thickness` (1 in 3D).
pub(crate) fn element_residuals<const D: usize>(
    model: &Model,
    u: &[f64],
    body: Option<&VectorField>,
    thickness: f64,
) -> Result<Vec<Vec<[f64; D]>>, CreError> {
    let mesh = &model.mesh;
    (0..mesh.num_cells())
        .into_par_iter()
        .map(|c| -> Result<Vec<[f64; D]>, CreError> {
            let mut ke = Vec::new();
            let kind = mesh.cell_type(c);
            let nodes = mesh.cell_nodes(c);
            let coords = model.cell_coords(c);
            alea_fem::assembly::element_stiffness(model, c, &mut ke)?;
            let m = nodes.len() * D;
            let ue = cell_values::<D>(u, nodes);
            let mut q = vec![[0.0; D]; nodes.len()];
            for a in 0..nodes.len() {
                for ca in 0..D {
                    let r = a * D + ca;
                    q[a][ca] = (0..m).map(|j| ke[r * m + j] * ue[j]).sum::<f64>() / thickness;
                }
            }
            if let Some(body) = body {
                let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
                for (xi, w) in rule.points.iter().zip(&rule.weights) {
                    let g = point_geometry(kind, &coords, *xi);
                    let b = body(g.x);
                    for a in 0..nodes.len() {
                        for ca in 0..D {
                            q[a][ca] -= w * g.det * g.n[a] * b[ca];
                        }
                    }
                }
            }
            Ok(q)
        })
        .collect()
}
