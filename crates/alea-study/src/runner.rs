//! Running a study's deterministic solves.
//!
//! The union of all methods' design points is run once (points shared by several methods are
//! run once). Runs go through one multiresolution [`LatinSolver`] (set-up and factorisations
//! shared) **generation by generation** of the schedule of [`crate::schedule`]: a tree grown
//! from the nominal point over the design, coarse to fine, generation `k` holding up to `2^k`
//! runs. The runs of a generation are solved in parallel, each warm-started from the interface
//! fields of its nearest converged runs of the earlier generations interpolated at its point
//! (moving least-squares weights, distances in the parameter box scaled to the unit cube). The
//! generations and the parents depend only on the design, never on the thread count, the number
//! of MPI ranks or on what a previous, interrupted invocation finished, so results are
//! identical with 1 or 2 threads, 1 or 3 ranks and after a resume. The parent look-up uses a
//! kd-tree ([`crate::spatial`]): `O(n log n)` for `n` runs, with exactly the brute-force
//! answers (ties to the earliest point).
//!
//! A generation's runs are independent of each other, so a [`BatchExecutor`] may solve them
//! anywhere, in the fixed groups of [`crate::solve::RUNS_PER_BATCH`] consecutive runs that share
//! their LATIN iterations' triangular solves ([`alea_latin::LatinSolver::run_batch`]):
//! [`LocalExecutor`] on the rayon pool, the MPI executor (feature `mpi`,
//! the `distributed` module) on other ranks. Each finished group of runs is committed to the
//! [`Store`] at once, by this process only (one synced transaction; groups finished while
//! another group's commit is syncing are committed together by the next one, their solver
//! thread going on meanwhile); `run_study` on a directory that already holds runs skips them (a
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
use crate::points::{PointIndex, canonicalise};
use crate::schedule::{combine, generations, parents};
use crate::solve::executor;
pub use crate::solve::{
    BatchExecutor, LocalExecutor, RunContext, RunJob, RunOutcome, RunSetup, install_executor,
};
use crate::spatial::KdTree;
use crate::store::{RunRecord, Store, point_key};
pub use crate::study::{Study, estimates_error};
pub use crate::study_runs::StudyRuns;

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
    /// Whether the user asked to stop (Ctrl-C in the Python package). Polled from the solver
    /// threads before each group of runs: once true, no further group starts, the groups under
    /// way finish and are committed, and [`run_study`] returns [`StudyError::Interrupted`]; a
    /// new invocation resumes from the committed runs. The MPI executor does not poll it.
    fn stop_requested(&self) -> bool {
        false
    }
}

/// A progress observer that does nothing.
pub struct NoProgress;
impl Progress for NoProgress {}

/// Runs handed to the executor at once (a generation may hold half the design).
const JOBS_PER_CALL: usize = 256;

/// One generation of a plan: `(point, parents)` with the parents as `(position in the plan's
/// run order, weight)`.
pub type PlannedGeneration = Vec<(usize, Vec<(usize, f64)>)>;

/// The plan of a fresh study over `points` (all runs assumed to converge): its generations
/// ([`crate::schedule`]), each a list of the points it solves with their warm-start parents
/// (positions in the run order: generation by generation) and weights. What [`run_study`]
/// computes before and between its batches, without solving anything (for benchmarks and
/// checks: the generations' sizes are the study's parallel width, their number its critical
/// path).
pub fn warm_start_plan(study: &Study, points: &[Vec<f64>]) -> Vec<PlannedGeneration> {
    let normalised: Vec<Vec<f64>> = points.iter().map(|p| study.normalise(p)).collect();
    let centre = study.normalise(&study.params.nominal);
    let gens = generations(&normalised, &centre);
    let refs: Vec<&[f64]> = gens
        .iter()
        .flatten()
        .map(|&i| normalised[i].as_slice())
        .collect();
    let mut sources = KdTree::new(centre.len(), &refs);
    let mut plan = Vec::with_capacity(gens.len());
    let mut at = 0;
    for generation in &gens {
        plan.push(
            generation
                .iter()
                .map(|&i| (i, parents(&sources, &refs, &normalised[i])))
                .collect(),
        );
        for k in at..at + generation.len() {
            sources.set_live(k, true);
        }
        at += generation.len();
    }
    plan
}

