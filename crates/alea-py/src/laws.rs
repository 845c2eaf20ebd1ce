//! Laws: the marginals of `alea_uq::law` as Python classes deriving from `Law`, and joint laws
//! (`Joint`: independent, Gaussian copula (Nataf), Student, Clayton, Gumbel and Frank copulas
//! from `alea_uq::joint` / `alea_uq::copula`).
//!
//! Every number (densities, distribution functions, quantiles, moments, draws) is computed by
//! `alea-uq`; draws use its seeded, chunked streams, so `sample(n, seed)` is the same whatever
//! the number of threads.

use std::sync::Arc;

use alea_uq::copula::{ClaytonCopula, FrankCopula, GumbelCopula, StudentCopula};
use alea_uq::design::monte_carlo;
use alea_uq::fit::{Family, fit_best};
use alea_uq::joint::{GaussianCopula, Independent, JointLaw};
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::law::{
    Beta, Empirical, Gamma, KdeLaw, LogNormal, Marginal, Normal, Triangular, TruncatedNormal,
    Uniform,
};
use numpy::{PyArray1, PyArray2};
use pyo3::PyClass;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{
    ArrayIn, MatrixResult, NonNegative, array1, array2, elementwise, points, square, uq_err,
    value_error, vector,
};

/// A one-dimensional probability law (base class of `Normal`, `Uniform`, ...).
///
/// Methods work elementwise on scalars and arrays of any shape: `pdf`, `cdf`, `sf`
/// (`1 - cdf`, accurate in the upper tail), `quantile`. `sample(n, seed)` draws `n` values by
/// inversion from seeded streams (same result for any number of threads).
#[pyclass(subclass, frozen, module = "alea", name = "Law")]
pub struct Law {
    pub(crate) inner: Arc<dyn Marginal>,
    repr: String,
}

impl Law {
    fn new(inner: Arc<dyn Marginal>, repr: String) -> Self {
        Self { inner, repr }
    }
}

#[pymethods]
impl Law {
    /// Probability density at `x` (0 outside the support).
    fn pdf<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
        elementwise(py, &x, |v| self.inner.pdf(v))
    }
    /// Distribution function `P(X <= x)`.
    fn cdf<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
        elementwise(py, &x, |v| self.inner.cdf(v))
    }
    /// Survival function `P(X > x)`.
    fn sf<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
        elementwise(py, &x, |v| self.inner.sf(v))
    }
    /// Inverse distribution function at probabilities `p` in `[0, 1]`; a probability outside
    /// it (or NaN) is a `ValueError` naming it, not a silent NaN.
    fn quantile<'py>(&self, py: Python<'py>, p: ArrayIn<'py>) -> PyResult<Bound<'py, PyAny>> {
        if let Some(bad) = p.as_array().iter().find(|v| !(0.0..=1.0).contains(*v)) {
            return Err(value_error(format!(
                "quantile: probabilities must be in [0, 1], got {bad}"
            )));
        }
        elementwise(py, &p, |v| self.inner.quantile(v))
    }
    /// `n` independent draws (seeded: the same `seed` gives the same draws).
    #[pyo3(signature = (n, seed = NonNegative(0)))]
    #[pyo3(text_signature = "($self, n, seed=0)")]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        n: NonNegative<usize>,
        seed: NonNegative<u64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let n = n.0;
        let seed = seed.0;
        let joint = Independent::new(vec![self.inner.clone()]).map_err(uq_err)?;
        let d = py.detach(|| monte_carlo(&joint, n, seed));
        Ok(array1(py, d.points().to_vec()))
    }
    /// Expectation.
    #[getter]
    fn mean(&self) -> f64 {
        self.inner.mean()
    }
    /// Standard deviation.
    #[getter]
    fn std(&self) -> f64 {
        self.inner.std()
    }
    /// Variance.
    #[getter]
    fn variance(&self) -> f64 {
        self.inner.std().powi(2)
    }
    /// Closed support `(lo, hi)` (bounds may be infinite).
    #[getter]
    fn support(&self) -> (f64, f64) {
        self.inner.support()
    }
    /// Short name of the family, e.g. `"truncated normal"`.
    #[getter]
    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn __repr__(&self) -> String {
        self.repr.clone()
    }
}

