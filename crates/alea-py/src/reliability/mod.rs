//! Rare-event probabilities from Python: FORM, SORM, importance sampling and subset simulation
//! of `alea_uq::reliability` on a Python callable or a fitted surrogate ([`model`]).
//!
//! The failure event is `g(X) <= 0` for a model `g` or, with `threshold = t`, `q(X) > t` for a
//! model `q` (the limit state `g = t - q`), with `X` distributed as the law (a `Joint`, a `Law`
//! or a list of `Law`s), analysed in the independent standard normal space `u` of the law
//! (`x = T^-1(u)`: Nataf for the Gaussian copula, Rosenblatt otherwise).
//!
//! * FORM is started from the median point and from `+-3` along every axis of the standard
//!   normal space (`2 d + 1` starts, as `[[reliability]]` tables of study files do) or from the
//!   given `starts` (`alea_uq::reliability::form_from_starts`); the distinct design points
//!   (apart by more than 10 % of the smaller `beta`) are all returned, the best is the one of
//!   smallest `beta`, and a warning says so when more than one lies within `beta_min + 1`:
//!   FORM, SORM and importance sampling around one design point then miss the others' share
//!   of the probability.
//! * SORM (Breitung, Tvedt) at the best design point (`form(...,
//!   second_order=True)`, which the Python package calls `alea.sorm`).
//! * Importance sampling centred at the best design point, drawn in rounds of 2 048 until its
//!   coefficient of variation reaches `target_cov` (a warning if `max_draws` came first).
//! * Subset simulation (Au & Beck) from the median, with its log-normal interval.
//!
//! The transform `x = T^-1(u)` saturates at the marginal quantiles of `Phi(+-8.2)` where the
//! law's own would return an infinite coordinate ([`tail`]), so the model is never called at
//! an infinite point.
//!
//! Every argument is checked before anything is evaluated; a bad one is a `ValueError` (or a
//! `TypeError` for a wrong type) naming it.

mod model;
mod result;

use std::sync::Arc;

use alea_uq::joint::JointLaw;
use alea_uq::reliability::{
    FormOptions, FormResult, ImportanceOptions, LimitState, SubsetOptions, axis_starts,
    form_from_starts, importance_sampling, sorm_at, subset_simulation,
};
use pyo3::exceptions::{PyRuntimeWarning, PyTypeError};
use pyo3::prelude::*;

pub use result::ReliabilityResult;

use crate::convert::{ArrayIn, NonNegative, points, value_error};
use crate::laws::law_arg;
use model::Model;

/// An integer argument `name >= min` (any Python int: a negative or huge value is a
/// `ValueError` naming the argument, not an `OverflowError`).
fn count(obj: &Bound<'_, PyAny>, name: &str, min: usize) -> PyResult<usize> {
    if obj.is_instance_of::<pyo3::types::PyFloat>() {
        return Err(PyTypeError::new_err(format!(
            "{name} must be an integer, got a float ({obj})"
        )));
    }
    let v: i128 = match obj.extract::<i128>() {
        Ok(v) => v,
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
            return Err(value_error(format!(
                "{name} must be an integer >= {min}, got {obj} (too large)"
            )));
        }
        Err(_) => {
            return Err(PyTypeError::new_err(format!(
                "{name} must be an integer, got {}",
                obj.get_type()
                    .name()
                    .map_or_else(|_| "another object".to_string(), |n| n.to_string())
            )));
        }
    };
    usize::try_from(v)
        .ok()
        .filter(|&n| n >= min)
        .ok_or_else(|| value_error(format!("{name} must be an integer >= {min}, got {v}")))
}

/// A real argument that must satisfy `ok` (`requirement` says how, for the message).
fn real(v: f64, name: &str, requirement: &str, ok: impl Fn(f64) -> bool) -> PyResult<f64> {
    if v.is_finite() && ok(v) {
        Ok(v)
    } else {
        Err(value_error(format!(
            "{name} must be {requirement}, got {v}"
        )))
    }
}

