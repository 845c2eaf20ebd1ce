//! One run of a study: the job ([`RunJob`]), its solve and error estimate ([`RunContext::solve`],
//! a pure function of the job) and its outcome ([`RunOutcome`]), the per-process set-up
//! ([`RunSetup`]), and the executors that solve the runs of a batch ([`BatchExecutor`]:
//! [`LocalExecutor`] on the rayon pool, the MPI one in the `distributed` module). The runner
//! schedules the batches and commits the outcomes.

use std::path::Path;
use std::sync::Arc;

use alea_latin::{LatinSolver, LocalState, RunStatus};
use rayon::prelude::*;

use crate::StudyError;
use crate::cre::CreSetup;
use crate::store::{RunRecord, run_file_stem};
use crate::study::{Study, estimates_error};

/// One pending run: its physical point and the converged state it starts from.
#[derive(Clone, Debug)]
pub struct RunJob {
    /// Parameter point (physical values).
    pub theta: Vec<f64>,
    /// Local-stage state interpolated from converged runs of the earlier generations
    /// (`None`: cold start).
    pub start: Option<Arc<LocalState>>,
}

/// A finished run before it is committed to the store.
#[derive(Clone, Debug)]
pub struct RunOutcome {
    /// The store row.
    pub rec: RunRecord,
    /// Displacements of every substructure, concatenated (the run's field data in the store).
    pub fields: Vec<f64>,
    /// Compact per-run error-estimate data, when the study estimates its error.
    pub cre: Option<Vec<f64>>,
    /// Seconds of the run's error estimate.
    pub estimate_seconds: f64,
}

/// The solver and error-estimator set-up of a study: built once per process (per MPI rank),
/// always in this order so that every process holds bit-identical factorisations.
pub struct RunSetup {
    /// The multiresolution solver.
    pub solver: Arc<LatinSolver>,
    /// Error estimation set-up, when the study estimates its error.
    pub cre: Option<Arc<CreSetup>>,
}

impl RunSetup {
    /// Builds the solver (and factorises), then the error estimator's set-up if the study has
    /// one.
    pub fn build(study: &Study) -> Result<Self, StudyError> {
        Self::build_on(study, None)
    }

    /// [`RunSetup::build`] of the solver of the study's runs: spread over the ranks of the
    /// exchange installed by [`install_rank_exchange`] if any (`[solver] ranks_per_run` under
    /// `mpirun`: each rank factorises the substructures it owns, module `alea_latin::ranks`).
    /// Every rank of the group builds it at the same time and solves the same runs.
    pub fn build_for_runs(study: &Study) -> Result<Self, StudyError> {
        Self::build_on(study, RANKS.get().cloned())
    }

    fn build_on(
        study: &Study,
        ranks: Option<Arc<dyn alea_latin::RankExchange>>,
    ) -> Result<Self, StudyError> {
        let solver = Arc::new(study.model.solver_on(ranks)?);
        let cre = if estimates_error(study) {
            Some(Arc::new(CreSetup::new(study, &solver)?))
        } else {
            None
        };
        Ok(RunSetup { solver, cre })
    }
}

/// Everything needed to solve one run: the study, its set-up and the study directory (where
/// per-run ParaView files go when `[output] vtu = true`).
#[derive(Clone, Copy)]
pub struct RunContext<'a> {
    /// The study.
    pub study: &'a Study,
    /// The solver.
    pub solver: &'a LatinSolver,
    /// Error estimation set-up, when the study estimates its error.
    pub cre: Option<&'a CreSetup>,
    /// The study directory.
    pub dir: &'a Path,
    /// Whether the run writes its ParaView files when `[output] vtu = true` (false for the
    /// paired solves of the error budget, `crate::paired_runs`: they are not the study's runs).
    pub files: bool,
    /// Whether the user asked to stop ([`crate::runner::Progress::stop_requested`]): the
    /// local executor starts no further group of runs once it returns true.
    pub stop: &'a (dyn Fn() -> bool + Sync),
}

/// A [`RunContext::stop`] that never stops.
pub fn never_stop() -> bool {
    false
}

