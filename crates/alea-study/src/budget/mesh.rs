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

/// The paired solves of the mesh part: per quantity, the signed differences
/// `q_h(xi_i) - q_h/2(xi_i)` at the design points (only where both runs converged).
pub struct MeshCheck {
    /// The design points.
    pub points: Vec<Vec<f64>>,
    /// `diff[q][i]`: quantity `q` at point `i` (`None`: a run did not converge).
    pub diff: Vec<Vec<Option<f64>>>,
    /// Nodes of the two models.
    pub nodes: (usize, usize),
}

impl MeshCheck {
    /// `D = 2 max_i |diff_i|` and `S = 2 (max_i diff_i - min_i diff_i)` of quantity `q`
    /// (`None` when no pair converged).
    pub fn bounds(&self, q: usize) -> Option<(f64, f64)> {
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
        Some((2.0 * max_abs, 2.0 * (hi - lo)))
    }
}

/// Solves `study` and its refined study at the `2 d + 1` design points (cold starts).
///
/// # Errors
/// Building either solver.
pub fn mesh_check(study: &Study, refined: &Study) -> Result<MeshCheck, StudyError> {
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
    let (fine, n1) = solve(refined)?;
    let diff = (0..study.qois.len())
        .map(|q| {
            coarse
                .iter()
                .zip(&fine)
                .map(|(a, b)| match (a, b) {
                    (Some(a), Some(b)) if a[q].is_finite() && b[q].is_finite() => Some(a[q] - b[q]),
                    _ => None,
                })
                .collect()
        })
        .collect();
    Ok(MeshCheck {
        points,
        diff,
        nodes: (n0, n1),
    })
}

/// Puts the mesh part into a quantity's budget: `D` for the mean and the quantiles, `S / 2`
/// for the standard deviation, `P(|q~ - t| <= D)` over the draws `samples` for `P(q > t)`;
/// totals updated.
pub fn apply(budget: &mut super::QoiBudget, samples: &[f64], bounds: (f64, f64), basis: String) {
    let (d, s) = bounds;
    let n = samples.len().max(1) as f64;
    for row in &mut budget.rows {
        let part = if row.statistic == "std" {
            0.5 * s
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
        row.mesh = Some(part);
        row.total = row.sampling + row.surrogate.unwrap_or(0.0) + part;
    }
    budget.mesh_basis = basis;
}
