//! The adaptive loop of an `adaptive` method (thesis 4.2, figure 4.6): runs -> stochastic
//! error estimate -> criterion -> new runs, on a piecewise-multilinear stochastic mesh.
//!
//! 1. Start from the corners of the parameter box and its centre (`2^d + 1` runs).
//! 2. Run every node of the mesh that is a run and not finished yet (warm-started from the
//!    nearest converged runs of earlier generations and steps; a resumed study finds them in the
//!    store).
//! 3. Estimate (crate `alea-estimate`): `e~`, `I_geo`, `I_sto` on the mesh's cells; the
//!    statistics of every quantity of interest on the current surrogate.
//! 4. Stop when `i_sto <= target` (if given), else when `i_sto <= i_geo` and `i_geo` changed by
//!    at most 10 % since the previous step (stable); or when the run budget is reached or no cell
//!    carries stochastic error.
//! 5. Mark and refine: the improved criterion marks every cell whose integrated stochastic
//!    error is at least `fraction` of the largest and, in each, runs the centre and the
//!    interpolated corners (edge / face midpoints of earlier refinements) where the error
//!    density is within `fraction` of the cell's largest (`alea_estimate::refine` says why:
//!    centres alone saturate, and the midpoints along directions where the response is linear
//!    carry no density, so the runs follow the directions where it bends), the maximum-error
//!    criterion searches the point of largest
//!    stochastic error density over the sub-cell centres of every cell and the interpolated
//!    nodes, and adds one run: the node itself, or the centre of the cell that holds the
//!    sub-cell centre (`alea_estimate::refine` says why). Then back to 2.
//!
//! A run that failed (not converged after its retries, or without equilibrium) leaves no error
//! estimate possible: the loop then splits the cells around failed runs to [`FAILURE_LEVEL`]
//! (within the run budget) to delimit their region, and stops; the method's statistics leave
//! that region out and report its probability (module `failure_region`).
//!
//! Every step is a pure function of the runs' results, so a resumed loop replays the same steps
//! and recomputes no run. Cost in the thesis's units (tables 4.3-4.4): a run counts 1, an
//! estimate 1.5.

use std::collections::HashMap;
use std::sync::{Arc, MutexGuard};

use alea_estimate::refine;
use alea_latin::LatinSolver;
use alea_uq::surrogate::{CellId, StochasticMesh};

use crate::StudyError;
use crate::analysis::{AnalysisSettings, analyse_method};
use crate::cre::{CreSetup, StudyParameters};
use crate::estimate::{ErrorSettings, MethodEstimateInput, error_settings, estimate_method};
use crate::goal;
use crate::method::{AdaptiveSettings, Criterion, Method};
pub use crate::runs::{AdaptiveOutcome, StepQoi, StepRecord};
use crate::store::{RunRecord, Store, point_key};
use crate::study::Study;

/// What the adaptive loop needs from the runner of a study's solves (the runner implements it
/// and calls [`run_adaptive`]; the loop depends on this trait, never on the runner).
pub(crate) trait AdaptiveRuns<'a> {
    /// The study.
    fn study(&self) -> &'a Study;
    /// Error estimation set-up, when the study estimates its error.
    fn cre(&self) -> Option<Arc<CreSetup>>;
    /// The solver.
    fn solver(&self) -> &LatinSolver;
    /// The finished runs by point key.
    fn by_key(&self) -> &HashMap<String, RunRecord>;
    /// Wall-clock seconds of the solves so far.
    fn solve_seconds(&self) -> f64;
    /// Wall-clock seconds of the runs' error estimates so far.
    fn estimate_seconds(&self) -> f64;
    /// Runs (or finds in the store) every point of `points` not finished yet.
    fn run_points(&mut self, points: &[Vec<f64>]) -> Result<(), StudyError>;
    /// The store (locked).
    fn store(&self) -> Result<MutexGuard<'_, Store>, StudyError>;
    /// Tells the progress observer about runs added by an adaptive step.
    fn announce(&self, more: usize);
}

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

/// What a goal's validation runs decided (module `goal_validation`).
enum Validated {
    /// The loop stops with this message (goal reached, or not reached within the budget).
    Stop(String),
    /// The leaves they found wrong were split: this many new runs.
    Refined(usize),
}