/// The initializer of a `Law` subclass.
fn sub<S: PyClass<BaseType = Law>>(law: Law, s: S) -> PyClassInitializer<S> {
    PyClassInitializer::from(law).add_subclass(s)
}

fn law<M: Marginal + 'static>(r: alea_uq::Result<M>, repr: String) -> PyResult<Law> {
    Ok(Law::new(Arc::new(r.map_err(uq_err)?), repr))
}

/// Normal law `N(mean, std^2)`.
#[pyclass(extends = Law, frozen, module = "alea", name = "Normal")]
pub struct NormalLaw;

#[pymethods]
impl NormalLaw {
    #[new]
    #[pyo3(signature = (mean = 0.0, std = 1.0))]
    fn py_new(mean: f64, std: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(sub(
            law(
                Normal::new(mean, std),
                format!("Normal(mean={mean}, std={std})"),
            )?,
            Self,
        ))
    }
}

/// Uniform law on `[lo, hi]`.
#[pyclass(extends = Law, frozen, module = "alea", name = "Uniform")]
pub struct UniformLaw;

#[pymethods]
impl UniformLaw {
    #[new]
    fn py_new(lo: f64, hi: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(sub(
            law(Uniform::new(lo, hi), format!("Uniform(lo={lo}, hi={hi})"))?,
            Self,
        ))
    }
}

/// Normal law `N(mean, std^2)` truncated to `[lo, hi]` (bounds may be infinite; far tails are
/// handled in log space).
#[pyclass(extends = Law, frozen, module = "alea", name = "TruncatedNormal")]
pub struct TruncatedNormalLaw;

#[pymethods]
impl TruncatedNormalLaw {
    #[new]
    fn py_new(mean: f64, std: f64, lo: f64, hi: f64) -> PyResult<PyClassInitializer<Self>> {
        let r = format!("TruncatedNormal(mean={mean}, std={std}, lo={lo}, hi={hi})");
        Ok(sub(law(TruncatedNormal::new(mean, std, lo, hi), r)?, Self))
    }
}

/// Lognormal law: `ln X ~ N(mu, sigma^2)`. `Lognormal.from_mean_std(mean, std)` gives the law
/// with those moments.
#[pyclass(extends = Law, frozen, module = "alea", name = "Lognormal")]
pub struct LognormalLaw;

#[pymethods]
impl LognormalLaw {
    #[new]
    fn py_new(mu: f64, sigma: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(sub(
            law(
                LogNormal::new(mu, sigma),
                format!("Lognormal(mu={mu}, sigma={sigma})"),
            )?,
            Self,
        ))
    }
    /// The lognormal law of mean `mean` and standard deviation `std`.
    #[staticmethod]
    fn from_mean_std(py: Python<'_>, mean: f64, std: f64) -> PyResult<Py<LognormalLaw>> {
        let m = LogNormal::from_mean_std(mean, std).map_err(uq_err)?;
        let r = format!("Lognormal.from_mean_std(mean={mean}, std={std})");
        Py::new(py, sub(Law::new(Arc::new(m), r), Self))
    }
}

/// Beta law with shapes `alpha`, `beta` on `[lo, hi]`.
#[pyclass(extends = Law, frozen, module = "alea", name = "Beta")]
pub struct BetaLaw;

#[pymethods]
impl BetaLaw {
    #[new]
    #[pyo3(signature = (alpha, beta, lo = 0.0, hi = 1.0))]
    fn py_new(alpha: f64, beta: f64, lo: f64, hi: f64) -> PyResult<PyClassInitializer<Self>> {
        let r = format!("Beta(alpha={alpha}, beta={beta}, lo={lo}, hi={hi})");
        Ok(sub(law(Beta::new(alpha, beta, lo, hi), r)?, Self))
    }
}

/// Gamma law with shape `k`, scale `theta` and location `loc`.
#[pyclass(extends = Law, frozen, module = "alea", name = "Gamma")]
pub struct GammaLaw;

#[pymethods]
impl GammaLaw {
    #[new]
    #[pyo3(signature = (shape, scale, loc = 0.0))]
    fn py_new(shape: f64, scale: f64, loc: f64) -> PyResult<PyClassInitializer<Self>> {
        let r = format!("Gamma(shape={shape}, scale={scale}, loc={loc})");
        Ok(sub(law(Gamma::new(shape, scale, loc), r)?, Self))
    }
}

