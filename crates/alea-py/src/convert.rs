//! NumPy arrays in and out, and Rust errors as Python exceptions.
//!
//! Inputs are taken as array-likes (lists, scalars, arrays of any numeric dtype), converted to
//! contiguous `float64` by NumPy. Points are `(n, d)` arrays, row-major on the Rust side; a
//! 1-D array of `n` values is accepted as `n` points only when `d == 1`, so a shape is never
//! guessed. Sizes and finiteness are checked here, before any Rust routine sees the data.

#[cfg(feature = "solver")]
use alea_study::StudyError;
use alea_uq::UqError;
use numpy::ndarray::{Array2, IxDyn};
use numpy::{
    AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayLikeDyn,
    PyUntypedArrayMethods,
};
#[cfg(feature = "solver")]
use pyo3::exceptions::PyFileNotFoundError;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyFloat;

/// Any array-like input, converted to `float64`.
pub type ArrayIn<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;

/// A new two-dimensional NumPy array of `f64` handed to Python, or the Python error.
pub type MatrixResult<'py> = PyResult<Bound<'py, PyArray2<f64>>>;

/// A non-negative integer argument (a size, a count, a seed): a negative value, or one too
/// large for `T`, is a `ValueError` naming the value, not pyo3's bare `OverflowError`.
pub struct NonNegative<T>(pub T);

impl<'a, 'py, T: TryFrom<i128>> FromPyObject<'a, 'py> for NonNegative<T> {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let v: i128 = obj.extract().map_err(|e: PyErr| {
            if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) {
                value_error(format!(
                    "expected a non-negative integer within range, got {} (too large)",
                    obj.as_any()
                ))
            } else {
                e
            }
        })?;
        T::try_from(v).map(NonNegative).map_err(|_| {
            value_error(format!(
                "expected a non-negative integer within range, got {v}"
            ))
        })
    }
}

/// `ValueError(message)`.
pub fn value_error(message: impl Into<String>) -> PyErr {
    PyValueError::new_err(message.into())
}

