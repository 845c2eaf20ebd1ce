//! Studies: the binding glue over `alea-pipeline`, the study pipeline, the same that `alea run`
//! and `alea report` call: running a study file and analysing every method
//! (`alea_pipeline::run_runs`, `analyse`), reading the runs of a study directory's
//! store (`stored_runs`), and rebuilding every output of a study directory (`rebuild`).
//!
//! The results cross to Python as plain dicts of NumPy arrays; the `alea` package turns them
//! into DataFrames. Nothing is computed here: every number is alea-study's.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, mpsc};
use std::time::Duration;

use alea_pipeline::{
    BudgetInterval, MethodOutcome, StudyResult, analyse, run_runs, sample_points, stored_runs,
};
use alea_pipeline::{Error as OutputError, Silent};
use alea_report::ReportError;
use alea_study::StudyError;
use alea_study::analysis::MethodResult;
use alea_study::runner::{Progress, Study};
use alea_study::store::RunRecord;
use numpy::PyArray1;
use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{NonNegative, array1, array2, python_terms, study_err, value_error};

/// An error of the study orchestration as a Python exception: study errors as `study_err`
/// does, a study directory in use by another process as `alea.StudyLocked` (naming the
/// holder), an interrupted study as `KeyboardInterrupt`, files that cannot be read or written
/// as `OSError` (`FileNotFoundError` for a directory without a store), a directory that is
/// not a study store as `ValueError`, bugs as `RuntimeError`. The message is the error's with
/// its causes (each once), in the terms of the Python API (`restart=True`, not `--restart`).
fn output_err(py: Python<'_>, e: OutputError) -> PyErr {
    let message = python_terms(&message_with_causes(&e));
    match e {
        OutputError::Study(StudyError::Busy { dir, holder }) => {
            study_locked(py, &message, &dir, &holder)
        }
        OutputError::Study(StudyError::Interrupted) => PyKeyboardInterrupt::new_err(message),
        OutputError::Study(s) => study_err(s),
        OutputError::NoStore { .. } => PyFileNotFoundError::new_err(message),
        OutputError::Store { .. } => value_error(message),
        OutputError::Write { .. }
        | OutputError::Report(ReportError::Io { .. } | ReportError::Json { .. }) => {
            PyOSError::new_err(message)
        }
        OutputError::Report(_) | OutputError::NonFinite | OutputError::Json(_) => {
            PyRuntimeError::new_err(message)
        }
    }
}

/// The error's message followed by its causes, each once.
fn message_with_causes(e: &OutputError) -> String {
    let mut message = e.to_string();
    let mut cause = std::error::Error::source(e);
    while let Some(c) = cause {
        let text = c.to_string();
        if !message.ends_with(&text) {
            message.push_str(&format!(": {text}"));
        }
        cause = c.source();
    }
    message
}

/// `alea.StudyLocked(message, directory, holder)` (a `ValueError` defined by the Python
/// package, `python/alea/_study.py`); a plain `ValueError` if that class cannot be found.
fn study_locked(py: Python<'_>, message: &str, dir: &Path, holder: &str) -> PyErr {
    let made = py
        .import("alea._study")
        .and_then(|m| m.getattr("StudyLocked"))
        .and_then(|cls| cls.call1((message, dir.display().to_string(), holder)));
    match made {
        Ok(err) => PyErr::from_value(err),
        Err(_) => value_error(message.to_string()),
    }
}

/// The progress of a study seen from Python: calls `progress(done, total)` after each
/// finished run (from the worker threads, attaching to the interpreter for the call), and
/// asks the runner to stop once an error is kept: the first exception the callback raises
/// (further calls are skipped), or the `KeyboardInterrupt` of a Ctrl-C seen by the waiting
/// thread ([`run_watched`]). The kept error is raised once the study has stopped.
struct PyProgress {
    callback: Option<Py<PyAny>>,
    done: AtomicUsize,
    total: AtomicUsize,
    error: Mutex<Option<PyErr>>,
    stop: AtomicBool,
}

impl PyProgress {
    fn new(callback: Option<Py<PyAny>>) -> Self {
        Self {
            callback,
            done: AtomicUsize::new(0),
            total: AtomicUsize::new(0),
            error: Mutex::new(None),
            stop: AtomicBool::new(false),
        }
    }

