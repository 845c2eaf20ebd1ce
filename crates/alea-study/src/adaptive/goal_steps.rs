//! The goal-oriented parts of an adaptive step (module `crate::goal`): the earlier mesh the
//! goal compares with, the goal step, the goal quantity's values and the budget in words.

use alea_uq::surrogate::StochasticMesh;

use crate::StudyError;
use crate::analysis::AnalysisSettings;
use crate::goal;
use crate::method::Goal;
use crate::store::RunRecord;
use crate::study::Study;

/// The earlier step of a goal-oriented loop's leaf indicators ([`goal`]): the last step's mesh
/// with at most half the runs of `mesh`, or the corners of the box (the runs of the start mesh
/// but its centre).
fn comparison_mesh(
    step_meshes: &[StochasticMesh],
    mesh: &StochasticMesh,
    params: &crate::ParamSpace,
) -> Result<StochasticMesh, StudyError> {
    match step_meshes
        .iter()
        .rev()
        .find(|s| 2 * s.num_runs() <= mesh.num_runs())
    {
        Some(s) => Ok(s.clone()),
        None => StochasticMesh::new(&params.lo, &params.hi, &vec![1; params.lo.len()])
            .map_err(StudyError::from),
    }
}

/// The goal quantity's value at every run of the mesh (`records` in run order).
pub(super) fn values_of_goal(records: &[RunRecord], goal: &Goal) -> Vec<f64> {
    records.iter().map(|r| r.qois[goal.quantity]).collect()
}

/// The goal step of `mesh` (the last of `step_meshes`) against an earlier step's mesh (the
/// goal's threshold checked against the runs' range at the `first` step).
pub(super) fn goal_step_of(
    study: &Study,
    g: &Goal,
    mesh: &StochasticMesh,
    step_meshes: &[StochasticMesh],
    first: bool,
    records: &[RunRecord],
    stats: &AnalysisSettings,
) -> Result<goal::GoalStep, StudyError> {
    let values: Vec<f64> = records.iter().map(|r| r.qois[g.quantity]).collect();
    if first {
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        g.check_threshold(lo, hi)?;
    }
    let coarse = comparison_mesh(step_meshes, mesh, &study.params)?;
    Ok(goal::goal_step(
        study,
        g,
        mesh,
        &coarse,
        &values,
        stats.samples,
        stats.confidence,
    ))
}

/// The goal statistics' budgets in words (and when the sampling part alone misses the
/// tolerance, which no run lowers).
pub(super) fn goal_budget_words(goal: &Goal, g: &goal::GoalStep) -> String {
    let mut budget = g
        .records
        .iter()
        .map(|r| format!("{} = {:.6} +- {:.2e}", r.statistic, r.value, r.total))
        .collect::<Vec<_>>()
        .join(", ");
    // No run lowers the sampling part: say so when it alone misses the tolerance.
    if let Some(r) = g
        .records
        .iter()
        .find(|r| !goal.tolerance.holds(r.sampling, r.value))
    {
        budget.push_str(&format!(
            "; the sampling part of {} alone, {:.2e}, exceeds the tolerance: more [statistics] samples lower it, more runs do not",
            r.statistic, r.sampling
        ));
    }
    budget
}
