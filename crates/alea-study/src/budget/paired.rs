//! The mesh and sliding parts of the error budget (issue 19), from paired solves of the study
//! and of a variant of it at the same design points. The mesh part: the study's model is
//! solved on its mesh `h` and on a finer mesh `h/2` (`[budget] refined_mesh`: the keys of
//! `[mesh]` that make it about twice as fine) at `2 d + 3` design points `xi_i` - the nominal
//! point, along each parameter its 5 % and 95 % quantiles with the others nominal, and with
//! two parameters or more the two diagonal points, every parameter at its 5 % and at its 95 %
//! quantile (`2 d + 1` points with one parameter; [`design_size`], [`design_points`]; solved
//! by the run and stored, never by an output: `crate::paired_runs`) - and
//!
//! ```text
//! delta_i = 2 |q_h(xi_i) - q_h/2(xi_i)|
//! ```
//!
//! estimates the mesh error of `q_h` at `xi_i`: Richardson's `|q_h - q_h/2| 2^p / (2^p - 1)`
//! with the lowest order `p = 1` (the conservative end: `p = 2` would give `4/3`; maxima of
//! stresses at re-entrant corners converge more slowly than the elements' order). Over the
//! parameter space the mesh error `b(xi)` is taken within `[-D, D]`, `D = max_i delta_i`, and
//! spreads by at most `S = max_i b_i - min_i b_i` (signed, doubled): a shift of every draw by at
//! most `D` moves the mean and every quantile by at most `D`, the standard deviation by at most
//! `S / 2 + ...` (bounded by `sigma(b) <= S / 2`), and `P(q > t)` by at most the share of
//! draws within their own shift of `t`, `P(|q~(xi) - t| <= |b~(xi)| + A)`, with `b~` an
//! anchored model of the differences over the parameters, first order along the axes plus one
//! coefficient for the pair terms fitted at the diagonal points, and `A` what that coefficient
//! cannot follow there ([`PairedCheck::shift_model`]; `P(|q~ - t| <= D)` when a pair did not
//! converge).
//!
//! Why the diagonal points (2 more paired solves): a difference that varies only through the
//! interaction of parameters vanishes along the axes through the nominal point (`0.2 (x -
//! 1/2) (y - 1/2)` on the unit square), so with the axis points alone every part was blind to
//! it, and `P(q > t)`'s part saw 0.15 - 0.33x of its change. With them it covers it at 1.8 -
//! 2.2x (the unit test below). What they still cannot see, with three parameters or more:
//! pair interactions of opposite signs that cancel on the diagonal, and which pair interacts
//! (one coefficient is spread over all pairs; with one interacting pair among three
//! parameters the part still covered the change, at 1.98 - 5.44x, the second unit test).

use alea_uq::law::Marginal;

use super::Statistic;
use crate::study::Study;

/// Paired solves of the study and another model of it (the refined mesh of the mesh part, the
/// large-sliding model of the sliding part, `Study::large_sliding`): per quantity, the signed
/// differences `q(xi_i) - q_other(xi_i)` at the design points (only where both runs
/// converged).
#[derive(Clone, Debug, PartialEq)]
pub struct PairedCheck {
    /// The design points.
    pub points: Vec<Vec<f64>>,
    /// `diff[q][i]`: quantity `q` at point `i` (`None`: a run did not converge).
    pub diff: Vec<Vec<Option<f64>>>,
    /// `base[q][i]`: the study's own value of quantity `q` at point `i`, where `diff` has one.
    pub base: Vec<Vec<Option<f64>>>,
    /// Nodes of the two models.
    pub nodes: (usize, usize),
}

impl PairedCheck {
    /// `D = factor max_i |diff_i|` and `S = factor (max_i diff_i - min_i diff_i)` of quantity
    /// `q` (`None` when no pair converged): `factor` 2 for the mesh part (Richardson, first
    /// order), 1 for the sliding part.
    pub fn bounds(&self, q: usize, factor: f64) -> Option<(f64, f64)> {
        let d: Vec<f64> = self.diff[q].iter().flatten().copied().collect();
        if d.is_empty() {
            return None;
        }
        let max_abs = d.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let (lo, hi) = d
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        Some((factor * max_abs, factor * (hi - lo)))
    }

