//! The result of a reliability analysis as a Python object.

use numpy::PyArray1;
use pyo3::prelude::*;

use crate::convert::{MatrixResult, array1, array2};

/// The outcome of `alea.form`, `sorm`, `importance_sampling` or `subset_simulation`.
///
/// Attributes
/// ----------
/// method : str
///     `"FORM"`, `"SORM"`, `"importance sampling"` or `"subset simulation"`.
/// pf : float
///     The failure probability: `Phi(-beta)` (FORM), Breitung's formula (SORM), the estimate
///     (importance sampling, subset simulation).
/// interval : tuple of float or None
///     Its confidence interval at `level` (sampling methods; FORM and SORM are asymptotic
///     approximations without one).
/// level : float or None
///     Confidence level of `interval`.
/// cov : float or None
///     Coefficient of variation of the estimator (sampling methods; None when no failure was
///     drawn).
/// beta : float or None
///     FORM reliability index `|u*|` of the design point (negative when the median point
///     fails); None for subset simulation, which needs no design point.
/// generalised_beta : float
///     `-Phi^-1(pf)` (infinite when `pf` is 0).
/// design_point, design_point_u : ndarray or None
///     The design point in the law's variables and in the standard normal space.
/// importance_factors : ndarray or None
///     `alpha_i^2` at the design point (sum 1).
/// design_points, design_point_betas : ndarray
///     Every distinct design point FORM found from its starts, `(k, d)` in the law's
///     variables, smallest `beta` first, and their `beta`.
/// curvatures : ndarray or None
///     SORM's principal curvatures at the design point.
/// pf_breitung, pf_tvedt : float or None
///     SORM's two approximations.
/// calls : int
///     Evaluations of the model (every FORM start included).
/// warnings : list of str
///     Several design points, a target coefficient of variation not reached, no failure drawn
///     (each also issued as a `RuntimeWarning`).
#[pyclass(frozen, module = "alea", name = "ReliabilityResult")]
pub struct ReliabilityResult {
    pub(crate) method: &'static str,
    pub(crate) pf: f64,
    pub(crate) interval: Option<(f64, f64)>,
    pub(crate) level: Option<f64>,
    pub(crate) cov: Option<f64>,
    pub(crate) beta: Option<f64>,
    pub(crate) design_point: Option<Vec<f64>>,
    pub(crate) design_point_u: Option<Vec<f64>>,
    pub(crate) importance_factors: Option<Vec<f64>>,
    pub(crate) design_points: Vec<(f64, Vec<f64>)>,
    pub(crate) curvatures: Option<Vec<f64>>,
    pub(crate) pf_breitung: Option<f64>,
    pub(crate) pf_tvedt: Option<f64>,
    pub(crate) calls: usize,
    pub(crate) warnings: Vec<String>,
    pub(crate) dim: usize,
}

fn opt_array<'py>(py: Python<'py>, v: &Option<Vec<f64>>) -> Option<Bound<'py, PyArray1<f64>>> {
    v.as_ref().map(|v| array1(py, v.clone()))
}

#[pymethods]
impl ReliabilityResult {
    #[getter]
    fn method(&self) -> &'static str {
        self.method
    }
    #[getter]
    fn pf(&self) -> f64 {
        self.pf
    }
    #[getter]
    fn interval(&self) -> Option<(f64, f64)> {
        self.interval
    }
    #[getter]
    fn level(&self) -> Option<f64> {
        self.level
    }
    #[getter]
    fn cov(&self) -> Option<f64> {
        self.cov
    }
    #[getter]
    fn beta(&self) -> Option<f64> {
        self.beta
    }
    #[getter]
    fn generalised_beta(&self) -> f64 {
        -alea_uq::special::norm_quantile(self.pf)
    }
    #[getter]
    fn design_point<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        opt_array(py, &self.design_point)
    }
    #[getter]
    fn design_point_u<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        opt_array(py, &self.design_point_u)
    }
    #[getter]
    fn importance_factors<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        opt_array(py, &self.importance_factors)
    }
    #[getter]
    fn design_points<'py>(&self, py: Python<'py>) -> MatrixResult<'py> {
        let v = self
            .design_points
            .iter()
            .flat_map(|(_, x)| x.iter().copied())
            .collect();
        array2(py, v, self.design_points.len(), self.dim)
    }
    #[getter]
    fn design_point_betas<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.design_points.iter().map(|(b, _)| *b).collect())
    }
    #[getter]
    fn curvatures<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        opt_array(py, &self.curvatures)
    }
    #[getter]
    fn pf_breitung(&self) -> Option<f64> {
        self.pf_breitung
    }
    #[getter]
    fn pf_tvedt(&self) -> Option<f64> {
        self.pf_tvedt
    }
    #[getter]
    fn calls(&self) -> usize {
        self.calls
    }
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }
    fn __repr__(&self) -> String {
        let mut s = format!("ReliabilityResult({}: pf {:.4e}", self.method, self.pf);
        if let (Some((lo, hi)), Some(l)) = (self.interval, self.level) {
            s.push_str(&format!(" [{lo:.4e}, {hi:.4e}] at {:.0} %", 100.0 * l));
        }
        if let Some(c) = self.cov {
            s.push_str(&format!(", cov {c:.3}"));
        }
        if let Some(b) = self.beta {
            s.push_str(&format!(", beta {b:.4}"));
        }
        s.push_str(&format!(", {} calls", self.calls));
        if !self.warnings.is_empty() {
            s.push_str(&format!(", {} warning(s)", self.warnings.len()));
        }
        s.push(')');
        s
    }
}
