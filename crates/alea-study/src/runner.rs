//! Running a study's deterministic solves.
//!
//! The union of all methods' design points is run once (points shared by several methods are
//! run once). Runs go through one multiresolution [`LatinSolver`] (set-up and factorisations
//! shared) in **batches of a fixed schedule** (sizes 1, 2, 4, then 8): the runs of a batch are
//! solved in parallel, each warm-started from the nearest converged run of the earlier batches
//! (distance in the parameter box scaled to the unit cube). The schedule depends only on the
//! design, never on the thread count, the number of MPI ranks or on what a previous,
//! interrupted invocation finished, so results are identical with 1 or 2 threads, 1 or 3 ranks
//! and after a resume. Points are ordered by a greedy nearest-neighbour walk from the nominal
//! point, so each batch starts near finished runs. The walk and the warm-start lookup use a
//! kd-tree ([`crate::spatial`]): `O(n log n)` for `n` runs, with exactly the brute-force
//! answers (ties to the earliest point).
//!
//! A batch's runs are independent of each other, so a [`BatchExecutor`] may solve them
//! anywhere: [`LocalExecutor`] on the rayon pool, the MPI executor (feature `mpi`,
//! the `distributed` module) on other ranks. Each finished run is committed to the [`Store`] at
//! once, by this process only; `run_study` on a directory that already holds runs skips them (a
//! resume) and loads their local-stage states for the warm starts.

use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use alea_latin::{LatinSolver, LocalState};
use rayon::prelude::*;

use crate::StudyError;
use crate::cre::CreSetup;
use crate::lock::StudyLock;
use crate::method::MethodKind;
use crate::run::executor;
pub use crate::run::{
    BatchExecutor, LocalExecutor, RunContext, RunJob, RunOutcome, RunSetup, install_executor,
};
pub use crate::runs::StudyRuns;
use crate::spatial::KdTree;
use crate::spatial::nn_order;
use crate::store::{RunRecord, Store, point_key};
pub use crate::study::{Study, estimates_error};

/// Observer of a running study (progress bars live in the binary).
pub trait Progress: Sync {
    /// The study has `total` runs, `done` of which are already in the store.
    fn begin(&self, _total: usize, _done: usize) {}
    /// A run finished (converged or not).
    fn finished(&self, _rec: &RunRecord) {}
    /// `n` more runs were added to the study (an adaptive step).
    fn more(&self, _n: usize) {}
    /// All runs are done.
    fn end(&self) {}
    /// Something the user should know (e.g. a lock taken over from a dead process).
    fn note(&self, _message: &str) {}
}

/// A progress observer that does nothing.
pub struct NoProgress;
impl Progress for NoProgress {}

/// The batches of the fixed schedule: indices into the ordered points.
fn schedule(n: usize) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut size = 1;
    while start < n {
        let end = (start + size).min(n);
        out.push(start..end);
        start = end;
        size = (size * 2).min(8);
    }
    out
}

/// The plan of a fresh study over `points` (all runs assumed to converge): the points in run
/// order with, for each, the position in that order of the run it warm-starts from. What
/// [`run_study`] computes before and between its batches, without solving anything (for
/// benchmarks and checks).
pub fn warm_start_plan(study: &Study, points: &[Vec<f64>]) -> Vec<(usize, Option<usize>)> {
    let normalised: Vec<Vec<f64>> = points.iter().map(|p| study.normalise(p)).collect();
    let centre = study.normalise(&study.params.nominal);
    let order = nn_order(&normalised, &centre);
    let refs: Vec<&[f64]> = order.iter().map(|&i| normalised[i].as_slice()).collect();
    let mut sources = KdTree::new(centre.len(), &refs);
    let mut plan = Vec::with_capacity(order.len());
    for batch in schedule(order.len()) {
        for j in batch.clone() {
            plan.push((
                order[j],
                sources.nearest(&normalised[order[j]]).map(|(_, k)| k),
            ));
        }
        for j in batch {
            sources.set_live(j, true);
        }
    }
    plan
}

