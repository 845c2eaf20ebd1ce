//! Energy-weighted samples of the admissible and FE stress fields, the data of the stochastic
//! estimator (thesis 3.2, 4.1; crate `alea-estimate`).
//!
//! For a substructure with reference Hooke matrices `D0_E` (every Young's modulus at factor 1)
//! and Cholesky factors `D0_E = R_E R_E^T`, a stress field `sigma` is represented by the vector
//! of its values at the quadrature points `x_q` of every cell, in **compliance coordinates**
//!
//! ```text
//! y_q = sqrt(w_q |J_q| t) R_E^{-1} sigma(x_q)          (3 numbers per point in 2D)
//! ```
//!
//! (`w_q` the rule weight, `|J_q|` the Jacobian, `t` the thickness), so that every compliance
//! inner product is a plain dot product:
//! `int sigma : D0^-1 : tau dx = sum_q y_q(sigma) . y_q(tau)`. With a Young's factor `alpha`
//! (`D = alpha D0`), `||sigma||^2_{D^-1} = |y(sigma)|^2 / alpha`.
//!
//! The quadrature rules are those of the phase-2 local problems ([`crate::eet::phase2`]: degree
//! `2 (p + k)` on triangles, `(p + k + 1)^2` Gauss points on quadrilaterals, richer on cells
//! with a curved edge: [`crate::eet::phase2::Phase2Rules::volume`]), so that
//! `|y(sigma_hat) - y(sigma_h)|^2 / alpha = theta^2` reproduces the deterministic estimate to
//! round-off. `y(sigma_h)` comes from the FE displacement and `y(sigma_hat)` from the phase-2
//! solution of a [`DomainEstimate`] of the same model (same mesh and cell order).
//!
//! 2D cells (Tri3, Quad4, Tri6, Quad8) only, as the estimate itself.

use alea_fem::Model;
use alea_mesh::CellType;

use crate::CreError;
use crate::domain::{CreOptions, DomainEstimate};
use crate::eet::phase2::Phase2Rules;
use crate::fe::{cell_values, check_jacobian, hooke, strain_h};
use crate::linalg::cholesky_factor;
use crate::poly::{PolyPoint, PolySpace};
use crate::topology::cell_is_curved;

/// A quadrature point: reference coordinates, physical coordinates and `sqrt(w |J| t)`.
type SamplePoint = ([f64; 3], [f64; 3], f64);

/// Quadrature points of every cell and the factors that map stresses to compliance
/// coordinates, built once per substructure (reference materials).
#[derive(Clone, Debug)]
pub struct EnergySampler {
    /// Per cell: reference and physical points and `sqrt(w |J| t)`.
    points: Vec<Vec<SamplePoint>>,
    /// Per cell: the phase-2 displacement space (its coefficients are the compact form of an
    /// admissible stress, see [`EnergySampler::admissible_from_coefficients`]).
    spaces: Vec<PolySpace>,
    /// Offset of each cell's coefficients (`num_cells + 1` entries).
    coefficient_offsets: Vec<usize>,
    /// Per cell: lower Cholesky factor of the reference Hooke matrix.
    factors: Vec<[[f64; 3]; 3]>,
    /// Offset of each cell's values in a sample vector (`num_cells + 1` entries).
    offsets: Vec<usize>,
}

/// The 2D admissible stresses of an estimate with `cells` cells.
fn plane_stresses(
    estimate: &DomainEstimate,
    cells: usize,
) -> Result<&[crate::eet::phase2::ElementStress], CreError> {
    let stresses = estimate.plane_stresses().ok_or_else(|| {
        CreError::Invalid("energy samples of a 3D estimate are not implemented".into())
    })?;
    if stresses.len() != cells {
        return Err(CreError::Invalid(format!(
            "estimate of {} cells for a sampler of {cells}",
            stresses.len()
        )));
    }
    Ok(stresses)
}

/// Lower Cholesky factor of a symmetric positive definite 3 x 3 matrix.
fn cholesky3(d: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let l = cholesky_factor(d.as_flattened(), 3)?;
    Some([0, 1, 2].map(|i| [l[3 * i], l[3 * i + 1], l[3 * i + 2]]))
}

/// `R^T e` for the lower factor `R`: the compliance coordinates of the stress `R R^T e` up to
/// the point's weight.
#[inline]
fn transposed_product(l: &[[f64; 3]; 3], e: &[f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (i..3).map(|k| l[k][i] * e[k]).sum())
}

