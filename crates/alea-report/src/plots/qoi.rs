//! What the PDF and CDF plots of a QoI share: the x range (which takes in the total intervals
//! of the mean and the quantiles up to half the data's width beyond it), the mean and the
//! failure thresholds.

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::super::format::num;
use super::super::{BudgetRow, QoiReport, Statistic, budget_row};
use super::common::{DrawResult, MEAN, THRESHOLD, err, extend, line_legend, pad};

/// The x range of a QoI's plots: samples, KDE grid, mean, and the thresholds that are not far
/// off (returned with a flag: on scale or not).
pub(super) fn qoi_x_range(q: &QoiReport, sorted: &[f64]) -> ((f64, f64), Vec<bool>) {
    let mut r = None;
    if let (Some(a), Some(b)) = (sorted.first(), sorted.last()) {
        extend(&mut r, *a);
        extend(&mut r, *b);
    }
    for (x, _) in &q.kde {
        extend(&mut r, *x);
    }
    extend(&mut r, q.mean);
    let (lo, hi) = r.unwrap_or((q.mean, q.mean));
    let w = if hi > lo {
        hi - lo
    } else {
        pad((lo, hi), 0.0).1 - lo
    };
    let on_scale: Vec<bool> = q
        .failure
        .iter()
        .map(|f| f.threshold >= lo - 0.5 * w && f.threshold <= hi + 0.5 * w)
        .collect();
    let mut r = Some((lo, hi));
    for (f, on) in q.failure.iter().zip(&on_scale) {
        if *on {
            extend(&mut r, f.threshold);
        }
    }
    for b in &q.budget {
        if matches!(b.statistic, Statistic::Mean | Statistic::Quantile(_)) {
            let (a, c) = b.interval();
            extend(&mut r, a.max(lo - 0.5 * w));
            extend(&mut r, c.min(hi + 0.5 * w));
        }
    }
    (pad(r.unwrap_or((lo, hi)), 0.03), on_scale)
}

/// The mean (its budget row's estimate where there is one), a dashed vertical line up to `top`.
pub(super) fn draw_mean<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    q: &QoiReport,
    top: f64,
) -> DrawResult {
    let mean = budget_row(&q.budget, Statistic::Mean).map_or(q.mean, BudgetRow::estimate);
    chart
        .draw_series(DashedLineSeries::new(
            [(mean, 0.0), (mean, top)],
            9,
            6,
            MEAN.stroke_width(2),
        ))
        .map_err(err)?
        .label(format!("mean = {}", num(mean, 4)))
        .legend(line_legend(MEAN, 2));
    Ok(())
}

pub(super) fn draw_thresholds<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    q: &QoiReport,
    on_scale: &[bool],
    top: f64,
) -> DrawResult {
    for (f, on) in q.failure.iter().zip(on_scale) {
        let label = format!(
            "P(q > {}) = {}{}",
            num(f.threshold, 4),
            num(
                budget_row(&q.budget, Statistic::Exceedance(f.threshold))
                    .map_or(f.probability, BudgetRow::estimate),
                3
            ),
            if *on { "" } else { " (threshold off scale)" }
        );
        // Off scale: no line, only the legend entry.
        let pts: Vec<(f64, f64)> = if *on {
            vec![(f.threshold, 0.0), (f.threshold, top)]
        } else {
            Vec::new()
        };
        chart
            .draw_series(LineSeries::new(pts, THRESHOLD.stroke_width(2)))
            .map_err(err)?
            .label(label)
            .legend(line_legend(THRESHOLD, 2));
    }
    Ok(())
}
