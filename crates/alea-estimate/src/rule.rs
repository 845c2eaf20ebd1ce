//! Integration rules over the parameter space: points `xi_q` with probability weights
//! `omega_q` (summing to 1), each tagged with the stochastic cell it belongs to, so that
//! `E[g] ~ sum_q omega_q g(xi_q)` and per-cell contributions are partial sums.
//!
//! The rule of the estimator ([`Rule::on_cells`]) is the thesis's third discretisation level
//! (4.2.1 b): on every cell `[a, b]` of a partition of the parameter box (the leaves of the
//! stochastic mesh, or a regular partition), a tensor Gauss-Legendre rule of `n` points per
//! direction with weights `w_GL f(xi)` (`f` the joint density), normalised by their sum
//! `P_box ~ P(xi in box)` (reported as [`Rule::captured`]): expectations are conditional on the
//! box, which holds `1 - 1e-6`-quantile boxes of unbounded laws. Exact for polynomials of degree
//! `2n - 1` per direction times the density, on each cell, so a cell partition that follows the
//! kinks of the integrand (the stochastic mesh of a piecewise-linear surrogate) keeps the rule
//! accurate.

use alea_uq::joint::JointLaw;
use alea_uq::quadrature::QuadratureRule;

use crate::EstimateError;

/// A box `(lo, hi)` of the parameter space.
pub type CellBox = (Vec<f64>, Vec<f64>);

/// Largest number of points of a rule (about 100 MB of points and results).
pub const MAX_POINTS: usize = 4_000_000;

/// An integration rule with cell tags.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// The points and their normalised weights.
    points: QuadratureRule,
    cells: Vec<usize>,
    captured: f64,
}