/// Runs the deterministic solves of a study and keeps the state they share: the solver, the
/// store, the finished runs (warm-start sources, in completion order of the fixed schedule).
pub(crate) struct Runner<'a> {
    pub(crate) study: &'a Study,
    pub(crate) dir: &'a Path,
    store: Mutex<Store>,
    pub(crate) solver: Arc<LatinSolver>,
    pub(crate) by_key: HashMap<String, RunRecord>,
    /// Points finished by this invocation (run or found in the store), in schedule order.
    finished: Vec<Vec<f64>>,
    finished_keys: HashSet<String>,
    /// Warm-start states of the finished runs (decoded once, on first use).
    states: Vec<Option<Arc<LocalState>>>,
    sizes: Vec<usize>,
    progress: &'a dyn Progress,
    exec: &'a dyn BatchExecutor,
    pub(crate) cre: Option<Arc<CreSetup>>,
    /// Compute missing runs (`false`: replay from the store only, counting missing runs).
    compute: bool,
    /// Points without a run in the store (replay only).
    pub(crate) missing: usize,
    pub(crate) computed: usize,
    pub(crate) resumed: usize,
    pub(crate) solve_seconds: f64,
    pub(crate) estimate_seconds: f64,
}

impl<'a> Runner<'a> {
    /// Runs (or finds in the store) every point of `points` that is not finished yet, in
    /// batches of the fixed schedule, each warm-started from the nearest converged run of the
    /// earlier batches.
    pub(crate) fn run_points(&mut self, points: &[Vec<f64>]) -> Result<(), StudyError> {
        let study = self.study;
        let mut seen = HashSet::new();
        let todo: Vec<Vec<f64>> = points
            .iter()
            .filter(|p| {
                let k = point_key(p);
                !self.finished_keys.contains(&k) && seen.insert(k)
            })
            .cloned()
            .collect();
        let check: Vec<Result<(), StudyError>> = todo
            .par_iter()
            .map(|p| study.check_point(&self.solver, p))
            .collect();
        check.into_iter().collect::<Result<(), _>>()?;
        let normalised: Vec<Vec<f64>> = todo.iter().map(|p| study.normalise(p)).collect();
        let centre = study.normalise(&study.params.nominal);
        let order = nn_order(&normalised, &centre);
        // Warm-start sources: the finished runs so far, then this call's in schedule order (tree
        // index = position in `finished`, so ties go to the earliest finished, as before);
        // a source is live once its batch is over and it converged.
        let prior = self.finished.len();
        let prior_norm: Vec<Vec<f64>> = self.finished.iter().map(|p| study.normalise(p)).collect();
        let refs: Vec<&[f64]> = prior_norm
            .iter()
            .map(|p| p.as_slice())
            .chain(order.iter().map(|&i| normalised[i].as_slice()))
            .collect();
        let mut sources = KdTree::new(centre.len(), &refs);
        for (k, p) in self.finished.iter().enumerate() {
            if self
                .by_key
                .get(&point_key(p))
                .is_some_and(|r| r.converged())
            {
                sources.set_live(k, true);
            }
        }
        let t0 = Instant::now();
        let (solver, cre) = (self.solver.clone(), self.cre.clone());
        let ctx = RunContext {
            study,
            solver: &solver,
            cre: cre.as_deref(),
            dir: self.dir,
        };
        for batch in schedule(order.len()) {
            let members: Vec<usize> = order[batch.clone()].to_vec();
            let mut pending: Vec<usize> = members
                .iter()
                .copied()
                .filter(|&i| !self.by_key.contains_key(&point_key(&todo[i])))
                .collect();
            self.resumed += members.len() - pending.len();
            if !self.compute {
                self.missing += pending.len();
                pending.clear();
            }
            let mut jobs = Vec::with_capacity(pending.len());
            for &i in &pending {
                let start = match sources.nearest(&normalised[i]) {
                    Some((_, k)) => self.state_of(k)?,
                    None => None,
                };
                jobs.push(RunJob {
                    theta: todo[i].clone(),
                    start,
                });
            }
            let done: Mutex<Vec<(RunRecord, f64)>> = Mutex::new(Vec::with_capacity(jobs.len()));
            let store = &self.store;
            let progress = self.progress;
            let commit = |out: RunOutcome| -> Result<(), StudyError> {
                store
                    .lock()
                    .map_err(|_| StudyError::Poisoned("store"))?
                    .commit(&out.rec, &out.fields, out.cre.as_deref())?;
                progress.finished(&out.rec);
                done.lock()
                    .map_err(|_| StudyError::Poisoned("run list"))?
                    .push((out.rec, out.estimate_seconds));
                Ok(())
            };
            let result = self.exec.execute(&ctx, &jobs, &commit);
            // Whatever finished is committed: keep it even when a run failed.
            for (rec, est) in done
                .into_inner()
                .map_err(|_| StudyError::Poisoned("run list"))?
            {
                self.computed += 1;
                self.estimate_seconds += est;
                self.by_key.insert(point_key(&rec.params), rec);
            }
            result?;
            for (j, &i) in members.iter().enumerate() {
                let k = prior + batch.start + j;
                self.finished.push(todo[i].clone());
                self.finished_keys.insert(point_key(&todo[i]));
                self.states.push(None);
                if self
                    .by_key
                    .get(&point_key(&todo[i]))
                    .is_some_and(|r| r.converged())
                {
                    sources.set_live(k, true);
                }
            }
        }
        self.solve_seconds += t0.elapsed().as_secs_f64();
        Ok(())
    }

