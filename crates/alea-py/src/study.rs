//! Studies: running a study file (`alea_study::runner::run_study`, then
//! `alea_study::analysis::analyse_method` for every method, as `alea run` does) and reading the
//! runs of a study directory's store (`alea_study::store::Store`).
//!
//! The results cross to Python as plain dicts of NumPy arrays; the `alea` package turns them
//! into DataFrames. Nothing is computed here: every number is alea-study's.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use alea_study::analysis::{MethodResult, analyse_method, analysis_settings};
use alea_study::method::MethodKind;
use alea_study::runner::{Progress, Study, run_study};
use alea_study::store::{RunRecord, Store, point_key};
use numpy::PyArray1;
use pyo3::exceptions::PyFileNotFoundError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{array1, array2, study_err, value_error};

/// Calls a Python `progress(done, total)` after each finished run (from the worker threads,
/// attaching to the interpreter for the call). The first exception it raises is kept, further
/// calls are skipped, and the exception is raised once the study has finished.
struct PyProgress {
    callback: Option<Py<PyAny>>,
    done: AtomicUsize,
    total: AtomicUsize,
    error: Mutex<Option<PyErr>>,
}

impl PyProgress {
    fn call(&self) {
        let Some(cb) = &self.callback else { return };
        let Ok(mut err) = self.error.lock() else {
            return;
        };
        if err.is_some() {
            return;
        }
        let (done, total) = (
            self.done.load(Ordering::SeqCst),
            self.total.load(Ordering::SeqCst),
        );
        if let Err(e) = Python::attach(|py| cb.call1(py, (done, total)).map(|_| ())) {
            *err = Some(e);
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
}

/// What a finished study hands to Python.
struct StudyOutput {
    study: StudyInfo,
    records: Vec<RunRecord>,
    computed: usize,
    resumed: usize,
    setup_seconds: f64,
    solve_seconds: f64,
    methods: Vec<(MethodResult, Option<Vec<f64>>)>,
}

/// Names and units of a study.
struct StudyInfo {
    title: String,
    file: String,
    hash: String,
    seed: u64,
    parameters: Vec<String>,
    parameter_units: Vec<String>,
    quantities: Vec<String>,
    quantity_units: Vec<String>,
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
            quantities: study.qois.iter().map(|q| q.name.clone()).collect(),
            quantity_units: study.qois.iter().map(|q| q.unit.clone()).collect(),
        }
    }

    fn to_dict<'py>(&self, py: Python<'py>, out: &Bound<'py, PyDict>) -> PyResult<()> {
        out.set_item("title", &self.title)?;
        out.set_item("study_file", &self.file)?;
        out.set_item("study_hash", &self.hash)?;
        out.set_item("seed", self.seed)?;
        out.set_item("parameters", PyList::new(py, &self.parameters)?)?;
        out.set_item("parameter_units", PyList::new(py, &self.parameter_units)?)?;
        out.set_item("quantities", PyList::new(py, &self.quantities)?)?;
        out.set_item("quantity_units", PyList::new(py, &self.quantity_units)?)?;
        Ok(())
    }
}

/// The parameter points of a Monte Carlo method's statistics, in the order of its samples: the
/// method's converged runs in design order. Returned only if it reproduces the method's samples
/// bit for bit (so it can never mislabel a sample).
fn monte_carlo_points(
    points: &[Vec<f64>],
    records: &[RunRecord],
    result: &MethodResult,
) -> Option<Vec<f64>> {
    let by_key: std::collections::HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    let used: Vec<&RunRecord> = points
        .iter()
        .filter_map(|p| by_key.get(&point_key(p)).copied())
        .filter(|r| r.converged())
        .collect();
    let same = used.len() == result.runs_used
        && result.qois.iter().enumerate().all(|(q, s)| {
            s.samples.len() == used.len()
                && s.samples
                    .iter()
                    .zip(&used)
                    .all(|(v, r)| r.qois.get(q).is_some_and(|x| x.to_bits() == v.to_bits()))
        });
    same.then(|| used.iter().flat_map(|r| r.params.iter().copied()).collect())
}