/// A goal whose budget is within its tolerance, checked against validation runs of the solver
/// drawn from the input law independently of `mesh` (round `round`; module `goal_validation`):
/// they agree (stop: goal reached), or the leaves holding the draws the surrogate gets wrong
/// are split within `max_runs` (the next round doubles the sample), or no split fits.
fn validate_goal<'a>(
    runner: &mut impl AdaptiveRuns<'a>,
    goal: &crate::method::Goal,
    mesh: &mut StochasticMesh,
    records: &[RunRecord],
    g: &goal::GoalStep,
    budget: &str,
    round: &mut u32,
    max_runs: usize,
) -> Result<Validated, StudyError> {
    let study = runner.study();
    let vpoints = crate::goal_validation::points(study, *round);
    let fresh = vpoints
        .iter()
        .filter(|p| !runner.by_key().contains_key(&point_key(p)))
        .count();
    runner.announce(fresh);
    runner.run_points(&vpoints)?;
    let validated: Vec<(Vec<f64>, f64)> = vpoints
        .iter()
        .filter_map(|p| runner.by_key().get(&point_key(p)))
        .filter(|r| r.converged())
        .map(|r| (r.params.clone(), r.qois[goal.quantity]))
        .collect();
    let value: Vec<f64> = g.records.iter().map(|r| r.value).collect();
    let verdict = crate::goal_validation::check(
        goal,
        study,
        mesh,
        &values_of_goal(records, goal),
        &validated,
        &value,
    );
    Ok(match verdict {
        crate::goal_validation::Verdict::Holds(errors) => {
            let said = errors
                .iter()
                .map(|(s, e)| format!("{s} {e:.2e}"))
                .collect::<Vec<_>>()
                .join(", ");
            Validated::Stop(format!(
                "goal reached: {budget}; {} validation runs agree (their estimate of the \
                 surrogate's error: {said})",
                validated.len()
            ))
        }
        crate::goal_validation::Verdict::Misses {
            statistic,
            error,
            leaves,
        } => {
            *round += 1;
            match split_within(mesh, &leaves, max_runs)? {
                0 => Validated::Stop(format!(
                    "goal not reached: its budget says {budget}, but {} validation runs \
                     estimate the surrogate's error of {statistic} at {error:.2e}, above the \
                     tolerance, and the run budget of {max_runs} leaves no split",
                    validated.len()
                )),
                new => Validated::Refined(new),
            }
        }
    })
}

/// A target stop (`i_sto <= target`) checked against the study's validation runs (module
/// `crate::target_validation`): their count for the mesh's runs, run (or found in the store)
/// now; every quantity's relative error within the target (stop, with what the runs say
/// appended to the stop message), or the leaves holding the points a quantity gets wrong are
/// split within `max_runs`. No validation runs (`[budget] validation_runs = 0`, or a replay
/// that finds none in the store): the stop stands as the estimate says.
fn validate_target<'a>(
    runner: &mut impl AdaptiveRuns<'a>,
    mesh: &mut StochasticMesh,
    records: &[RunRecord],
    head: &str,
    target: f64,
    max_runs: usize,
) -> Result<Validated, StudyError> {
    let study = runner.study();
    let n = study.validation_runs.unwrap_or_else(|| {
        (mesh.num_runs() / 4).clamp(
            crate::validation_runs::AUTO_MIN,
            crate::validation_runs::AUTO_MAX,
        )
    });
    let vpoints = crate::validation_runs::points(study, n);
    if vpoints.is_empty() {
        return Ok(Validated::Stop(head.to_string()));
    }
    let fresh = vpoints
        .iter()
        .filter(|p| !runner.by_key().contains_key(&point_key(p)))
        .count();
    runner.announce(fresh);
    runner.run_points(&vpoints)?;
    let validated: Vec<(Vec<f64>, Vec<f64>)> = vpoints
        .iter()
        .filter_map(|p| runner.by_key().get(&point_key(p)))
        .filter(|r| r.converged())
        .map(|r| (r.params.clone(), r.qois.clone()))
        .collect();
    let found = vpoints
        .iter()
        .filter(|p| runner.by_key().contains_key(&point_key(p)))
        .count();
    if found < vpoints.len() {
        // Replayed from a store written before target stops were validated.
        return Ok(Validated::Stop(head.to_string()));
    }
    if validated.len() < 2 {
        return Ok(Validated::Stop(format!(
            "{head}; {} of {} validation runs converged: too few to check the target",
            validated.len(),
            vpoints.len()
        )));
    }
    let values: Vec<Vec<f64>> = (0..study.qois.len())
        .map(|q| records.iter().map(|r| r.qois[q]).collect())
        .collect();
    Ok(
        match crate::target_validation::check(study, mesh, &values, &validated, target) {
            crate::target_validation::TargetVerdict::Holds(errors) => {
                let said = errors
                    .iter()
                    .map(|(q, e)| format!("{q} {:.2} %", 100.0 * e))
                    .collect::<Vec<_>>()
                    .join(", ");
                Validated::Stop(format!(
                    "{head}; {} validation runs agree (the surrogate's RMS error relative to each quantity's: {said})",
                    validated.len()
                ))
            }
            crate::target_validation::TargetVerdict::Misses {
                quantity,
                relative,
                leaves,
            } => match split_within(mesh, &leaves, max_runs)? {
                0 => Validated::Stop(format!(
                    "target not met: {head}, but {} validation runs put the surrogate's RMS error of {quantity} at {:.2} % of its size, above the target, and the run budget of {max_runs} leaves no split",
                    validated.len(),
                    100.0 * relative
                )),
                new => Validated::Refined(new),
            },
        },
    )
}