/// A library error as a Python exception: file errors as `OSError`, the rest as `ValueError`
/// (every message names the object and the field).
pub fn uq_err(e: UqError) -> PyErr {
    match e {
        UqError::File { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// A study error as a Python exception: I/O errors as `OSError` (`FileNotFoundError` for a
/// missing file), input and computation errors as `ValueError` (input errors name the file,
/// line and field).
#[cfg(feature = "solver")]
pub fn study_err(e: StudyError) -> PyErr {
    let message = python_terms(&e.to_string());
    match &e {
        StudyError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(message)
        }
        StudyError::Io { .. } => PyOSError::new_err(message),
        _ => PyValueError::new_err(message),
    }
}

/// A message of the study crates, written for the command line, in the terms of `alea.run`:
/// `--restart` is `restart=True`, `--dir` is `directory=`, `--threads N` is `threads=N`, and
/// "`alea run STUDY --dir DIR`" is "`alea.run("STUDY", directory="DIR")`" ("`alea run`" alone
/// "`alea.run`").
#[cfg(feature = "solver")]
pub fn python_terms(message: &str) -> String {
    let mut out = rewrite_run_commands(message);
    for (cli, python) in [
        ("give --dir a directory", "give directory= a directory"),
        ("use another --dir", "pass another directory="),
        ("`alea run`", "`alea.run`"),
        ("--restart", "restart=True"),
        ("--threads ", "threads="),
        ("--dir", "directory="),
    ] {
        out = out.replace(cli, python);
    }
    out
}

/// Every "`alea run STUDY --dir DIR`" of `message` as "`alea.run('STUDY', directory='DIR')`".
#[cfg(feature = "solver")]
fn rewrite_run_commands(message: &str) -> String {
    const START: &str = "`alea run ";
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find(START) {
        let after = &rest[i + START.len()..];
        let Some(end) = after.find('`') else { break };
        let Some((study, dir)) = after[..end].split_once(" --dir ") else {
            out.push_str(&rest[..i + START.len()]);
            rest = after;
            continue;
        };
        out.push_str(&rest[..i]);
        out.push_str(&format!("`alea.run({study:?}, directory={dir:?})`"));
        rest = &after[end + 1..];
    }
    out.push_str(rest);
    out
}

/// A shape as Python prints it: `(3,)`, `(10, 2)`.
fn shape_str(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

fn data(a: &ArrayIn<'_>) -> Vec<f64> {
    a.as_array().iter().copied().collect()
}

fn check_finite(v: &[f64], what: &str) -> PyResult<()> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(value_error(format!(
            "{what}: entry {i} is {} (values must be finite)",
            v[i]
        ))),
        None => Ok(()),
    }
}

/// Points as a row-major `n x d` vector: a 2-D `(n, d)` array, or 1-D `(n,)` when `d == 1`.
/// Every coordinate must be finite.
pub fn points(a: &ArrayIn<'_>, d: usize, what: &str) -> PyResult<(Vec<f64>, usize)> {
    let shape = a.shape().to_vec();
    let n = match shape.as_slice() {
        [n, dd] if *dd == d => *n,
        [n] if d == 1 => *n,
        _ => {
            return Err(value_error(format!(
                "{what}: expected an array of shape (n, {d}){}, got shape {}",
                if d == 1 { " or (n,)" } else { "" },
                shape_str(&shape)
            )));
        }
    };
    let v = data(a);
    check_finite(&v, what)?;
    Ok((v, n))
}

/// A 1-D vector of finite values; `len`, if given, is its required length.
pub fn vector(a: &ArrayIn<'_>, len: Option<usize>, what: &str) -> PyResult<Vec<f64>> {
    let shape = a.shape().to_vec();
    let ok = match (shape.as_slice(), len) {
        ([n], Some(l)) => *n == l,
        ([_], None) => true,
        _ => false,
    };
    if !ok {
        return Err(value_error(match len {
            Some(l) => format!(
                "{what}: expected a 1-D array of length {l}, got shape {}",
                shape_str(&shape)
            ),
            None => format!(
                "{what}: expected a 1-D array, got shape {}",
                shape_str(&shape)
            ),
        }));
    }
    let v = data(a);
    check_finite(&v, what)?;
    Ok(v)
}

/// A square `d x d` matrix, row-major.
pub fn square(a: &ArrayIn<'_>, d: usize, what: &str) -> PyResult<Vec<f64>> {
    if a.shape() != [d, d] {
        return Err(value_error(format!(
            "{what}: expected a ({d}, {d}) matrix, got shape {}",
            shape_str(a.shape())
        )));
    }
    let v = data(a);
    check_finite(&v, what)?;
    Ok(v)
}

/// `f` applied to every entry; same shape as the input (a Python float for a scalar input).
pub fn elementwise<'py>(
    py: Python<'py>,
    x: &ArrayIn<'py>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = x.shape().to_vec();
    let out: Vec<f64> = x.as_array().iter().map(|&v| f(v)).collect();
    if shape.is_empty() {
        return Ok(PyFloat::new(py, out[0]).into_any());
    }
    let arr = numpy::ndarray::ArrayD::from_shape_vec(IxDyn(&shape), out)
        .map_err(|e| value_error(e.to_string()))?;
    Ok(PyArrayDyn::from_owned_array(py, arr).into_any())
}

/// A row-major `n x d` vector as an `(n, d)` array.
pub fn array2(
    py: Python<'_>,
    v: Vec<f64>,
    n: usize,
    d: usize,
) -> PyResult<Bound<'_, PyArray2<f64>>> {
    Array2::from_shape_vec((n, d), v)
        .map(|a| a.into_pyarray(py))
        .map_err(|e| value_error(format!("internal shape error: {e}")))
}

/// A vector as a 1-D array.
pub fn array1(py: Python<'_>, v: Vec<f64>) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}