/// Triangular law on `[lo, hi]` with mode `mode`.
#[pyclass(extends = Law, frozen, module = "alea", name = "Triangular")]
pub struct TriangularLaw;

#[pymethods]
impl TriangularLaw {
    #[new]
    fn py_new(lo: f64, mode: f64, hi: f64) -> PyResult<PyClassInitializer<Self>> {
        let r = format!("Triangular(lo={lo}, mode={mode}, hi={hi})");
        Ok(sub(law(Triangular::new(lo, mode, hi), r)?, Self))
    }
}

/// Empirical law of data (linearly interpolated empirical distribution function).
#[pyclass(extends = Law, frozen, module = "alea", name = "Empirical")]
pub struct EmpiricalLaw;

#[pymethods]
impl EmpiricalLaw {
    #[new]
    fn py_new(data: ArrayIn<'_>) -> PyResult<PyClassInitializer<Self>> {
        let v = vector(&data, None, "Empirical data")?;
        let r = format!("Empirical(<{} values>)", v.len());
        Ok(sub(law(Empirical::new(&v), r)?, Self))
    }
}

fn bandwidth(b: &Bound<'_, PyAny>) -> PyResult<Bandwidth> {
    if let Ok(h) = b.extract::<f64>() {
        return Ok(Bandwidth::Fixed(h));
    }
    match b.extract::<String>()?.as_str() {
        "isj" => Ok(Bandwidth::Isj),
        "silverman" => Ok(Bandwidth::Silverman),
        other => Err(value_error(format!(
            "bandwidth: unknown rule '{other}'; expected 'isj', 'silverman' or a number"
        ))),
    }
}

/// A Gaussian kernel density estimate of data used as a law; `bandwidth` is `"isj"`
/// (improved Sheather-Jones, the default), `"silverman"` or a number.
#[pyclass(extends = Law, frozen, module = "alea", name = "Kde")]
pub struct KdeLawPy {
    bandwidth: f64,
}

#[pymethods]
impl KdeLawPy {
    #[new]
    #[pyo3(signature = (data, bandwidth = None))]
    fn py_new(
        data: ArrayIn<'_>,
        bandwidth: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let v = vector(&data, None, "Kde data")?;
        let bw = match bandwidth {
            Some(b) => self::bandwidth(b)?,
            None => Bandwidth::Isj,
        };
        let kde = Kde::new(&v, bw).map_err(uq_err)?;
        let h = kde.bandwidth();
        let r = format!("Kde(<{} values>, bandwidth={h})", v.len());
        Ok(sub(
            Law::new(Arc::new(KdeLaw::new(kde)), r),
            Self { bandwidth: h },
        ))
    }
    /// The kernel bandwidth.
    #[getter]
    fn bandwidth(&self) -> f64 {
        self.bandwidth
    }
}