    /// The warm-start state of the `k`-th finished run (decoded from its record once).
    fn state_of(&mut self, k: usize) -> Result<Option<Arc<LocalState>>, StudyError> {
        if self.states[k].is_none() {
            let rec = self
                .by_key
                .get(&point_key(&self.finished[k]))
                .ok_or_else(|| StudyError::Internal("a finished run is missing".into()))?;
            self.states[k] = LocalState::from_slice(&self.sizes, &rec.state).map(Arc::new);
        }
        Ok(self.states[k].clone())
    }

    /// The store (locked).
    pub(crate) fn store(&self) -> Result<std::sync::MutexGuard<'_, Store>, StudyError> {
        self.store.lock().map_err(|_| StudyError::Poisoned("store"))
    }

    /// Tells the progress observer about runs added by an adaptive step.
    pub(crate) fn announce(&self, more: usize) {
        self.progress.more(more);
    }
}

impl<'a> crate::adaptive::AdaptiveRuns<'a> for Runner<'a> {
    fn study(&self) -> &'a Study {
        self.study
    }
    fn cre(&self) -> Option<Arc<CreSetup>> {
        self.cre.clone()
    }
    fn solver(&self) -> &LatinSolver {
        &self.solver
    }
    fn by_key(&self) -> &HashMap<String, RunRecord> {
        &self.by_key
    }
    fn solve_seconds(&self) -> f64 {
        self.solve_seconds
    }
    fn estimate_seconds(&self) -> f64 {
        self.estimate_seconds
    }
    fn run_points(&mut self, points: &[Vec<f64>]) -> Result<(), StudyError> {
        Runner::run_points(self, points)
    }
    fn store(&self) -> Result<std::sync::MutexGuard<'_, Store>, StudyError> {
        Runner::store(self)
    }
    fn announce(&self, more: usize) {
        Runner::announce(self, more);
    }
}

/// Runs (or resumes) every design point of `study` in the study directory `dir`, then the
/// adaptive methods' loops.
pub fn run_study(
    study: &Study,
    dir: &Path,
    restart: bool,
    progress: &dyn Progress,
) -> Result<StudyRuns, StudyError> {
    let lock = StudyLock::acquire(dir, &format!("alea run {}", study.source.path.display()))?;
    if let Some(previous) = lock.previous() {
        progress.note(&format!(
            "took over the lock of {} left by {previous}, which is no longer running",
            dir.display()
        ));
    }
    execute(study, dir, restart, progress, lock, true).map(|(runs, _)| runs)
}