/// Runs the deterministic solves of a study and keeps the state they share: the solver, the
/// store, the finished runs (warm-start sources, in the order of the schedule's generations).
pub(crate) struct Runner<'a> {
    pub(crate) study: &'a Study,
    pub(crate) dir: &'a Path,
    store: Mutex<Store>,
    pub(crate) solver: Arc<LatinSolver>,
    pub(crate) by_key: HashMap<String, RunRecord>,
    /// Points finished by this invocation (run or found in the store), in schedule order.
    finished: Vec<Vec<f64>>,
    finished_keys: HashSet<String>,
    /// Points per interface (the shape of a warm-start state).
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
    /// A run slid beyond small sliding and the user was told (once per invocation, as it
    /// happens; the outputs' notes count them all, `crate::sliding_note`).
    slide_noted: std::sync::atomic::AtomicBool,
}

impl<'a> Runner<'a> {
    /// Opens the study directory's store (`restart`: discarding a previous version's runs),
    /// keeps its usable runs (module `integrity`) and builds the solver once; with the index of
    /// the stored runs' points, canonical in the order they were stored (a point within
    /// round-off of a stored run is that run, module `points`).
    pub(crate) fn open(
        study: &'a Study,
        dir: &'a Path,
        restart: bool,
        progress: &'a dyn Progress,
        compute: bool,
    ) -> Result<(Self, PointIndex), StudyError> {
        let store = Store::open_study(dir, &study.hash, study.identity.keys(), restart)?;
        store.save_study(&study.source.path, &study.source.text)?;
        let note = |m: &str| progress.note(m);
        // Warm-start states are read only by a runner that solves.
        let stored = match compute {
            true => store.runs()?,
            false => store.runs_without_states()?,
        };
        let previous = crate::integrity::usable_runs(study, &store, stored, compute, &note);
        let mut index = PointIndex::new(&study.params.lo, &study.params.hi);
        for r in &previous {
            index.insert(&r.params);
        }
        let by_key: HashMap<String, RunRecord> = previous
            .into_iter()
            .map(|r| (point_key(&r.params), r))
            .collect();
        let RunSetup { solver, cre } = RunSetup::build_for_runs(study)?;
        let runner = Runner {
            study,
            dir,
            store: Mutex::new(store),
            sizes: solver.interface_sizes(),
            solver,
            by_key,
            finished: Vec::new(),
            finished_keys: HashSet::new(),
            progress,
            exec: executor(),
            cre,
            compute,
            missing: 0,
            computed: 0,
            resumed: 0,
            solve_seconds: 0.0,
            estimate_seconds: 0.0,
            slide_noted: std::sync::atomic::AtomicBool::new(false),
        };
        Ok((runner, index))
    }