    /// Keeps `e` (unless an error is kept already) and asks the runner to stop.
    fn fail(&self, e: PyErr) {
        self.stop.store(true, Ordering::SeqCst);
        if let Ok(mut err) = self.error.lock()
            && err.is_none()
        {
            *err = Some(e);
        }
    }

    /// The kept error, if any.
    fn take_error(&self) -> Option<PyErr> {
        self.error.lock().ok().and_then(|mut e| e.take())
    }

    fn call(&self) {
        let Some(cb) = &self.callback else { return };
        if self.stop.load(Ordering::SeqCst) {
            return;
        }
        let (done, total) = (
            self.done.load(Ordering::SeqCst),
            self.total.load(Ordering::SeqCst),
        );
        if let Err(e) = Python::attach(|py| cb.call1(py, (done, total)).map(|_| ())) {
            self.fail(e);
        }
    }
}

impl Progress for PyProgress {
    fn begin(&self, total: usize, done: usize) {
        self.total.store(total, Ordering::SeqCst);
        self.done.store(done, Ordering::SeqCst);
        self.call();
    }
    fn finished(&self, _rec: &RunRecord) {
        self.done.fetch_add(1, Ordering::SeqCst);
        self.call();
    }
    fn more(&self, n: usize) {
        self.total.fetch_add(n, Ordering::SeqCst);
    }
    fn stop_requested(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }
}

/// How often the thread waiting for a study checks for signals (Ctrl-C).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `job` on a thread of its own while the calling thread waits without the interpreter
/// lock, checking for signals every [`SIGNAL_POLL`]; a signal's exception (`KeyboardInterrupt`
/// for Ctrl-C) goes to `interrupt`, and the job is waited for all the same (it is asked to stop
/// through `interrupt`, and returns once its finished work is safe).
fn run_watched<T: Send>(
    py: Python<'_>,
    job: impl FnOnce() -> T + Send,
    interrupt: impl Fn(PyErr),
) -> PyResult<T> {
    let out = std::thread::scope(|s| {
        let (tx, rx) = mpsc::channel::<()>();
        let worker = s.spawn(move || {
            let out = job();
            // The receiver may be gone only if the waiting thread panicked.
            let _ = tx.send(());
            out
        });
        // In a mutex: the receiver crosses to the detached closure by reference.
        let rx = Mutex::new(rx);
        loop {
            let finished = py.detach(|| {
                let Ok(rx) = rx.lock() else { return true };
                !matches!(
                    rx.recv_timeout(SIGNAL_POLL),
                    Err(mpsc::RecvTimeoutError::Timeout)
                )
            });
            if finished {
                break;
            }
            if let Err(e) = py.check_signals() {
                interrupt(e);
            }
        }
        worker.join()
    });
    out.map_err(|_| PyRuntimeError::new_err("the study panicked"))
}

/// What a finished study hands to Python.
struct StudyOutput {
    study: StudyInfo,
    records: Vec<RunRecord>,
    computed: usize,
    resumed: usize,
    setup_seconds: f64,
    solve_seconds: f64,
    /// Each method's statistics with their draws and the parameter points of the draws.
    methods: Vec<(MethodResult, Option<Vec<f64>>)>,
    /// The study's result, as in `summary.json` (without error estimates): what the methods'
    /// dicts and the reliability results are made of, besides the draws.
    result: StudyResult,
}

/// Names and units of a study, its parameters' laws and its random fields.
struct StudyInfo {
    title: String,
    file: String,
    hash: String,
    seed: u64,
    parameters: Vec<String>,
    parameter_units: Vec<String>,
    /// Each parameter's law as `summary.json` describes it, its box and nominal value.
    parameter_laws: Vec<String>,
    parameter_lo: Vec<f64>,
    parameter_hi: Vec<f64>,
    parameter_nominal: Vec<f64>,
    quantities: Vec<String>,
    quantity_units: Vec<String>,
    fields: Vec<FieldInfo>,
}