    /// The shift of quantity `q` over the parameter space, `factor` times an anchored
    /// (cut-HDMR) model of the differences, when every pair converged:
    ///
    /// ```text
    /// delta(xi) = delta_0 + sum_j g_j(xi_j) + c mean_{j < k} s_j(xi_j) s_k(xi_k),
    /// ```
    ///
    /// `delta_0` the difference at the nominal point and `g_j` piecewise linear through
    /// `(lo_j, delta_j^lo - delta_0)`, `(nominal_j, 0)`, `(hi_j, delta_j^hi - delta_0)` (the
    /// 5 % / 95 % points), constant beyond them (no extrapolation); with two parameters or more,
    /// `c` the mean misfit of the first-order terms at the two diagonal points (where every
    /// `s_j s_k` is 1), `s_j` the offset from the nominal value in units of the distance to the
    /// 5 % / 95 % point, held at -1 / 1 beyond, and `A` half the difference of the two misfits
    /// ([`ShiftModel::reach`]). `None` when a pair is missing. The `P(q > t)` part built on it
    /// is checked against the true change (BENCHMARKS.md "Error budget per quantity").
    pub fn shift_model(&self, q: usize, factor: f64) -> Option<ShiftModel> {
        let d: Vec<f64> = self.diff[q].iter().copied().collect::<Option<Vec<f64>>>()?;
        let dim = self.points[0].len();
        if d.len() != design_size(dim) {
            return None;
        }
        let axes: Vec<[(f64, f64); 3]> = (0..dim)
            .map(|j| {
                [
                    (self.points[1 + 2 * j][j], factor * (d[1 + 2 * j] - d[0])),
                    (self.points[0][j], 0.0),
                    (self.points[2 + 2 * j][j], factor * (d[2 + 2 * j] - d[0])),
                ]
            })
            .collect();
        let mut model = ShiftModel {
            nominal: factor * d[0],
            axes,
            pairs: 0.0,
            asymmetry: 0.0,
        };
        // What the first-order model misses at the two diagonal points, where every pair term
        // `s_j s_k` is 1: their mean is the pairs' coefficient, half their difference what a
        // single coefficient cannot follow.
        if d.len() > 2 * dim + 1 {
            let misfit = |i: usize| factor * d[i] - model.at(&self.points[i]);
            let (lo, hi) = (misfit(2 * dim + 1), misfit(2 * dim + 2));
            model.pairs = 0.5 * (lo + hi);
            model.asymmetry = 0.5 * (hi - lo).abs();
        }
        Some(model)
    }

    /// The largest relative difference `max_i |diff_i / q(xi_i)|` of quantity `q` over the
    /// points where the study's value is not zero (`None` when there is none).
    pub fn relative(&self, q: usize) -> Option<f64> {
        self.diff[q]
            .iter()
            .zip(&self.base[q])
            .filter_map(|(d, b)| match (d, b) {
                (Some(d), Some(b)) if *b != 0.0 => Some((d / b).abs()),
                _ => None,
            })
            .reduce(f64::max)
    }
}

/// The anchored model of a paired difference ([`PairedCheck::shift_model`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ShiftModel {
    /// `factor delta_0`.
    nominal: f64,
    /// Per parameter, the three nodes `(xi_j, factor (delta_j - delta_0))` in the order 5 %,
    /// nominal, 95 %.
    axes: Vec<[(f64, f64); 3]>,
    /// `c`, the coefficient of the pair terms: the mean misfit of the first-order model at the
    /// two diagonal points (every parameter at its 5 %, at its 95 % quantile; 0 with one
    /// parameter).
    pairs: f64,
    /// `A`, half the difference of those two misfits.
    asymmetry: f64,
}

impl ShiftModel {
    /// How far the difference may reach at `xi`: `|delta(xi)| + A`.
    pub fn reach(&self, xi: &[f64]) -> f64 {
        self.at(xi).abs() + self.asymmetry
    }

    /// The modelled shift at the parameter point `xi`: the first-order terms and, with two
    /// parameters or more, `c` times the mean of the pair terms `s_j s_k`, `s_j` the offset of
    /// `xi_j` from the nominal value in units of the distance to the 5 % (below) or 95 %
    /// (above) point, held at -1 / 1 beyond them.
    pub fn at(&self, xi: &[f64]) -> f64 {
        let first = self.nominal
            + self
                .axes
                .iter()
                .zip(xi)
                .map(|(nodes, &x)| piecewise_linear(nodes, x))
                .sum::<f64>();
        if self.pairs == 0.0 {
            return first;
        }
        // `sum_{j < k} s_j s_k = ((sum_j s_j)^2 - sum_j s_j^2) / 2`: no allocation per draw.
        let (sum, squares) = self
            .axes
            .iter()
            .zip(xi)
            .map(|(n, &x)| {
                let (lo, mid, hi) = (n[0].0, n[1].0, n[2].0);
                let v = if x >= mid {
                    if hi > mid {
                        (x - mid) / (hi - mid)
                    } else {
                        0.0
                    }
                } else if mid > lo {
                    (x - mid) / (mid - lo)
                } else {
                    0.0
                };
                v.clamp(-1.0, 1.0)
            })
            .fold((0.0, 0.0), |(a, b), s| (a + s, b + s * s));
        let dim = self.axes.len();
        let pairs = 0.5 * (sum * sum - squares);
        first + self.pairs * pairs / (dim * (dim - 1) / 2) as f64
    }
}

