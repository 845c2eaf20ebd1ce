//! Warnings on draws of a surrogate that leave what the runs say (issue 42, item 3).
//!
//! A surrogate is evaluated at the Monte Carlo draws; where the runs miss a feature (a kink, a
//! contact that opens) a polynomial oscillates between them and its draws leave
//! - the **physical range** of a quantity that cannot be negative (a length or area in a
//!   contact status, a slip, a normal force or pressure, a friction dissipation, a von Mises
//!   stress): every negative draw is impossible, and the share of them is warned about;
//! - the **range of the runs** `[min, max]` of the method's converged runs: not impossible (the
//!   runs need not reach the extremes of the law), but a share of the draws beyond it larger
//!   than [`OUTSIDE_SHARE`] says that the statistics there come from the surrogate's
//!   extrapolation, not from the model.
//!
//! Measured on the shipped simple blade root (`examples/blade-root-simple.toml`, chaos of degree
//! 4): 47.8 % of the draws of the stick length were negative while all 50 runs are >= 0.

use crate::analysis::MethodResult;
use crate::method::{Method, MethodKind};
use crate::qoi::QoiKind;
use crate::store::{RunRecord, point_key};
use crate::study::Study;

/// The share of the draws beyond the runs' range above which it is warned about.
pub const OUTSIDE_SHARE: f64 = 0.01;

/// True for the quantities that cannot be negative ([`QoiKind::nonnegative`]).
pub fn nonnegative(kind: &QoiKind) -> bool {
    kind.nonnegative()
}

/// The warnings of one method's draws (empty for Monte Carlo on the model, whose draws are its
/// runs, and for a method without statistics).
pub fn draw_range_warnings(
    study: &Study,
    method: &Method,
    result: &MethodResult,
    records: &[RunRecord],
) -> Vec<String> {
    if method.kind == MethodKind::MonteCarlo {
        return Vec::new();
    }
    let by_key: std::collections::HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    let runs: Vec<&RunRecord> = method
        .points
        .iter()
        .filter_map(|p| by_key.get(&point_key(p)).copied())
        .filter(|r| r.converged())
        .collect();
    let mut out = Vec::new();
    for (q, stats) in result.qois.iter().enumerate() {
        let (Some(qoi), false) = (study.qois.get(q), stats.samples.is_empty()) else {
            continue;
        };
        let values: Vec<f64> = runs.iter().map(|r| r.qois[q]).collect();
        let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !(lo.is_finite() && hi.is_finite()) {
            continue;
        }
        let n = stats.samples.len() as f64;
        let unit = if qoi.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", qoi.unit)
        };
        let share =
            |f: &dyn Fn(f64) -> bool| stats.samples.iter().filter(|&&v| f(v)).count() as f64 / n;
        // The draws of a quantity that cannot be negative were projected onto `>= 0` by the
        // analysis, which kept the share of negative ones and the lowest (`QoiStats::negative`).
        let min_draw = stats
            .samples
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
            .min(stats.negative.1);
        let negative = share(&|v| v < 0.0).max(stats.negative.0);
        if nonnegative(&qoi.kind) && negative > 0.0 && lo >= 0.0 {
            out.push(format!(
                "method '{}': {:.1} % of the draws of '{}' are negative (down to {min_draw:.4e}{unit}), \
                 which it cannot be ({}), while all {} runs are >= 0: the surrogate oscillates \
                 between the runs (a kink or a contact that opens?); those draws are taken as 0 \
                 in its statistics, which are still not the model's there - more runs, or a \
                 piecewise-linear or adaptive method",
                method.label,
                100.0 * negative,
                qoi.name,
                qoi.what,
                values.len()
            ));
        }
        let tol = 1e-9 * (hi - lo).abs().max(hi.abs()).max(lo.abs());
        let outside = share(&|v| v < lo - tol || v > hi + tol);
        if outside > OUTSIDE_SHARE {
            let max_draw = stats
                .samples
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max);
            out.push(format!(
                "method '{}': {:.1} % of the draws of '{}' leave the range of its {} runs \
                 [{lo:.4e}, {hi:.4e}]{unit} (draws from {min_draw:.4e} to {max_draw:.4e}): the \
                 statistics there extrapolate the surrogate",
                method.label,
                100.0 * outside,
                qoi.name,
                values.len()
            ));
        }
    }
    out
}
