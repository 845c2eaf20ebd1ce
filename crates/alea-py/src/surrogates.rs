//! Surrogates built from arrays of points and values: polynomial chaos
//! (`alea_uq::surrogate::PcSurrogate`: regression, quadrature projection, sparse LARS) and
//! piecewise multilinear interpolation on a grid (`alea_uq::surrogate::StochasticMesh`).
//!
//! Both are linear in the run values, `q~(xi) = sum_k w_k(xi) q_k` (thesis (1.22));
//! `weights(points)` returns the dense `w_k` so that the same weights interpolate anything
//! computed per run (fields, other quantities).

use alea_uq::basis::{MultiIndexSet, PcBasis};
use alea_uq::joint::JointLaw;
use alea_uq::law::Marginal;
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::{
    LarsOptions, LarsReport, LinearSurrogate, PcExpansion, PcMethod, PcSurrogate, RunData,
    StochasticMesh,
};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::sync::Arc;

use crate::convert::{
    ArrayIn, MatrixResult, NonNegative, array1, array2, points, uq_err, value_error, vector,
};
use crate::laws::{independent_marginals, law_arg};

fn basis(m: &[Arc<dyn Marginal>], degree: usize, q: Option<f64>) -> PyResult<PcBasis> {
    let set = MultiIndexSet::hyperbolic(m.len(), degree, q.unwrap_or(1.0)).map_err(uq_err)?;
    PcBasis::new(m, set).map_err(uq_err)
}

/// The chaos basis of total degree `degree` (q-norm `q`) on the marginals of `law`, and the runs
/// `points` (`(K, d)`) with their `values` (`(K,)`).
fn basis_and_runs(
    law: &Bound<'_, PyAny>,
    degree: usize,
    q: Option<f64>,
    points: &ArrayIn<'_>,
    values: &ArrayIn<'_>,
) -> PyResult<(PcBasis, Vec<f64>, Vec<f64>)> {
    let m = independent_marginals(law, "PolynomialChaos law")?;
    let b = basis(&m, degree, q)?;
    let (p, k) = self::points(points, m.len(), "PolynomialChaos points")?;
    let v = vector(values, Some(k), "PolynomialChaos values")?;
    Ok((b, p, v))
}

/// Dense weights `w_k(x)` of a linear surrogate at each point, `(n, K)`.
fn dense_weights(sur: &(dyn LinearSurrogate + Sync), pts: &[f64], d: usize) -> Vec<f64> {
    let k = sur.num_runs();
    let mut out = vec![0.0; pts.len() / d * k];
    out.par_chunks_mut(k.max(1))
        .zip(pts.par_chunks(d))
        .for_each_init(Vec::new, |w, (row, x)| {
            sur.weights(x, w);
            for &(j, wj) in w.iter() {
                row[j] += wj;
            }
        });
    out
}

/// The `weights` method of a surrogate: dense `w_k(x)` at `points` (`(n, d)`), shape `(n, K)`.
fn weights_array<'py>(
    py: Python<'py>,
    sur: &(dyn LinearSurrogate + Sync),
    points: &ArrayIn<'py>,
    d: usize,
) -> MatrixResult<'py> {
    let (p, n) = self::points(points, d, "weights points")?;
    let out = py.detach(|| dense_weights(sur, &p, d));
    array2(py, out, n, sur.num_runs())
}

/// A polynomial chaos expansion `q~(x) = sum_a s_a Psi_a(x)` in the orthonormal polynomials of
/// independent marginals, fitted to run values.
///
/// Build it with `PolynomialChaos.regression`, `.projection` or `.lars`, or `.load` a saved
/// one. Statistics come from the coefficients: `mean = s_0`, `variance = sum_{a != 0} s_a^2`,
/// Sobol' indices from sums of squared coefficients.
#[pyclass(frozen, module = "alea", name = "PolynomialChaos")]
pub struct PolynomialChaos {
    sur: PcSurrogate,
    exp: PcExpansion,
    points: Vec<f64>,
    values: Vec<f64>,
    lars: Option<LarsReport>,
}

