//! The mesh part of the error budget (issue 19), from paired solves: the study's model is
//! solved on its mesh `h` and on a finer mesh `h/2` (`[budget] refined_mesh`: the keys of
//! `[mesh]` that make it about twice as fine) at `2 d + 1` design points `xi_i` - the nominal
//! point and, along each parameter, its 5 % and 95 % quantiles with the others nominal - and
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
//! `S / 2 + ...` (bounded by `sigma(b) <= S / 2`), and `P(q > t)` by at most
//! `P(|q~ - t| <= D)`, read off the draws.

use alea_uq::law::Marginal;

use crate::StudyError;
use crate::run::{RunContext, RunJob, RunSetup};
use crate::study::Study;

/// Quantity values of each design point (`None`: the run did not converge).
type PointValues = Vec<Option<Vec<f64>>>;

/// Paired solves of the study and another model of it (the refined mesh of the mesh part, the
/// large-sliding model of the sliding part, `Study::large_sliding`): per quantity, the signed
/// differences `q(xi_i) - q_other(xi_i)` at the design points (only where both runs
/// converged).
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

/// Solves `study` and `other` (its refined or large-sliding study) at the `2 d + 1` design
/// points (cold starts).
///
/// # Errors
/// Building either solver.
pub fn paired_check(study: &Study, other: &Study) -> Result<PairedCheck, StudyError> {
    let p = &study.params;
    let mut points = vec![p.nominal.clone()];
    for (j, m) in p.marginals.iter().enumerate() {
        for u in [0.05, 0.95] {
            let mut x = p.nominal.clone();
            x[j] = Marginal::quantile(m.as_ref(), u).clamp(p.lo[j], p.hi[j]);
            points.push(x);
        }
    }
    let solve = |s: &Study| -> Result<(PointValues, usize), StudyError> {
        let setup = RunSetup::build(s)?;
        let ctx = RunContext {
            study: s,
            solver: &setup.solver,
            cre: None,
            dir: std::path::Path::new("."),
        };
        let dofs = (0..setup.solver.num_subs())
            .map(|k| setup.solver.model(k).mesh.num_nodes())
            .sum::<usize>();
        let values = points
            .iter()
            .map(|x| {
                ctx.solve(&RunJob {
                    theta: x.clone(),
                    start: None,
                })
                .ok()
                .filter(|o| o.rec.converged())
                .map(|o| o.rec.qois)
            })
            .collect();
        Ok((values, dofs))
    };
    let (coarse, n0) = solve(study)?;
    let (fine, n1) = solve(other)?;
    let pair = |q: usize, i: usize| match (&coarse[i], &fine[i]) {
        (Some(a), Some(b)) if a[q].is_finite() && b[q].is_finite() => Some((a[q], a[q] - b[q])),
        _ => None,
    };
    let n = points.len();
    let diff = (0..study.qois.len())
        .map(|q| (0..n).map(|i| pair(q, i).map(|p| p.1)).collect())
        .collect();
    let base = (0..study.qois.len())
        .map(|q| (0..n).map(|i| pair(q, i).map(|p| p.0)).collect())
        .collect();
    Ok(PairedCheck {
        points,
        diff,
        base,
        nodes: (n0, n1),
    })
}

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
/// (`sigma` the standard deviation of the draws) -, `P(|q~ - t| <= D)` over the draws
/// `samples` for `P(q > t)`; totals updated.
pub fn apply(
    budget: &mut super::QoiBudget,
    samples: &[f64],
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
        let part = if row.statistic == "std" {
            (0.5 * s).max(scaled)
        } else if let Some(t) = row
            .statistic
            .strip_prefix("P(> ")
            .and_then(|r| r.strip_suffix(')'))
            .and_then(|t| t.parse::<f64>().ok())
        {
            samples.iter().filter(|&&v| (v - t).abs() <= d).count() as f64 / n
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