/// A `[[field]]` of a study: its Karhunen-Loeve discretisation.
struct FieldInfo {
    name: String,
    /// Its interface (empty for a field over a substructure's cells).
    interface: String,
    /// Its substructure (empty for a field along an interface).
    substructure: String,
    unit: String,
    description: String,
    transform: String,
    /// Index of its first KL variable among the parameters.
    first_variable: usize,
    eigenvalues: Vec<f64>,
    captured_fraction: f64,
    total_variance: f64,
    /// Node coordinates, `n x 3` row-major.
    nodes: Vec<f64>,
    /// Cells (segments or triangles) by node index.
    cells: Vec<Vec<usize>>,
    /// Modes at the nodes, `m x n` row-major (row `k`: mode `k`, L2-normalised), as
    /// `alea.KarhunenLoeve.modes`.
    modes: Vec<f64>,
}

impl FieldInfo {
    fn of(study: &Study, f: &alea_study::random_field::StudyField) -> Self {
        let kl = f.field.kl();
        let mesh = kl.mesh();
        let m = kl.num_modes();
        let modes: Vec<f64> = (0..m).flat_map(|k| kl.mode(k).iter().copied()).collect();
        Self {
            name: f.name.clone(),
            interface: f
                .interface()
                .and_then(|i| study.model.assembly.interfaces.get(i))
                .map_or_else(String::new, |i| i.name.clone()),
            substructure: match f.domain {
                alea_study::random_field::FieldDomain::Substructure(s) => study
                    .model
                    .assembly
                    .subs
                    .get(s)
                    .map_or_else(String::new, |s| s.name.clone()),
                alea_study::random_field::FieldDomain::Interface(_) => String::new(),
            },
            unit: f.unit.clone(),
            description: f.description.clone(),
            transform: format!("{:?}", f.field.transform()),
            first_variable: f.first_variable,
            eigenvalues: kl.eigenvalues().to_vec(),
            captured_fraction: kl.captured_fraction(),
            total_variance: kl.total_variance(),
            nodes: mesh.nodes().iter().flatten().copied().collect(),
            cells: (0..mesh.num_cells())
                .map(|c| mesh.cell(c).to_vec())
                .collect(),
            modes,
        }
    }

    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("name", &self.name)?;
        d.set_item("interface", &self.interface)?;
        d.set_item("substructure", &self.substructure)?;
        d.set_item("unit", &self.unit)?;
        d.set_item("description", &self.description)?;
        d.set_item("transform", &self.transform)?;
        d.set_item("first_variable", self.first_variable)?;
        d.set_item("eigenvalues", array1(py, self.eigenvalues.clone()))?;
        d.set_item("captured_fraction", self.captured_fraction)?;
        d.set_item("total_variance", self.total_variance)?;
        let n = self.nodes.len() / 3;
        d.set_item("nodes", array2(py, self.nodes.clone(), n, 3)?)?;
        d.set_item("cells", self.cells.clone())?;
        let m = self.eigenvalues.len();
        d.set_item("modes", array2(py, self.modes.clone(), m, n)?)?;
        Ok(d)
    }
}

impl StudyInfo {
    fn of(study: &Study) -> Self {
        Self {
            title: study.title(),
            file: study.source.path.display().to_string(),
            hash: study.hash.clone(),
            seed: study.seed,
            parameters: study.params.names.clone(),
            parameter_units: study.params.units.clone(),
            parameter_laws: study.params.descriptions.clone(),
            parameter_lo: study.params.lo.clone(),
            parameter_hi: study.params.hi.clone(),
            parameter_nominal: study.params.nominal.clone(),
            quantities: study.qois.iter().map(|q| q.name.clone()).collect(),
            quantity_units: study.qois.iter().map(|q| q.unit.clone()).collect(),
            fields: study
                .params
                .fields
                .iter()
                .map(|f| FieldInfo::of(study, f))
                .collect(),
        }
    }

    fn to_dict<'py>(&self, py: Python<'py>, out: &Bound<'py, PyDict>) -> PyResult<()> {
        out.set_item("title", &self.title)?;
        out.set_item("study_file", &self.file)?;
        out.set_item("study_hash", &self.hash)?;
        out.set_item("seed", self.seed)?;
        out.set_item("parameters", PyList::new(py, &self.parameters)?)?;
        out.set_item("parameter_units", PyList::new(py, &self.parameter_units)?)?;
        out.set_item("parameter_laws", PyList::new(py, &self.parameter_laws)?)?;
        out.set_item("parameter_lo", array1(py, self.parameter_lo.clone()))?;
        out.set_item("parameter_hi", array1(py, self.parameter_hi.clone()))?;
        out.set_item(
            "parameter_nominal",
            array1(py, self.parameter_nominal.clone()),
        )?;
        let fields = PyList::empty(py);
        for f in &self.fields {
            fields.append(f.to_dict(py)?)?;
        }
        out.set_item("fields", fields)?;
        out.set_item("quantities", PyList::new(py, &self.quantities)?)?;
        out.set_item("quantity_units", PyList::new(py, &self.quantity_units)?)?;
        Ok(())
    }
}

