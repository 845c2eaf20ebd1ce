//! The two adaptive criteria of the thesis (4.2.2), marking where the stochastic mesh
//! (`alea_uq::surrogate::StochasticMesh`, piecewise multilinear) needs new runs:
//!
//! - **maximum error** (4.2.2.1): one new run where the stochastic error density
//!   `rho_sto(xi) = sto(xi) f(xi)` is largest, then a new estimate. The candidates are the
//!   centres of the `2^(d depth)` sub-cells of every leaf (shallower in leaves near the mesh's
//!   finest level `MAX_LEVEL`) and the nodes that are interpolated, not run
//!   (`StochasticMesh::interpolated_nodes`). At an interpolated node the node itself becomes the
//!   run (`StochasticMesh::promote`): its value was frozen by an interpolation, refining around
//!   it never corrects it, and the density keeps its peak there; if it lies on the edge of a
//!   coarser leaf, whose interpolant its value must follow, that leaf is refined at its centre
//!   first (the run of this step; the node can become a run at a later one). At a sub-cell
//!   centre the leaf that holds it gets the run at its centre (`StochasticMesh::refine_centred`):
//!   a run at the
//!   point itself would change the dyadic surrogate only on the sub-cell whose centre it is
//!   (`1 / 2^(d depth)` of the leaf, its other nodes interpolated), and the loop then put run
//!   after run around the peak of a smooth density with the error unchanged (measured on the
//!   simple blade root: 35 runs within 1e-4 of one point, `i_sto` stuck at 0.21 %). On the
//!   centre of its leaf the run carries the leaf's whole hat function, as a new node of the
//!   thesis's structured mesh does between its neighbouring mesh lines;
//! - **improved** (4.2.2.2): the stochastic error integrated over each leaf,
//!   `int_cell sto(xi) f(xi) dxi` (the per-cell sums of [`crate::Estimate::cells`]); every leaf
//!   whose contribution is at least `fraction` (the thesis: 50 %) of the largest is refined at its
//!   centre (`StochasticMesh::refine_centred`), several runs per estimate.

use alea_uq::joint::JointLaw;
use alea_uq::surrogate::{CellId, MAX_LEVEL, StochasticMesh};
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

/// How the maximum-error criterion adds its run (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Enrich {
    /// Refine this leaf at its centre (the point is a sub-cell centre inside it, or an
    /// interpolated node on its edge).
    Centre(CellId),
    /// Make the interpolated node at the point a run.
    Node,
}

/// Where the maximum-error criterion adds its run: the candidate of largest density.
#[derive(Clone, Debug, PartialEq)]
pub struct MaxError {
    /// How.
    pub enrich: Enrich,
    /// The candidate point of largest density.
    pub point: Vec<f64>,
    /// `rho_sto` there.
    pub density: f64,
}

/// The candidate point of largest stochastic error density over the sub-cell centres of
/// depth `depth` of every leaf of `mesh` and its interpolated nodes (module doc), with that
/// density; `None` if the density is nowhere positive. Ties go to the first candidate (leaves
/// in id order, then the nodes in key order).
///
/// # Errors
/// From the mesh.
pub fn max_error_point(
    mesh: &StochasticMesh,
    est: &Estimator,
    weights: &dyn Weights,
    params: &dyn Parameters,
    law: &dyn JointLaw,
    depth: u32,
) -> Result<Option<MaxError>, EstimateError> {
    let d = mesh.dim();
    let mut cands = Vec::new();
    let mut owner = Vec::new();
    for c in mesh.leaves() {
        // Leaves refined close to the mesh's finest level get shallower candidates (a leaf at
        // the finest level none): a loop that keeps refining one spot ends by choosing
        // elsewhere instead of failing.
        let room = MAX_LEVEL.saturating_sub(mesh.level(c) + 1);
        if mesh.level(c) >= MAX_LEVEL {
            continue;
        }
        let pts = mesh.sub_cell_centres(c, depth.min(room))?;
        owner.extend(std::iter::repeat_n(Enrich::Centre(c), pts.len() / d.max(1)));
        cands.extend(pts);
    }
    for (p, master) in mesh.interpolated_nodes() {
        owner.push(master.map_or(Enrich::Node, Enrich::Centre));
        cands.extend(p);
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
    Ok(best.map(|(i, v)| MaxError {
        enrich: owner[i],
        point: cands[i * d..(i + 1) * d].to_vec(),
        density: v,
    }))
}
