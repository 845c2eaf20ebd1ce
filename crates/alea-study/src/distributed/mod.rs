//! Studies over MPI ranks (feature `mpi`): `mpirun -np N alea run study.toml`.
//!
//! Every rank loads the study file and builds its solver (and the error estimator's set-up)
//! once, in the same order as a single process does ([`RunSetup::build`]), so every rank holds
//! bit-identical factorisations. Rank 0 (the *leader*) runs the study as a single process would
//! (the store, the schedule, the adaptive decisions, the analysis and every output
//! are its alone) except that the runs of each generation of the schedule go through
//! [`MpiExecutor`]: in the groups of [`RUNS_PER_BATCH`] consecutive runs that one process
//! solves together ([`RunContext::solve_batch`]: the LATIN runs of a group share their
//! triangular solves, so a run's result depends on its group), each group handed to whichever
//! rank has a free solver thread (the other ranks first, rank 0 last), each run with the
//! warm-start state it starts from. A rank sends back each run's store row, field data and
//! error-estimate data; rank 0 commits them as they arrive.
//!
//! **Same results for every rank count.** A run is a pure function of its group's points and
//! warm-start states (interpolated from converged runs of *earlier* generations), and the
//! generations and their warm starts depend only on the design ([`crate::runner`],
//! `schedule.rs`: the one schedule, for one process and for any number of ranks), and so do
//! the groups. Which rank solves a group, and when, changes nothing: `summary.json` is
//! byte-identical to a single-process run's.
//!
//! **Warm starts travel with the work.** A job carries its start state (`12 x` interface points
//! `f64`s); the alternative - every rank keeping every converged state - costs `N - 1` copies of
//! every state instead of one per remote run, and the state is small beside the run's fields
//! that come back anyway (measured in `BENCHMARKS.md`).
//!
//! **Failures.** A run that fails (or panics) on a rank is reported as `rank r failed on the
//! run at a = .., b = ..: <why>`; the runs in flight on the other ranks are finished and
//! committed first, so running the same command again resumes, with any rank count. A rank that
//! dies makes `mpirun` stop the job and name the rank; `<dir>/mpi-dispatch.log` lists which runs
//! each rank was given in each batch. Committed runs are never lost (see [`crate::store`]).
//!
//! **No busy waiting.** MPI is initialised with `Threading::Funneled`: only the main thread of a
//! rank calls MPI; its solver threads take jobs from a channel. The main thread polls with
//! non-blocking probes and sleeps between polls (20 us doubling to 1 ms), so an idle rank leaves
//! its core to the solver threads of the ranks it shares a node with. Sends are non-blocking and
//! drain incoming messages until they complete, so two ranks sending large messages to each
//! other never deadlock.
//!
//! Threads per rank: `--threads` if given, else the node's cores divided by the ranks on the
//! node (from `MPI_Comm_split_type(SHARED)`).
//!
//! **Ranks per run** (`[solver] ranks_per_run = R`, module `group`): the ranks form groups of
//! `R`, each solving one run spread over its ranks (each factorises only its substructures);
//! the groups' first ranks take the place of the ranks above, with one solver thread each.

mod dispatch;
mod group;
mod stats;
mod transport;
mod wire;

use std::collections::VecDeque;
use std::io::Write;
use std::path::Path;
use std::sync::{Arc, Mutex, mpsc};

use mpi::Threading;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;

use crate::StudyError;
use crate::solve::{BatchExecutor, RUNS_PER_BATCH, RunContext, RunJob, RunOutcome, RunSetup};
use crate::store::run_file_stem;
use crate::study::Study;
use group::Place;
pub use group::{MpiExchange, ranks_per_run};
pub use stats::Stats;
use transport::{Incoming, Nap, send, try_receive};

const TAG_READY: i32 = 11;
const TAG_JOB: i32 = 12;
const TAG_RESULT: i32 = 13;
const TAG_STOP: i32 = 14;

/// What this process is in an MPI job.
pub enum Role {
    /// Not started by an MPI launcher, or a job of one rank: run as usual.
    Single,
    /// Rank 0 of a job of several ranks.
    Leader(Leader),
    /// Any other rank.
    Worker(Worker),
}