fn run(
    path: &Path,
    dir: &Path,
    restart: bool,
    progress: &PyProgress,
) -> Result<StudyOutput, OutputError> {
    let ran = run_runs(path, dir, restart, progress, &Silent)?;
    let analysis = analyse(&ran.study, &ran.runs, &ran.settings);
    let result = StudyResult::of_analysis(&ran.study, &ran.runs, &analysis, &[]);
    let methods = ran
        .runs
        .methods
        .iter()
        .zip(analysis.results)
        .map(|(m, r)| {
            let points = sample_points(m, &ran.runs.records, &r);
            (r, points)
        })
        .collect();
    Ok(StudyOutput {
        study: StudyInfo::of(&ran.study),
        records: ran.runs.records,
        computed: ran.runs.computed,
        resumed: ran.runs.resumed,
        setup_seconds: ran.runs.setup_seconds,
        solve_seconds: ran.runs.solve_seconds,
        methods,
        result,
    })
}

fn records_dict<'py>(
    py: Python<'py>,
    records: &[RunRecord],
    d: usize,
    m: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let n = records.len();
    let out = PyDict::new(py);
    let mut params = Vec::with_capacity(n * d);
    let mut qois = Vec::with_capacity(n * m);
    for r in records {
        if r.params.len() != d {
            return Err(value_error(format!(
                "a stored run has {} parameters, expected {d}",
                r.params.len()
            )));
        }
        params.extend_from_slice(&r.params);
        qois.extend((0..m).map(|q| r.qois.get(q).copied().unwrap_or(f64::NAN)));
    }
    out.set_item("params", array2(py, params, n, d)?)?;
    out.set_item("qois", array2(py, qois, n, m)?)?;
    out.set_item(
        "status",
        PyList::new(py, records.iter().map(|r| r.status.as_str()))?,
    )?;
    out.set_item(
        "iterations",
        PyArray1::from_vec(py, records.iter().map(|r| r.iterations as i64).collect()),
    )?;
    out.set_item(
        "residual",
        array1(py, records.iter().map(|r| r.residual).collect()),
    )?;
    out.set_item(
        "seconds",
        array1(py, records.iter().map(|r| r.seconds).collect()),
    )?;
    Ok(out)
}