impl Rule {
    /// A rule from row-major points (`dim` per point), weights (normalised here to sum 1) and
    /// cell tags.
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] on inconsistent lengths, non-finite points, negative weights
    /// or a zero total weight; [`EstimateError::TooLarge`] beyond [`MAX_POINTS`].
    pub fn new(
        dim: usize,
        points: Vec<f64>,
        weights: Vec<f64>,
        cells: Vec<usize>,
    ) -> Result<Self, EstimateError> {
        if dim == 0 || points.len() != dim * weights.len() || cells.len() != weights.len() {
            return Err(EstimateError::Invalid(format!(
                "rule of dimension {dim}: {} coordinates, {} weights, {} cell tags",
                points.len(),
                weights.len(),
                cells.len()
            )));
        }
        if weights.len() > MAX_POINTS {
            return Err(EstimateError::TooLarge(format!(
                "integration rule of {} points (at most {MAX_POINTS}): use fewer cells or points per cell",
                weights.len()
            )));
        }
        if points.iter().any(|x| !x.is_finite())
            || weights.iter().any(|w| !(w.is_finite() && *w >= 0.0))
        {
            return Err(EstimateError::Invalid(
                "rule with a non-finite point or a negative weight".into(),
            ));
        }
        let total: f64 = weights.iter().sum();
        if !(total > 0.0) {
            return Err(EstimateError::Invalid(
                "rule with zero total weight (the law has no mass on its cells)".into(),
            ));
        }
        let weights = weights.into_iter().map(|w| w / total).collect();
        let points = QuadratureRule::new(dim, points, weights)
            .map_err(|e| EstimateError::Invalid(e.to_string()))?;
        Ok(Rule {
            points,
            cells,
            captured: total,
        })
    }

    /// Tensor Gauss-Legendre rules of `order` points per direction on each cell `(lo, hi)`,
    /// weighted by the joint density of `law` (module doc). Cell `i` of the list gets tag
    /// `tags[i]`.
    ///
    /// # Errors
    /// As [`Rule::new`]; [`EstimateError::TooLarge`] before allocating when
    /// `cells x order^dim` exceeds [`MAX_POINTS`].
    pub fn on_cells(
        cells: &[CellBox],
        tags: &[usize],
        order: usize,
        law: &dyn JointLaw,
    ) -> Result<Self, EstimateError> {
        let dim = law.dim();
        if tags.len() != cells.len() || order == 0 {
            return Err(EstimateError::Invalid(format!(
                "{} cells, {} tags, order {order}",
                cells.len(),
                tags.len()
            )));
        }
        let per = (order as u128).checked_pow(dim as u32).unwrap_or(u128::MAX);
        let total = per.saturating_mul(cells.len() as u128);
        if total > MAX_POINTS as u128 {
            return Err(EstimateError::TooLarge(format!(
                "integration rule of {} cells x {order}^{dim} points = {total} points (at most {MAX_POINTS})",
                cells.len()
            )));
        }
        let mut points = Vec::with_capacity(total as usize * dim);
        let mut weights = Vec::with_capacity(total as usize);
        let mut tag = Vec::with_capacity(total as usize);
        for ((lo, hi), &t) in cells.iter().zip(tags) {
            if lo.len() != dim || hi.len() != dim {
                return Err(EstimateError::Invalid(format!(
                    "cell of dimension {} in a {dim}-parameter space",
                    lo.len()
                )));
            }
            let q = QuadratureRule::gauss_legendre_box(lo, hi, order)?;
            for i in 0..q.len() {
                let x = q.node(i);
                let f = law.pdf(x);
                points.extend_from_slice(x);
                weights.push(q.weights()[i] * if f.is_finite() { f.max(0.0) } else { 0.0 });
                tag.push(t);
            }
        }
        Rule::new(dim, points, weights, tag)
    }

    /// The `n^d` cells of a regular partition of the box `[lo, hi]`, first direction fastest.
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] for an empty box or `n = 0`; [`EstimateError::TooLarge`]
    /// beyond [`MAX_POINTS`] cells.
    pub fn regular_cells(lo: &[f64], hi: &[f64], n: usize) -> Result<Vec<CellBox>, EstimateError> {
        let d = lo.len();
        if d == 0 || hi.len() != d || n == 0 || lo.iter().zip(hi).any(|(a, b)| !(b > a)) {
            return Err(EstimateError::Invalid(format!(
                "regular partition of the box {lo:?} - {hi:?} in {n} cells per direction"
            )));
        }
        let count = (n as u128).checked_pow(d as u32).unwrap_or(u128::MAX);
        if count > MAX_POINTS as u128 {
            return Err(EstimateError::TooLarge(format!(
                "{n}^{d} = {count} cells (at most {MAX_POINTS})"
            )));
        }
        let mut out = Vec::with_capacity(count as usize);
        let mut idx = vec![0usize; d];
        for _ in 0..count {
            let a: Vec<f64> = (0..d)
                .map(|j| lo[j] + (hi[j] - lo[j]) * idx[j] as f64 / n as f64)
                .collect();
            let b: Vec<f64> = (0..d)
                .map(|j| lo[j] + (hi[j] - lo[j]) * (idx[j] + 1) as f64 / n as f64)
                .collect();
            out.push((a, b));
            for v in idx.iter_mut() {
                *v += 1;
                if *v < n {
                    break;
                }
                *v = 0;
            }
        }
        Ok(out)
    }

    /// The cells of the tensor partition whose breakpoints in direction `j` are `breaks[j]`
    /// (sorted, duplicates within `1e-12` of the range merged), first direction fastest: e.g.
    /// the union of two regular grids' nodes, so that a rule on these cells follows the kinks of
    /// both grids' piecewise-linear weights.
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] for a direction with fewer than two distinct breakpoints or a
    /// non-finite one; [`EstimateError::TooLarge`] beyond [`MAX_POINTS`] cells.
    pub fn product_cells(breaks: &[Vec<f64>]) -> Result<Vec<CellBox>, EstimateError> {
        let d = breaks.len();
        let mut axes = Vec::with_capacity(d);
        for (j, b) in breaks.iter().enumerate() {
            let mut v: Vec<f64> = b.clone();
            if v.iter().any(|x| !x.is_finite()) {
                return Err(EstimateError::Invalid(format!(
                    "non-finite breakpoint in direction {j}"
                )));
            }
            v.sort_by(f64::total_cmp);
            let range = v.last().copied().unwrap_or(0.0) - v.first().copied().unwrap_or(0.0);
            v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * range);
            if v.len() < 2 || !(range > 0.0) {
                return Err(EstimateError::Invalid(format!(
                    "direction {j} needs two distinct breakpoints, got {b:?}"
                )));
            }
            axes.push(v);
        }
        let count = axes.iter().map(|a| (a.len() - 1) as u128).product::<u128>();
        if d == 0 || count > MAX_POINTS as u128 {
            return Err(EstimateError::TooLarge(format!(
                "{count} cells of a tensor partition in {d} directions (at most {MAX_POINTS})"
            )));
        }
        let mut out = Vec::with_capacity(count as usize);
        let mut idx = vec![0usize; d];
        for _ in 0..count {
            let a: Vec<f64> = (0..d).map(|j| axes[j][idx[j]]).collect();
            let b: Vec<f64> = (0..d).map(|j| axes[j][idx[j] + 1]).collect();
            out.push((a, b));
            for (j, v) in idx.iter_mut().enumerate() {
                *v += 1;
                if *v < axes[j].len() - 1 {
                    break;
                }
                *v = 0;
            }
        }
        Ok(out)
    }

    /// A rule from a quadrature rule of the stochastic toolkit (probability weights; one cell).
    ///
    /// # Errors
    /// As [`Rule::new`].
    pub fn from_quadrature(q: &QuadratureRule) -> Result<Self, EstimateError> {
        Rule::new(
            q.dim(),
            q.nodes().to_vec(),
            q.weights().to_vec(),
            vec![0; q.len()],
        )
    }

    /// Equal weights on sample points (Monte Carlo; one cell).
    ///
    /// # Errors
    /// As [`Rule::new`].
    pub fn equal_weights(dim: usize, points: Vec<f64>) -> Result<Self, EstimateError> {
        let n = points.len().checked_div(dim).unwrap_or(0);
        Rule::new(dim, points, vec![1.0; n], vec![0; n])
    }

    /// Number of parameters.
    pub fn dim(&self) -> usize {
        self.points.dim()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True if there is no point.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Point `q`.
    pub fn point(&self, q: usize) -> &[f64] {
        self.points.node(q)
    }

    /// Probability weight of point `q`.
    pub fn weight(&self, q: usize) -> f64 {
        self.points.weights()[q]
    }

    /// All weights.
    pub fn weights(&self) -> &[f64] {
        self.points.weights()
    }

    /// Cell tag of point `q`.
    pub fn cell(&self, q: usize) -> usize {
        self.cells[q]
    }

    /// Sum of the raw weights before normalisation (for [`Rule::on_cells`]: the probability
    /// of the cells under the law, up to the quadrature error).
    pub fn captured(&self) -> f64 {
        self.captured
    }
}