/// True if an MPI launcher started this process (OpenMPI's `mpirun`, Hydra's `mpiexec`, Slurm's
/// `srun` with PMI or PMIx).
fn launched_by_mpi() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
}

/// Initialises MPI if an MPI launcher started this process, sizes the rayon pool of this rank
/// (`threads`, else the node's cores over the ranks on the node) and says what this process is.
/// With `per_run` ranks per run (`[solver] ranks_per_run`, [`ranks_per_run`]), the ranks are
/// split into groups of `per_run` (module `group`) and the group's exchange is installed for
/// the study's solver ([`crate::solve::install_rank_exchange`]).
pub fn start(threads: Option<usize>, per_run: usize) -> Result<Role, StudyError> {
    if !launched_by_mpi() {
        return Ok(Role::Single);
    }
    let per_run = per_run.max(1);
    let need = if per_run > 1 {
        Threading::Multiple
    } else {
        Threading::Funneled
    };
    let (universe, provided) = mpi::initialize_with_threading(need)
        .ok_or_else(|| StudyError::Mpi("MPI was initialised twice".into()))?;
    let rank_of = |t: Threading| match t {
        Threading::Single => 0,
        Threading::Funneled => 1,
        Threading::Serialized => 2,
        Threading::Multiple => 3,
    };
    if rank_of(provided) < rank_of(need) {
        return Err(StudyError::Mpi(format!(
            "the MPI library does not support the threads needed ({need:?}; {provided:?} provided)"
        )));
    }
    let world = universe.world();
    let (rank, size) = (world.rank(), world.size());
    let on_node = world.split_shared(rank).size().max(1) as usize;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = threads.unwrap_or((cores / on_node).max(1)).max(1);
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global();
    if size == 1 {
        return Ok(Role::Single);
    }
    if per_run > 1 {
        let exchange = group::split(&world, per_run)?;
        crate::solve::install_rank_exchange(Arc::new(exchange));
    }
    let place = Place::of(rank as usize, per_run);
    // In groups, one solver thread per rank: a group solves one group of runs at a time, its
    // ranks in the same order.
    let solvers = if per_run > 1 { 1 } else { threads };
    let comm = World {
        comm: world,
        thread: std::thread::current().id(),
    };
    if rank == 0 {
        Ok(Role::Leader(Leader {
            inner: Arc::new(LeaderInner {
                world: comm,
                size: size as usize,
                place,
                state: Mutex::new(LeaderState {
                    ready: None,
                    capacity: vec![solvers; size as usize],
                    stats: Stats {
                        ranks: size as usize,
                        threads: vec![threads; size as usize],
                        runs: vec![0; size as usize],
                        ..Stats::default()
                    },
                    next_id: 0,
                    batches: 0,
                    log: None,
                }),
            }),
            _universe: universe,
        }))
    } else {
        Ok(Role::Worker(Worker {
            world: comm,
            rank: rank as usize,
            place,
            threads: solvers,
            _universe: universe,
        }))
    }
}

/// The world communicator, used only from the thread that initialised MPI.
struct World {
    comm: SimpleCommunicator,
    thread: std::thread::ThreadId,
}

// SAFETY: MPI is initialised with `Threading::Funneled` and every use of the communicator goes
// through `World::get`, which refuses any thread but the one that initialised MPI: the handle is
// never used from two threads, nor from a thread MPI does not allow.
unsafe impl Send for World {}
unsafe impl Sync for World {}

impl World {
    fn get(&self) -> Result<&SimpleCommunicator, StudyError> {
        if std::thread::current().id() == self.thread {
            Ok(&self.comm)
        } else {
            Err(StudyError::Mpi(
                "MPI used from a thread other than the one that initialised it".into(),
            ))
        }
    }
}

