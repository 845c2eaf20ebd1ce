//! Energy-weighted samples of the FE stress alone, for substructures whose admissible stress is
//! not built (the 3D substructures of a study that estimates, as the thesis's 3D turbine
//! (5.2.6), only the interface part): the stochastic estimator (crate `alea-estimate`) then
//! uses them only to normalise its relative indicators by the FE energy.
//!
//! Same compliance coordinates as [`crate::EnergySampler`], on the **stiffness rule** of each
//! cell (`alea_fem::Quadrature::stiffness`: 2 x 2 x 2 Gauss points on Hex8, 4 / 11 points on
//! Tet4 / Tet10, ...): with `D0_E = R_E R_E^T` (Cholesky, `n_voigt x n_voigt`, reference
//! material of factor 1),
//!
//! ```text
//! y_q = sqrt(w_q |J_q| t) R_E^{-1} sigma_h(x_q) = sqrt(w_q |J_q| t) alpha R_E^T eps(u)(x_q)
//! ```
//!
//! so that `|y|^2 / alpha = sum_q w_q |J_q| t eps^T (alpha D0) eps = u^T K(alpha) u`: the
//! samples reproduce the FE energy of the assembled stiffness exactly (to round-off), for any
//! cell type and dimension. The physical gradients of every point are computed once (a few MB
//! per 10 000 Hex8 cells); sampling a displacement is then a product per point.

use alea_fem::kinematics::point_geometry;
use alea_fem::{Model, Quadrature};

use crate::CreError;
use crate::fe::check_jacobian;
use crate::linalg::cholesky_factor;

/// Stiffness-rule points of every cell and the maps from strains to compliance coordinates,
/// built once per substructure (reference materials).
#[derive(Clone, Debug)]
pub struct FeEnergySampler {
    /// Spatial dimension (displacement components per node).
    dim: usize,
    /// Voigt size of the analysis (3 in 2D, 6 in 3D).
    nv: usize,
    /// Offset of each cell's points (`num_cells + 1` entries).
    cell_points: Vec<usize>,
    /// Per point: `sqrt(w |J| t)`.
    scale: Vec<f64>,
    /// Per point: offset of its node gradients in `grads` (`num_points + 1` entries).
    grad_offsets: Vec<usize>,
    /// Physical gradients `dN_a/dx_l` of the cell's nodes at each point, `3` per node.
    grads: Vec<f64>,
    /// Per cell: lower Cholesky factor `R` of the reference Hooke matrix, row-major `nv x nv`.
    factors: Vec<f64>,
    /// Offset of each cell's values in a sample vector (`num_cells + 1` entries).
    offsets: Vec<usize>,
}

impl FeEnergySampler {
    /// Builds the sampler of `model` (its materials are the reference ones, factor 1).
    ///
    /// # Errors
    /// [`CreError::Invalid`] for a Hooke matrix that is not positive definite, FE errors for
    /// degenerate cells or missing materials.
    pub fn new(model: &Model) -> Result<Self, CreError> {
        let mesh = &model.mesh;
        let dim = mesh.dim;
        let nv = model.analysis.n_voigt();
        let th = model.analysis.thickness();
        let mut rules: Vec<(alea_mesh::CellType, Quadrature)> = Vec::new();
        let mut out = FeEnergySampler {
            dim,
            nv,
            cell_points: vec![0],
            scale: Vec::new(),
            grad_offsets: vec![0],
            grads: Vec::new(),
            factors: Vec::with_capacity(mesh.num_cells() * nv * nv),
            offsets: vec![0],
        };
        for c in 0..mesh.num_cells() {
            let kind = mesh.cell_type(c);
            if !rules.iter().any(|r| r.0 == kind) {
                rules.push((kind, Quadrature::stiffness(kind)));
            }
            let rule = &rules
                .iter()
                .find(|r| r.0 == kind)
                .expect("rule just added")
                .1;
            let coords = model.cell_coords(c);
            let l = cholesky_factor(&model.material(c)?.hooke(model.analysis), nv).ok_or_else(
                || CreError::Invalid(format!("cell {c}: Hooke matrix is not positive definite")),
            )?;
            out.factors.extend_from_slice(&l);
            for (xi, w) in rule.points.iter().zip(&rule.weights) {
                let g = point_geometry(kind, &coords, *xi);
                check_jacobian(&g, c, kind)?;
                out.scale.push((w * g.det * th).sqrt());
                out.grads.extend(g.grad[..g.nn].iter().flatten());
                out.grad_offsets.push(out.grads.len());
            }
            out.cell_points.push(out.scale.len());
            out.offsets.push(out.offsets[c] + nv * rule.len());
        }
        Ok(out)
    }

    /// Length of a sample vector.
    pub fn len(&self) -> usize {
        self.offsets.last().copied().unwrap_or(0)
    }

    /// True if the model has no cell.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Offset of each cell's values in a sample vector (`num_cells + 1` entries).
    pub fn cell_offsets(&self) -> &[usize] {
        &self.offsets
    }

    /// Samples of the FE stress `sigma_h = alpha D0 eps(u)` of the displacement `u` (node-major,
    /// `dim` per node, all nodes of `model`, the sampler's model) with Young's factor `alpha`.
    ///
    /// # Errors
    /// [`CreError::Invalid`] if `u` does not have `dim` values per node of the model or the
    /// model has another number of cells.
    pub fn fe_stress(&self, model: &Model, u: &[f64], alpha: f64) -> Result<Vec<f64>, CreError> {
        let mesh = &model.mesh;
        let (dim, nv) = (self.dim, self.nv);
        if u.len() != dim * mesh.num_nodes() || mesh.num_cells() + 1 != self.offsets.len() {
            return Err(CreError::Invalid(format!(
                "FE samples of {} values on {} cells for a sampler of {} cells in {dim}D",
                u.len(),
                mesh.num_cells(),
                self.offsets.len() - 1
            )));
        }
        let mut out = Vec::with_capacity(self.len());
        let mut eps = [0.0; 6];
        for c in 0..mesh.num_cells() {
            let nodes = mesh.cell_nodes(c);
            let l = &self.factors[c * nv * nv..(c + 1) * nv * nv];
            for q in self.cell_points[c]..self.cell_points[c + 1] {
                let grads = &self.grads[self.grad_offsets[q]..self.grad_offsets[q + 1]];
                eps.fill(0.0);
                for (a, &n) in nodes.iter().enumerate() {
                    let gr = &grads[3 * a..3 * a + 3];
                    let un = &u[dim * n..dim * n + dim];
                    if dim == 2 {
                        // [xx, yy, xy] with engineering shear.
                        eps[0] += gr[0] * un[0];
                        eps[1] += gr[1] * un[1];
                        eps[2] += gr[1] * un[0] + gr[0] * un[1];
                    } else {
                        // [xx, yy, zz, yz, xz, xy] with engineering shears.
                        eps[0] += gr[0] * un[0];
                        eps[1] += gr[1] * un[1];
                        eps[2] += gr[2] * un[2];
                        eps[3] += gr[2] * un[1] + gr[1] * un[2];
                        eps[4] += gr[2] * un[0] + gr[0] * un[2];
                        eps[5] += gr[1] * un[0] + gr[0] * un[1];
                    }
                }
                // y = sqrt(w |J| t) alpha R^T eps.
                let s = self.scale[q] * alpha;
                for i in 0..nv {
                    let v: f64 = (i..nv).map(|k| l[k * nv + i] * eps[k]).sum();
                    out.push(s * v);
                }
            }
        }
        Ok(out)
    }
}