/// Solves `L y = s` (lower triangular).
fn forward3(l: &[[f64; 3]; 3], s: &[f64; 3]) -> [f64; 3] {
    let y0 = s[0] / l[0][0];
    let y1 = (s[1] - l[1][0] * y0) / l[1][1];
    let y2 = (s[2] - l[2][0] * y0 - l[2][1] * y1) / l[2][2];
    [y0, y1, y2]
}

impl EnergySampler {
    /// Builds the sampler of `model` (its materials are the reference ones, factor 1).
    ///
    /// # Errors
    /// [`CreError::UnsupportedCell`] for 3D cells, [`CreError::Invalid`] for a non-positive
    /// Hooke matrix or invalid options, FE errors for degenerate cells.
    pub fn new(model: &Model, options: &CreOptions) -> Result<Self, CreError> {
        options.validate()?;
        let mesh = &model.mesh;
        let th = model.analysis.thickness();
        let by_order = [
            Phase2Rules::new(1 + options.extra_degree),
            Phase2Rules::new(2 + options.extra_degree),
        ];
        let mut points = Vec::with_capacity(mesh.num_cells());
        let mut factors = Vec::with_capacity(mesh.num_cells());
        let mut offsets = vec![0];
        let mut spaces = Vec::with_capacity(mesh.num_cells());
        let mut coefficient_offsets = vec![0];
        for c in 0..mesh.num_cells() {
            let kind = mesh.cell_type(c);
            let rule = match kind {
                CellType::Tri3 | CellType::Tri6 | CellType::Quad4 | CellType::Quad8 => {
                    by_order[kind.order().clamp(1, 2) - 1].volume(kind, cell_is_curved(mesh, c))
                }
                other => {
                    return Err(CreError::UnsupportedCell {
                        cell: c,
                        kind: other.to_string(),
                    });
                }
            };
            let coords = model.cell_coords(c);
            let d = hooke(model.material(c)?, model.analysis);
            let l = cholesky3(&d).ok_or_else(|| {
                CreError::Invalid(format!("cell {c}: Hooke matrix is not positive definite"))
            })?;
            let zero = vec![0.0; 2 * coords.len()];
            let mut pts = Vec::with_capacity(rule.len());
            for (xi, w) in rule.points.iter().zip(&rule.weights) {
                let (_, g) = strain_h(kind, &coords, &zero, *xi);
                check_jacobian(&g, c, kind)?;
                pts.push((*xi, g.x, (w * g.det * th).sqrt()));
            }
            offsets.push(offsets[c] + 3 * pts.len());
            points.push(pts);
            factors.push(l);
            let space = PolySpace::new(kind.order().clamp(1, 2) + options.extra_degree, &coords);
            coefficient_offsets.push(coefficient_offsets[c] + space.len());
            spaces.push(space);
        }
        Ok(EnergySampler {
            points,
            spaces,
            coefficient_offsets,
            factors,
            offsets,
        })
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
    /// 2 per node) with Young's factor `alpha`.
    pub fn fe_stress(&self, model: &Model, u: &[f64], alpha: f64) -> Vec<f64> {
        let mesh = &model.mesh;
        let mut out = Vec::with_capacity(self.len());
        for (c, pts) in self.points.iter().enumerate() {
            let kind = mesh.cell_type(c);
            let coords = model.cell_coords(c);
            let ue: Vec<f64> = cell_values::<2>(u, mesh.cell_nodes(c));
            let l = &self.factors[c];
            for (xi, _, s) in pts {
                let (e, _) = strain_h(kind, &coords, &ue, *xi);
                // y = R^-1 (alpha R R^T e) = alpha R^T e.
                for v in transposed_product(l, &e) {
                    out.push(s * alpha * v);
                }
            }
        }
        out
    }

    /// Reference and physical coordinates of the sample points of cell `c`, in sample order.
    ///
    /// # Panics
    /// If `c` is not a cell of the sampler's model.
    pub fn cell_points(&self, c: usize) -> impl Iterator<Item = ([f64; 3], [f64; 3])> + '_ {
        self.points[c].iter().map(|(xi, x, _)| (*xi, *x))
    }