/// The piecewise-linear interpolant through `nodes` (abscissae increasing or equal), constant
/// beyond the end nodes.
fn piecewise_linear(nodes: &[(f64, f64); 3], x: f64) -> f64 {
    if x <= nodes[0].0 {
        return nodes[0].1;
    }
    for w in nodes.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x <= x1 {
            return if x1 > x0 {
                y0 + (y1 - y0) * (x - x0) / (x1 - x0)
            } else {
                y1
            };
        }
    }
    nodes[2].1
}

/// Number of design points of the paired solves with `dim` parameters: the nominal point, two
/// per parameter, and with two parameters or more the two diagonal points.
pub fn design_size(dim: usize) -> usize {
    2 * dim + 1 + if dim >= 2 { 2 } else { 0 }
}

/// The [`design_size`] design points of the paired solves of `study`: the nominal point, along
/// each parameter its 5 % and 95 % quantiles (clamped to its range) with the others nominal,
/// and with two parameters or more every parameter at its 5 %, then at its 95 % quantile.
pub fn design_points(study: &Study) -> Vec<Vec<f64>> {
    let p = &study.params;
    let mut points = vec![p.nominal.clone()];
    for (j, m) in p.marginals.iter().enumerate() {
        for u in [0.05, 0.95] {
            let mut x = p.nominal.clone();
            x[j] = Marginal::quantile(m.as_ref(), u).clamp(p.lo[j], p.hi[j]);
            points.push(x);
        }
    }
    if p.marginals.len() >= 2 {
        for u in [0.05, 0.95] {
            let x = (0..p.marginals.len())
                .map(|j| Marginal::quantile(p.marginals[j].as_ref(), u).clamp(p.lo[j], p.hi[j]))
                .collect();
            points.push(x);
        }
    }
    points
}

/// The quantity values of one paired solve: `None` when it did not converge (or failed).
pub type PointValues = Option<Vec<f64>>;

impl PairedCheck {
    /// The check of `qois` quantities from the paired solves at `points`: `coarse[i]` the
    /// study's values at point `i`, `fine[i]` the other model's, `nodes` the two models' node
    /// counts. A pair counts where both converged with a finite value.
    pub fn from_solves(
        qois: usize,
        points: Vec<Vec<f64>>,
        coarse: &[PointValues],
        fine: &[PointValues],
        nodes: (usize, usize),
    ) -> Self {
        let pair = |q: usize, i: usize| match (&coarse[i], &fine[i]) {
            (Some(a), Some(b)) if a[q].is_finite() && b[q].is_finite() => Some((a[q], a[q] - b[q])),
            _ => None,
        };
        let n = points.len();
        let diff = (0..qois)
            .map(|q| (0..n).map(|i| pair(q, i).map(|p| p.1)).collect())
            .collect();
        let base = (0..qois)
            .map(|q| (0..n).map(|i| pair(q, i).map(|p| p.0)).collect())
            .collect();
        PairedCheck {
            points,
            diff,
            base,
            nodes,
        }
    }
}

/// What the study's paired solves give one part of the budget: the check, or why the part is
/// not estimated (the error of building the other model's solver, or that the paired solves
/// are not all stored - a study run by an older alea).
pub type PairedResult = Result<PairedCheck, String>;

/// Which part of a budget [`apply`] fills.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// Space discretisation (`[budget] refined_mesh`).
    Mesh,
    /// Small against large sliding (`[budget] large_sliding`).
    Sliding,
}

