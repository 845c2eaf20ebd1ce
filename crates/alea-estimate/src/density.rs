//! Maps of the stochastic error density over the parameter space (thesis 4.2.1 b, figures 4.7
//! to 4.11): `rho_sto(xi) = sto(xi) f(xi)` and `rho(xi) = e^2(xi) f(xi)` (`f` the joint
//! density), the contributions per unit parameter volume to `I_sto^2` and `e~^2`.
//!
//! With two parameters the map is the density on an `n x n` grid of cell centres of the box.
//! With `d > 2` there is one map per pair of parameters `(j, k)`, the marginal density
//! `int rho(xi) dxi_others` with the other parameters integrated by a tensor Gauss-Legendre rule
//! over their box; its order is the largest (at most 6, at least 2) that keeps the total number
//! of evaluations within a budget.

use alea_uq::joint::JointLaw;
use alea_uq::quadrature::QuadratureRule;
use rayon::prelude::*;

use crate::{EstimateError, Estimator, Parameters, Weights};

/// A density map over parameters `axes[0]` (x, fastest) and `axes[1]` (y).
#[derive(Clone, Debug, PartialEq)]
pub struct PairMap {
    /// The two parameters.
    pub axes: [usize; 2],
    /// Cell-centre abscissae of the grid along `axes[0]`.
    pub x: Vec<f64>,
    /// Cell-centre abscissae along `axes[1]`.
    pub y: Vec<f64>,
    /// Stochastic error density, `x.len() * y.len()` values, x fastest.
    pub sto: Vec<f64>,
    /// Total error density, same layout.
    pub e2: Vec<f64>,
}

/// Maps of every pair of parameters on an `n x n` grid of the box `[lo, hi]` (module doc),
/// with at most about `budget` evaluations of the estimate.
///
/// # Errors
/// [`EstimateError::Invalid`] for fewer than 2 parameters, an empty box or `n < 2`;
/// [`EstimateError::TooLarge`] when even the coarsest rule exceeds the budget.
pub fn pair_maps(
    est: &Estimator,
    weights: &dyn Weights,
    params: &dyn Parameters,
    law: &dyn JointLaw,
    lo: &[f64],
    hi: &[f64],
    n: usize,
    budget: usize,
) -> Result<Vec<PairMap>, EstimateError> {
    let d = lo.len();
    if d < 2 || hi.len() != d || n < 2 || lo.iter().zip(hi).any(|(a, b)| !(b > a)) {
        return Err(EstimateError::Invalid(format!(
            "density maps need at least 2 parameters, a non-empty box and n >= 2 (d = {d}, n = {n})"
        )));
    }
    let pairs: Vec<[usize; 2]> = (0..d)
        .flat_map(|j| (j + 1..d).map(move |k| [j, k]))
        .collect();
    let per_pair = (n * n) as f64 * pairs.len() as f64;
    let order = if d == 2 {
        1
    } else {
        let m = (budget as f64 / per_pair)
            .powf(1.0 / (d - 2) as f64)
            .floor() as usize;
        m.clamp(2, 6)
    };
    let evals = per_pair * (order as f64).powi(d as i32 - 2);
    if evals > 4.0 * budget.max(1) as f64 {
        return Err(EstimateError::TooLarge(format!(
            "density maps of {} pairs on {n} x {n} grids with {order}^{} other-parameter points = {evals:.0} evaluations (budget {budget})",
            pairs.len(),
            d - 2
        )));
    }
    let centres = |j: usize| -> Vec<f64> {
        (0..n)
            .map(|i| lo[j] + (hi[j] - lo[j]) * (i as f64 + 0.5) / n as f64)
            .collect()
    };
    pairs
        .iter()
        .map(|&[j, k]| {
            let others: Vec<usize> = (0..d).filter(|&i| i != j && i != k).collect();
            let rule = if others.is_empty() {
                None
            } else {
                let a: Vec<f64> = others.iter().map(|&i| lo[i]).collect();
                let b: Vec<f64> = others.iter().map(|&i| hi[i]).collect();
                Some(QuadratureRule::gauss_legendre_box(&a, &b, order)?)
            };
            let (xs, ys) = (centres(j), centres(k));
            let grid: Vec<(f64, f64)> = ys
                .iter()
                .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
                .collect();
            let vals: Vec<(f64, f64)> = grid
                .par_iter()
                .map_init(
                    || (Vec::new(), vec![0.0; d]),
                    |(w, xi), &(x, y)| {
                        xi[j] = x;
                        xi[k] = y;
                        let eval = |xi: &[f64], wq: f64, w: &mut Vec<(usize, f64)>| {
                            let f = law.pdf(xi);
                            if !(f.is_finite() && f > 0.0) {
                                return (0.0, 0.0);
                            }
                            weights.weights(xi, w);
                            let p = est.at(xi, w, params);
                            (wq * f * p.sto2(), wq * f * p.e2())
                        };
                        match &rule {
                            None => eval(xi, 1.0, w),
                            Some(r) => {
                                let (mut s, mut e) = (0.0, 0.0);
                                for q in 0..r.len() {
                                    for (slot, &i) in others.iter().enumerate() {
                                        xi[i] = r.node(q)[slot];
                                    }
                                    let (a, b) = eval(xi, r.weights()[q], w);
                                    s += a;
                                    e += b;
                                }
                                (s, e)
                            }
                        }
                    },
                )
                .collect();
            Ok(PairMap {
                axes: [j, k],
                x: xs,
                y: ys,
                sto: vals.iter().map(|v| v.0).collect(),
                e2: vals.iter().map(|v| v.1).collect(),
            })
        })
        .collect()
}
