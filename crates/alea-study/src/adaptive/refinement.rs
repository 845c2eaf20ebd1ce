//! How the adaptive loop adds runs to its stochastic mesh: full splits of leaves within the
//! run budget, and the refinement by the estimate's criterion (the improved criterion's
//! actions, or the point of largest stochastic error).

use alea_estimate::{Estimator, refine};
use alea_latin::LatinSolver;
use alea_uq::surrogate::{CellId, StochasticMesh};

use crate::StudyError;
use crate::cre::StudyParameters;
use crate::method::Surrogate;
use crate::study::Study;

/// Splits the leaves `cells` of `mesh` in full, in order, while the mesh keeps at most
/// `max_runs` runs (the first split that would exceed it ends the splitting); the number of
/// new runs.
pub(super) fn split_within(
    mesh: &mut StochasticMesh,
    cells: &[CellId],
    max_runs: usize,
) -> Result<usize, StudyError> {
    let before = mesh.num_runs();
    for &c in cells {
        let mut trial = mesh.clone();
        trial.refine(&[c]).map_err(StudyError::from)?;
        if trial.num_runs() > max_runs {
            break;
        }
        *mesh = trial;
    }
    Ok(mesh.num_runs() - before)
}

/// What the estimate of a step gives the refinement.
pub(super) struct EstimateOfStep<'a> {
    /// The study.
    pub(super) study: &'a Study,
    /// Its solver (the friction profiles at the interface points).
    pub(super) solver: &'a LatinSolver,
    /// The step's estimator.
    pub(super) est: &'a Estimator,
    /// The step's surrogate.
    pub(super) sur: &'a Surrogate,
}

/// The improved criterion: marks the cells whose integrated stochastic error (`cells`) is at
/// least `fraction` of the largest and applies the actions of the largest densities within
/// `room` runs; the number of new runs, or why there is nothing to refine.
pub(super) fn refine_improved(
    mesh: &mut StochasticMesh,
    input: &EstimateOfStep,
    cells: &[(usize, f64, f64)],
    fraction: f64,
    room: usize,
) -> Result<Result<usize, &'static str>, StudyError> {
    let (study, params) = (input.study, &input.study.params);
    let marked = refine::improved(cells, fraction).map_err(StudyError::from)?;
    if marked.is_empty() {
        return Ok(Err("no cell carries stochastic error"));
    }
    let sp = StudyParameters::new(&study.model.parametric, input.solver);
    let mut actions = refine::improved_actions(
        mesh,
        &marked,
        input.est,
        input.sur,
        &sp,
        params.joint.as_ref(),
        fraction,
    )
    .map_err(StudyError::from)?;
    // Keep the largest densities within the budget (actions come sorted; a split
    // along m of d directions adds up to 2^(d - m) runs).
    let d = params.lo.len();
    let full = (1u32 << d) - 1;
    let mut cost = 0;
    actions.retain(|(a, _)| {
        let c = match a {
            refine::ImprovedAction::Split(_, m) => 1usize << (d - m.count_ones() as usize),
            _ => 1,
        };
        let keep = cost + c <= room;
        if keep {
            cost += c;
        }
        keep
    });
    if actions.is_empty() {
        return Ok(Err(
            "no point of the marked cells carries stochastic error within the run budget",
        ));
    }
    let before = mesh.num_runs();
    let mut splits = Vec::new();
    for (a, _) in &actions {
        match a {
            refine::ImprovedAction::Promote(p) => {
                mesh.promote(p).map_err(StudyError::from)?;
            }
            refine::ImprovedAction::Centre(c) => splits.push((*c, full)),
            refine::ImprovedAction::Split(c, m) => splits.push((*c, *m)),
        }
    }
    mesh.refine_directions(&splits).map_err(StudyError::from)?;
    Ok(Ok(mesh.num_runs() - before))
}

/// The maximum-error criterion: one run at the point of largest stochastic error density
/// (searched to `depth`), the node itself or the centre of its cell; 1 new run, or why there
/// is none.
pub(super) fn refine_max_error(
    mesh: &mut StochasticMesh,
    input: &EstimateOfStep,
    depth: u32,
) -> Result<Result<usize, &'static str>, StudyError> {
    let study = input.study;
    let sp = StudyParameters::new(&study.model.parametric, input.solver);
    let best = refine::max_error_point(
        mesh,
        input.est,
        input.sur,
        &sp,
        study.params.joint.as_ref(),
        depth,
    )
    .map_err(StudyError::from)?;
    let Some(best) = best else {
        return Ok(Err("no point carries stochastic error"));
    };
    match best.enrich {
        refine::Enrich::Centre(cell) => {
            mesh.refine_centred(&[cell]).map_err(StudyError::from)?;
        }
        refine::Enrich::Node => {
            mesh.promote(&best.point).map_err(StudyError::from)?;
        }
    }
    Ok(Ok(1))
}