/// Solves a group of runs together ([`RunContext::solve_batch`]), turning an error or a panic
/// into a message per run.
fn solve_caught(
    ctx: &RunContext<'_>,
    group: &[(u64, RunJob)],
) -> Vec<(u64, Result<RunOutcome, String>)> {
    let jobs: Vec<RunJob> = group.iter().map(|(_, j)| j.clone()).collect();
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| ctx.solve_batch(&jobs))) {
        Ok(outs) => group
            .iter()
            .zip(outs)
            .map(|((id, _), out)| (*id, out.map_err(|e| e.to_string())))
            .collect(),
        Err(p) => {
            let why = format!(
                "panicked: {}",
                p.downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| p.downcast_ref::<&str>().copied())
                    .unwrap_or("(no message)")
            );
            group
                .iter()
                .map(|(id, _)| (*id, Err(why.clone())))
                .collect()
        }
    }
}

/// A group of runs for a solver thread: `(job id, job)` each.
type Group = Vec<(u64, RunJob)>;

/// A solver thread of a rank: takes groups of jobs from `rx` until it closes, sends each run's
/// outcome to `tx`.
fn solver_thread(
    ctx: &RunContext<'_>,
    rx: &Mutex<mpsc::Receiver<Group>>,
    tx: mpsc::Sender<(u64, Result<RunOutcome, String>)>,
) {
    loop {
        let next = match rx.lock() {
            Ok(r) => r.recv(),
            Err(_) => return,
        };
        let Ok(group) = next else { return };
        for out in solve_caught(ctx, &group) {
            if tx.send(out).is_err() {
                return;
            }
        }
    }
}

struct LeaderState {
    /// `None` until every rank reported; then `Ok` or the set-up errors of the ranks.
    ready: Option<Result<(), String>>,
    capacity: Vec<usize>,
    stats: Stats,
    next_id: u64,
    batches: usize,
    log: Option<std::io::BufWriter<std::fs::File>>,
}

struct LeaderInner {
    world: World,
    size: usize,
    /// Rank 0's group (module `group`).
    place: Place,
    state: Mutex<LeaderState>,
}

/// Rank 0 of a job: install [`Leader::executor`], run the study as usual, then
/// [`Leader::finish`].
pub struct Leader {
    inner: Arc<LeaderInner>,
    _universe: mpi::environment::Universe,
}

/// The executor of rank 0: the runs of a batch over every rank.
pub struct MpiExecutor(Arc<LeaderInner>);

impl Leader {
    /// The executor to install with [`crate::runner::install_executor`].
    pub fn executor(&self) -> Box<MpiExecutor> {
        Box::new(MpiExecutor(self.inner.clone()))
    }

    /// Stops the other ranks (after they reported their set-up) and returns the job's traffic.
    pub fn finish(self) -> Result<Stats, StudyError> {
        let inner = &self.inner;
        let world = inner.world.get()?;
        let mut st = inner
            .state
            .lock()
            .map_err(|_| StudyError::Poisoned("MPI state"))?;
        if st.ready.is_none() {
            let _ = wait_ready(world, inner.size, &mut st);
        }
        for r in 1..inner.size {
            send(world, r, TAG_STOP, &[], None);
        }
        if let Some(log) = st.log.as_mut() {
            let _ = log.flush();
        }
        st.stats.batches = st.batches;
        Ok(st.stats.clone())
    }
}

/// Receives every worker's set-up report.
fn wait_ready(world: &SimpleCommunicator, size: usize, st: &mut LeaderState) -> Result<(), String> {
    let mut errors = Vec::new();
    let mut nap = Nap::new();
    let mut left = size - 1;
    while left > 0 {
        match try_receive(world, None, Some(TAG_READY)) {
            Some((r, _, bytes)) => {
                left -= 1;
                nap.reset();
                let mut rd = wire::Reader::new(&bytes);
                // 0 from the ranks of a group other than its first (module `group`).
                let threads = rd.u64().unwrap_or(1) as usize;
                st.capacity[r] = threads;
                st.stats.threads[r] = threads;
                match rd.u64() {
                    Ok(1) => {}
                    _ => errors.push(format!(
                        "rank {r} could not set up the study: {}",
                        rd.str().unwrap_or_else(|e| e.0)
                    )),
                }
            }
            None => nap.sleep(),
        }
    }
    errors.sort();
    let res = if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("; "))
    };
    st.ready = Some(res.clone());
    res
}