impl PolynomialChaos {
    fn new(
        sur: PcSurrogate,
        points: Vec<f64>,
        values: Vec<f64>,
        lars: Option<LarsReport>,
    ) -> PyResult<Self> {
        let exp = sur.expansion(&values).map_err(uq_err)?;
        Ok(Self {
            sur,
            exp,
            points,
            values,
            lars,
        })
    }
    fn dim(&self) -> usize {
        self.sur.basis().dim()
    }
    /// The expansion as a function of a point (`dim` coordinates), for the reliability methods.
    pub(crate) fn function(&self) -> (usize, impl Fn(&[f64]) -> f64 + Sync + '_) {
        (self.dim(), |x: &[f64]| self.exp.eval(x))
    }
}

#[pymethods]
impl PolynomialChaos {
    /// Least-squares chaos on the runs `points` (`(K, d)`) with values `values` (`(K,)`): basis
    /// of total degree `degree` (hyperbolic with q-norm `q` if given, `0 < q <= 1`) in the
    /// orthonormal polynomials of the marginals of `law` (independent variables).
    #[staticmethod]
    #[pyo3(signature = (law, degree, points, values, q = None))]
    fn regression(
        py: Python<'_>,
        law: &Bound<'_, PyAny>,
        degree: NonNegative<usize>,
        points: ArrayIn<'_>,
        values: ArrayIn<'_>,
        q: Option<f64>,
    ) -> PyResult<Self> {
        let degree = degree.0;
        let (b, p, v) = basis_and_runs(law, degree, q, &points, &values)?;
        let sur = py
            .detach(|| PcSurrogate::regression(b, &p))
            .map_err(uq_err)?;
        Self::new(sur, p, v, None)
    }

    /// Chaos by quadrature projection, `s_a = sum_k w_k q_k Psi_a(x_k)`, on a rule with nodes
    /// `nodes` (`(K, d)`) and weights `weights` (`(K,)`, summing to 1; see `alea.quadrature`).
    #[staticmethod]
    #[pyo3(signature = (law, degree, nodes, weights, values, q = None))]
    fn projection(
        law: &Bound<'_, PyAny>,
        degree: NonNegative<usize>,
        nodes: ArrayIn<'_>,
        weights: ArrayIn<'_>,
        values: ArrayIn<'_>,
        q: Option<f64>,
    ) -> PyResult<Self> {
        let degree = degree.0;
        let m = independent_marginals(law, "PolynomialChaos law")?;
        let b = basis(&m, degree, q)?;
        let (p, k) = points(&nodes, m.len(), "PolynomialChaos nodes")?;
        let w = vector(&weights, Some(k), "PolynomialChaos weights")?;
        let v = vector(&values, Some(k), "PolynomialChaos values")?;
        let rule = QuadratureRule::new(m.len(), p.clone(), w).map_err(uq_err)?;
        let sur = PcSurrogate::projection(b, &rule).map_err(uq_err)?;
        Self::new(sur, p, v, None)
    }

    /// Sparse chaos by hybrid least-angle regression (Blatman & Sudret 2011): LARS orders the
    /// candidate terms of the degree-`degree` basis, each prefix is scored by its corrected
    /// leave-one-out error and the best one is refitted by least squares.
    /// The path is OpenTURNS' (raw orthonormal columns, constant first): on the same points
    /// it keeps the same terms. `max_terms_fraction`: largest number of terms as a fraction of
    /// the runs (1: up to `runs - 1`); `stop_factor`: beyond 10 terms, stop once the error
    /// exceeds this factor times the best so far (or 0.5).
    #[staticmethod]
    #[pyo3(signature = (law, degree, points, values, q = None, max_terms_fraction = 1.0, stop_factor = 2.0))]
    fn lars(
        py: Python<'_>,
        law: &Bound<'_, PyAny>,
        degree: NonNegative<usize>,
        points: ArrayIn<'_>,
        values: ArrayIn<'_>,
        q: Option<f64>,
        max_terms_fraction: f64,
        stop_factor: f64,
    ) -> PyResult<Self> {
        let degree = degree.0;
        let (b, p, v) = basis_and_runs(law, degree, q, &points, &values)?;
        let opts = LarsOptions {
            max_terms_fraction,
            stop_factor,
        };
        let (sur, report) = py
            .detach(|| PcSurrogate::lars_with(b, &p, &v, &opts))
            .map_err(uq_err)?;
        Self::new(sur, p, v, Some(report))
    }

