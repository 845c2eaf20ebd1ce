//! Goal-oriented adaptive refinement (issue 19): an adaptive method with a `goal` refines where
//! the surrogate error of one quantity's statistic is largest and stops when that statistic's
//! error budget ([`crate::budget`]) is within the user's tolerance.
//!
//! At each step, on `N` Monte Carlo draws `xi_i` (at most 100 000, seeded):
//! - **budget** of the goal statistic `S` (`P(q > t)`, or the mean and the standard deviation):
//!   its surrogate part against the mesh of the last step with at most half the runs and the
//!   mesh one level coarser (the comparisons of the final budget, so the loop stops on the
//!   number the report gives) plus its sampling part;
//! - **leaf indicators** from `delta(xi) = max(|q~ - q~_P|, |q~ - q~_c|)`, what the budget's
//!   comparisons say the surrogate may be off by at `xi` (`q~_P` the interpolant over each
//!   leaf's parent, `alea_uq::surrogate::ParentLevel`; `q~_c` the earlier step), summed over
//!   the draws in the leaf and divided by `N`:
//!   - mean / std goal: `eta_L = (1/N) sum_{xi_i in L} delta(xi_i)`;
//!   - failure-probability goal: `eta_L = (1/N) #{xi_i in L : |q~(xi_i) - t| <= delta(xi_i)}`,
//!     the probability of the draws whose side of the limit state `q = t` the error could
//!     change.
//!
//! The loop then splits (all directions, one run at the centre) every leaf with `eta_L` at
//! least `fraction` (the improved criterion's, default 0.5) of the largest, within the run
//! budget.

use alea_uq::design;
use alea_uq::surrogate::{CellId, LinearSurrogate, ParentLevel, StochasticMesh};

use crate::budget::{SurrogatePart, qoi_budget};
use crate::method::Goal;
pub use crate::runs::GoalRecord;
use crate::study::Study;

/// Draws per goal step, at most.
const MAX_DRAWS: usize = 100_000;

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
    let n = samples.clamp(2, MAX_DRAWS);
    let draws = design::monte_carlo(
        study.params.joint.as_ref(),
        n,
        study.seed.wrapping_add(0x6f61_6c21),
    );
    let pts = draws.points();
    let clamp = |x: &[f64]| -> Vec<f64> {
        (0..d)
            .map(|j| x[j].clamp(study.params.lo[j], study.params.hi[j]))
            .collect()
    };
    let parent = ParentLevel::new(mesh.clone());
    let mut fine = Vec::with_capacity(n);
    let mut earlier = Vec::with_capacity(n);
    let mut eta = vec![0.0; 0];
    let leaves = mesh.leaves();
    let mut slot = std::collections::HashMap::new();
    for (i, &c) in leaves.iter().enumerate() {
        slot.insert(c, i);
    }
    eta.resize(leaves.len(), 0.0);
    for x in pts.chunks(d) {
        let x = clamp(x);
        let qf = mesh.interpolate(&x, values);
        let qc = coarse.interpolate(&x, &values[..coarse.num_runs()]);
        let qp = parent.eval(&x, values);
        fine.push(qf);
        earlier.push(qc);
        // What the comparisons of the budget say the surrogate may be off by here.
        let surplus = (qf - qp).abs().max((qf - qc).abs());
        let share = match goal.threshold {
            Some(t) => f64::from(u8::from((qf - t).abs() <= surplus && surplus > 0.0)),
            None => surplus,
        };
        if let Some(leaf) = mesh.locate(&x) {
            eta[slot[&leaf]] += share / n as f64;
        }
    }
    let what = format!(
        "the stochastic mesh of {} runs and the mesh one level coarser",
        coarse.num_runs()
    );
    let parent_values: Vec<f64> = pts
        .chunks(d)
        .map(|x| parent.eval(&clamp(x), values))
        .collect();
    let thresholds: Vec<f64> = goal.threshold.into_iter().collect();
    let budget = qoi_budget(
        &fine,
        SurrogatePart::Comparison(
            vec![(&earlier, true, true), (&parent_values, false, true)],
            what,
        ),
        &[],
        &thresholds,
        confidence,
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
                statistic: row.statistic.clone(),
                value: row.value,
                surrogate: row.surrogate.unwrap_or(0.0),
                sampling: row.sampling,
                total: row.total,
            }
        })
        .collect();
    let reached = records
        .iter()
        .all(|r| goal.tolerance.holds(r.total, r.value));
    GoalStep {
        records,
        reached,
        indicators: leaves.into_iter().zip(eta).collect(),
    }
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