    /// Energy coordinates `z_q = sqrt(w_q |J_q| t) R^T eps_q` of a strain field (engineering
    /// shear, `[e_xx, e_yy, g_xy]`) at the sample points of cells `cells`, appended to `out` in
    /// sample order; `strain(c, xi, x)` gives the strain at the point of reference coordinates
    /// `xi` and physical coordinates `x` of cell `c` (e.g. a field of another mesh located at
    /// `x`). Then `int eps(u) : D0 : eps(v) = z(u) . z(v)` over those cells, and
    /// [`EnergySampler::fe_stress`] of a displacement is `alpha` times its `z`: the samples of the
    /// efficiency index's reference distance (`alea_estimate::reference`).
    ///
    /// # Panics
    /// If `cells` is not a range of cells of the sampler's model.
    pub fn strain_samples(
        &self,
        cells: std::ops::Range<usize>,
        mut strain: impl FnMut(usize, [f64; 3], [f64; 3]) -> [f64; 3],
        out: &mut Vec<f64>,
    ) {
        for c in cells {
            let l = &self.factors[c];
            for (xi, x, s) in &self.points[c] {
                let e = strain(c, *xi, *x);
                for v in transposed_product(l, &e) {
                    out.push(s * v);
                }
            }
        }
    }

    /// The strain `[e_xx, e_yy, g_xy]` of the displacement `u` of `model` (node-major, 2 per
    /// node) at reference coordinates `xi` of cell `c`.
    ///
    /// # Panics
    /// If `c` is not a cell of `model` or `u` is too short.
    pub fn strain_at(model: &Model, u: &[f64], c: usize, xi: [f64; 3]) -> [f64; 3] {
        let mesh = &model.mesh;
        let ue: Vec<f64> = cell_values::<2>(u, mesh.cell_nodes(c));
        strain_h(mesh.cell_type(c), &model.cell_coords(c), &ue, xi).0
    }

    /// Offset of each cell's phase-2 coefficients in a coefficient vector (`num_cells + 1`
    /// entries).
    pub fn coefficient_offsets(&self) -> &[usize] {
        &self.coefficient_offsets
    }

    /// The phase-2 coefficients of every cell of an estimate, concatenated in cell order: the
    /// compact form of its admissible stress (`sigma_hat = alpha D0 eps(sum_j a_j v_j)`).
    ///
    /// # Errors
    /// [`CreError::Invalid`] if the estimate does not belong to this sampler's model and options.
    pub fn coefficients(&self, estimate: &DomainEstimate) -> Result<Vec<f64>, CreError> {
        let stresses = plane_stresses(estimate, self.spaces.len())?;
        let mut out = Vec::with_capacity(self.coefficient_offsets[self.spaces.len()]);
        for (c, st) in stresses.iter().enumerate() {
            let n = self.coefficient_offsets[c + 1] - self.coefficient_offsets[c];
            if st.coeffs.len() != n {
                return Err(CreError::Invalid(format!(
                    "cell {c}: {} phase-2 coefficients, the sampler expects {n} (other extra degree?)",
                    st.coeffs.len()
                )));
            }
            out.extend_from_slice(&st.coeffs);
        }
        Ok(out)
    }

    /// Samples of the admissible stress `alpha D0 eps(v)` of the cells `cells` from their
    /// phase-2 coefficients (`coefficients` as returned by [`EnergySampler::coefficients`],
    /// all cells): the values of those cells, in order, are appended to `out`.
    ///
    /// # Panics
    /// If `coefficients` is shorter than the model's coefficient count or a cell is out of range.
    pub fn admissible_from_coefficients(
        &self,
        coefficients: &[f64],
        alpha: f64,
        cells: std::ops::Range<usize>,
        out: &mut Vec<f64>,
    ) {
        let mut p = PolyPoint::default();
        for c in cells {
            let a = &coefficients[self.coefficient_offsets[c]..self.coefficient_offsets[c + 1]];
            let l = &self.factors[c];
            for (_, x, s) in &self.points[c] {
                self.spaces[c].eval(*x, false, &mut p);
                let mut e = [0.0; 3];
                for (aj, ej) in a.iter().zip(&p.eps) {
                    for k in 0..3 {
                        e[k] += aj * ej[k];
                    }
                }
                for v in transposed_product(l, &e) {
                    out.push(s * alpha * v);
                }
            }
        }
    }

    /// Samples of the admissible stress of a phase-2 estimate of the same model (any Young's
    /// factor: the estimate's stresses carry it).
    ///
    /// # Errors
    /// [`CreError::Invalid`] if the estimate has another number of cells.
    pub fn admissible_stress(&self, estimate: &DomainEstimate) -> Result<Vec<f64>, CreError> {
        let stresses = plane_stresses(estimate, self.points.len())?;
        let mut out = Vec::with_capacity(self.len());
        for ((pts, st), l) in self.points.iter().zip(stresses).zip(&self.factors) {
            for (_, x, s) in pts {
                let y = forward3(l, &st.stress(*x));
                out.extend(y.iter().map(|v| s * v));
            }
        }
        Ok(out)
    }
}
