//! # alea-py: the Python front door of alea
//!
//! The extension module `alea._core` (PyO3, stable ABI for CPython >= 3.9) behind the Python
//! package `alea` (`python/alea/`). It is a thin layer: it converts NumPy arrays to and from
//! the row-major slices of `alea-uq` and `alea-study`, checks shapes and finiteness, releases
//! the interpreter lock around long computations, and maps errors to Python exceptions. Every
//! number comes from the Rust crates.
//!
//! * [`laws`]: `Law` and its subclasses (`Normal`, `Uniform`, `TruncatedNormal`, `Lognormal`,
//!   `Beta`, `Gamma`, `Triangular`, `Empirical`, `Kde`), `fit`, and `Joint` (independent and
//!   copulas);
//! * [`designs`]: `monte_carlo`, `lhs`, `sobol`, `grid`, `pc_collocation`, `quadrature`;
//! * [`surrogates`]: `PolynomialChaos` (regression, projection, LARS; statistics, Sobol'
//!   indices, LOO errors, save/load) and `PiecewiseLinear`;
//! * [`fields`]: `KarhunenLoeve` (Galerkin KL of a random field on a P1 mesh, realisations with
//!   Gaussian, lognormal or bounded transforms);
//! * [`reliability`]: `form` (and SORM), `importance_sampling`, `subset_simulation` of a Python
//!   callable (vectorised, `(n, d)` points to `n` values) or of a fitted `PolynomialChaos` /
//!   `PiecewiseLinear` (evaluated in Rust), with `ReliabilityResult`;
//! * [`study`]: running a study file, reading a study directory's store and rebuilding its
//!   outputs (summary, samples, fields, HTML report), through `alea-pipeline` as the CLI does.
//!   Only with the cargo feature `solver` (default): without it (`--no-default-features`) the
//!   module is the UQ toolkit of `alea-uq` alone, `_core.SOLVER` is `False`, and the Python
//!   functions that need a solver (`alea.run`, `open_store`, `report`) raise
//!   `alea.SolverNotBuilt`.

use pyo3::prelude::*;

mod convert;
mod designs;
mod fields;
mod laws;
mod reliability;
#[cfg(feature = "solver")]
mod study;
mod surrogates;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SOLVER", cfg!(feature = "solver"))?;
    // Results independent of the thread count (faer's global dense kernels sequential).
    #[cfg(feature = "solver")]
    alea_study::use_sequential_dense_kernels();
    m.add_class::<laws::Law>()?;
    m.add("Normal", m.py().get_type::<laws::NormalLaw>())?;
    m.add("Uniform", m.py().get_type::<laws::UniformLaw>())?;
    m.add(
        "TruncatedNormal",
        m.py().get_type::<laws::TruncatedNormalLaw>(),
    )?;
    m.add("Lognormal", m.py().get_type::<laws::LognormalLaw>())?;
    m.add("Beta", m.py().get_type::<laws::BetaLaw>())?;
    m.add("Gamma", m.py().get_type::<laws::GammaLaw>())?;
    m.add("Triangular", m.py().get_type::<laws::TriangularLaw>())?;
    m.add("Empirical", m.py().get_type::<laws::EmpiricalLaw>())?;
    m.add("Kde", m.py().get_type::<laws::KdeLawPy>())?;
    m.add_class::<laws::JointPy>()?;
    m.add_function(wrap_pyfunction!(laws::fit, m)?)?;
    m.add_function(wrap_pyfunction!(designs::monte_carlo, m)?)?;
    m.add_function(wrap_pyfunction!(designs::lhs, m)?)?;
    m.add_function(wrap_pyfunction!(designs::sobol, m)?)?;
    m.add_function(wrap_pyfunction!(designs::grid, m)?)?;
    m.add_function(wrap_pyfunction!(designs::pc_collocation, m)?)?;
    m.add_function(wrap_pyfunction!(designs::quadrature, m)?)?;
    m.add_class::<surrogates::PolynomialChaos>()?;
    m.add_class::<surrogates::PiecewiseLinear>()?;
    m.add_class::<fields::KarhunenLoeve>()?;
    m.add_class::<reliability::ReliabilityResult>()?;
    m.add_function(wrap_pyfunction!(reliability::form_py, m)?)?;
    m.add_function(wrap_pyfunction!(reliability::importance_sampling_py, m)?)?;
    m.add_function(wrap_pyfunction!(reliability::subset_simulation_py, m)?)?;
    #[cfg(feature = "solver")]
    {
        m.add_function(wrap_pyfunction!(study::run_study_file, m)?)?;
        m.add_function(wrap_pyfunction!(study::read_store, m)?)?;
        m.add_function(wrap_pyfunction!(study::rebuild_outputs, m)?)?;
    }
    Ok(())
}