    /// Loads a chaos saved by `save` (JSON: basis, linear map, runs).
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        let (sur, runs) = PcSurrogate::load_json(&path).map_err(uq_err)?;
        if runs.values_per_run != 1 {
            return Err(value_error(format!(
                "{}: holds {} values per run; PolynomialChaos reads files with one",
                path.display(),
                runs.values_per_run
            )));
        }
        Self::new(sur, runs.points, runs.values, None)
    }

    /// Saves the chaos and its runs as JSON (every float round-trips exactly).
    fn save(&self, path: std::path::PathBuf) -> PyResult<()> {
        let runs = RunData {
            points: self.points.clone(),
            values: self.values.clone(),
            values_per_run: 1,
        };
        self.sur.save_json(&path, &runs).map_err(uq_err)
    }

    /// Values of the expansion at `points` (`(n, d)`), shape `(n,)`.
    fn predict<'py>(
        &self,
        py: Python<'py>,
        points: ArrayIn<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let d = self.dim();
        let (p, _) = self::points(&points, d, "predict points")?;
        let out = py.detach(|| p.par_chunks(d).map(|x| self.exp.eval(x)).collect());
        Ok(array1(py, out))
    }

    /// Dense weights `w_k(x)` at `points` (`(n, d)`), shape `(n, K)`: `predict(x) = w @ values`
    /// and `w @ F` interpolates any per-run array `F` (`(K, m)`) the same way.
    fn weights<'py>(&self, py: Python<'py>, points: ArrayIn<'py>) -> MatrixResult<'py> {
        weights_array(py, &self.sur, &points, self.dim())
    }

    /// Mean `E[q~] = s_0`.
    #[getter]
    fn mean(&self) -> f64 {
        self.exp.mean()
    }
    /// Variance `sum_{a != 0} s_a^2`.
    #[getter]
    fn variance(&self) -> f64 {
        self.exp.variance()
    }
    /// Standard deviation.
    #[getter]
    fn std(&self) -> f64 {
        self.exp.variance().sqrt()
    }
    /// First-order Sobol' indices, shape `(d,)`.
    fn sobol_first<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.exp.sobol_first())
    }
    /// Total Sobol' indices, shape `(d,)`.
    fn sobol_total<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.exp.sobol_total())
    }
    /// Sobol' index of exactly the group `variables` (e.g. `[0, 2]` is `S_13`); all groups sum
    /// to 1.
    fn sobol_index(&self, variables: Vec<usize>) -> PyResult<f64> {
        if let Some(v) = variables.iter().find(|&&v| v >= self.dim()) {
            return Err(value_error(format!(
                "sobol_index: variable {v} out of range (d = {})",
                self.dim()
            )));
        }
        Ok(self.exp.sobol_index(&variables))
    }
    /// Second-order interaction indices `S_ij`, symmetric `(d, d)` with a zero diagonal.
    fn sobol_second_order<'py>(&self, py: Python<'py>) -> MatrixResult<'py> {
        let d = self.dim();
        array2(py, self.exp.sobol_second_order(), d, d)
    }
    /// Coefficients `s_a`, in the order of `multi_indices`.
    #[getter]
    fn coefficients<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array1(py, self.exp.coefficients().to_vec())
    }
    /// Degrees of each basis term per variable, shape `(P, d)`.
    #[getter]
    fn multi_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u16>>> {
        let set = self.sur.basis().indices();
        let d = set.dim();
        let v: Vec<u16> = set.iter().flat_map(|a| a.iter().copied()).collect();
        numpy::ndarray::Array2::from_shape_vec((set.len(), d), v)
            .map(|a| numpy::IntoPyArray::into_pyarray(a, py))
            .map_err(|e| value_error(e.to_string()))
    }
    /// Normalised leave-one-out error `e_LOO` (regression and LARS; biased low when the basis
    /// was chosen on the same data).
    #[getter]
    fn loo_error(&self) -> PyResult<f64> {
        self.sur.loo_error(&self.values).map_err(uq_err)
    }
    /// Corrected leave-one-out error `T(P, K) e_LOO` (Chapelle et al.; Blatman & Sudret), the
    /// error to report (regression and LARS).
    #[getter]
    fn corrected_loo_error(&self) -> PyResult<f64> {
        self.sur.corrected_loo_error(&self.values).map_err(uq_err)
    }
    /// `"regression"`, `"projection"` or `"lars"`.
    #[getter]
    fn method(&self) -> &'static str {
        match (self.sur.method(), &self.lars) {
            (_, Some(_)) => "lars",
            (PcMethod::Regression, None) => "regression",
            (PcMethod::Projection, None) => "projection",
        }
    }
    /// LARS only: `(terms, corrected LOO error)` of each prefix examined, shape `(n, 2)`.
    #[getter]
    fn lars_path<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        self.lars
            .as_ref()
            .map(|r| {
                let v = r.path.iter().flat_map(|&(t, e)| [t as f64, e]).collect();
                array2(py, v, r.path.len(), 2)
            })
            .transpose()
    }
    /// Lower bound of the condition number of the design matrix (1 for projection).
    #[getter]
    fn condition_estimate(&self) -> f64 {
        self.sur.condition_estimate()
    }
    /// Warnings about the fit (ill-conditioning, too few points per coefficient).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.sur.warnings()
    }
    /// Number of runs `K`.
    #[getter]
    fn num_runs(&self) -> usize {
        self.sur.num_runs()
    }
    /// Number of variables `d`.
    #[getter(dim)]
    fn py_dim(&self) -> usize {
        self.dim()
    }
    fn __repr__(&self) -> String {
        format!(
            "PolynomialChaos({}, d={}, terms={}, runs={}, mean={}, std={})",
            self.method(),
            self.dim(),
            self.sur.basis().len(),
            self.sur.num_runs(),
            self.exp.mean(),
            self.exp.variance().sqrt()
        )
    }
}

