//! The interface fields of a cycle on a **re-paired** interface (large sliding, module
//! [`crate::large_sliding`]): each step of the cycle has its own pairing, found in that step's
//! deformed configuration.
//!
//! **What a point is.** The interface points of every pairing of a re-paired interface are
//! multiplier nodes of one side `P`, the side of its first pairing (kept by every re-pairing):
//! a point is a **material point of side `P`**, named by its mesh node
//! (`InterfacePairing::point_nodes`; at the edge of the covered zone its position and row are
//! those of the covered part of its support, and change with the coverage). Its partner on the
//! other side is the material point its projection row reaches in the current configuration,
//! and changes from step to step. The set of points can change too: a node of `P` that the
//! other side stops covering (at the ends of a contact that slides) has no point in that
//! step's pairing. The cycle's points are the union over its steps; a point absent from a
//! step is open there (no partner, no force).
//!
//! **The jump.** With total displacements `u` and the rows of the current pairing, the
//! tangential jump of step `k` at point `i` is the one the solver works with,
//! `j_k = [Pi_k u_k]_t = (Pi_2 u_2 - Pi_1 u_1)_t` (module [`crate::large_sliding`]: since the
//! pairing follows the deformed configuration, `(Pi_2 (X_2 + u_2) - Pi_1 (X_1 + u_1))_t = 0`
//! and `j_k = -(Pi_2 X_2 - Pi_1 X_1)_t`: the initial-configuration offset of the point's
//! current partner, the total slip of material point `i` along the other side). The jump at
//! the step's start is the slip origin of the incremental Coulomb law of that step,
//! `j0_k = [Pi_k u_{k-1}]_t` (the previous step's displacement between the points the step's
//! pairing pairs: [`crate::large_sliding::step_origins`]); it differs from `j_{k-1}` (the
//! previous pairing's rows) by the strain of the other side times the slide between the two
//! pairings. With `q_k` the tangential force on side 2 and `w_i^k` the step's weight:
//!
//! ```text
//!   slip amplitude   delta_i = 1/2 max_{k,l closed} |j_k - j_l|
//!   work per cycle   W_i = sum_k -(j_k - j0_k) . q_k,    W = sum_k sum_i w_i^k (-(j_k - j0_k) . q_k)
//! ```
//! so `W` is exactly the sum of the cycle steps' friction dissipations
//! ([`crate::large_sliding::step_friction_dissipation`]), and in small sliding (one pairing,
//! `j0_k = j_{k-1}`) these are the formulas of [`super::slip_cycle`]. `tau_i`, the stick
//! margin and the stick zone are per material point as there.

use std::collections::BTreeMap;

use alea_mesh::vec3::dot;

use super::{FrettingError, SlipCycle, V3, tangential};
use crate::InterfaceResult;

/// The mesh node of each point of `it`, on the side carrying them: the pairing's
/// (`InterfacePairing::point_nodes`, the multiplier nodes), else the node of largest
/// coefficient of that side's rows.
fn point_nodes(it: &InterfaceResult, side: usize) -> &[usize] {
    if it.pairing.point_nodes.len() == it.points.len() {
        &it.pairing.point_nodes
    } else {
        &it.nodes[side]
    }
}

/// One step of a cycle on a re-paired interface: its interface result (on the step's last
/// pairing) and the tangential jump at the step's start at each of its points
/// ([`crate::large_sliding::step_origins`]).
#[derive(Clone, Copy, Debug)]
pub struct CycleStep<'a> {
    /// The step's interface result.
    pub result: &'a InterfaceResult,
    /// `j0` per point of `result`.
    pub origin: &'a [V3],
}

/// The interface fields of a cycle of steps on a re-paired interface whose points are on side
/// `point_side` (0 or 1; module doc): per point of the union of the steps' points, in the
/// order of their nodes.
///
/// # Errors
/// [`FrettingError::EmptyCycle`], [`FrettingError::PerfectInterface`],
/// [`FrettingError::Invalid`] (a side other than 0 or 1), [`FrettingError::Mismatch`] (steps
/// of other interfaces, origins of other lengths, a node carrying two points).
pub fn slip_cycle_repaired(
    steps: &[CycleStep<'_>],
    point_side: usize,
) -> Result<SlipCycle, FrettingError> {
    let first = steps.first().ok_or(FrettingError::EmptyCycle)?.result;
    if first.law == "perfect" {
        return Err(FrettingError::PerfectInterface(first.name.clone()));
    }
    if point_side > 1 {
        return Err(FrettingError::Invalid(format!("side {point_side}: 0 or 1")));
    }
    let mismatch = || FrettingError::Mismatch(first.name.clone());
    let mut index: BTreeMap<usize, usize> = BTreeMap::new();
    for s in steps {
        let it = s.result;
        let np = it.points.len();
        let lengths = [
            point_nodes(it, point_side).len(),
            it.weights.len(),
            it.what[0].len(),
            it.what[1].len(),
            it.fhat[1].len(),
            it.status.len(),
            s.origin.len(),
        ];
        if it.name != first.name || it.law != first.law || lengths.iter().any(|&l| l != np) {
            return Err(mismatch());
        }
        index.extend(point_nodes(it, point_side).iter().map(|&n| (n, 0)));
        let mut distinct = point_nodes(it, point_side).to_vec();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() != np {
            return Err(mismatch());
        }
    }
    for (i, v) in index.values_mut().enumerate() {
        *v = i;
    }
    let np = index.len();
    let mut out = SlipCycle {
        x: vec![[0.0; 3]; np],
        weights: vec![0.0; np],
        closed: vec![false; np],
        stick: vec![true; np],
        stick_margin: vec![f64::INFINITY; np],
        slip_amplitude: vec![0.0; np],
        work: vec![0.0; np],
        tau: vec![0.0; np],
        nodes: index.keys().copied().collect(),
        dissipated: 0.0,
    };
    let mut jumps: Vec<Vec<V3>> = vec![Vec::new(); np];
    let mut present = vec![0usize; np];
    for s in steps {
        let it = s.result;
        let nodes = point_nodes(it, point_side);
        for p in 0..it.points.len() {
            let i = index[&nodes[p]];
            present[i] += 1;
            out.x[i] = it.points[p].x;
            out.weights[i] = it.weights[p];
            let n = it.points[p].normal;
            let f = it.side2_force(p);
            let q = tangential(f, n);
            let w = -dot(&it.step_slip(p, s.origin), &q);
            out.work[i] += w;
            out.dissipated += it.weights[p] * w;
            if out.record_step(i, q, f, n, it.points[p].mu, it.status[p]) {
                jumps[i].push(it.step_slip(p, &[]));
            }
        }
    }
    for i in 0..np {
        // Absent from a step: open there (no partner).
        out.stick[i] &= present[i] == steps.len();
        out.finish_point(i, &jumps[i]);
    }
    Ok(out)
}