/// Fits the usual families to `data` by maximum likelihood and ranks them by BIC (best first).
///
/// `families`: names among `"normal"`, `"lognormal"`, `"uniform"`, `"gamma"` and
/// `("beta", lo, hi)` (beta on given bounds); default: the first four. Returns a list of dicts
/// with `law` (a `Law`), `family`, `parameters`, `log_likelihood`, `aic`, `bic`, `ks`
/// (Kolmogorov-Smirnov statistic), `ks_pvalue` (conservative with estimated parameters) and
/// `anderson_darling`.
#[pyfunction]
#[pyo3(signature = (data, families = None))]
pub fn fit<'py>(
    py: Python<'py>,
    data: ArrayIn<'py>,
    families: Option<&Bound<'py, PyList>>,
) -> PyResult<Bound<'py, PyList>> {
    let v = vector(&data, None, "fit data")?;
    let fams = match families {
        None => vec![Family::Normal, Family::LogNormal, Family::Uniform, Family::Gamma],
        Some(list) => list
            .iter()
            .map(|f| {
                if let Ok((name, a, b)) = f.extract::<(String, f64, f64)>()
                    && name == "beta"
                {
                    return Ok(Family::Beta { a, b });
                }
                match f.extract::<String>()?.as_str() {
                    "normal" => Ok(Family::Normal),
                    "lognormal" => Ok(Family::LogNormal),
                    "uniform" => Ok(Family::Uniform),
                    "gamma" => Ok(Family::Gamma),
                    other => Err(value_error(format!(
                        "fit: unknown family '{other}'; expected normal, lognormal, uniform, gamma or ('beta', lo, hi)"
                    ))),
                }
            })
            .collect::<PyResult<Vec<_>>>()?,
    };
    let fitted = fit_best(&v, &fams).map_err(uq_err)?;
    let out = PyList::empty(py);
    for f in fitted {
        let d = PyDict::new(py);
        let params: Vec<String> = f
            .parameters
            .iter()
            .map(|(n, x)| format!("{n}={x}"))
            .collect();
        let repr = format!("{}({})", f.law.name(), params.join(", "));
        d.set_item("law", Py::new(py, Law::new(f.law.clone(), repr))?)?;
        d.set_item("family", f.law.name())?;
        let p = PyDict::new(py);
        for (n, x) in &f.parameters {
            p.set_item(*n, *x)?;
        }
        d.set_item("parameters", p)?;
        d.set_item("log_likelihood", f.log_likelihood)?;
        d.set_item("aic", f.aic)?;
        d.set_item("bic", f.bic)?;
        d.set_item("ks", f.ks)?;
        d.set_item("ks_pvalue", f.ks_pvalue)?;
        d.set_item("anderson_darling", f.anderson_darling)?;
        out.append(d)?;
    }
    Ok(out)
}

/// A joint law of `d` random variables: independent marginals (`correlation=None`) or a
/// Gaussian copula (Nataf) with the given correlation matrix of the normal scores. Other
/// copulas: `Joint.student`, `Joint.clayton`, `Joint.gumbel`, `Joint.frank`.
///
/// Points are `(n, d)` arrays. `to_unit` / `from_unit` are the isoprobabilistic map to
/// independent uniforms on `[0, 1]^d` and back; `to_standard_normal` / `from_standard_normal`
/// map to independent standard normals (the Nataf transform for the Gaussian copula).
#[pyclass(frozen, module = "alea", name = "Joint")]
pub struct JointPy {
    pub(crate) inner: Arc<dyn JointLaw>,
    pub(crate) marginals: Vec<Arc<dyn Marginal>>,
    marginal_objects: Vec<Py<Law>>,
    correlation: Option<Vec<f64>>,
    kind: &'static str,
}

/// Marginals and the Python objects they came from.
type Marginals = (Vec<Arc<dyn Marginal>>, Vec<Py<Law>>);

fn marginals_of(list: &Bound<'_, PyAny>) -> PyResult<Marginals> {
    let mut m = Vec::new();
    let mut objs = Vec::new();
    for item in list.try_iter()? {
        let item = item?;
        let law = item.cast::<Law>().map_err(|_| {
            PyTypeError::new_err("marginals: expected a list of alea laws (Normal, Uniform, ...)")
        })?;
        m.push(law.get().inner.clone());
        objs.push(law.clone().unbind());
    }
    if m.is_empty() {
        return Err(value_error("marginals: at least one law is needed"));
    }
    Ok((m, objs))
}

impl JointPy {
    fn build(
        marginals: &Bound<'_, PyAny>,
        make: impl FnOnce(Vec<Arc<dyn Marginal>>) -> PyResult<Arc<dyn JointLaw>>,
        correlation: Option<Vec<f64>>,
        kind: &'static str,
    ) -> PyResult<Self> {
        let (m, objs) = marginals_of(marginals)?;
        let inner = make(m.clone())?;
        Ok(Self {
            inner,
            marginals: m,
            marginal_objects: objs,
            correlation,
            kind,
        })
    }