fn run(
    path: &Path,
    dir: &Path,
    restart: bool,
    progress: &PyProgress,
) -> Result<StudyOutput, alea_study::StudyError> {
    let study = Study::load(path)?;
    let settings = analysis_settings(&study)?;
    let runs = run_study(&study, dir, restart, progress)?;
    let methods = runs
        .methods
        .iter()
        .map(|m| {
            let r = analyse_method(&study, m, &runs.records, &settings);
            let pts = if m.kind == MethodKind::MonteCarlo && !r.qois.is_empty() {
                monte_carlo_points(&m.points, &runs.records, &r)
            } else if r.points.is_empty() {
                None
            } else {
                Some(r.points.clone())
            };
            (r, pts)
        })
        .collect();
    Ok(StudyOutput {
        study: StudyInfo::of(&study),
        records: runs.records,
        computed: runs.computed,
        resumed: runs.resumed,
        setup_seconds: runs.setup_seconds,
        solve_seconds: runs.solve_seconds,
        methods,
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

fn method_dict<'py>(
    py: Python<'py>,
    r: &MethodResult,
    points: Option<&Vec<f64>>,
    d: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("label", &r.label)?;
    out.set_item("description", &r.description)?;
    out.set_item("design_runs", r.design_runs)?;
    out.set_item("runs_used", r.runs_used)?;
    out.set_item("draws", r.draws)?;
    out.set_item("error", r.error.as_deref())?;
    out.set_item("surrogate_seconds", r.surrogate_seconds)?;
    out.set_item("monte_carlo_seconds", r.monte_carlo_seconds)?;
    let left = PyList::empty(py);
    for (p, s) in &r.left_out {
        left.append((p.clone(), s.as_str()))?;
    }
    out.set_item("left_out", left)?;
    let stats = PyList::empty(py);
    for s in &r.qois {
        let q = PyDict::new(py);
        q.set_item("quantity", &s.name)?;
        q.set_item("unit", &s.unit)?;
        q.set_item("mean", s.mean)?;
        q.set_item("std", s.std)?;
        q.set_item("skewness", s.skewness)?;
        q.set_item("min", s.min)?;
        q.set_item("max", s.max)?;
        q.set_item("mean_ci_half_width", s.mean_ci_half_width)?;
        q.set_item("quantiles", s.quantiles.clone())?;
        q.set_item("bandwidth", s.bandwidth)?;
        let kx: Vec<f64> = s.kde.iter().map(|p| p.0).collect();
        let ky: Vec<f64> = s.kde.iter().map(|p| p.1).collect();
        q.set_item("kde_x", array1(py, kx))?;
        q.set_item("kde_pdf", array1(py, ky))?;
        let f = PyList::empty(py);
        for fs in &s.failure {
            f.append((fs.threshold, fs.probability, fs.ci_low, fs.ci_high))?;
        }
        q.set_item("failure", f)?;
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
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if threads == Some(0) {
        return Err(value_error("threads must be at least 1"));
    }
    let pool = threads
        .map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build())
        .transpose()
        .map_err(|e| value_error(format!("thread pool: {e}")))?;
    let prog = PyProgress {
        callback: progress,
        done: AtomicUsize::new(0),
        total: AtomicUsize::new(0),
        error: Mutex::new(None),
    };
    let out = py.detach(|| match &pool {
        Some(p) => p.install(|| run(&path, &directory, restart, &prog)),
        None => run(&path, &directory, restart, &prog),
    });
    if let Some(e) = prog.error.lock().ok().and_then(|mut e| e.take()) {
        return Err(e);
    }
    let out = out.map_err(study_err)?;
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
    for (r, p) in &out.methods {
        methods.append(method_dict(py, r, p.as_ref(), d)?)?;
    }
    dict.set_item("methods", methods)?;
    Ok(dict)
}

/// The study hash recorded in a store's database (read only).
fn stored_hash(dir: &Path) -> PyResult<String> {
    let db = dir.join("study.db");
    let conn =
        rusqlite::Connection::open_with_flags(&db, rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY)
            .map_err(|e| value_error(format!("{}: {e}", db.display())))?;
    conn.query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
        r.get::<_, String>(0)
    })
    .map_err(|e| value_error(format!("{}: not a study store ({e})", db.display())))
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
    if !directory.join("study.db").is_file() {
        return Err(PyFileNotFoundError::new_err(format!(
            "{}: no study store here (no study.db)",
            directory.display()
        )));
    }
    let dict = PyDict::new(py);
    let (hash, info) = match study {
        Some(path) => {
            let s = py.detach(|| Study::load(&path)).map_err(study_err)?;
            (s.hash.clone(), Some(StudyInfo::of(&s)))
        }
        None => (stored_hash(&directory)?, None),
    };
    let records = Store::open(&directory, &hash, false)
        .and_then(|s| s.runs())
        .map_err(study_err)?;
    let d = match &info {
        Some(i) => i.parameters.len(),
        None => records.first().map_or(0, |r| r.params.len()),
    };
    let m = match &info {
        Some(i) => i.quantities.len(),
        None => records.iter().map(|r| r.qois.len()).max().unwrap_or(0),
    };
    if let Some(i) = &info {
        i.to_dict(py, &dict)?;
    }
    dict.set_item("study_hash", hash)?;
    dict.set_item("directory", directory.display().to_string())?;
    dict.set_item("runs", records_dict(py, &records, d, m)?)?;
    Ok(dict)
}