/// Runs a study (`compute`) or replays it from the store alone (`!compute`: runs missing from
/// the store are counted, not computed, and an adaptive loop stops at the first missing run).
/// Returns the runs and the number of missing ones.
pub(crate) fn execute(
    study: &Study,
    dir: &Path,
    restart: bool,
    progress: &dyn Progress,
    lock: StudyLock,
    compute: bool,
) -> Result<(StudyRuns, usize), StudyError> {
    let store = Store::open(dir, &study.hash, restart)?;
    store.save_study(&study.source.path, &study.source.text)?;
    let note = |m: &str| progress.note(m);
    let previous = crate::integrity::usable_runs(study, &store, store.runs()?, compute, &note);
    let by_key: HashMap<String, RunRecord> = previous
        .into_iter()
        .map(|r| (point_key(&r.params), r))
        .collect();
    let RunSetup { solver, cre } = RunSetup::build(study)?;
    let fixed: Vec<Vec<f64>> = {
        let mut seen = std::collections::HashSet::new();
        study
            .methods
            .iter()
            .filter(|m| !matches!(m.kind, MethodKind::Adaptive(_)))
            .flat_map(|m| m.points.iter())
            .filter(|p| seen.insert(point_key(p)))
            .cloned()
            .collect()
    };
    let adaptive_start: usize = study
        .methods
        .iter()
        .filter(|m| matches!(m.kind, MethodKind::Adaptive(_)))
        .map(|m| m.points.len())
        .sum();
    let done_before = fixed
        .iter()
        .filter(|p| by_key.contains_key(&point_key(p)))
        .count();
    progress.begin(fixed.len() + adaptive_start, done_before);
    let mut runner = Runner {
        study,
        dir,
        store: Mutex::new(store),
        sizes: solver.interface_sizes(),
        solver,
        by_key,
        finished: Vec::new(),
        finished_keys: HashSet::new(),
        states: Vec::new(),
        progress,
        exec: executor(),
        cre,
        compute,
        missing: 0,
        computed: 0,
        resumed: 0,
        solve_seconds: 0.0,
        estimate_seconds: 0.0,
    };
    runner.run_points(&fixed)?;
    let mut methods = study.methods.clone();
    let mut adaptive = Vec::new();
    for (m, method) in methods.iter_mut().enumerate() {
        if let MethodKind::Adaptive(settings) = method.kind {
            let outcome = crate::adaptive::run_adaptive(&mut runner, m, &settings)?;
            method.points = (0..outcome.mesh.num_runs())
                .map(|r| outcome.mesh.run_point(r).to_vec())
                .collect();
            method.mesh = Some(outcome.mesh.clone());
            method.coarse_mesh = Some(outcome.coarse_mesh.clone());
            adaptive.push(outcome);
        }
    }
    progress.end();
    let mut order: Vec<Vec<f64>> = fixed;
    let mut seen: std::collections::HashSet<String> = order.iter().map(|p| point_key(p)).collect();
    for m in &methods {
        if matches!(m.kind, MethodKind::Adaptive(_)) {
            order.extend(
                m.points
                    .iter()
                    .filter(|p| seen.insert(point_key(p)))
                    .cloned(),
            );
        }
    }
    let records: Vec<RunRecord> = order
        .iter()
        .filter_map(|p| runner.by_key.get(&point_key(p)).cloned())
        .collect();
    if compute && records.len() != order.len() {
        return Err(StudyError::Internal("a run is missing".into()));
    }
    let missing = runner.missing;
    Ok((
        StudyRuns {
            records,
            computed: runner.computed,
            resumed: runner.resumed,
            setup_seconds: runner.solver.setup_seconds,
            solve_seconds: runner.solve_seconds,
            estimate_seconds: runner.estimate_seconds,
            solver: runner.solver.clone(),
            methods,
            adaptive,
            cre: runner.cre.clone(),
            lock,
        },
        missing,
    ))
}
