//! Goal-oriented adaptive refinement (issue 19): an adaptive method with a `goal` refines where
//! the surrogate error of one quantity's statistic is largest and stops when that statistic's
//! error budget ([`crate::budget`]) is within the user's tolerance.
//!
//! At each step, on the `N` Monte Carlo draws `xi_i` of the final analysis (the study's
//! `samples`, the same seed: the last step's budget is the report's, to the digit):
//! - **budget** of the goal statistic `S` (`P(q > t)`, or the mean and the standard deviation):
//!   its surrogate part against the mesh one level coarser where it can be coarsened
//!   (`alea_uq::surrogate::ParentLevel::coarsenable`) and the smooth fits on the same runs (the
//!   comparisons of the final budget, so the loop stops on the number the report gives) plus
//!   its sampling part;
//! - **leaf indicators** from `delta(xi) = max(|q~ - q~_P|, |q~ - q~_c|, |q~ - q~_s|)`, what the
//!   surrogate may be off by at `xi` (`q~_P` the interpolant over each leaf's parent,
//!   `alea_uq::surrogate::ParentLevel::new`, also where the sibling was refined further; `q~_c`
//!   the mesh of the last step with at most half the runs; `q~_s` the credible smooth fits,
//!   [`crate::budget::smooth_fits`]), summed over the draws in the leaf and divided by `N`.
//!   These are wider than the budget's comparisons: beside a resolved kink the parent's
//!   interpolant straddles the kink and marks the leaf, which costs runs, not a wrong error
//!   bar (the budget's own comparisons were 60 - 120x over there, crate `alea-uq`, module
//!   `parent`); the goal acceptance of BENCHMARKS.md was measured with them:
//!   - mean / std goal: `eta_L = (1/N) sum_{xi_i in L} delta(xi_i)`;
//!   - failure-probability goal: `eta_L = (1/N) #{xi_i in L : |q~(xi_i) - t| <= delta(xi_i)}`,
//!     the probability of the draws whose side of the limit state `q = t` the error could
//!     change.
//!
//! The loop then splits every leaf with `eta_L` at least `fraction` (the improved criterion's,
//! default 0.5) of the largest, largest first, while the run budget allows: a full split, every
//! new node a run (`StochasticMesh::refine`: the centre and the edge midpoints in 2D), not the
//! centred split of the estimate-driven criteria, whose edge midpoints stay interpolated and
//! keep the parent's error along the edges. Measured on the 2D turbine (30 runs, goal
//! `P(vm_fillet > 1165)`, reference 0.04123 from 225 runs): centred splits end at 0.0382,
//! full splits at 0.0413 (BENCHMARKS.md "Error budget per quantity").

use alea_uq::design;
use alea_uq::surrogate::{CellId, LinearSurrogate, ParentLevel, StochasticMesh};
use rayon::prelude::*;

use crate::budget::{SurrogatePart, credible_fit, qoi_budget, smooth_fits};
use crate::method::Goal;
use crate::study::Study;
pub use crate::study_runs::GoalRecord;

/// A surrogate's value at a clamped draw, with scratch space for its weights.
type AtDraw<'a> = dyn Fn(&[f64], &mut Vec<f64>, &mut Vec<(usize, f64)>) -> f64 + Sync + 'a;

/// One goal step: the goal statistics' budgets and the leaf indicators.
pub struct GoalStep {
    /// One record per goal statistic.
    pub records: Vec<GoalRecord>,
    /// True when every goal statistic's budget is within the tolerance.
    pub reached: bool,
    /// `(leaf, eta_L)` for every leaf of the mesh.
    pub indicators: Vec<(CellId, f64)>,
}