    /// Runs (or finds in the store) every point of `points` that is not finished yet, one
    /// generation of the schedule after the other, each run warm-started from its parents among
    /// the converged runs of the earlier generations and calls ([`crate::schedule`]).
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
        let gens = generations(&normalised, &centre);
        // Warm-start sources: the finished runs so far, then this call's generation by
        // generation (tree index = position in `finished`); a source is live once its
        // generation is over and it converged.
        let prior_norm: Vec<Vec<f64>> = self.finished.iter().map(|p| study.normalise(p)).collect();
        let refs: Vec<&[f64]> = prior_norm
            .iter()
            .map(|p| p.as_slice())
            .chain(gens.iter().flatten().map(|&i| normalised[i].as_slice()))
            .collect();
        let mut sources = KdTree::new(centre.len(), &refs);
        for k in 0..self.finished.len() {
            if self.is_source(&self.finished[k]) {
                sources.set_live(k, true);
            }
        }
        let t0 = Instant::now();
        let (solver, cre) = (self.solver.clone(), self.cre.clone());
        let progress = self.progress;
        let stop = || progress.stop_requested();
        let ctx = RunContext {
            study,
            solver: &solver,
            cre: cre.as_deref(),
            dir: self.dir,
            stop: &stop,
            files: true,
        };
        for members in &gens {
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
            // The runs of a generation start from earlier generations only: they go to the
            // executor in chunks (memory of the start states bounded), which changes nothing.
            for chunk in pending.chunks(JOBS_PER_CALL) {
                self.run_chunk(&ctx, chunk, &todo, &normalised, &sources, &refs)?;
            }
            for &i in members {
                let k = self.finished.len();
                self.finished.push(todo[i].clone());
                self.finished_keys.insert(point_key(&todo[i]));
                if self.is_source(&todo[i]) {
                    sources.set_live(k, true);
                }
            }
        }
        self.solve_seconds += t0.elapsed().as_secs_f64();
        Ok(())
    }

    /// Solves the runs `chunk` (indices into `todo`) of one generation, warm-started from
    /// their parents among the live `sources`, and commits each as it finishes.
    fn run_chunk(
        &mut self,
        ctx: &RunContext<'_>,
        chunk: &[usize],
        todo: &[Vec<f64>],
        normalised: &[Vec<f64>],
        sources: &KdTree,
        refs: &[&[f64]],
    ) -> Result<(), StudyError> {
        let mut jobs = Vec::with_capacity(chunk.len());
        for &i in chunk {
            let start = self.start_state(&parents(sources, refs, &normalised[i]))?;
            jobs.push(RunJob {
                theta: todo[i].clone(),
                start,
            });
        }
        let done: Mutex<Vec<(RunRecord, f64)>> = Mutex::new(Vec::with_capacity(jobs.len()));
        let store = &self.store;
        let progress = self.progress;
        let slide_noted = &self.slide_noted;
        let note_committed = |out: RunOutcome| -> Result<(), StudyError> {
            progress.finished(&out.rec);
            if let Some(c) = &out.rec.slide
                && c.ratio > alea_latin::sliding::SMALL_SLIDING_LIMIT
                && !slide_noted.swap(true, std::sync::atomic::Ordering::Relaxed)
            {
                progress.note(&format!(
                    "warning: the run at {:?} slid by {:.4e} on interface '{}', {:.2} x the local \
                     mesh size: beyond small sliding (> {} x), its contact zone, gap and pressure \
                     may be wrong (the runs beyond small sliding are counted in the notes of the \
                     outputs)",
                    out.rec.params,
                    c.slip,
                    c.interface,
                    c.ratio,
                    alea_latin::sliding::SMALL_SLIDING_LIMIT
                ));
            }
            done.lock()
                .map_err(|_| StudyError::Poisoned("run list"))?
                .push((out.rec, out.estimate_seconds));
            Ok(())
        };
        // Groups finished while another group's commit is being synced wait here, and are
        // committed together by the next commit (or by the flush after the executor): one
        // synced transaction for all of them, and the solver thread that finished them goes on
        // solving instead of waiting for the disk. A run is noted (finished, warm-start source)
        // only once its transaction is committed.
        let pending: Mutex<Vec<RunOutcome>> = Mutex::new(Vec::new());
        let commit_pending = |store: &Store| -> Result<(), StudyError> {
            let outs = std::mem::take(
                &mut *pending
                    .lock()
                    .map_err(|_| StudyError::Poisoned("pending runs"))?,
            );
            if outs.is_empty() {
                return Ok(());
            }
            let group: Vec<crate::store::RunToCommit<'_>> = outs
                .iter()
                .map(|o| (&o.rec, o.fields.as_slice(), o.cre.as_deref()))
                .collect();
            store.commit_group(&group)?;
            for out in outs {
                note_committed(out)?;
            }
            Ok(())
        };
        let commit = |outs: Vec<RunOutcome>| -> Result<(), StudyError> {
            pending
                .lock()
                .map_err(|_| StudyError::Poisoned("pending runs"))?
                .extend(outs);
            match store.try_lock() {
                Ok(store) => commit_pending(&store),
                // Another thread is committing: it or the next commit takes these runs.
                Err(std::sync::TryLockError::WouldBlock) => Ok(()),
                Err(std::sync::TryLockError::Poisoned(_)) => Err(StudyError::Poisoned("store")),
            }
        };
        let mut result = self.exec.execute(ctx, &jobs, &commit);
        // The runs still waiting: committed now (also after a failed run: whatever finished
        // is kept).
        let flushed = store
            .lock()
            .map_err(|_| StudyError::Poisoned("store"))
            .and_then(|s| commit_pending(&s));
        if result.is_ok() {
            result = flushed;
        }
        // Whatever finished is committed: keep it even when a run failed.
        for (rec, est) in done
            .into_inner()
            .map_err(|_| StudyError::Poisoned("run list"))?
        {
            self.computed += 1;
            self.estimate_seconds += est;
            self.by_key.insert(point_key(&rec.params), rec);
        }
        result
    }

    /// Whether the run at `p` is a warm-start source: finished, converged, with a state of
    /// this solver's shape.
    fn is_source(&self, p: &[f64]) -> bool {
        let len: usize = self.sizes.iter().map(|n| 12 * n).sum();
        self.by_key
            .get(&point_key(p))
            .is_some_and(|r| r.converged() && r.state.len() == len)
    }

    /// The warm-start state interpolated from `parents` (`(finished index, weight)`; `None`:
    /// cold start).
    fn start_state(&self, parents: &[(usize, f64)]) -> Result<Option<Arc<LocalState>>, StudyError> {
        let mut states = Vec::with_capacity(parents.len());
        for &(k, w) in parents {
            let rec = self
                .by_key
                .get(&point_key(&self.finished[k]))
                .ok_or_else(|| StudyError::Internal("a finished run is missing".into()))?;
            states.push((rec.state.as_slice(), w));
        }
        if states.is_empty() {
            return Ok(None);
        }
        Ok(LocalState::from_slice(&self.sizes, &combine(&states)).map(Arc::new))
    }

    /// The store (locked).
    pub(crate) fn store(&self) -> Result<std::sync::MutexGuard<'_, Store>, StudyError> {
        self.store.lock().map_err(|_| StudyError::Poisoned("store"))
    }

    /// Tells the progress observer about runs added by an adaptive step.
    pub(crate) fn announce(&self, more: usize) {
        self.progress.more(more);
    }

    /// The paired solves of the budget's mesh and sliding parts (module `paired_runs`): the
    /// missing ones solved (when computing: a replay solves none), then every part's check read
    /// from the store.
    fn paired_solves(&mut self) -> Result<crate::paired_runs::PairedSolves, StudyError> {
        let study = self.study;
        let mut out = crate::paired_runs::PairedSolves::default();
        if crate::paired_runs::count(study) == 0 {
            return Ok(out);
        }
        if self.compute {
            let progress = self.progress;
            let finished = |r: &RunRecord| progress.finished(r);
            let stop = || progress.stop_requested();
            let (computed, resumed, seconds) =
                crate::paired_runs::run(study, &self.store, &self.solver, &finished, &stop)?;
            (out.computed, out.resumed, out.seconds) = (computed, resumed, seconds);
        }
        (out.mesh, out.sliding) = crate::paired_runs::read(study, &*self.store()?)?;
        Ok(out)
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
    let (mut runner, mut index) = Runner::open(study, dir, restart, progress, compute)?;
    let mut methods = study.methods.clone();
    canonicalise(
        &mut index,
        methods
            .iter_mut()
            .filter(|m| !matches!(m.kind, MethodKind::Adaptive(_)))
            .map(|m| &mut m.points),
    );
    let fixed: Vec<Vec<f64>> = {
        let mut seen = std::collections::HashSet::new();
        methods
            .iter()
            .filter(|m| !matches!(m.kind, MethodKind::Adaptive(_)))
            .flat_map(|m| m.points.iter())
            .filter(|p| seen.insert(point_key(p)))
            .cloned()
            .collect()
    };
    let validation_upfront = begin(
        study,
        &methods,
        &fixed,
        &runner.by_key,
        &*runner.store()?,
        progress,
    )?;
    runner.run_points(&fixed)?;
    crate::sparse::select_bases(study, &mut methods, &runner.by_key);
    let mut adaptive = Vec::new();
    for (m, method) in methods.iter_mut().enumerate() {
        if let MethodKind::Adaptive(settings) = method.kind.clone() {
            let outcome = crate::adaptive::run_adaptive(&mut runner, m, &settings)?;
            method.points = (0..outcome.mesh.num_runs())
                .map(|r| outcome.mesh.run_point(r).to_vec())
                .collect();
            method.mesh = Some(outcome.mesh.clone());
            adaptive.push(outcome);
        }
    }
    // Runs of the solver confirming surrogates' failure probabilities (`solver_runs`).
    let confirmation = {
        let by_key = &runner.by_key;
        let lookup = |p: &[f64]| by_key.get(&point_key(p));
        crate::reliability::solver::confirmation_points(study, &methods, &lookup)
    };
    if !confirmation.is_empty() {
        runner.announce(confirmation.len());
        runner.run_points(&confirmation)?;
    }
    // Validation runs of the surrogates' statistics (module `validation_runs`).
    let validation =
        crate::validation_runs::points(study, crate::validation_runs::count(study, &methods));
    let fresh = validation
        .iter()
        .skip(validation_upfront)
        .filter(|p| !runner.by_key.contains_key(&point_key(p)))
        .count();
    if fresh > 0 {
        runner.announce(fresh);
    }
    if !validation.is_empty() {
        // Stored ones are counted as resumed.
        runner.run_points(&validation)?;
    }
    let paired = runner.paired_solves()?;
    progress.end();
    let order = run_order(fixed, &methods, confirmation, validation);
    // The records move out of the runner (each holds its warm-start state: cloning them would
    // double the study's memory at its peak - 2.4 GB for 10 000 runs of the 2D turbine); a
    // point listed twice gets a copy of its first record.
    let mut by_key = std::mem::take(&mut runner.by_key);
    let mut placed: HashMap<String, usize> = HashMap::with_capacity(order.len());
    let mut records: Vec<RunRecord> = Vec::with_capacity(order.len());
    for p in &order {
        let key = point_key(p);
        if let Some(r) = by_key.remove(&key) {
            placed.insert(key, records.len());
            records.push(r);
        } else if let Some(&i) = placed.get(&key) {
            records.push(records[i].clone());
        }
    }
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
            paired,
            lock,
        },
        missing,
    ))
}