/// One method's dict: `outcome` (its part of the study's result) with the timings and the
/// draws of `r` (its statistics as analysed) and the parameter points of the draws.
fn method_dict<'py>(
    py: Python<'py>,
    (r, outcome): (&MethodResult, &MethodOutcome),
    points: Option<&Vec<f64>>,
    d: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("label", &outcome.account.label)?;
    out.set_item("description", &outcome.account.description)?;
    out.set_item("design_runs", outcome.account.design_runs)?;
    out.set_item("runs_used", outcome.account.runs_used)?;
    out.set_item("draws", outcome.draws)?;
    out.set_item("error", outcome.account.error.as_deref())?;
    out.set_item("surrogate_seconds", r.surrogate_seconds)?;
    out.set_item("monte_carlo_seconds", r.monte_carlo_seconds)?;
    let left = PyList::empty(py);
    for (p, s) in &outcome.account.left_out {
        left.append((p.clone(), s.as_str()))?;
    }
    out.set_item("left_out", left)?;
    // The region of the failed runs, left out of the statistics (None: no run failed).
    match &outcome.account.failure_region {
        Some(f) => {
            let region = PyDict::new(py);
            region.set_item("failed_runs", f.failed_runs)?;
            region.set_item("probability", f.probability)?;
            region.set_item("interval", (f.ci_low, f.ci_high))?;
            region.set_item("left_out", f.left_out)?;
            region.set_item("basis", &f.basis)?;
            out.set_item("failure_region", region)?;
        }
        None => out.set_item("failure_region", py.None())?,
    }
    let stats = PyList::empty(py);
    for s in &outcome.qois {
        let q = PyDict::new(py);
        q.set_item("quantity", &s.name)?;
        q.set_item("unit", &s.unit)?;
        for (key, value) in [
            ("mean", s.distribution.mean),
            ("std", s.distribution.std),
            ("skewness", s.distribution.skewness),
            ("min", s.distribution.min),
            ("max", s.distribution.max),
            ("mean_ci_half_width", s.distribution.mean_ci_half_width),
        ] {
            q.set_item(key, value)?;
        }
        q.set_item("quantiles", s.distribution.quantiles.clone())?;
        q.set_item("bandwidth", s.distribution.bandwidth)?;
        let kx: Vec<f64> = s.distribution.kde.iter().map(|p| p.0).collect();
        let ky: Vec<f64> = s.distribution.kde.iter().map(|p| p.1).collect();
        q.set_item("kde_x", array1(py, kx))?;
        q.set_item("kde_pdf", array1(py, ky))?;
        // Each failure probability: threshold, value, its sampling-only (Wilson) interval, then
        // the estimate and the total interval of its budget row (None without a budget; issue
        // 40, item 3).
        let f = PyList::empty(py);
        for fs in &s.failure {
            f.append((
                fs.threshold,
                fs.probability,
                fs.ci_low,
                fs.ci_high,
                fs.estimate,
                fs.interval.map(|i| i[0]),
                fs.interval.map(|i| i[1]),
            ))?;
        }
        q.set_item("failure", f)?;
        // Each budget row: its parts, then what users read, the estimate (corrected by the
        // validation runs where there are some) and the total interval.
        let budget = PyList::empty(py);
        if let Some(b) = &s.budget {
            for BudgetInterval {
                row,
                estimate,
                interval: [lo, hi],
            } in &b.rows
            {
                budget.append((
                    row.statistic.to_string(),
                    row.value,
                    row.mesh,
                    row.surrogate,
                    row.sampling,
                    row.sliding,
                    row.total,
                    *estimate,
                    *lo,
                    *hi,
                ))?;
            }
            q.set_item("surrogate_basis", &b.surrogate_basis)?;
            q.set_item("mesh_basis", &b.mesh_basis)?;
            q.set_item("sliding_basis", &b.sliding_basis)?;
            q.set_item("budget_draws", b.draws)?;
            // The surrogate's residuals at the validation runs (None without validation runs).
            let errors = match &b.validation_errors {
                Some(e) => {
                    let d = PyDict::new(py);
                    d.set_item("runs", e.runs)?;
                    d.set_item("rms", e.rms)?;
                    d.set_item("max", e.max)?;
                    d.set_item("scale", e.scale)?;
                    d.set_item("relative", e.relative)?;
                    Some(d)
                }
                None => None,
            };
            q.set_item("validation_errors", errors)?;
        }
        q.set_item("budget", budget)?;
        // Sobol' indices (studies with random fields), as in summary.json.
        let sobol = match &s.sobol {
            Some(v) => Some(serde_json::to_string(v).map_err(|e| value_error(e.to_string()))?),
            None => None,
        };
        q.set_item("sobol_json", sobol)?;
        stats.append(q)?;
    }
    out.set_item("statistics", stats)?;
    // Draws: parameter points (draws, d) and quantity values (draws, m), row i = draw i.
    let m = r.qois.len();
    let n = r.qois.first().map_or(0, |s| s.samples.len());
    if m > 0 && r.qois.iter().all(|s| s.samples.len() == n) {
        let mut v = Vec::with_capacity(n * m);
        for i in 0..n {
            v.extend(r.qois.iter().map(|s| s.samples[i]));
        }
        out.set_item("samples", array2(py, v, n, m)?)?;
        match points {
            Some(p) if p.len() == n * d => out.set_item("points", array2(py, p.clone(), n, d)?)?,
            _ => out.set_item("points", py.None())?,
        }
    } else {
        out.set_item("samples", py.None())?;
        out.set_item("points", py.None())?;
    }
    Ok(out)
}