/// The goal step of `mesh` whose runs have the goal quantity's `values`, compared with
/// `coarse` (an earlier step's mesh: its runs are a prefix of `mesh`'s).
pub fn goal_step(
    study: &Study,
    goal: &Goal,
    mesh: &StochasticMesh,
    coarse: &StochasticMesh,
    values: &[f64],
    samples: usize,
    confidence: f64,
) -> GoalStep {
    let d = study.params.names.len();
    let n = samples.max(2);
    // The draws of the final analysis (`crate::analysis`: same count, same seed).
    let draws = design::monte_carlo(
        study.params.joint.as_ref(),
        n,
        study.seed.wrapping_add(0x9e37_79b9),
    );
    let pts = draws.points();
    let clamp = |x: &[f64]| -> Vec<f64> {
        (0..d)
            .map(|j| x[j].clamp(study.params.lo[j], study.params.hi[j]))
            .collect()
    };
    let parent = ParentLevel::new(mesh.clone());
    let coarsenable = ParentLevel::coarsenable(mesh.clone());
    // The surrogate, the earlier step and the parent level of the indicators, the coarsenable
    // level of the budget and the smooth fits of both at the draws (no smooth fit below 6 runs
    // in 2D).
    let run_points: Vec<Vec<f64>> = (0..mesh.num_runs())
        .map(|k| mesh.run_point(k).to_vec())
        .collect();
    let smooth = smooth_fits(&study.params, &run_points);
    let fit = |s: &crate::budget::Comparison,
               x: &[f64],
               t: &mut Vec<f64>,
               w: &mut Vec<(usize, f64)>|
     -> f64 {
        s.surrogate.weights(x, t, w);
        w.iter().map(|&(k, wk)| wk * values[s.runs[k]]).sum()
    };
    // Every surrogate at every draw, one column at a time, in parallel (in draw order: thread-
    // count independent; no allocation per draw but the clamped point).
    let column = |eval: &AtDraw| {
        pts.par_chunks(d)
            .map_init(
                || (vec![0.0; d], Vec::new()),
                |(t, w), x| eval(&clamp(x), t, w),
            )
            .collect::<Vec<f64>>()
    };
    let fine = column(&|x, _, _| mesh.interpolate(x, values));
    let earlier = column(&|x, _, _| coarse.interpolate(x, &values[..coarse.num_runs()]));
    let parent_values = column(&|x, _, _| parent.eval(x, values));
    let coarsenable_values = column(&|x, _, _| coarsenable.eval(x, values));
    let smoothed: Vec<Vec<f64>> = smooth
        .iter()
        .map(|s| column(&|x, t, w| fit(s, x, t, w)))
        .collect();
    let located: Vec<Option<CellId>> = pts.par_chunks(d).map(|x| mesh.locate(&clamp(x))).collect();
    // The smooth fits that follow the runs (as in the final budget).
    let smoothed: Vec<(&crate::budget::Comparison, Vec<f64>)> = smooth
        .iter()
        .zip(smoothed)
        .filter(|(s, at_draws)| {
            let (mut t, mut w) = (vec![0.0; d], Vec::new());
            let at_runs: Vec<f64> = run_points
                .iter()
                .map(|x| fit(s, x, &mut t, &mut w))
                .collect();
            credible_fit(&at_runs, values, at_draws, &fine)
        })
        .collect();
    // Leaf indicators: what the comparisons say the surrogate may be off by at each draw.
    let leaves = mesh.leaves();
    let slot: std::collections::HashMap<CellId, usize> =
        leaves.iter().enumerate().map(|(i, &c)| (c, i)).collect();
    let mut eta = vec![0.0; leaves.len()];
    for (i, &qf) in fine.iter().enumerate() {
        let mut surplus = (qf - parent_values[i]).abs().max((qf - earlier[i]).abs());
        for (_, column) in &smoothed {
            surplus = surplus.max((qf - column[i]).abs());
        }
        let share = match goal.threshold {
            Some(t) => f64::from(u8::from((qf - t).abs() <= surplus && surplus > 0.0)),
            None => surplus,
        };
        if let Some(leaf) = located[i] {
            eta[slot[&leaf]] += share / n as f64;
        }
    }
    let what =
        std::iter::once("the mesh one level coarser (every family of leaves merged)".to_string())
            .chain(smoothed.iter().map(|(s, _)| s.description.clone()))
            .collect::<Vec<_>>()
            .join(" and ");
    let thresholds: Vec<f64> = goal.threshold.into_iter().collect();
    let budget = qoi_budget(
        &fine,
        SurrogatePart::Comparison(
            std::iter::once((&coarsenable_values[..], false, true))
                .chain(smoothed.iter().map(|(_, v)| (&v[..], false, true)))
                .collect(),
            what,
        ),
        &[],
        &thresholds,
        confidence,
        None,
    );
    let rows: Vec<usize> = match goal.threshold {
        Some(_) => vec![2],
        None => vec![0, 1],
    };
    let records: Vec<GoalRecord> = rows
        .into_iter()
        .map(|r| {
            let row = &budget.rows[r];
            GoalRecord {
                statistic: row.statistic,
                value: row.value,
                surrogate: row.surrogate.unwrap_or(0.0),
                sampling: row.sampling,
                total: row.total,
            }
        })
        .collect();
    // A part not estimated is no part of size 0: the goal is then not reached.
    let estimated = rows_estimated(&budget.rows, goal.threshold.is_some());
    let reached = estimated
        && records
            .iter()
            .all(|r| goal.tolerance.holds(r.total, r.value));
    GoalStep {
        records,
        reached,
        indicators: leaves.into_iter().zip(eta).collect(),
    }
}

/// True when every goal row's surrogate part was estimated (`P(q > t)` with a threshold, else
/// the mean and the std).
fn rows_estimated(rows: &[crate::budget::BudgetRow], threshold: bool) -> bool {
    let goal_rows: &[usize] = if threshold { &[2] } else { &[0, 1] };
    goal_rows
        .iter()
        .all(|&r| rows.get(r).is_some_and(|row| row.surrogate.is_some()))
}

/// The leaves to split: every leaf whose indicator is at least `fraction` of the largest
/// (largest first), none when no leaf carries any.
pub fn marked_leaves(indicators: &[(CellId, f64)], fraction: f64) -> Vec<(CellId, f64)> {
    let max = indicators.iter().map(|&(_, e)| e).fold(0.0, f64::max);
    if max <= 0.0 {
        return Vec::new();
    }
    let mut out: Vec<(CellId, f64)> = indicators
        .iter()
        .copied()
        .filter(|&(_, e)| e >= fraction * max)
        .collect();
    out.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    out
}