/// The goal quantity's value at every run of the mesh (`records` in run order).
fn values_of_goal(records: &[RunRecord], goal: &crate::method::Goal) -> Vec<f64> {
    records.iter().map(|r| r.qois[goal.quantity]).collect()
}

/// The level to which the adaptive loop splits the cells around failed runs (a cell edge of
/// 1/8 of the box): deep enough to delimit a region holding a few percent of the law, shallow
/// enough that a region of failures does not take the whole run budget.
pub const FAILURE_LEVEL: u32 = 3;

/// Splits (in full, within `max_runs`) every leaf of `mesh` below [`FAILURE_LEVEL`] whose
/// interpolant uses a failed run (`failed[k]` per run, tested at the leaf's centre where every
/// corner has a weight); the number of new runs, `None` when no leaf qualifies or fits.
fn delimit_failures(
    mesh: &mut StochasticMesh,
    failed: &[bool],
    max_runs: usize,
) -> Result<Option<usize>, StudyError> {
    use alea_uq::surrogate::LinearSurrogate;
    let mut w = Vec::new();
    let cells: Vec<_> = mesh
        .leaves()
        .into_iter()
        .filter(|&c| {
            mesh.level(c) < FAILURE_LEVEL && {
                LinearSurrogate::weights(&*mesh, &mesh.cell_centre(c), &mut w);
                crate::failure_region::touches(&w, failed)
            }
        })
        .collect();
    let new = split_within(mesh, &cells, max_runs)?;
    Ok((new > 0).then_some(new))
}

