//! Reaction forces of the substructures of an assembly.
//!
//! Each linear stage solves `K u = f + M_Gamma F` on the free dofs of substructure `s`
//! (`f`: external loads, `M_Gamma F`: the lumped interface forces of the last linear stage,
//! `sum_i m_i F_s,i` at interface node `i`). The nodal reactions are the residual
//! `r = K u - f - M_Gamma F` (full node-major vector): the forces the constraints exert on the
//! substructure, zero (to solver precision) on free dofs. The resultant of `r` over a group
//! is the reaction on that group; for every substructure, `sum r + sum f + sum M_Gamma F = 0`.

use alea_fem::{FemError, post};

use crate::{LatinSolver, RunResult};

/// Nodal reactions of substructure `s` in run `result`, for the external load vector `loads`
/// (full node-major, the run's load cases times their factors). Interface forces use the
/// interface points' lumped weights (the same on both sides of a node-matched interface).
///
/// # Errors
/// On an element-level failure (degenerate cell).
pub fn nodal_reactions(
    solver: &LatinSolver,
    result: &RunResult,
    s: usize,
    loads: &[f64],
) -> Result<Vec<f64>, FemError> {
    let model = result.scaled_model(solver.model(s), s);
    let dim = model.mesh.dim;
    let mut r = post::internal_forces(&model, &result.displacements[s])?;
    for (a, f) in r.iter_mut().zip(loads) {
        *a -= f;
    }
    for it in &result.interfaces {
        for side in 0..2 {
            if it.subs[side] != s {
                continue;
            }
            for (i, &node) in it.nodes[side].iter().enumerate() {
                for c in 0..dim {
                    r[node * dim + c] -= it.weights[i] * it.f[side][i][c];
                }
            }
        }
    }
    Ok(r)
}

/// The sum of the nodal vectors `r` (node-major, `dim` per node) over `nodes`.
pub fn group_sum(r: &[f64], dim: usize, nodes: &[usize]) -> [f64; 3] {
    let mut s = [0.0; 3];
    for &n in nodes {
        for c in 0..dim {
            s[c] += r[n * dim + c];
        }
    }
    s
}
