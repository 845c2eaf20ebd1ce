//! What a study's runs produced: the runs ([`StudyRuns`]) and the outcome of each adaptive
//! method's loop ([`AdaptiveOutcome`], one [`StepRecord`] per step). Data only: the runner and
//! the adaptive loop fill them, the services (fields, reports) read them.

use std::sync::Arc;

use alea_latin::LatinSolver;
use alea_uq::surrogate::StochasticMesh;

use crate::cre::CreSetup;
use crate::estimate::SurrogateEstimate;
use crate::lock::StudyLock;
use crate::method::Method;
use crate::paired_runs::PairedSolves;
use crate::store::RunRecord;

/// What `run_study` (module `runner`) returns.
pub struct StudyRuns {
    /// Every run's record: the fixed designs' points in
    /// [`Study::all_points`](crate::study::Study::all_points) order, then the runs of the
    /// adaptive methods in the order they were chosen.
    pub records: Vec<RunRecord>,
    /// Runs computed by this invocation.
    pub computed: usize,
    /// Runs found in the store.
    pub resumed: usize,
    /// Solver set-up seconds.
    pub setup_seconds: f64,
    /// Wall-clock seconds of the solves of this invocation.
    pub solve_seconds: f64,
    /// Wall-clock seconds of the runs' deterministic error estimates of this invocation
    /// (included in `solve_seconds`).
    pub estimate_seconds: f64,
    /// The solver (for field output and further runs).
    pub solver: Arc<LatinSolver>,
    /// The study's methods as they ended: adaptive methods with their stochastic mesh and runs.
    pub methods: Vec<Method>,
    /// The adaptive loops, one per adaptive method (in method order).
    pub adaptive: Vec<AdaptiveOutcome>,
    /// Error estimation set-up, when the study estimates its error.
    pub cre: Option<Arc<CreSetup>>,
    /// The paired solves of the error budget's mesh and sliding parts (`crate::paired_runs`):
    /// their checks as stored, and this invocation's counts.
    pub paired: PairedSolves,
    /// The study directory's lock, held as long as these runs are (outputs are written under
    /// it).
    pub lock: StudyLock,
}

/// Statistics of one quantity of interest at one step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepQoi {
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub std: f64,
    /// `P(q > threshold)` for each threshold of the quantity.
    pub failure: Vec<f64>,
}

/// One step of the loop.
#[derive(Clone, Debug)]
pub struct StepRecord {
    /// Runs of the surrogate at this step.
    pub runs: usize,
    /// Runs added by the refinement that ended this step (0 for the last step).
    pub new_runs: usize,
    /// The estimate.
    pub error: SurrogateEstimate,
    /// Statistics of each quantity of interest on this step's surrogate.
    pub qois: Vec<StepQoi>,
    /// Seconds of this step's solves (wall clock).
    pub solve_seconds: f64,
    /// Seconds of this step's estimate (per-run CRE of its new runs + stochastic estimate).
    pub estimate_seconds: f64,
    /// Cumulative cost in the thesis's units: runs + 1.5 x estimates.
    pub thesis_cost: f64,
    /// A goal-oriented method: the goal statistics' budgets at this step (empty otherwise).
    pub goal: Vec<GoalRecord>,
}

/// The error budget of one goal statistic at one adaptive step (`crate::goal`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct GoalRecord {
    /// The mean, the standard deviation or `P(> t)`.
    pub statistic: crate::budget::Statistic,
    /// Its value on this step's surrogate.
    pub value: f64,
    /// Surrogate part of its budget.
    pub surrogate: f64,
    /// Sampling part.
    pub sampling: f64,
    /// Total.
    pub total: f64,
}

/// The outcome of one adaptive method.
#[derive(Clone, Debug)]
pub struct AdaptiveOutcome {
    /// Index of the method in the study.
    pub method: usize,
    /// The final stochastic mesh (its runs are the method's runs).
    pub mesh: StochasticMesh,
    /// Every step, in order.
    pub steps: Vec<StepRecord>,
    /// Why the loop stopped.
    pub stop: String,
    /// Set when the loop could not go on (a run that did not converge).
    pub error: Option<String>,
    /// The estimator of the last step (for maps and element fields).
    pub estimator: Option<alea_estimate::Estimator>,
}

impl StudyRuns {
    /// How the solver's linear stage is solved, substructure by substructure (`[solver]
    /// linear_stage`): `linear stage: D1 condensed (184 interface unknowns, 0.3 MB), ...`.
    ///
    /// A substructure cut into subdomains (`[solver] subdomains`) is one entry: `disk in 24
    /// subdomains of 19 800 dof on average (3 condensed)`.
    ///
    /// Ends with the factors' memory and how many are stored in single precision (`[solver]
    /// factor_precision`): `; factors 1.31 GB (30 of 30 in single precision)`.
    pub fn linear_stage_line(&self) -> String {
        let summary = self.solver.linear_stage_summary();
        let bytes: f64 = summary.iter().map(|s| s.factor_bytes).sum();
        let single = summary.iter().filter(|s| s.single_precision).count();
        let factors = format!(
            "; factors {:.2} GB ({single} of {} in single precision)",
            bytes / 1e9,
            summary.len()
        );
        let Some(split) = self.solver.split() else {
            return format!(
                "linear stage: {}{factors}",
                stage_entries(&summary).join(", ")
            );
        };
        let parts: Vec<String> = (0..self.solver.num_subs())
            .map(|s| {
                let inner = split.parts_of(s);
                if inner.len() == 1 {
                    return stage_entries(&summary[inner[0]..=inner[0]]).join("");
                }
                let dofs: usize = inner.iter().map(|&i| summary[i].dofs).sum();
                let condensed = inner.iter().filter(|&&i| summary[i].condensed).count();
                format!(
                    "{} in {} subdomains of {} dof on average ({condensed} condensed)",
                    self.solver.sub_name(s),
                    inner.len(),
                    dofs / inner.len()
                )
            })
            .collect();
        format!("linear stage: {}{factors}", parts.join(", "))
    }
}

/// One entry per substructure of [`StudyRuns::linear_stage_line`].
fn stage_entries(summary: &[alea_latin::LinearStageSummary]) -> Vec<String> {
    summary
        .iter()
        .map(|s| {
            if s.condensed {
                format!(
                    "{} condensed ({} interface unknowns, {:.1} MB)",
                    s.name,
                    s.interface_unknowns,
                    s.bytes / 1e6
                )
            } else {
                format!(
                    "{} volume solves ({} dof, {} interface unknowns)",
                    s.name, s.dofs, s.interface_unknowns
                )
            }
        })
        .collect()
}
