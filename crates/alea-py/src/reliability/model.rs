//! The model of a reliability analysis: a Python callable, or a fitted surrogate evaluated
//! without Python, and how an analysis runs on it.
//!
//! A Python callable is vectorised: it receives an `(n, d)` NumPy array of points and returns
//! `n` values (shape `(n,)` or `(n, 1)`). The algorithms of `alea_uq::reliability` evaluate the
//! limit state one point at a time, so it is called with `n = 1`; the contract is the
//! vectorised one so that a function written for it keeps working when points come in blocks.
//! An analysis on a callable runs on one worker thread of its own (one Python call at a time,
//! no contention for the interpreter lock) while the calling thread waits without the lock
//! and checks for signals every 50 ms, so Ctrl-C stops it. The first exception the callable
//! raises, a value it returns that is not a finite number, or a signal stops the analysis:
//! every later evaluation returns NaN at once without calling Python, the algorithm ends, and
//! that exception is raised.
//!
//! A surrogate (`PolynomialChaos`, `PiecewiseLinear`) is evaluated in Rust, in parallel, with
//! the interpreter lock released. Either way the results do not depend on the thread count.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

use numpy::{AllowTypeChange, PyArray1, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

use crate::surrogates::{PiecewiseLinear, PolynomialChaos};

/// A Python callable of an `(n, d)` array, with the first error it caused.
pub struct PyFunction {
    f: Py<PyAny>,
    d: usize,
    stop: AtomicBool,
    error: Mutex<Option<PyErr>>,
}

impl PyFunction {
    /// Records `e` unless an error is already recorded, and stops every later call.
    fn fail(&self, e: PyErr) {
        if let Ok(mut slot) = self.error.lock()
            && slot.is_none()
        {
            *slot = Some(e);
        }
        self.stop.store(true, Ordering::SeqCst);
    }

    /// `f(x)` for one point (an `(1, d)` array); NaN once stopped.
    fn eval(&self, x: &[f64]) -> f64 {
        if self.stop.load(Ordering::Relaxed) {
            return f64::NAN;
        }
        match Python::attach(|py| self.call(py, x)) {
            Ok(v) => v,
            Err(e) => {
                self.fail(e);
                f64::NAN
            }
        }
    }

    fn call(&self, py: Python<'_>, x: &[f64]) -> PyResult<f64> {
        let points = PyArray1::from_slice(py, x).reshape([1, self.d])?;
        let out = self.f.bind(py).call1((points,))?;
        if out.is_none() {
            return Err(PyTypeError::new_err(
                "the model must return an array of n numbers for an (n, d) array of points; it \
                 returned None",
            ));
        }
        let values: PyArrayLikeDyn<'_, f64, AllowTypeChange> = out.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "the model must return an array of n numbers for an (n, d) array of points; it \
                 returned {}",
                out.get_type()
                    .name()
                    .map_or_else(|_| "an object".to_string(), |n| format!("a {n}"))
            ))
        })?;
        let shape = values.shape().to_vec();
        if !(shape == [1] || shape == [1, 1]) {
            return Err(PyValueError::new_err(format!(
                "the model must return n values, shape (n,), for an (n, d) array of points; for \
                 1 point (shape (1, {})) it returned shape {shape:?}: write it vectorised, e.g. \
                 `lambda x: 3.0 - x[:, 0] - x[:, 1]`",
                self.d
            )));
        }
        let v = values.as_array().iter().copied().next().unwrap_or(f64::NAN);
        if !v.is_finite() {
            return Err(PyValueError::new_err(format!(
                "the model returned {v} at the point {x:?}: values must be finite numbers"
            )));
        }
        Ok(v)
    }
}

/// What is analysed: a Python callable or a fitted surrogate.
pub enum Model<'a> {
    /// A Python callable of an `(n, d)` array.
    Python(PyFunction),
    /// A polynomial chaos.
    Chaos(&'a PolynomialChaos),
    /// A piecewise-linear interpolant on a grid.
    Grid(&'a PiecewiseLinear),
}

impl<'a> Model<'a> {
    /// Reads the `model` argument for a law of `d` variables.
    ///
    /// # Errors
    /// `TypeError` if it is neither a surrogate nor callable; `ValueError` if a surrogate has
    /// another dimension than the law.
    pub fn of(obj: &'a Bound<'_, PyAny>, d: usize, what: &str) -> PyResult<Self> {
        let surrogate_dim = |sd: usize, kind: &str| {
            if sd == d {
                Ok(())
            } else {
                Err(PyValueError::new_err(format!(
                    "{what}: the {kind} has {sd} variables, the law {d}"
                )))
            }
        };
        if let Ok(pc) = obj.cast::<PolynomialChaos>() {
            let pc = pc.get();
            surrogate_dim(pc.function().0, "PolynomialChaos")?;
            return Ok(Model::Chaos(pc));
        }
        if let Ok(pl) = obj.cast::<PiecewiseLinear>() {
            let pl = pl.get();
            surrogate_dim(pl.function().0, "PiecewiseLinear")?;
            return Ok(Model::Grid(pl));
        }
        if obj.is_callable() {
            return Ok(Model::Python(PyFunction {
                f: obj.clone().unbind(),
                d,
                stop: AtomicBool::new(false),
                error: Mutex::new(None),
            }));
        }
        Err(PyTypeError::new_err(format!(
            "{what}: the model must be a callable of an (n, d) array of points returning n \
             values, a PolynomialChaos or a PiecewiseLinear; got {}",
            obj.get_type()
                .name()
                .map_or_else(|_| "another object".to_string(), |n| n.to_string())
        )))
    }

    /// The model's value at `x`.
    pub fn eval(&self, x: &[f64]) -> f64 {
        match self {
            Model::Python(f) => f.eval(x),
            Model::Chaos(pc) => (pc.function().1)(x),
            Model::Grid(pl) => (pl.function().1)(x),
        }
    }

    /// Runs `job` (an analysis evaluating this model) and returns its result, or the first
    /// error of the Python callable (its own exception, a non-finite value, or a signal).
    pub fn run<R: Send>(&self, py: Python<'_>, job: impl FnOnce() -> R + Send) -> PyResult<R> {
        let Model::Python(f) = self else {
            return Ok(py.detach(job));
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(|e| PyValueError::new_err(format!("thread pool: {e}")))?;
        let done = (Mutex::new(false), Condvar::new());
        let (pool, done) = (&pool, &done);
        let out = std::thread::scope(|s| {
            let worker = s.spawn(move || {
                let r = pool.install(job);
                if let Ok(mut d) = done.0.lock() {
                    *d = true;
                }
                done.1.notify_all();
                r
            });
            loop {
                let finished = py.detach(|| {
                    let Ok(guard) = done.0.lock() else {
                        return true;
                    };
                    done.1
                        .wait_timeout_while(guard, Duration::from_millis(50), |d| !*d)
                        .map_or(true, |(d, _)| *d)
                });
                if finished || worker.is_finished() {
                    break;
                }
                if let Err(e) = py.check_signals() {
                    f.fail(e);
                }
            }
            worker.join()
        });
        let out = out.map_err(|_| {
            pyo3::exceptions::PyRuntimeError::new_err("the reliability analysis panicked")
        })?;
        if let Some(e) = f.error.lock().ok().and_then(|mut e| e.take()) {
            return Err(e);
        }
        Ok(out)
    }
}