/// Puts a paired-solve part into a quantity's budget: `D` for the mean and the quantiles,
/// `S / 2` for the standard deviation - at least `r sigma` when a relative change `r` is given
/// (`sigma` the standard deviation of the draws) -, and for `P(q > t)` the share of the draws
/// `samples` within their own shift of `t`,
///
/// ```text
/// P( |q~(xi) - t| <= reach(xi) ),
/// ```
///
/// with `reach = |delta| + A` from the shift model of the differences at the draws' points
/// `shifts` (one per draw, [`ShiftModel::reach`]), or without it (a pair did not converge)
/// `P(|q~ - t| <= D)`; totals updated. Why the shift model for `P` only, measured: the band
/// `|q~ - t| <= D` counts every draw within the largest shift of `t`, 10 - 22x the true change
/// of `P(vm_fillet > 1165)` under large sliding on the 2D turbine. Why both sides of `t`: the
/// share of draws the model moves across `t` (one side) covered the change of the piecewise
/// linear surrogate's `P` (1.47x) but not of the chaos's (0.66x), whose fit on the shifted runs
/// changes its shape between them, not only its level.
pub fn apply(
    budget: &mut super::QoiBudget,
    samples: &[f64],
    shifts: Option<&[f64]>,
    bounds: (f64, f64),
    relative: Option<f64>,
    which: Part,
    basis: String,
) {
    let (d, s) = bounds;
    let n = samples.len().max(1) as f64;
    let sigma = alea_uq::stats::Summary::of(samples).std;
    let scaled = relative
        .map(|r| r * sigma)
        .filter(|v| v.is_finite())
        .unwrap_or(0.0);
    for row in &mut budget.rows {
        let part = if row.statistic == Statistic::Std {
            (0.5 * s).max(scaled)
        } else if let Statistic::Exceedance(t) = row.statistic {
            match shifts {
                Some(shift) => {
                    samples
                        .iter()
                        .zip(shift)
                        .filter(|&(&v, &b)| (v - t).abs() <= b.abs())
                        .count() as f64
                        / n
                }
                None => samples.iter().filter(|&&v| (v - t).abs() <= d).count() as f64 / n,
            }
        } else {
            d
        };
        match which {
            Part::Mesh => row.mesh = Some(part),
            Part::Sliding => row.sliding = Some(part),
        }
        row.total = row.sum_of_parts();
    }
    match which {
        Part::Mesh => budget.mesh_basis = basis,
        Part::Sliding => budget.sliding_basis = Some(basis),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::budget::{SurrogatePart, qoi_budget};

    /// `q = x + y` on the unit square (midpoint grid of 400 x 400 draws) and a second model
    /// `q - delta(x, y)`; the true change of `P(q > t)` is counted on the same draws. From the
    /// differences at the 7 design points alone, the part of `P(q > t)` covers it within 3.5x
    /// for a linear, a quadratic, an interacting `delta` and a pure interaction centred at the
    /// nominal point, `0.2 (x - 1/2) (y - 1/2)`, which vanishes at the 5 axis points (measured
    /// 1.83 - 2.19x; the band `|q - t| <= D`, 2.70 - 10.8x; with the axis points alone the pure
    /// interaction was seen at 0.15 - 0.33x).
    #[test]
    fn p_part_from_the_shift_model_covers_exact_changes_tightly() {
        let n = 400;
        let mut points = Vec::with_capacity(2 * n * n);
        let mut samples = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let (x, y) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                points.extend([x, y]);
                samples.push(x + y);
            }
        }
        // The design of `design_points` on U(0, 1)^2: nominal, the 5 % / 95 % points, the
        // diagonal points.
        let design = [
            [0.5, 0.5],
            [0.05, 0.5],
            [0.95, 0.5],
            [0.5, 0.05],
            [0.5, 0.95],
            [0.05, 0.05],
            [0.95, 0.95],
        ];
        type Difference = fn(f64, f64) -> f64;
        let cases: [(&str, Difference); 4] = [
            ("0.1 x", |x, _| 0.1 * x),
            ("0.2 x^2", |x, _| 0.2 * x * x),
            ("0.2 x y", |x, y| 0.2 * x * y),
            ("0.2 (x - 1/2) (y - 1/2)", |x, y| {
                0.2 * (x - 0.5) * (y - 0.5)
            }),
        ];
        for (name, delta) in cases {
            let check = PairedCheck {
                points: design.iter().map(|p| p.to_vec()).collect(),
                diff: vec![design.iter().map(|p| Some(delta(p[0], p[1]))).collect()],
                base: vec![design.iter().map(|p| Some(p[0] + p[1])).collect()],
                nodes: (1, 1),
            };
            let model = check.shift_model(0, 1.0).expect("every pair converged");
            let shifts: Vec<f64> = points.chunks(2).map(|x| model.reach(x)).collect();
            let bounds = check.bounds(0, 1.0).unwrap();
            for t in [1.0, 1.5] {
                let part = |shifts: Option<&[f64]>| {
                    let mut b = qoi_budget(&samples, SurrogatePart::Exact, &[], &[t], 0.95, None);
                    apply(
                        &mut b,
                        &samples,
                        shifts,
                        bounds,
                        None,
                        Part::Sliding,
                        String::new(),
                    );
                    b.rows[2].sliding.unwrap()
                };
                let (first_order, band) = (part(Some(&shifts)), part(None));
                let above = |shift: bool| {
                    samples
                        .iter()
                        .zip(points.chunks(2))
                        .filter(|(q, x)| *q - if shift { delta(x[0], x[1]) } else { 0.0 } > t)
                        .count() as f64
                        / samples.len() as f64
                };
                let change = (above(false) - above(true)).abs();
                eprintln!(
                    "delta = {name}, P(q > {t}): change {change:.4}, shift model {first_order:.4} ({:.2}x), band {band:.4} ({:.2}x)",
                    first_order / change,
                    band / change
                );
                assert!(
                    first_order >= change && first_order <= 3.5 * change,
                    "delta = {name}, t = {t}: P part {first_order} for a change of {change}"
                );
            }
            if name == "0.1 x" {
                // Within the design's range the model is exact (the difference is linear in
                // x); beyond the 5 % / 95 % points it is held constant, not extrapolated.
                assert!((model.at(&[0.3, 0.8]) - 0.03).abs() < 1e-12);
                assert!((model.at(&[1.0, 0.5]) - 0.095).abs() < 1e-12);
            }
        }
    }

    /// Three parameters, `q = x + y + z` on U(0, 1)^3 (midpoint grid of 80^3 draws), and a
    /// difference through the interaction of one pair only, `0.2 (x - 1/2) (y - 1/2)`: the
    /// design's 9 points see its size at the diagonal points, but the one pair coefficient is
    /// spread over the three pairs, so the modelled shift is wrong in place. Measured: the
    /// part is 1.98x (t = 1.5) and 5.44x (t = 2) the true change; asserted: covered, within
    /// 10x.
    #[test]
    fn p_part_with_one_interacting_pair_among_three_parameters() {
        let n = 80;
        let mut points = Vec::with_capacity(3 * n * n * n);
        let mut samples = Vec::with_capacity(n * n * n);
        for i in 0..n * n * n {
            let x = [i % n, (i / n) % n, i / (n * n)].map(|k| (k as f64 + 0.5) / n as f64);
            points.extend(x);
            samples.push(x.iter().sum::<f64>());
        }
        let mut design = vec![[0.5; 3]];
        for j in 0..3 {
            for u in [0.05, 0.95] {
                let mut x = [0.5; 3];
                x[j] = u;
                design.push(x);
            }
        }
        design.extend([[0.05; 3], [0.95; 3]]);
        assert_eq!(design.len(), design_size(3));
        let delta = |x: &[f64]| 0.2 * (x[0] - 0.5) * (x[1] - 0.5);
        let check = PairedCheck {
            points: design.iter().map(|p| p.to_vec()).collect(),
            diff: vec![design.iter().map(|p| Some(delta(p))).collect()],
            base: vec![design.iter().map(|p| Some(p.iter().sum())).collect()],
            nodes: (1, 1),
        };
        let model = check.shift_model(0, 1.0).unwrap();
        let shifts: Vec<f64> = points.chunks(3).map(|x| model.reach(x)).collect();
        for t in [1.5, 2.0] {
            let mut b = qoi_budget(&samples, SurrogatePart::Exact, &[], &[t], 0.95, None);
            let bounds = check.bounds(0, 1.0).unwrap();
            apply(
                &mut b,
                &samples,
                Some(&shifts),
                bounds,
                None,
                Part::Sliding,
                String::new(),
            );
            let part = b.rows[2].sliding.unwrap();
            let above = |shift: bool| {
                samples
                    .iter()
                    .zip(points.chunks(3))
                    .filter(|(q, x)| *q - if shift { delta(x) } else { 0.0 } > t)
                    .count() as f64
                    / samples.len() as f64
            };
            let change = (above(false) - above(true)).abs();
            eprintln!(
                "3 parameters, one interacting pair, P(q > {t}): change {change:.4}, part {part:.4} ({:.2}x)",
                part / change
            );
            assert!(
                part >= change && part <= 10.0 * change,
                "t = {t}: part {part}, change {change}"
            );
        }
    }
}