impl BatchExecutor for MpiExecutor {
    fn execute(
        &self,
        ctx: &RunContext<'_>,
        jobs: &[RunJob],
        commit: &(dyn Fn(Vec<RunOutcome>) -> Result<(), StudyError> + Sync),
    ) -> Result<(), StudyError> {
        let inner = &*self.0;
        let world = inner.world.get()?;
        let mut guard = inner
            .state
            .lock()
            .map_err(|_| StudyError::Poisoned("MPI state"))?;
        let st = &mut *guard;
        if st.ready.is_none() {
            let _ = wait_ready(world, inner.size, st);
        }
        if let Some(Err(e)) = &st.ready {
            return Err(StudyError::Mpi(e.clone()));
        }
        if jobs.is_empty() {
            return Ok(());
        }
        st.batches += 1;
        if st.log.is_none() {
            st.log = Some(dispatch::open_dispatch_log(ctx.dir, inner.size)?);
        }
        let size = inner.size;
        // The runs go out in the groups the local executor solves together (consecutive runs,
        // `RUNS_PER_BATCH` each): a group is one job of a solver thread, wherever it runs.
        let ngroups = jobs.len().div_ceil(RUNS_PER_BATCH);
        let group = |g: usize| g * RUNS_PER_BATCH..((g + 1) * RUNS_PER_BATCH).min(jobs.len());
        let mut queue: VecDeque<usize> = (0..ngroups).collect();
        // Runs of each group not back yet; groups in flight per rank.
        let mut left: Vec<usize> = (0..ngroups).map(|g| group(g).len()).collect();
        let mut groups_out = vec![0usize; size];
        // In flight per rank: (job id, index in `jobs`).
        let mut inflight: Vec<Vec<(u64, usize)>> = vec![Vec::new(); size];
        let mut first_err: Option<StudyError> = None;
        let study = ctx.study;
        let fail = |r: usize, i: usize, why: &str| {
            StudyError::Mpi(format!(
                "rank {r} failed on the run at {}: {why} (the runs that finished are committed: \
                 run the same command again, with any number of ranks, to resume)",
                study.describe_point(&jobs[i].theta)
            ))
        };
        let (job_tx, job_rx) = mpsc::channel::<Group>();
        let job_rx = Mutex::new(job_rx);
        std::thread::scope(|s| -> Result<(), StudyError> {
            let (res_tx, res_rx) = mpsc::channel::<(u64, Result<RunOutcome, String>)>();
            for _ in 0..st.capacity[0] {
                let (rx, tx) = (&job_rx, res_tx.clone());
                s.spawn(move || solver_thread(ctx, rx, tx));
            }
            drop(res_tx);
            let mut nap = Nap::new();
            let result = loop {
                // Hand out work: other ranks first, rank 0 (which also commits) last.
                let mut arrived: Vec<Incoming> = Vec::new();
                if first_err.is_none() {
                    for r in (1..size).chain([0]) {
                        while groups_out[r] < st.capacity[r] {
                            let Some(g) = queue.pop_front() else { break };
                            let mut out: Group = Vec::with_capacity(group(g).len());
                            for i in group(g) {
                                let id = st.next_id;
                                st.next_id += 1;
                                if let Some(log) = st.log.as_mut() {
                                    let _ = writeln!(
                                        log,
                                        "{} {r} <- {} ({})",
                                        st.batches,
                                        run_file_stem(&jobs[i].theta),
                                        study.describe_point(&jobs[i].theta)
                                    );
                                }
                                out.push((id, jobs[i].clone()));
                                inflight[r].push((id, i));
                            }
                            groups_out[r] += 1;
                            arrived
                                .extend(dispatch::send_group(world, inner, st, r, out, &job_tx)?);
                        }
                    }
                    if let Some(log) = st.log.as_mut() {
                        let _ = log.flush();
                    }
                }
                let mut busy = !arrived.is_empty();
                while let Some(m) = try_receive(world, None, Some(TAG_RESULT)) {
                    arrived.push(m);
                    busy = true;
                }
                // The other ranks' results, then rank 0's own, in that order.
                let mut done = Vec::with_capacity(arrived.len());
                for (r, _, bytes) in arrived {
                    st.stats.result_bytes += bytes.len() as u64;
                    let (id, out) = wire::decode_result(&bytes).map_err(|e| {
                        StudyError::Mpi(format!("a result from rank {r} does not decode: {}", e.0))
                    })?;
                    done.push((r, id, out));
                }
                while let Ok((id, out)) = res_rx.try_recv() {
                    busy = true;
                    done.push((0, id, out));
                }
                for (r, id, out) in done {
                    let back = Back {
                        jobs,
                        commit,
                        fail: &fail,
                    };
                    back.handle(
                        r,
                        id,
                        out,
                        &mut inflight,
                        &mut left,
                        &mut groups_out,
                        &mut first_err,
                        &mut st.stats,
                    )?;
                }
                if inflight.iter().all(Vec::is_empty) && (queue.is_empty() || first_err.is_some()) {
                    break Ok(());
                }
                nap.pace(busy);
            };
            drop(job_tx);
            result
        })?;
        match first_err {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

/// What a result coming back from a rank is checked against and committed with.
struct Back<'a> {
    /// The jobs of the `execute` call.
    jobs: &'a [RunJob],
    /// Commits finished runs.
    commit: &'a (dyn Fn(Vec<RunOutcome>) -> Result<(), StudyError> + Sync),
    /// The error of rank `r` failing on job `i`.
    fail: &'a dyn Fn(usize, usize, &str) -> StudyError,
}

impl Back<'_> {
    /// Takes the result `out` of job `id` back from rank `r`: off its in-flight list, its group
    /// counted, committed (or its error kept as the first one).
    #[allow(clippy::too_many_arguments)]
    fn handle(
        &self,
        r: usize,
        id: u64,
        out: Result<RunOutcome, String>,
        inflight: &mut [Vec<(u64, usize)>],
        left: &mut [usize],
        groups_out: &mut [usize],
        first_err: &mut Option<StudyError>,
        stats: &mut Stats,
    ) -> Result<(), StudyError> {
        let (jobs, fail) = (self.jobs, self.fail);
        let k = inflight[r]
            .iter()
            .position(|&(x, _)| x == id)
            .ok_or_else(|| StudyError::Mpi(format!("rank {r} returned a run it was not given")))?;
        let (_, i) = inflight[r].swap_remove(k);
        let g = i / RUNS_PER_BATCH;
        left[g] -= 1;
        if left[g] == 0 {
            groups_out[r] -= 1;
        }
        match out {
            Ok(o) => {
                if o.rec.params != jobs[i].theta {
                    return Err(fail(r, i, "its result is for another point"));
                }
                stats.runs[r] += 1;
                if let Err(e) = (self.commit)(vec![o]) {
                    first_err.get_or_insert(e);
                }
            }
            Err(why) => {
                first_err.get_or_insert(fail(r, i, &why));
            }
        }
        Ok(())
    }
}

/// A rank other than 0: builds its solver, then solves the runs rank 0 sends until told to
/// stop.
pub struct Worker {
    world: World,
    rank: usize,
    /// Its group (module `group`): the first rank talks to rank 0, the others to it.
    place: Place,
    /// Solver threads.
    threads: usize,
    _universe: mpi::environment::Universe,
}

impl Worker {
    /// This rank.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// Loads the study at `path`, builds its solver, reports to rank 0, and solves the runs it
    /// is sent (per-run ParaView files, if the study asks for them, go to `dir`) until rank 0
    /// says stop. Set-up errors are reported to rank 0, which prints them; the error returned
    /// here is a failure of the exchange itself.
    pub fn serve(self, path: &Path, dir: &Path) -> Result<(), StudyError> {
        let world = self.world.get()?;
        let setup = Study::load(path).and_then(|study| {
            let s = RunSetup::build_for_runs(&study)?;
            Ok((study, s))
        });
        let head = self.place.head == self.rank;
        let mut w = wire::Writer::default();
        // The runs it takes at once: none for the ranks of a group other than its first.
        w.u64(if head { self.threads as u64 } else { 0 });
        match &setup {
            Ok(_) => w.u64(1),
            Err(e) => w.u64(0).str(&e.to_string()),
        };
        let mut stash: VecDeque<Incoming> =
            send(world, 0, TAG_READY, &w.into_bytes(), Some(TAG_STOP)).into();
        let Ok((study, s)) = setup else {
            // Wait for rank 0 to stop the job (it reports the error).
            let mut nap = Nap::new();
            while stash.is_empty() {
                match try_receive(world, Some(0), Some(TAG_STOP)) {
                    Some(m) => stash.push_back(m),
                    None => nap.sleep(),
                }
            }
            return Ok(());
        };
        let ctx = RunContext {
            study: &study,
            solver: &s.solver,
            cre: s.cre.as_deref(),
            dir,
            stop: &crate::solve::never_stop,
            files: true,
        };
        let sizes = s.solver.interface_sizes();
        let (job_tx, job_rx) = mpsc::channel::<Group>();
        let job_rx = Mutex::new(job_rx);
        std::thread::scope(|sc| -> Result<(), StudyError> {
            let (res_tx, res_rx) = mpsc::channel::<(u64, Result<RunOutcome, String>)>();
            for _ in 0..self.threads {
                let (rx, tx) = (&job_rx, res_tx.clone());
                let ctx = &ctx;
                sc.spawn(move || solver_thread(ctx, rx, tx));
            }
            drop(res_tx);
            let mut in_flight = 0usize;
            let mut stop = false;
            let mut nap = Nap::new();
            let result = 'serve: loop {
                let mut busy = false;
                // The first rank of a group hears from rank 0; the others from it (jobs) and
                // rank 0 (stop).
                let boss = if head { Some(0) } else { None };
                while let Some(m) = stash.pop_front().or_else(|| try_receive(world, boss, None)) {
                    busy = true;
                    match m.1 {
                        TAG_STOP => stop = true,
                        TAG_JOB => {
                            // Its group solves the job with it (module `group`).
                            if head {
                                for r in self.place.members() {
                                    stash.extend(send(world, r, TAG_JOB, &m.2, None));
                                }
                            }
                            // A group of runs solved together; a run that does not decode is
                            // answered at once (with its id if it can be read, so rank 0 names
                            // the run), the others are solved.
                            let entries = match wire::decode_group(&m.2, &sizes) {
                                Ok(v) => v,
                                Err(e) => vec![Err((None, e))],
                            };
                            let mut group: Group = Vec::with_capacity(entries.len());
                            for entry in entries {
                                match entry {
                                    Ok(job) => group.push(job),
                                    Err(_) if !head => {}
                                    Err((id, e)) => {
                                        let bytes = wire::encode_result(
                                            id.unwrap_or(u64::MAX),
                                            &Err(format!("its job does not decode: {}", e.0)),
                                        );
                                        stash.extend(send(world, 0, TAG_RESULT, &bytes, None));
                                    }
                                }
                            }
                            if group.is_empty() {
                                continue;
                            }
                            in_flight += group.len();
                            if job_tx.send(group).is_err() {
                                break 'serve Err(StudyError::Mpi(format!(
                                    "rank {}: its solver threads stopped",
                                    self.rank
                                )));
                            }
                        }
                        other => {
                            break 'serve Err(StudyError::Mpi(format!(
                                "rank {}: unexpected message tag {other} from rank 0",
                                self.rank
                            )));
                        }
                    }
                }
                while let Ok((id, out)) = res_rx.try_recv() {
                    busy = true;
                    in_flight -= 1;
                    // The group's first rank answers for the group.
                    if head {
                        let bytes = wire::encode_result(id, &out);
                        stash.extend(send(world, 0, TAG_RESULT, &bytes, None));
                    }
                }
                if stop && in_flight == 0 {
                    break Ok(());
                }
                nap.pace(busy);
            };
            drop(job_tx);
            result
        })
    }
}