/// The law, the model and the threshold of an analysis, checked.
struct Problem<'a> {
    law: Arc<dyn JointLaw>,
    model: Model<'a>,
    threshold: Option<f64>,
}

impl<'a> Problem<'a> {
    fn new(
        model: &'a Bound<'_, PyAny>,
        law: &Bound<'_, PyAny>,
        threshold: Option<f64>,
        what: &str,
    ) -> PyResult<Self> {
        let arg = law_arg(law, &format!("{what} law"))?;
        // The laws' own maps from the standard normal space are finite in the far tails
        // (`alea_uq::law::Marginal::quantile_of_normal`).
        let law: Arc<dyn JointLaw> = arg.joint;
        let model = Model::of(model, law.dim(), what)?;
        if let Model::Grid(pl) = &model {
            pl.check_law(law.as_ref(), what)?;
        }
        if let Some(t) = threshold {
            real(t, "threshold", "a finite number", |_| true)?;
        }
        Ok(Self {
            law,
            model,
            threshold,
        })
    }

    /// Runs `analysis` on the limit state (in the worker the model needs), then issues its
    /// warnings as `RuntimeWarning`s.
    fn run(
        &self,
        py: Python<'_>,
        analysis: impl FnOnce(&LimitState) -> Result<ReliabilityResult, String> + Send,
    ) -> PyResult<ReliabilityResult> {
        let out = self.model.run(py, || {
            let q = |x: &[f64]| self.model.eval(x);
            let ls = match self.threshold {
                Some(t) => LimitState::exceedance(self.law.as_ref(), q, t),
                None => LimitState::new(self.law.as_ref(), q),
            };
            analysis(&ls).map(|mut r| {
                r.calls = ls.calls();
                r
            })
        })?;
        let r = out.map_err(value_error)?;
        let category = py.get_type::<PyRuntimeWarning>();
        for w in &r.warnings {
            let text = std::ffi::CString::new(w.replace('\0', " "))
                .map_err(|e| value_error(e.to_string()))?;
            PyErr::warn(py, &category, &text, 1)?;
        }
        Ok(r)
    }
}

/// FORM options and starts, checked.
struct FormSetup {
    opts: FormOptions,
    starts: Vec<Option<Vec<f64>>>,
}

impl FormSetup {
    fn new(
        d: usize,
        starts: Option<ArrayIn<'_>>,
        tol: f64,
        max_iter: &Bound<'_, PyAny>,
        step: f64,
    ) -> PyResult<Self> {
        let opts = FormOptions {
            max_iter: count(max_iter, "max_iter", 1)?,
            tol: real(tol, "tol", "> 0", |v| v > 0.0)?,
            step: real(step, "step", "> 0", |v| v > 0.0)?,
            start: None,
        };
        let starts = match starts {
            Some(s) => {
                let (v, n) = points(&s, d, "starts")?;
                if n == 0 {
                    return Err(value_error("starts: at least one starting point is needed"));
                }
                v.chunks(d).map(|u| Some(u.to_vec())).collect()
            }
            None => axis_starts(d),
        };
        Ok(Self { opts, starts })
    }

    /// FORM from every start: the result of the best design point (smallest `beta`, with the
    /// options that found it), every distinct design point, and the warning on several.
    fn run(
        &self,
        ls: &LimitState,
        method: &'static str,
    ) -> Result<(ReliabilityResult, FormOptions, FormResult), String> {
        let starts = form_from_starts(ls, &self.starts, &self.opts);
        let warnings = starts.several_design_points().into_iter().collect();
        let found = starts.found;
        let Some((f, opts)) = starts.best else {
            return Err(format!(
                "FORM: no start converged ({} starts): {}",
                self.starts.len(),
                starts.first_error.unwrap_or_default()
            ));
        };
        let r = ReliabilityResult {
            method,
            pf: f.pf,
            interval: None,
            level: None,
            cov: None,
            beta: Some(f.beta),
            design_point: Some(f.x_star.clone()),
            design_point_u: Some(f.u_star.clone()),
            importance_factors: Some(f.importance_factors()),
            design_points: found.iter().map(|g| (g.beta, g.x_star.clone())).collect(),
            curvatures: None,
            pf_breitung: None,
            pf_tvedt: None,
            calls: 0,
            warnings,
            dim: ls.dim(),
        };
        Ok((r, opts, f))
    }
}