/// Splits the leaves `cells` of `mesh` in full, in order, while the mesh keeps at most
/// `max_runs` runs (the first split that would exceed it ends the splitting); the number of
/// new runs.
fn split_within(
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

/// The start mesh: the parameter box with its corners and centre as runs.
pub fn start_mesh(lo: &[f64], hi: &[f64]) -> Result<StochasticMesh, StudyError> {
    let uq = StudyError::from;
    let mut mesh = StochasticMesh::new(lo, hi, &vec![1; lo.len()]).map_err(uq)?;
    mesh.refine_centred(&[0]).map_err(uq)?;
    Ok(mesh)
}

/// Runs the adaptive loop of method `m`.
pub(crate) fn run_adaptive<'a>(
    runner: &mut impl AdaptiveRuns<'a>,
    m: usize,
    settings: &AdaptiveSettings,
) -> Result<AdaptiveOutcome, StudyError> {
    let study = runner.study();
    let setup = runner
        .cre()
        .ok_or_else(|| StudyError::Internal("adaptive method without error estimation".into()))?;
    let err_settings: ErrorSettings = error_settings(study)?;
    let stats: AnalysisSettings = crate::analysis::analysis_settings(study)?;
    let params = &study.params;
    let mut mesh = start_mesh(&params.lo, &params.hi)?;
    let mut steps: Vec<StepRecord> = Vec::new();
    // The mesh of every step: the error budget compares with an earlier one.
    let mut step_meshes: Vec<StochasticMesh> = Vec::new();
    let mut estimates = 0usize;
    let mut last_estimator = None;
    // Rounds of goal validation runs so far (module `goal_validation`).
    let mut validation_round = 0u32;
    let (stop, error) = loop {
        let points: Vec<Vec<f64>> = (0..mesh.num_runs())
            .map(|r| mesh.run_point(r).to_vec())
            .collect();
        let (solve0, est0) = (runner.solve_seconds(), runner.estimate_seconds());
        runner.run_points(&points)?;
        let solve_seconds = runner.solve_seconds() - solve0;
        if let Some(p) = points
            .iter()
            .find(|p| !runner.by_key().contains_key(&point_key(p)))
        {
            // Replayed from the store (`alea report`): the loop stops where the runs end.
            break (
                "a run is missing".to_string(),
                Some(format!(
                    "the run at {p:?} is missing from the study directory; the adaptive stochastic mesh needs every run"
                )),
            );
        }
        let failed: Vec<bool> = points
            .iter()
            .map(|p| {
                runner
                    .by_key()
                    .get(&point_key(p))
                    .is_some_and(|r| !r.converged())
            })
            .collect();
        if failed.iter().any(|&f| f) {
            // Runs failed (module `failure_region`): no error estimate is possible on a mesh
            // with failed nodes, so the loop delimits the region around them and stops; the
            // method's statistics leave that region out.
            let count = failed.iter().filter(|&&f| f).count();
            match delimit_failures(&mut mesh, &failed, settings.max_runs)? {
                Some(new) => {
                    runner.announce(new);
                    continue;
                }
                None => {
                    break (
                        format!(
                            "{count} run(s) failed: the cells around them were split to level \
                             {FAILURE_LEVEL} (or the run budget) to delimit the region, which the \
                             statistics leave out; no error estimate on a mesh with failed runs"
                        ),
                        None,
                    );
                }
            }
        }
        let mut method: Method = study.methods[m].clone();
        method.points = points.clone();
        method.mesh = Some(mesh.clone());
        let sur = method.surrogate(params, &points)?;
        let (est, merr) = {
            let store = runner.store()?;
            estimate_method(&MethodEstimateInput {
                study,
                setup: &setup,
                solver: runner.solver(),
                store: &store,
                method: &method,
                points: &points,
                sur: &sur,
                settings: &err_settings,
            })?
        };
        estimates += 1;
        let records: Vec<_> = points
            .iter()
            .filter_map(|p| runner.by_key().get(&point_key(p)).cloned())
            .collect();
        let analysis = analyse_method(study, &method, &records, &stats);
        let qois = analysis
            .qois
            .iter()
            .map(|q| StepQoi {
                mean: q.mean,
                std: q.std,
                failure: q.failure.iter().map(|f| f.probability).collect(),
            })
            .collect();
        let (i_sto, i_geo) = (merr.estimate.i_sto(), merr.estimate.i_geo());
        let estimate_seconds = runner.estimate_seconds() - est0 + merr.seconds;
        let runs = mesh.num_runs();
        let thesis_cost = runs as f64 + 1.5 * estimates as f64;
        let previous_geo = steps.last().map(|s| s.error.estimate.i_geo());
        let cells = merr.estimate.cells.clone();
        last_estimator = Some(est.clone());
        step_meshes.push(mesh.clone());
        let goal_step = match &settings.goal {
            Some(g) => {
                let values: Vec<f64> = records.iter().map(|r| r.qois[g.quantity]).collect();
                if steps.is_empty() {
                    let (lo, hi) = values
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                            (a.min(v), b.max(v))
                        });
                    g.check_threshold(lo, hi)?;
                }
                let coarse = comparison_mesh(&step_meshes, &mesh, params)?;
                Some(goal::goal_step(
                    study,
                    g,
                    &mesh,
                    &coarse,
                    &values,
                    stats.samples,
                    stats.confidence,
                ))
            }
            None => None,
        };
        steps.push(StepRecord {
            runs,
            new_runs: 0,
            error: merr,
            qois,
            solve_seconds,
            estimate_seconds,
            thesis_cost,
            goal: goal_step
                .as_ref()
                .map_or_else(Vec::new, |g| g.records.clone()),
        });
        // A goal's budget compares surrogates built on the same runs: where the runs miss a
        // feature every comparison misses it alike (issue 40: a 5-run start design said "goal
        // reached" with an error twice its bar while i_sto was 31 %). The goal is not taken as
        // reached while the CRE estimate says the surrogate needs more runs (`i_sto` above the
        // `[error] warn` level): the loop then refines where the estimate's stochastic error
        // sits, as the estimate-driven loop does.
        let blind_goal = goal_step
            .as_ref()
            .is_some_and(|g| g.reached && i_sto > err_settings.warn);
        if let (Some(g), Some(goal), false) = (&goal_step, &settings.goal, blind_goal) {
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
            if g.reached {
                match validate_goal(
                    runner,
                    goal,
                    &mut mesh,
                    &records,
                    g,
                    &budget,
                    &mut validation_round,
                    settings.max_runs,
                )? {
                    Validated::Stop(message) => break (message, None),
                    Validated::Refined(new) => {
                        if let Some(s) = steps.last_mut() {
                            s.new_runs = new;
                        }
                        runner.announce(new);
                        continue;
                    }
                }
            }
            if runs >= settings.max_runs {
                break (
                    format!(
                        "run budget of {} reached (goal: {budget})",
                        settings.max_runs
                    ),
                    None,
                );
            }
            let fraction = match settings.criterion {
                Criterion::Improved { fraction } => fraction,
                Criterion::MaxError { .. } => 0.5,
            };
            let marked = goal::marked_leaves(&g.indicators, fraction);
            if marked.is_empty() {
                break (format!("no leaf carries goal error ({budget})"), None);
            }
            // Full splits (every new node a run), largest indicator first, within the budget.
            let cells: Vec<CellId> = marked.iter().map(|&(c, _)| c).collect();
            let new = split_within(&mut mesh, &cells, settings.max_runs)?;
            if new == 0 {
                break (
                    format!(
                        "run budget of {} reached: the next split needs more runs (goal: {budget})",
                        settings.max_runs
                    ),
                    None,
                );
            }
            if let Some(s) = steps.last_mut() {
                s.new_runs = new;
            }
            runner.announce(new);
            continue;
        }
        match settings.target {
            Some(t) if i_sto <= t => {
                let head = format!("i_sto = {i_sto:.4} <= target {t}");
                match validate_target(runner, &mut mesh, &records, &head, t, settings.max_runs)? {
                    Validated::Stop(message) => break (message, None),
                    Validated::Refined(new) => {
                        if let Some(s) = steps.last_mut() {
                            s.new_runs = new;
                        }
                        runner.announce(new);
                        continue;
                    }
                }
            }
            None if i_sto <= i_geo
                && previous_geo.is_some_and(|g| (g - i_geo).abs() <= 0.1 * i_geo) =>
            {
                break (
                    format!("i_sto = {i_sto:.4} <= i_geo = {i_geo:.4}, i_geo stable"),
                    None,
                );
            }
            _ => {}
        }
        if runs >= settings.max_runs {
            break (format!("run budget of {} reached", settings.max_runs), None);
        }
        let new = match settings.criterion {
            Criterion::Improved { fraction } => {
                let marked = refine::improved(&cells, fraction).map_err(StudyError::from)?;
                if marked.is_empty() {
                    break ("no cell carries stochastic error".to_string(), None);
                }
                let sp = StudyParameters::new(&study.model.parametric, runner.solver());
                let mut actions = refine::improved_actions(
                    &mesh,
                    &marked,
                    &est,
                    &sur,
                    &sp,
                    params.joint.as_ref(),
                    fraction,
                )
                .map_err(StudyError::from)?;
                // Keep the largest densities within the budget (actions come sorted; a split
                // along m of d directions adds up to 2^(d - m) runs).
                let d = params.lo.len();
                let full = (1u32 << d) - 1;
                let room = settings.max_runs - runs;
                let mut cost = 0;
                actions.retain(|(a, _)| {
                    let c = match a {
                        refine::ImprovedAction::Split(_, m) => {
                            1usize << (d - m.count_ones() as usize)
                        }
                        _ => 1,
                    };
                    let keep = cost + c <= room;
                    if keep {
                        cost += c;
                    }
                    keep
                });
                if actions.is_empty() {
                    break (
                        "no point of the marked cells carries stochastic error within the run budget"
                            .to_string(),
                        None,
                    );
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
                mesh.num_runs() - before
            }
            Criterion::MaxError { depth } => {
                let sp = StudyParameters::new(&study.model.parametric, runner.solver());
                let best =
                    refine::max_error_point(&mesh, &est, &sur, &sp, params.joint.as_ref(), depth)
                        .map_err(StudyError::from)?;
                let Some(best) = best else {
                    break ("no point carries stochastic error".to_string(), None);
                };
                match best.enrich {
                    refine::Enrich::Centre(cell) => {
                        mesh.refine_centred(&[cell]).map_err(StudyError::from)?;
                    }
                    refine::Enrich::Node => {
                        mesh.promote(&best.point).map_err(StudyError::from)?;
                    }
                }
                1
            }
        };
        if let Some(s) = steps.last_mut() {
            s.new_runs = new;
        }
        runner.announce(new);
    };
    Ok(AdaptiveOutcome {
        method: m,
        mesh,
        steps,
        stop,
        error,
        estimator: last_estimator,
    })
}
