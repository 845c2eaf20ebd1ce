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
//! cell type and dimension. The points' geometry (`|J_q|`, the physical gradients) is computed
//! again at each sampling, from the model's coordinates, by the function that checked it at
//! construction (`alea_fem::kinematics::point_geometry`, the same bits): storing it would take
//! 192 doubles per Hex8 cell (0.3 GB on the 3D turbine refined once, 190 000 cells), for about
//! 0.2 s of recomputation per sampled run there. The Cholesky factors `R_E` are stored once per
//! distinct material.

use std::collections::HashMap;

use alea_fem::kinematics::point_geometry;
use alea_fem::{Model, Quadrature};

use crate::CreError;
use crate::fe::check_jacobian;
use crate::linalg::cholesky_factor;

/// The stiffness rules of a model's cell types and the maps from strains to compliance
/// coordinates, built once per substructure (reference materials).
#[derive(Clone, Debug)]
pub struct FeEnergySampler {
    /// Spatial dimension (displacement components per node).
    dim: usize,
    /// Voigt size of the analysis (3 in 2D, 6 in 3D).
    nv: usize,
    /// Thickness factor `t` of the analysis.
    thickness: f64,
    /// The stiffness rule of each cell type of the mesh.
    rules: Vec<(alea_mesh::CellType, Quadrature)>,
    /// Lower Cholesky factors `R` of the distinct reference Hooke matrices, row-major
    /// `nv x nv` each.
    factors: Vec<f64>,
    /// Per cell: its factor in `factors`.
    factor_of_cell: Vec<u32>,
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
        let mut out = FeEnergySampler {
            dim,
            nv,
            thickness: model.analysis.thickness(),
            rules: Vec::new(),
            factors: Vec::new(),
            factor_of_cell: Vec::with_capacity(mesh.num_cells()),
            offsets: vec![0],
        };
        // Distinct factors by their bits.
        let mut known: HashMap<Vec<u64>, u32> = HashMap::new();
        let mut coords = Vec::new();
        for c in 0..mesh.num_cells() {
            let kind = mesh.cell_type(c);
            if !out.rules.iter().any(|r| r.0 == kind) {
                out.rules.push((kind, Quadrature::stiffness(kind)));
            }
            let rule = out.rule(kind);
            model.cell_coords_into(c, &mut coords);
            for xi in &rule.points {
                check_jacobian(&point_geometry(kind, &coords, *xi), c, kind)?;
            }
            let points = rule.points.len();
            let l = cholesky_factor(&model.material(c)?.hooke(model.analysis), nv).ok_or_else(
                || CreError::Invalid(format!("cell {c}: Hooke matrix is not positive definite")),
            )?;
            let bits: Vec<u64> = l.iter().map(|v| v.to_bits()).collect();
            let next = known.len() as u32;
            let id = *known.entry(bits).or_insert_with(|| {
                out.factors.extend_from_slice(&l);
                next
            });
            out.factor_of_cell.push(id);
            out.offsets.push(out.offsets[c] + nv * points);
        }
        Ok(out)
    }

    /// The stiffness rule of cell type `kind` (one of the mesh's).
    fn rule(&self, kind: alea_mesh::CellType) -> &Quadrature {
        &self
            .rules
            .iter()
            .find(|r| r.0 == kind)
            .expect("a rule per cell type of the mesh")
            .1
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
        let mut coords = Vec::new();
        for c in 0..mesh.num_cells() {
            let nodes = mesh.cell_nodes(c);
            let kind = mesh.cell_type(c);
            let rule = self.rule(kind);
            let f = self.factor_of_cell[c] as usize;
            let l = &self.factors[f * nv * nv..(f + 1) * nv * nv];
            model.cell_coords_into(c, &mut coords);
            for (xi, w) in rule.points.iter().zip(&rule.weights) {
                let g = point_geometry(kind, &coords, *xi);
                eps.fill(0.0);
                for (a, &n) in nodes.iter().enumerate() {
                    let gr = &g.grad[a];
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
                let s = (w * g.det * self.thickness).sqrt() * alpha;
                for i in 0..nv {
                    let v: f64 = (i..nv).map(|k| l[k * nv + i] * eps[k]).sum();
                    out.push(s * v);
                }
            }
        }
        Ok(out)
    }
}