/// FORM: the first-order reliability method, `pf ~ Phi(-beta)` at the design point; with
/// `second_order`, SORM there (`alea.sorm`).
///
/// Parameters
/// ----------
/// model : callable, PolynomialChaos or PiecewiseLinear
///     A callable takes an `(n, d)` NumPy array of points and returns `n` values (e.g.
///     `lambda x: 3.0 - x[:, 0] - x[:, 1]`); at present it is called with one point at a time
///     (`n = 1`). A surrogate is evaluated in Rust, without Python calls.
/// law : Joint, Law or list of Law
///     The law of the `d` variables (a PiecewiseLinear needs a law supported in its box).
/// threshold : float, optional
///     Without it, failure is `model(x) <= 0`; with it, `model(x) > threshold`.
/// starts : array (k, d), optional
///     FORM starting points in the standard normal space (default: the median point and `+-3`
///     along every axis).
/// tol, max_iter, step
///     HL-RF tolerance, iteration limit and finite-difference step (standard normal space).
/// second_order : bool
///     SORM at the best design point: `pf` is then Breitung's formula
///     `Phi(-beta) prod_i (1 + beta kappa_i)^-1/2`, with `pf_tvedt` Tvedt's three-term one and
///     the principal `curvatures`, from the Hessian at the best design point (`2 d^2 + 1`
///     more calls).
///
/// Returns
/// -------
/// ReliabilityResult
///     `pf`, `beta`, the design point, importance factors, every distinct design point, calls
///     and warnings (no interval: FORM and SORM are asymptotic approximations).
///
/// Raises
/// ------
/// ValueError
///     A bad argument, a model value that is not finite, no FORM start converging, or (SORM)
///     a curvature with `1 + beta kappa <= 0`. Any exception the callable raises propagates
///     unchanged.
#[pyfunction]
#[pyo3(name = "form", signature = (model, law, *, threshold = None, starts = None, tol = 1e-6, max_iter = None, step = 1e-4, second_order = false),
    text_signature = "(model, law, *, threshold=None, starts=None, tol=1e-06, max_iter=100, step=0.0001, second_order=False)")]
#[allow(clippy::too_many_arguments)]
pub fn form_py(
    py: Python<'_>,
    model: &Bound<'_, PyAny>,
    law: &Bound<'_, PyAny>,
    threshold: Option<f64>,
    starts: Option<ArrayIn<'_>>,
    tol: f64,
    max_iter: Option<&Bound<'_, PyAny>>,
    step: f64,
    second_order: bool,
) -> PyResult<ReliabilityResult> {
    let what = if second_order { "sorm" } else { "form" };
    let p = Problem::new(model, law, threshold, what)?;
    let setup = form_setup(py, p.law.dim(), starts, tol, max_iter, step)?;
    p.run(py, |ls| {
        if !second_order {
            return setup.run(ls, "FORM").map(|r| r.0);
        }
        let (mut r, opts, f) = setup.run(ls, "SORM")?;
        let s = sorm_at(ls, f, &opts).map_err(|e| format!("SORM: {e}"))?;
        r.pf = s.pf_breitung;
        r.pf_breitung = Some(s.pf_breitung);
        r.pf_tvedt = Some(s.pf_tvedt);
        r.curvatures = Some(s.curvatures);
        Ok(r)
    })
}

