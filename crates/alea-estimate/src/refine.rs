//! The two adaptive criteria of the thesis (4.2.2), marking where the stochastic mesh
//! (`alea_uq::surrogate::StochasticMesh`, piecewise multilinear) needs new runs:
//!
//! - **maximum error** (4.2.2.1): one new run at the point of largest stochastic error density
//!   `rho_sto(xi) = sto(xi) f(xi)`, searched over the centres of the `2^(d depth)` sub-cells of
//!   every leaf (dyadic points, so that `StochasticMesh::refine_at_point` can complete the
//!   structured mesh around the run with interpolated nodes; shallower in leaves near the
//!   mesh's finest level `MAX_LEVEL`), then a new estimate;
//! - **improved** (4.2.2.2): the stochastic error integrated over each leaf,
//!   `int_cell sto(xi) f(xi) dxi` (the per-cell sums of [`crate::Estimate::cells`]); every leaf
//!   whose contribution is at least `fraction` (the thesis: 50 %) of the largest is refined at its
//!   centre (`StochasticMesh::refine_centred`), several runs per estimate.

use alea_uq::joint::JointLaw;
use alea_uq::surrogate::{MAX_LEVEL, StochasticMesh};
use rayon::prelude::*;

use crate::{EstimateError, Estimator, Parameters, Weights};

/// Leaves to refine by the improved criterion, from per-cell `(cell, sto, e2)` contributions:
/// those with `sto >= fraction * max sto` and `sto > 0`, in increasing cell order.
///
/// # Errors
/// [`EstimateError::Invalid`] if `fraction` is not in `(0, 1]`.
pub fn improved(cells: &[(usize, f64, f64)], fraction: f64) -> Result<Vec<usize>, EstimateError> {
    if !(fraction > 0.0 && fraction <= 1.0) {
        return Err(EstimateError::Invalid(format!(
            "refinement fraction must be in (0, 1], got {fraction}"
        )));
    }
    let max = cells.iter().map(|c| c.1).fold(0.0, f64::max);
    if !(max > 0.0) {
        return Ok(Vec::new());
    }
    let mut out: Vec<usize> = cells
        .iter()
        .filter(|c| c.1 > 0.0 && c.1 >= fraction * max)
        .map(|c| c.0)
        .collect();
    out.sort_unstable();
    Ok(out)
}

/// The candidate point of largest stochastic error density over the sub-cell centres of
/// depth `depth` of every leaf of `mesh`, with that density; `None` if the density is nowhere
/// positive. Ties go to the first candidate (leaves in id order).
///
/// # Errors
/// From the mesh (a depth beyond its maximum level).
pub fn max_error_point(
    mesh: &StochasticMesh,
    est: &Estimator,
    weights: &dyn Weights,
    params: &dyn Parameters,
    law: &dyn JointLaw,
    depth: u32,
) -> Result<Option<(Vec<f64>, f64)>, EstimateError> {
    let d = mesh.dim();
    let mut cands = Vec::new();
    for c in mesh.leaves() {
        // Leaves refined close to the mesh's finest level get shallower candidates (a leaf at
        // the finest level none): a loop that keeps refining one spot ends by choosing
        // elsewhere instead of failing.
        let room = MAX_LEVEL.saturating_sub(mesh.level(c) + 1);
        if mesh.level(c) >= MAX_LEVEL {
            continue;
        }
        cands.extend(mesh.sub_cell_centres(c, depth.min(room))?);
    }
    let vals: Vec<f64> = cands
        .par_chunks(d)
        .map_init(Vec::new, |w, xi| {
            let f = law.pdf(xi);
            if !(f.is_finite() && f > 0.0) {
                return 0.0;
            }
            weights.weights(xi, w);
            f * est.at(xi, w, params).sto2()
        })
        .collect();
    let mut best: Option<(usize, f64)> = None;
    for (i, &v) in vals.iter().enumerate() {
        if v > 0.0 && best.is_none_or(|b| v > b.1) {
            best = Some((i, v));
        }
    }
    Ok(best.map(|(i, v)| (cands[i * d..(i + 1) * d].to_vec(), v)))
}