    /// A copula of one parameter `theta` built by `new` (no correlation matrix).
    fn one_parameter<C: JointLaw + 'static>(
        marginals: &Bound<'_, PyAny>,
        theta: f64,
        new: fn(Vec<Arc<dyn Marginal>>, f64) -> alea_uq::error::Result<C>,
        kind: &'static str,
    ) -> PyResult<Self> {
        Self::build(
            marginals,
            move |m| Ok(Arc::new(new(m, theta).map_err(uq_err)?)),
            None,
            kind,
        )
    }

    fn dim(&self) -> usize {
        self.marginals.len()
    }

    fn map_points<'py>(
        &self,
        py: Python<'py>,
        x: ArrayIn<'py>,
        what: &str,
        f: impl Fn(&dyn JointLaw, &[f64], &mut [f64]) + Sync,
    ) -> MatrixResult<'py> {
        let d = self.dim();
        let (v, n) = points(&x, d, what)?;
        let law = self.inner.as_ref();
        let out = py.detach(|| {
            use rayon::prelude::*;
            let mut out = vec![0.0; v.len()];
            out.par_chunks_mut(d)
                .zip(v.par_chunks(d))
                .for_each(|(o, p)| f(law, p, o));
            out
        });
        array2(py, out, n, d)
    }
}

#[pymethods]
impl JointPy {
    #[new]
    #[pyo3(signature = (marginals, correlation = None))]
    fn py_new(marginals: &Bound<'_, PyAny>, correlation: Option<ArrayIn<'_>>) -> PyResult<Self> {
        let (m, _) = marginals_of(marginals)?;
        match correlation {
            None => Self::build(
                marginals,
                |m| Ok(Arc::new(Independent::new(m).map_err(uq_err)?)),
                None,
                "independent",
            ),
            Some(c) => {
                let r = square(&c, m.len(), "correlation")?;
                let rc = r.clone();
                Self::build(
                    marginals,
                    move |m| Ok(Arc::new(GaussianCopula::new(m, rc).map_err(uq_err)?)),
                    Some(r),
                    "gaussian copula",
                )
            }
        }
    }

    /// Student copula with correlation matrix `correlation` and `nu` degrees of freedom.
    #[staticmethod]
    fn student(marginals: &Bound<'_, PyAny>, correlation: ArrayIn<'_>, nu: f64) -> PyResult<Self> {
        let (m, _) = marginals_of(marginals)?;
        let r = square(&correlation, m.len(), "correlation")?;
        let rc = r.clone();
        Self::build(
            marginals,
            move |m| Ok(Arc::new(StudentCopula::new(m, rc, nu).map_err(uq_err)?)),
            Some(r),
            "student copula",
        )
    }

    /// Clayton copula with parameter `theta > 0` (any dimension), or `-1 < theta < 0` (negative
    /// dependence, two variables).
    #[staticmethod]
    fn clayton(marginals: &Bound<'_, PyAny>, theta: f64) -> PyResult<Self> {
        Self::one_parameter(marginals, theta, ClaytonCopula::new, "clayton copula")
    }

    /// Gumbel copula with parameter `theta >= 1` (two variables).
    #[staticmethod]
    fn gumbel(marginals: &Bound<'_, PyAny>, theta: f64) -> PyResult<Self> {
        Self::one_parameter(marginals, theta, GumbelCopula::new, "gumbel copula")
    }

    /// Frank copula with parameter `theta != 0` (two variables).
    #[staticmethod]
    fn frank(marginals: &Bound<'_, PyAny>, theta: f64) -> PyResult<Self> {
        Self::one_parameter(marginals, theta, FrankCopula::new, "frank copula")
    }