/// Piecewise multilinear interpolation on a regular grid of the box `[lo, hi]` with `cells[j]`
/// cells in direction `j` (the thesis's stochastic finite elements; 1 to 6 variables).
///
/// The runs are the grid's nodes in the order of `PiecewiseLinear.nodes(lo, hi, cells)`
/// (first direction fastest): evaluate the model there and pass the values.
#[pyclass(frozen, module = "alea", name = "PiecewiseLinear")]
pub struct PiecewiseLinear {
    mesh: StochasticMesh,
    values: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
}

fn mesh(
    lo: &ArrayIn<'_>,
    hi: &ArrayIn<'_>,
    cells: &[usize],
) -> PyResult<(StochasticMesh, Vec<f64>, Vec<f64>)> {
    let lo = vector(lo, None, "PiecewiseLinear lo")?;
    let hi = vector(hi, Some(lo.len()), "PiecewiseLinear hi")?;
    let m = StochasticMesh::new(&lo, &hi, cells).map_err(uq_err)?;
    Ok((m, lo, hi))
}

impl PiecewiseLinear {
    /// Checks that `l` has the grid's dimension and a support inside the box (`what`: the
    /// caller, for the message).
    pub(crate) fn check_law(&self, l: &dyn JointLaw, what: &str) -> PyResult<()> {
        if l.dim() != self.lo.len() {
            return Err(value_error(format!(
                "{what}: the law has {} variables, the PiecewiseLinear grid has {}",
                l.dim(),
                self.lo.len()
            )));
        }
        let (a, b) = l.bounds();
        for j in 0..a.len() {
            let tol = 1e-12 * (self.hi[j] - self.lo[j]);
            if a[j] < self.lo[j] - tol || b[j] > self.hi[j] + tol {
                return Err(value_error(format!(
                    "{what}: variable {j} has support [{}, {}] outside the PiecewiseLinear grid's \
                     [{}, {}]; use a law supported in the box (uniform, truncated normal, ...)",
                    a[j], b[j], self.lo[j], self.hi[j]
                )));
            }
        }
        Ok(())
    }

    /// The interpolant as a function of a point inside the box, for the reliability methods.
    pub(crate) fn function(&self) -> (usize, impl Fn(&[f64]) -> f64 + Sync + '_) {
        (self.lo.len(), |x: &[f64]| {
            self.mesh.interpolate(x, &self.values)
        })
    }