/// Runs (or resumes) the study file `path` in the study directory `directory` and analyses
/// every method; returns a dict of arrays (see the `alea` package's `run`).
#[pyfunction]
#[pyo3(signature = (path, directory, restart = false, threads = None, progress = None))]
pub fn run_study_file<'py>(
    py: Python<'py>,
    path: PathBuf,
    directory: PathBuf,
    restart: bool,
    threads: Option<NonNegative<usize>>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let threads = threads.map(|v| v.0);
    if threads == Some(0) {
        return Err(value_error("threads must be at least 1"));
    }
    let pool = threads
        .map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build())
        .transpose()
        .map_err(|e| value_error(format!("thread pool: {e}")))?;
    let prog = PyProgress::new(progress);
    let job = || match &pool {
        Some(p) => p.install(|| run(&path, &directory, restart, &prog)),
        None => run(&path, &directory, restart, &prog),
    };
    let out = run_watched(py, job, |e| prog.fail(e))?;
    if let Some(e) = prog.take_error() {
        return Err(e);
    }
    let out = out.map_err(|e| output_err(py, e))?;
    let d = out.study.parameters.len();
    let m = out.study.quantities.len();
    let dict = PyDict::new(py);
    out.study.to_dict(py, &dict)?;
    dict.set_item("directory", directory.display().to_string())?;
    dict.set_item("runs", records_dict(py, &out.records, d, m)?)?;
    dict.set_item("computed", out.computed)?;
    dict.set_item("resumed", out.resumed)?;
    dict.set_item("setup_seconds", out.setup_seconds)?;
    dict.set_item("solve_seconds", out.solve_seconds)?;
    let methods = PyList::empty(py);
    for ((r, p), outcome) in out.methods.iter().zip(&out.result.methods) {
        methods.append(method_dict(py, (r, outcome), p.as_ref(), d)?)?;
    }
    dict.set_item("methods", methods)?;
    let reliability =
        serde_json::to_string(&out.result.reliability).unwrap_or_else(|_| "[]".into());
    dict.set_item("reliability_json", reliability)?;
    Ok(dict)
}

/// Reads the runs stored in a study directory without running anything. With `study` (the
/// study file), the store must hold that version of it and names come from it.
#[pyfunction]
#[pyo3(signature = (directory, study = None))]
pub fn read_store<'py>(
    py: Python<'py>,
    directory: PathBuf,
    study: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let stored = py
        .detach(|| stored_runs(&directory, study.as_deref()))
        .map_err(|e| output_err(py, e))?;
    let records = &stored.records;
    let info = stored.study.as_ref().map(StudyInfo::of);
    let d = match &info {
        Some(i) => i.parameters.len(),
        None => records.first().map_or(0, |r| r.params.len()),
    };
    let m = match &info {
        Some(i) => i.quantities.len(),
        None => records.iter().map(|r| r.qois.len()).max().unwrap_or(0),
    };
    let dict = PyDict::new(py);
    if let Some(i) = &info {
        i.to_dict(py, &dict)?;
    }
    dict.set_item("study_hash", &stored.hash)?;
    dict.set_item("directory", directory.display().to_string())?;
    dict.set_item("runs", records_dict(py, records, d, m)?)?;
    Ok(dict)
}

/// Rebuilds every output of a study directory from its store, computing no run (as
/// `alea report DIR`); returns the files written and the warnings (see the `alea` package's
/// `report`).
#[pyfunction]
pub fn rebuild_outputs<'py>(py: Python<'py>, directory: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let out = py
        .detach(|| alea_pipeline::rebuild(&directory, "alea.report", &Silent))
        .map_err(|e| output_err(py, e))?;
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    let dict = PyDict::new(py);
    dict.set_item("summary", out.summary.display().to_string())?;
    dict.set_item("samples", path(&out.samples))?;
    dict.set_item("fields", path(&out.fields))?;
    dict.set_item("error_fields", path(&out.error_fields))?;
    let (html, plots) = match &out.report {
        Some(r) => (
            Some(r.html.display().to_string()),
            r.plots.iter().map(|p| p.display().to_string()).collect(),
        ),
        None => (None, Vec::new()),
    };
    dict.set_item("report", html)?;
    dict.set_item("plots", PyList::new(py, plots)?)?;
    let notes = out.notes.iter().map(|n| python_terms(n));
    dict.set_item("notes", PyList::new(py, notes)?)?;
    Ok(dict)
}