    /// Number of variables.
    #[getter(dim)]
    fn py_dim(&self) -> usize {
        self.dim()
    }
    /// The marginal laws.
    #[getter]
    fn marginals(&self, py: Python<'_>) -> Vec<Py<Law>> {
        self.marginal_objects
            .iter()
            .map(|m| m.clone_ref(py))
            .collect()
    }
    /// Correlation matrix of the normal scores (Gaussian and Student copulas), else `None`.
    #[getter]
    fn correlation<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let d = self.dim();
        self.correlation
            .as_ref()
            .map(|c| array2(py, c.clone(), d, d))
            .transpose()
    }
    /// `"independent"`, `"gaussian copula"`, ...
    #[getter]
    fn kind(&self) -> &'static str {
        self.kind
    }
    /// Smallest box `(lo, hi)` containing the support (bounds may be infinite).
    #[getter]
    fn bounds<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        let (lo, hi) = self.inner.bounds();
        (array1(py, lo), array1(py, hi))
    }
    /// Joint density at the points `x` (`(n, d)`), shape `(n,)`.
    fn pdf<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let d = self.dim();
        let (v, _) = points(&x, d, "pdf points")?;
        let law = self.inner.as_ref();
        let out = py.detach(|| {
            use rayon::prelude::*;
            v.par_chunks(d).map(|p| law.pdf(p)).collect::<Vec<f64>>()
        });
        Ok(array1(py, out))
    }
    /// `n` independent draws, shape `(n, d)` (seeded; identical for any number of threads).
    #[pyo3(signature = (n, seed = NonNegative(0)))]
    #[pyo3(text_signature = "($self, n, seed=0)")]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        n: NonNegative<usize>,
        seed: NonNegative<u64>,
    ) -> MatrixResult<'py> {
        let (n, seed) = (n.0, seed.0);
        let law = self.inner.clone();
        let d = py.detach(move || monte_carlo(law.as_ref(), n, seed));
        array2(py, d.points().to_vec(), n, self.dim())
    }
    /// Map points `x` to independent uniforms on the unit cube.
    fn to_unit<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> MatrixResult<'py> {
        self.map_points(py, x, "to_unit points", |l, p, o| l.x_to_unit(p, o))
    }
    /// Map unit-cube points `u` to the law's space.
    #[pyo3(name = "from_unit")]
    fn unit_to_x<'py>(&self, py: Python<'py>, u: ArrayIn<'py>) -> MatrixResult<'py> {
        self.map_points(py, u, "from_unit points", |l, p, o| l.unit_to_x(p, o))
    }
    /// Map points `x` to independent standard normal variables.
    fn to_standard_normal<'py>(&self, py: Python<'py>, x: ArrayIn<'py>) -> MatrixResult<'py> {
        self.map_points(py, x, "to_standard_normal points", |l, p, o| {
            l.x_to_standard_normal(p, o)
        })
    }
    /// Map independent standard normal points `y` to the law's space.
    #[pyo3(name = "from_standard_normal")]
    fn standard_normal_to_x<'py>(&self, py: Python<'py>, y: ArrayIn<'py>) -> MatrixResult<'py> {
        self.map_points(py, y, "from_standard_normal points", |l, p, o| {
            l.standard_normal_to_x(p, o)
        })
    }
    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let m = self
            .marginal_objects
            .iter()
            .map(|o| Ok(o.bind(py).repr()?.to_string()))
            .collect::<PyResult<Vec<_>>>()?;
        Ok(format!("Joint({}, [{}])", self.kind, m.join(", ")))
    }
}

/// A law argument: a `Joint`, a `Law` (one variable) or a sequence of `Law`s (independent).
pub struct LawArg {
    /// The joint law.
    pub joint: Arc<dyn JointLaw>,
    /// Its marginals when the variables are independent.
    pub independent: Option<Vec<Arc<dyn Marginal>>>,
}

/// Reads a law argument (see [`LawArg`]).
pub fn law_arg(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<LawArg> {
    if let Ok(j) = obj.cast::<JointPy>() {
        let j = j.get();
        return Ok(LawArg {
            joint: j.inner.clone(),
            independent: (j.kind == "independent").then(|| j.marginals.clone()),
        });
    }
    if let Ok(l) = obj.cast::<Law>() {
        let m = vec![l.get().inner.clone()];
        return Ok(LawArg {
            joint: Arc::new(Independent::new(m.clone()).map_err(uq_err)?),
            independent: Some(m),
        });
    }
    if obj.try_iter().is_ok() {
        let (m, _) = marginals_of(obj)
            .map_err(|e| PyTypeError::new_err(format!("{what}: {}", e.value(obj.py()))))?;
        return Ok(LawArg {
            joint: Arc::new(Independent::new(m.clone()).map_err(uq_err)?),
            independent: Some(m),
        });
    }
    Err(PyTypeError::new_err(format!(
        "{what}: expected a Joint, a Law or a list of Laws"
    )))
}

/// The independent marginals of a law argument (polynomial chaos, collocation, quadrature).
pub fn independent_marginals(
    obj: &Bound<'_, PyAny>,
    what: &str,
) -> PyResult<Vec<Arc<dyn Marginal>>> {
    law_arg(obj, what)?.independent.ok_or_else(|| {
        value_error(format!(
            "{what}: needs independent variables; for a copula, work in the independent standard \
             normal variables (Joint.to_standard_normal / from_standard_normal)"
        ))
    })
}