fn form_setup(
    py: Python<'_>,
    d: usize,
    starts: Option<ArrayIn<'_>>,
    tol: f64,
    max_iter: Option<&Bound<'_, PyAny>>,
    step: f64,
) -> PyResult<FormSetup> {
    let default = pyo3::types::PyInt::new(py, FormOptions::default().max_iter);
    FormSetup::new(d, starts, tol, max_iter.unwrap_or(&default), step)
}

/// Importance sampling centred at the FORM design point, `u ~ N(u*, I)`, drawn in rounds of
/// 2 048 until the coefficient of variation is at most `target_cov`.
///
/// Parameters
/// ----------
/// model, law, threshold, starts
///     As `form` (FORM finds the design point first).
/// target_cov : float
///     Target coefficient of variation, in (0, 1) (default 0.05).
/// max_draws : int
///     Largest number of draws, >= 2048 (default 10^6; a warning if reached first).
/// level : float
///     Confidence level of the interval `pf +- z sd / sqrt(N)`, in (0, 1).
/// seed : int
///     Seed (the result does not depend on the thread count).
///
/// Returns
/// -------
/// ReliabilityResult
///     `pf`, `interval`, `cov`, `calls` (FORM's included), the design point(s) and warnings
///     (several design points: compare with `subset_simulation`).
#[pyfunction]
#[pyo3(name = "importance_sampling", signature = (model, law, *, threshold = None, target_cov = 0.05, max_draws = None, level = 0.95, seed = NonNegative(1), starts = None),
    text_signature = "(model, law, *, threshold=None, target_cov=0.05, max_draws=1000000, level=0.95, seed=1, starts=None)")]
#[allow(clippy::too_many_arguments)]
pub fn importance_sampling_py(
    py: Python<'_>,
    model: &Bound<'_, PyAny>,
    law: &Bound<'_, PyAny>,
    threshold: Option<f64>,
    target_cov: f64,
    max_draws: Option<&Bound<'_, PyAny>>,
    level: f64,
    seed: NonNegative<u64>,
    starts: Option<ArrayIn<'_>>,
) -> PyResult<ReliabilityResult> {
    let p = Problem::new(model, law, threshold, "importance_sampling")?;
    let max_draws = match max_draws {
        Some(m) => count(m, "max_draws", 2048)?,
        None => ImportanceOptions::default().max_draws,
    };
    let opts = ImportanceOptions {
        target_cov: real(target_cov, "target_cov", "in (0, 1)", |v| {
            v > 0.0 && v < 1.0
        })?,
        max_draws,
        level: real(level, "level", "in (0, 1)", |v| v > 0.0 && v < 1.0)?,
        seed: seed.0,
    };
    let setup = form_setup(py, p.law.dim(), starts, 1e-6, None, 1e-4)?;
    p.run(py, |ls| {
        let (mut r, _, f) = setup.run(ls, "importance sampling")?;
        let before = ls.calls();
        let e =
            importance_sampling(ls, &f, &opts).map_err(|e| format!("importance sampling: {e}"))?;
        let draws = ls.calls() - before;
        r.pf = e.p;
        r.interval = Some((e.lower, e.upper));
        r.level = Some(e.level);
        r.cov = e.cov.is_finite().then_some(e.cov);
        if e.p == 0.0 {
            r.warnings.push(format!(
                "importance sampling drew no failure in {draws} draws: pf is 0 with a zero-width \
                 interval; check the design point, or use subset simulation"
            ));
        } else if e.cov > opts.target_cov {
            r.warnings.push(format!(
                "importance sampling stopped at max_draws ({draws} draws) with a coefficient of \
                 variation of {:.3}, above its target {}",
                e.cov, opts.target_cov
            ));
        }
        Ok(r)
    })
}