impl RunContext<'_> {
    /// Solves one run (and its error estimate when the study has one), writes its ParaView
    /// files if asked; commits nothing. A pure function of the job: the same on every thread and
    /// every MPI rank.
    pub fn solve(&self, job: &RunJob) -> Result<RunOutcome, StudyError> {
        let first = self.attempt(job, self.input(job))?;
        self.retried(job, first)
    }

    /// The retries of a run that did not converge (issue 35): a run that ended "not
    /// converged" or "diverged" is solved again cold (the warm start may be what misled it),
    /// then cold with the damped settings of [`alea_latin::RunInput::damped`] (no Anderson
    /// acceleration, twice the iteration limit), and the first attempt that converges is the
    /// run; if none does, the last attempt is. A run without equilibrium is not retried: its
    /// status is a finding about the model (a drift, or a certificate that no admissible
    /// interface forces balance the loads), not about the iteration. The run's iteration
    /// count is that of every attempt, and its status says that it was retried.
    fn retried(&self, job: &RunJob, first: RunOutcome) -> Result<RunOutcome, StudyError> {
        let retryable = |o: &RunOutcome| {
            // With [[step]]s the status is prefixed by the step that failed.
            o.rec.status.ends_with(RunStatus::NotConverged.label())
                || o.rec.status.ends_with(RunStatus::Diverged.label())
        };
        if !retryable(&first) {
            return Ok(first);
        }
        let mut spent = first.rec.iterations;
        let cold = RunJob {
            theta: job.theta.clone(),
            start: None,
        };
        let mut last = first;
        for (damped, how) in [(false, "cold"), (true, "cold and damped")] {
            let mut input = self.input(&cold);
            input.damped = damped;
            let mut out = self.attempt(&cold, input)?;
            spent += out.rec.iterations;
            out.rec.iterations = spent;
            let converged = out.rec.converged();
            if !converged {
                out.rec.status = format!("{} (also retried {how})", out.rec.status);
            }
            last = out;
            if converged {
                break;
            }
        }
        Ok(last)
    }

    /// One attempt at a run: the solve of `input` (the job's, or a retry's) and its outcome.
    fn attempt(&self, job: &RunJob, input: alea_latin::RunInput) -> Result<RunOutcome, StudyError> {
        let study = self.study;
        if alea_latin::large_sliding::uses_large_sliding(&study.model.assembly) {
            // Each step re-paired in its deformed configuration, on the assembly of its
            // imposed displacements.
            let mut assemblies = vec![&study.model.assembly];
            assemblies.extend(study.step_models.iter().map(|m| &m.assembly));
            let steps = crate::steps::run_large_sliding(
                study.steps.as_ref(),
                &assemblies,
                &study.model.options,
                &study.model.repairing,
                &input,
            )?;
            return self.outcome(job, StepRuns::Repaired(&steps));
        }
        // With [[step]]s, one result per step run (module `steps`); the last is the run's.
        let results = match &study.steps {
            None => vec![self.solver.run_shared(&input)?],
            Some(plan) => {
                let others = study.step_solvers()?;
                crate::steps::run_study_history(plan, self.solver, others, &input)?
            }
        };
        self.outcome(job, StepRuns::Paired(results))
    }

    /// Solves the runs of `jobs` as one batch of the solver ([`LatinSolver::run_batch`]: one
    /// multi-column solve per substructure and iteration for all of them), then each run's
    /// quantities, estimate and files as [`RunContext::solve`] does; the outcomes in job order.
    /// Runs with [[step]]s are solved one at a time (each is a history of solves).
    pub fn solve_batch(&self, jobs: &[RunJob]) -> Vec<Result<RunOutcome, StudyError>> {
        if self.study.steps.is_some()
            || alea_latin::large_sliding::uses_large_sliding(&self.study.model.assembly)
        {
            return jobs.par_iter().map(|job| self.solve(job)).collect();
        }
        let inputs: Vec<_> = jobs.iter().map(|job| self.input(job)).collect();
        let results = self.solver.run_batch(&inputs);
        jobs.par_iter()
            .zip(results.into_par_iter())
            .map(|(job, res)| {
                let first = self.outcome(job, StepRuns::Paired(vec![res?]))?;
                self.retried(job, first)
            })
            .collect()
    }

    /// The solver input of a job.
    fn input(&self, job: &RunJob) -> alea_latin::RunInput {
        let mut input = self.study.model.parametric.run_input(&job.theta);
        input.initial = job.start.clone();
        input
    }

    /// The outcome of a job from its solver results (one per load step; the last is the
    /// run's).
    fn outcome(&self, job: &RunJob, runs: StepRuns<'_>) -> Result<RunOutcome, StudyError> {
        let study = self.study;
        let theta = job.theta.as_slice();
        let repaired = matches!(runs, StepRuns::Repaired(_));
        // Per step: its result, its solver (large sliding: that of its last pairing) and the
        // tangential jump at its start (where its slip, work and dissipation count from).
        let point_sides = match &runs {
            StepRuns::Paired(_) => Vec::new(),
            StepRuns::Repaired(steps) => steps
                .last()
                .map_or_else(Vec::new, |s| s.point_sides.clone()),
        };
        let (results, solvers, origins) = match runs {
            StepRuns::Paired(results) => {
                let origins = (0..results.len())
                    .map(|k| {
                        let prev = k.checked_sub(1).map(|p| &results[p]);
                        alea_latin::steps::step_origins(prev, &results[k])
                    })
                    .collect::<Vec<_>>();
                let solvers = vec![self.solver; results.len()];
                (results, solvers, origins)
            }
            StepRuns::Repaired(steps) => (
                steps.iter().map(|s| s.result.clone()).collect::<Vec<_>>(),
                steps.iter().map(|s| &s.solver).collect::<Vec<_>>(),
                (0..steps.len())
                    .map(|k| {
                        let prev = k.checked_sub(1).map(|p| &steps[p]);
                        alea_latin::large_sliding::step_origins(&steps[k], prev)
                    })
                    .collect::<Vec<_>>(),
            ),
        };
        let (Some(res), Some(&solver)) = (results.last(), solvers.last()) else {
            return Err(StudyError::Failed("no load step ran".into()));
        };
        let view = study.steps.as_ref().map(|plan| {
            crate::cycle::HistoryView::new(plan.steps.len(), plan.cycle.as_ref(), results.len())
        });
        let qois = study
            .qois
            .iter()
            .map(|q| {
                let v = view.as_ref();
                crate::steps::eval_qoi(q, &solvers, &results, &origins, v, &point_sides)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut status = match (res.status, solver.equilibrium_report(res)) {
            (RunStatus::NoEquilibrium, Some(why)) => format!("no equilibrium: {why}"),
            (st, _) => st.label().to_string(),
        };
        if let Some(plan) = &study.steps
            && res.status != RunStatus::Converged
        {
            status = crate::steps::history_status(plan, &results, solver, status);
        }
        // The state later runs start from: that of the first step (every later step starts
        // from its own run's previous step). None with large sliding: the runs' pairings
        // differ (an empty state is no warm-start source, and each step starts from its
        // predicted configuration).
        let state = if repaired {
            Vec::new()
        } else {
            results[0].end_state().to_vec()
        };
        let slide = largest_slide(&results, &solvers);
        let rec = RunRecord {
            slide,
            params: theta.to_vec(),
            status,
            iterations: results.iter().map(|r| r.iterations).sum(),
            residual: res
                .residuals
                .last()
                .copied()
                .filter(|v| v.is_finite())
                .unwrap_or(f64::MAX),
            seconds: results.iter().map(|r| r.timings.total).sum(),
            qois: qois
                .iter()
                .map(|&v| if v.is_finite() { v } else { f64::NAN })
                .collect(),
            history: results
                .iter()
                .flat_map(|r| &r.residuals)
                .map(|v| if v.is_finite() { *v } else { f64::MAX })
                .collect(),
            state,
        };
        if rec.qois.iter().any(|v| v.is_nan()) && rec.converged() {
            return Err(StudyError::NonFiniteQoi {
                theta: theta.to_vec(),
            });
        }
        let (cre, estimate_seconds) = match (self.cre, rec.converged()) {
            (Some(setup), true) => {
                let c = setup.estimate_run(study, self.solver, theta, res)?;
                let s = c.seconds;
                (Some(c.to_values()), s)
            }
            _ => (None, 0.0),
        };
        let fields: Vec<f64> = res.displacements.iter().flatten().copied().collect();
        if self.files && study.output.vtu.unwrap_or(false) {
            let stem = run_file_stem(theta);
            match &study.steps {
                None => {
                    let path = self.dir.join("vtu").join(format!("{stem}.vtm"));
                    alea_latin::output::write_run(&path, solver, res)?;
                }
                Some(plan) => {
                    for (k, r) in results.iter().enumerate() {
                        let name = format!("{stem}-{}-{}.vtm", k + 1, plan.steps[k].name);
                        let path = self.dir.join("vtu").join(name);
                        alea_latin::output::write_step(
                            path,
                            solvers[k],
                            r,
                            None,
                            Some(&origins[k]),
                        )?;
                    }
                }
            }
        }
        Ok(RunOutcome {
            rec,
            fields,
            cre,
            estimate_seconds,
        })
    }
}

/// The solver results of one run's steps.
enum StepRuns<'s> {
    /// On the solver of the study (and of its steps' imposed values): the pairing of the
    /// initial configuration.
    Paired(Vec<alea_latin::RunResult>),
    /// With large sliding: each step on the solver of its last pairing.
    Repaired(&'s [alea_latin::large_sliding::SlidingStep]),
}

/// The largest slide over the local mesh size of a run's steps, on any contact interface
/// (`alea_latin::sliding`), named by its interface; `None` without a contact interface.
fn largest_slide(
    results: &[alea_latin::RunResult],
    solvers: &[&LatinSolver],
) -> Option<crate::store::RunSlide> {
    results
        .iter()
        .zip(solvers)
        .flat_map(|(r, s)| {
            alea_latin::sliding::slide_checks(s, r)
                .into_iter()
                .map(move |c| (r.interfaces[c.interface].name.clone(), c))
        })
        .max_by(|a, b| a.1.ratio.total_cmp(&b.1.ratio))
        .map(|(interface, c)| crate::store::RunSlide {
            interface,
            slip: c.slip,
            ratio: c.ratio,
        })
}

/// Solves the pending runs of one batch. Every run of a batch is independent of the others
/// (they start from runs of earlier generations only), so an executor may solve them in any order,
/// on any thread or process: the outcomes do not change.
pub trait BatchExecutor: Sync {
    /// Solves every job and hands the outcomes to `commit` as they finish, a group of runs
    /// solved together at once (committed together: one synced store commit per group), from
    /// any thread, in any order. Returns the first error (in job order for the local
    /// executor); runs that finished before an error are committed all the same.
    fn execute(
        &self,
        ctx: &RunContext<'_>,
        jobs: &[RunJob],
        commit: &(dyn Fn(Vec<RunOutcome>) -> Result<(), StudyError> + Sync),
    ) -> Result<(), StudyError>;
}

/// Runs solved together by the single-process executor ([`RunContext::solve_batch`]): the
/// runs of a generation in consecutive groups of this many (fixed, whatever the thread count).
pub const RUNS_PER_BATCH: usize = 8;

/// The single-process executor: the runs of a generation in groups of [`RUNS_PER_BATCH`]
/// solved together, the groups in parallel on the rayon pool.
pub struct LocalExecutor;

impl BatchExecutor for LocalExecutor {
    fn execute(
        &self,
        ctx: &RunContext<'_>,
        jobs: &[RunJob],
        commit: &(dyn Fn(Vec<RunOutcome>) -> Result<(), StudyError> + Sync),
    ) -> Result<(), StudyError> {
        let results: Vec<Result<(), StudyError>> = jobs
            .par_chunks(RUNS_PER_BATCH)
            .flat_map_iter(|group| {
                // Asked to stop: no new group starts (the groups under way finish and commit).
                if (ctx.stop)() {
                    return vec![Err(StudyError::Interrupted)];
                }
                // The group's finished runs are committed together, the failed ones reported.
                let mut done = Vec::with_capacity(group.len());
                let mut results: Vec<Result<(), StudyError>> = Vec::new();
                for out in ctx.solve_batch(group) {
                    match out {
                        Ok(o) => done.push(o),
                        Err(e) => results.push(Err(e)),
                    }
                }
                results.insert(0, commit(done));
                results
            })
            .collect();
        results.into_iter().collect()
    }
}

static RANKS: std::sync::OnceLock<Arc<dyn alea_latin::RankExchange>> = std::sync::OnceLock::new();

/// Installs the ranks the study's runs are spread over ([`RunSetup::build_for_runs`]; the MPI
/// launch installs its group's, `crate::distributed`). Returns false if some were installed
/// already.
pub fn install_rank_exchange(ranks: Arc<dyn alea_latin::RankExchange>) -> bool {
    RANKS.set(ranks).is_ok()
}

static EXECUTOR: std::sync::OnceLock<Box<dyn BatchExecutor + Send>> = std::sync::OnceLock::new();

/// Installs the executor `run_study` uses in this process (the binary installs the MPI one
/// when it runs under `mpirun`). Returns false if one was installed already.
pub fn install_executor(exec: Box<dyn BatchExecutor + Send>) -> bool {
    EXECUTOR.set(exec).is_ok()
}

/// The executor of this process: the installed one, else [`LocalExecutor`].
pub(crate) fn executor() -> &'static dyn BatchExecutor {
    match EXECUTOR.get() {
        Some(e) => e.as_ref(),
        None => &LocalExecutor,
    }
}