/// Tells `progress` how many runs the study has and how many of them are stored (`by_key`): the
/// fixed designs' runs, the adaptive methods' start designs, the validation runs when they are
/// known now (without an adaptive method) and the paired solves of the budget. Returns the
/// validation runs counted.
fn begin(
    study: &Study,
    methods: &[crate::method::Method],
    fixed: &[Vec<f64>],
    by_key: &HashMap<String, RunRecord>,
    store: &Store,
    progress: &dyn Progress,
) -> Result<usize, StudyError> {
    let adaptive_start: usize = study
        .methods
        .iter()
        .filter(|m| matches!(m.kind, MethodKind::Adaptive(_)))
        .map(|m| m.points.len())
        .sum();
    // Without an adaptive method the validation runs are known now: counted from the start.
    let validation_upfront = if adaptive_start == 0 {
        crate::validation_runs::count(study, methods)
    } else {
        0
    };
    let done_before = fixed
        .iter()
        .chain(&crate::validation_runs::points(study, validation_upfront))
        .filter(|p| by_key.contains_key(&point_key(p)))
        .count();
    // The paired solves of the budget's mesh and sliding parts (module `paired_runs`).
    let paired_total = crate::paired_runs::count(study);
    let paired_done = if paired_total > 0 {
        crate::paired_runs::settled(study, store)?
    } else {
        0
    };
    progress.begin(
        fixed.len() + adaptive_start + validation_upfront + paired_total,
        done_before + paired_done,
    );
    Ok(validation_upfront)
}

/// The order of a study's runs: the fixed designs' points, the adaptive methods' runs in the
/// order they were chosen, the confirmation runs, the validation runs (each point once).
fn run_order(
    fixed: Vec<Vec<f64>>,
    methods: &[crate::method::Method],
    confirmation: Vec<Vec<f64>>,
    validation: Vec<Vec<f64>>,
) -> Vec<Vec<f64>> {
    let mut order: Vec<Vec<f64>> = fixed;
    let mut seen: HashSet<String> = order.iter().map(|p| point_key(p)).collect();
    for m in methods {
        if matches!(m.kind, MethodKind::Adaptive(_)) {
            order.extend(
                m.points
                    .iter()
                    .filter(|p| seen.insert(point_key(p)))
                    .cloned(),
            );
        }
    }
    order.extend(
        confirmation
            .into_iter()
            .chain(validation)
            .filter(|p| seen.insert(point_key(p))),
    );
    order
}