    /// Moments `(E[q~], E[q~^2])` under `law`, whose support must lie in the box.
    fn moments(&self, law: &Bound<'_, PyAny>, order: usize) -> PyResult<(f64, f64)> {
        let l = law_arg(law, "PiecewiseLinear law")?.joint;
        self.check_law(l.as_ref(), "PiecewiseLinear moments")?;
        let pdf = |x: &[f64]| l.pdf(x);
        let ew = self.mesh.expected_weights(pdf, order).map_err(uq_err)?;
        let mass: f64 = ew.iter().sum();
        if !(mass > 0.0) {
            return Err(value_error(
                "PiecewiseLinear moments: the law has no mass on the grid",
            ));
        }
        let mean = ew.iter().zip(&self.values).map(|(w, q)| w * q).sum::<f64>() / mass;
        let m2 = self
            .mesh
            .weight_second_moments(pdf, order)
            .map_err(uq_err)?
            .iter()
            .map(|&(k, l, m)| {
                let f = if k == l { 1.0 } else { 2.0 };
                f * m * self.values[k] * self.values[l]
            })
            .sum::<f64>()
            / mass;
        Ok((mean, m2))
    }
}

#[pymethods]
impl PiecewiseLinear {
    #[new]
    fn py_new(
        lo: ArrayIn<'_>,
        hi: ArrayIn<'_>,
        cells: Vec<usize>,
        values: ArrayIn<'_>,
    ) -> PyResult<Self> {
        let (mesh, lo, hi) = mesh(&lo, &hi, &cells)?;
        let values = vector(&values, Some(mesh.num_runs()), "PiecewiseLinear values")?;
        Ok(Self {
            mesh,
            values,
            lo,
            hi,
        })
    }

    /// The grid's nodes (the runs), shape `(prod(cells[j] + 1), d)`, first direction fastest.
    #[staticmethod]
    fn nodes<'py>(
        py: Python<'py>,
        lo: ArrayIn<'py>,
        hi: ArrayIn<'py>,
        cells: Vec<usize>,
    ) -> MatrixResult<'py> {
        let (m, lo, _) = mesh(&lo, &hi, &cells)?;
        array2(py, m.run_points().to_vec(), m.num_runs(), lo.len())
    }

    /// Interpolated values at `points` (`(n, d)`, inside the box), shape `(n,)`.
    fn predict<'py>(
        &self,
        py: Python<'py>,
        points: ArrayIn<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let d = self.lo.len();
        let (p, _) = self::points(&points, d, "predict points")?;
        if let Some((i, x)) = p
            .chunks(d)
            .enumerate()
            .find(|(_, x)| self.mesh.locate(x).is_none())
        {
            return Err(value_error(format!(
                "predict: point {i} {x:?} is outside the grid [{:?}, {:?}]",
                self.lo, self.hi
            )));
        }
        let out = py.detach(|| {
            p.par_chunks(d)
                .map(|x| self.mesh.interpolate(x, &self.values))
                .collect()
        });
        Ok(array1(py, out))
    }

    /// Dense weights `w_k(x)` at `points`, shape `(n, K)` (at most `2^d` non-zero per row).
    fn weights<'py>(&self, py: Python<'py>, points: ArrayIn<'py>) -> MatrixResult<'py> {
        weights_array(py, &self.mesh, &points, self.lo.len())
    }

    /// `E[q~]` under `law` (supported in the box): `sum_k E[w_k] q_k`, each `E[w_k]` integrated
    /// with an `order`-point Gauss-Legendre rule per cell, divided by the computed mass of the
    /// law on the box.
    #[pyo3(signature = (law, order = 4))]
    fn mean(&self, law: &Bound<'_, PyAny>, order: usize) -> PyResult<f64> {
        Ok(self.moments(law, order)?.0)
    }

    /// `Var[q~]` under `law` (supported in the box), from `E[w_k w_l]` integrated as in `mean`.
    #[pyo3(signature = (law, order = 4))]
    fn variance(&self, law: &Bound<'_, PyAny>, order: usize) -> PyResult<f64> {
        let (m, m2) = self.moments(law, order)?;
        Ok((m2 - m * m).max(0.0))
    }

    /// Number of runs (grid nodes).
    #[getter]
    fn num_runs(&self) -> usize {
        self.mesh.num_runs()
    }
    fn __repr__(&self) -> String {
        format!(
            "PiecewiseLinear(lo={:?}, hi={:?}, runs={})",
            self.lo,
            self.hi,
            self.mesh.num_runs()
        )
    }
}