/// Subset simulation (Au & Beck 2001): nested failure domains at the `p0` quantile of each
/// level, conditional samples by the preconditioned Crank-Nicolson random walk.
///
/// Parameters
/// ----------
/// model, law, threshold
///     As `form`.
/// samples_per_level : int
///     Samples per level `N` (default 2000); `p0 N` must be a whole number dividing `N`.
/// p0 : float
///     Conditional probability of the intermediate levels, in (0, 0.5] (default 0.1).
/// rho : float
///     Correlation of the random-walk proposal, in [0, 1) (default 0.8).
/// max_levels : int
///     Largest number of levels, >= 1 (default 30; if the failure domain is not reached, `pf`
///     is 0, the interval `(0, p0^max_levels)` and a warning says so).
/// level : float
///     Confidence level of the interval `pf exp(+- z cov)`, in (0, 1).
/// seed : int
///     Seed (the result does not depend on the thread count).
///
/// Returns
/// -------
/// ReliabilityResult
///     `pf`, `interval`, `cov`, `calls` (no design point).
#[pyfunction]
#[pyo3(name = "subset_simulation", signature = (model, law, *, threshold = None, samples_per_level = None, p0 = 0.1, rho = 0.8, max_levels = None, level = 0.95, seed = NonNegative(1)),
    text_signature = "(model, law, *, threshold=None, samples_per_level=2000, p0=0.1, rho=0.8, max_levels=30, level=0.95, seed=1)")]
#[allow(clippy::too_many_arguments)]
pub fn subset_simulation_py(
    py: Python<'_>,
    model: &Bound<'_, PyAny>,
    law: &Bound<'_, PyAny>,
    threshold: Option<f64>,
    samples_per_level: Option<&Bound<'_, PyAny>>,
    p0: f64,
    rho: f64,
    max_levels: Option<&Bound<'_, PyAny>>,
    level: f64,
    seed: NonNegative<u64>,
) -> PyResult<ReliabilityResult> {
    let p = Problem::new(model, law, threshold, "subset_simulation")?;
    let defaults = SubsetOptions::default();
    let opts = SubsetOptions {
        samples_per_level: match samples_per_level {
            Some(n) => count(n, "samples_per_level", 1)?,
            None => defaults.samples_per_level,
        },
        p0: real(p0, "p0", "in (0, 0.5]", |v| v > 0.0 && v <= 0.5)?,
        rho: real(rho, "rho", "in [0, 1)", |v| (0.0..1.0).contains(&v))?,
        max_levels: match max_levels {
            Some(n) => count(n, "max_levels", 1)?,
            None => defaults.max_levels,
        },
        level: real(level, "level", "in (0, 1)", |v| v > 0.0 && v < 1.0)?,
        seed: seed.0,
    };
    let nc = opts.p0 * opts.samples_per_level as f64;
    if (nc - nc.round()).abs() > 1e-9
        || nc.round() < 1.0
        || !opts.samples_per_level.is_multiple_of(nc.round() as usize)
    {
        return Err(value_error(format!(
            "subset_simulation: p0 * samples_per_level = {nc} must be a whole number >= 1 \
             dividing samples_per_level = {}",
            opts.samples_per_level
        )));
    }
    p.run(py, |ls| {
        let e = subset_simulation(ls, &opts).map_err(|e| format!("subset simulation: {e}"))?;
        let mut warnings = Vec::new();
        if e.p == 0.0 {
            warnings.push(format!(
                "subset simulation did not reach the failure domain in {} levels: pf is below \
                 {:.3e} (the interval's upper bound)",
                opts.max_levels, e.upper
            ));
        }
        Ok(ReliabilityResult {
            method: "subset simulation",
            pf: e.p,
            interval: Some((e.lower, e.upper)),
            level: Some(e.level),
            cov: e.cov.is_finite().then_some(e.cov),
            beta: None,
            design_point: None,
            design_point_u: None,
            importance_factors: None,
            design_points: Vec::new(),
            curvatures: None,
            pf_breitung: None,
            pf_tvedt: None,
            calls: 0,
            warnings,
            dim: ls.dim(),
        })
    })
}
