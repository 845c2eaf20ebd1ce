//! Designs of experiments from `alea_uq::design` and quadrature rules from
//! `alea_uq::quadrature`, returned as `(n, d)` NumPy arrays (row `i` is point `i`).

use alea_uq::design::{
    latin_hypercube, latin_hypercube_maximin, monte_carlo as mc, pc_collocation as pcc,
    sobol as sobol_design, tensor_grid,
};
use alea_uq::quadrature::QuadratureRule;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::convert::{
    ArrayIn, MatrixResult, NonNegative, array1, array2, uq_err, value_error, vector,
};
use crate::laws::{independent_marginals, law_arg};

/// `n` independent draws of `law` (a `Joint`, a `Law` or a list of `Law`s), shape `(n, d)`.
/// Seeded: the same `seed` gives the same points for any number of threads.
#[pyfunction]
#[pyo3(signature = (law, n, seed = NonNegative(0)))]
#[pyo3(text_signature = "(law, n, seed=0)")]
pub fn monte_carlo<'py>(
    py: Python<'py>,
    law: &Bound<'py, PyAny>,
    n: NonNegative<usize>,
    seed: NonNegative<u64>,
) -> MatrixResult<'py> {
    let n = n.0;
    let seed = seed.0;
    let l = law_arg(law, "monte_carlo law")?.joint;
    let d = l.dim();
    let design = py.detach(move || mc(l.as_ref(), n, seed));
    array2(py, design.points().to_vec(), n, d)
}

/// Latin hypercube of `n` points of `law`: one point per stratum of probability `1/n` in each
/// direction, mapped through the law's isoprobabilistic map (so dependent laws work too).
/// `maximin=k` keeps the best of `k` hypercubes for the smallest pairwise distance.
#[pyfunction]
#[pyo3(signature = (law, n, seed = NonNegative(0), maximin = None))]
#[pyo3(text_signature = "(law, n, seed=0, maximin=None)")]
pub fn lhs<'py>(
    py: Python<'py>,
    law: &Bound<'py, PyAny>,
    n: NonNegative<usize>,
    seed: NonNegative<u64>,
    maximin: Option<NonNegative<usize>>,
) -> MatrixResult<'py> {
    let n = n.0;
    let seed = seed.0;
    let maximin = maximin.map(|v| v.0);
    let l = law_arg(law, "lhs law")?.joint;
    let d = l.dim();
    let design = py.detach(move || match maximin {
        Some(k) => latin_hypercube_maximin(l.as_ref(), n, seed, k),
        None => latin_hypercube(l.as_ref(), n, seed),
    });
    array2(py, design.points().to_vec(), n, d)
}

/// First `n` points of the Sobol' sequence (Joe-Kuo directions, up to 40 variables) mapped
/// through `law`; scrambled (linear matrix scramble and digital shift) when `scramble_seed` is
/// given.
#[pyfunction]
#[pyo3(signature = (law, n, scramble_seed = None))]
pub fn sobol<'py>(
    py: Python<'py>,
    law: &Bound<'py, PyAny>,
    n: NonNegative<usize>,
    scramble_seed: Option<u64>,
) -> MatrixResult<'py> {
    let n = n.0;
    let l = law_arg(law, "sobol law")?.joint;
    let d = l.dim();
    let design = py
        .detach(move || sobol_design(l.as_ref(), n, scramble_seed))
        .map_err(uq_err)?;
    array2(py, design.points().to_vec(), n, d)
}

/// Tensor grid on the box `[lo, hi]` with `counts[j]` equispaced nodes in direction `j`
/// (bounds included; one node is the centre); the last direction varies fastest.
#[pyfunction]
pub fn grid<'py>(
    py: Python<'py>,
    lo: ArrayIn<'py>,
    hi: ArrayIn<'py>,
    counts: Vec<usize>,
) -> MatrixResult<'py> {
    let lo = vector(&lo, None, "grid lo")?;
    let hi = vector(&hi, Some(lo.len()), "grid hi")?;
    let design = tensor_grid(&lo, &hi, &counts).map_err(uq_err)?;
    array2(py, design.points().to_vec(), design.len(), lo.len())
}

/// `n` collocation points for a chaos of degree `degree` (Berveiller, Sudret & Lemaire): the
/// roots of the degree `degree + 1` orthonormal polynomial of each marginal, tensorised, the
/// `n` of highest density first. `law`: independent variables.
#[pyfunction]
pub fn pc_collocation<'py>(
    py: Python<'py>,
    law: &Bound<'py, PyAny>,
    degree: NonNegative<usize>,
    n: NonNegative<usize>,
) -> MatrixResult<'py> {
    let degree = degree.0;
    let n = n.0;
    let m = independent_marginals(law, "pc_collocation law")?;
    let design = pcc(&m, degree, n).map_err(uq_err)?;
    array2(py, design.points().to_vec(), n, m.len())
}

/// Quadrature nodes `(n, d)` and weights `(n,)`.
type NodesWeights<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<f64>>);

/// A quadrature rule for the independent variables of `law`: `(nodes (n, d), weights (n,))`,
/// weights summing to 1 (expectations under the law).
///
/// Exactly one of: `order` (tensor Gauss rule, an int or one per variable); `level` (Smolyak
/// sparse grid on Gauss rules, `level >= d`, exact for total degree `2 (level - d) + 1`); or
/// `level` with `nested=True` (Smolyak on nested Clenshaw-Curtis / Genz-Keister rules, uniform
/// and normal variables, `level >= 0`).
#[pyfunction]
#[pyo3(signature = (law, order = None, level = None, nested = false))]
pub fn quadrature<'py>(
    py: Python<'py>,
    law: &Bound<'py, PyAny>,
    order: Option<&Bound<'py, PyAny>>,
    level: Option<NonNegative<usize>>,
    nested: bool,
) -> PyResult<NodesWeights<'py>> {
    let level = level.map(|v| v.0);
    let m = independent_marginals(law, "quadrature law")?;
    let rule = quadrature_rule(&m, order, level, nested)?;
    let (n, d) = (rule.len(), rule.dim());
    Ok((
        array2(py, rule.nodes().to_vec(), n, d)?,
        array1(py, rule.weights().to_vec()),
    ))
}

fn quadrature_rule(
    m: &[std::sync::Arc<dyn alea_uq::law::Marginal>],
    order: Option<&Bound<'_, PyAny>>,
    level: Option<usize>,
    nested: bool,
) -> PyResult<QuadratureRule> {
    match (order, level) {
        (Some(o), None) => {
            if nested {
                return Err(value_error(
                    "quadrature: nested=True goes with level, not order",
                ));
            }
            let orders = match o.extract::<usize>() {
                Ok(k) => vec![k; m.len()],
                Err(_) => o.extract::<Vec<usize>>()?,
            };
            QuadratureRule::tensor_gauss(m, &orders).map_err(uq_err)
        }
        (None, Some(l)) if nested => QuadratureRule::smolyak_nested(m, l).map_err(uq_err),
        (None, Some(l)) => QuadratureRule::smolyak(m, l).map_err(uq_err),
        _ => Err(value_error(
            "quadrature: give exactly one of order (tensor Gauss) and level (Smolyak)",
        )),
    }
}
