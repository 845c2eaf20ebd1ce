//! The empirical CDF of a QoI with its quantiles, each with its total interval as a horizontal
//! error bar at its probability (the budget rows' intervals, issue 40, item 3; the marker at
//! the row's estimate).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::format::count;
use super::super::{BudgetRow, QoiReport, Statistic, budget_row};
use super::common::{
    DrawResult, KDE, QUANTILE, axis_label, chart, configure_legend, err, grid, line_legend, ticks,
};
use super::marks::{clipped_interval, error_bar};
use super::qoi::{draw_mean, draw_thresholds, qoi_x_range};

/// Points drawn at most for the empirical CDF.
const CDF_POINTS: usize = 2000;

pub(super) fn draw_cdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    q: &QoiReport,
    sorted: &[f64],
) -> DrawResult {
    let ((lo, hi), on_scale) = qoi_x_range(q, sorted);
    let mut chart = chart(
        root,
        format!("Cumulative distribution of {}", q.name),
        lo..hi,
        -0.02..1.04,
    )?;
    grid(&mut chart.configure_mesh())
        .x_desc(axis_label(&q.name, &q.unit))
        .y_desc("probability")
        .x_labels(8)
        .y_labels(11)
        .x_label_formatter(&ticks(lo, hi, 8))
        .y_label_formatter(&ticks(0.0, 1.0, 10))
        .draw()
        .map_err(err)?;
    let n = sorted.len();
    if n > 0 {
        let nf = n as f64;
        let mut pts = vec![(lo, 0.0), (sorted[0], 0.0)];
        if n <= CDF_POINTS {
            for (k, &x) in sorted.iter().enumerate() {
                pts.push((x, k as f64 / nf));
                pts.push((x, (k + 1) as f64 / nf));
            }
        } else {
            for i in 0..CDF_POINTS {
                let k = i * (n - 1) / (CDF_POINTS - 1);
                pts.push((sorted[k], (k + 1) as f64 / nf));
            }
        }
        pts.push((hi, 1.0));
        chart
            .draw_series(LineSeries::new(pts, KDE.stroke_width(2)))
            .map_err(err)?
            .label(format!("empirical CDF ({} samples)", count(n)))
            .legend(line_legend(KDE, 2));
    }
    draw_mean(&mut chart, q, 1.0)?;
    let bars: Vec<_> = q
        .quantiles
        .iter()
        .filter_map(|&(p, _)| {
            Some((
                p,
                clipped_interval(&q.budget, Statistic::Quantile(p), (lo, hi))?,
            ))
        })
        .collect();
    if !bars.is_empty() {
        chart
            .draw_series(bars.iter().map(|&(p, b)| error_bar(p, b, QUANTILE)))
            .map_err(err)?
            .label("total intervals of the quantiles")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], QUANTILE.stroke_width(2)));
    }
    if !q.quantiles.is_empty() {
        chart
            .draw_series(
                q.quantiles
                    .iter()
                    .map(|&(p, v)| {
                        let statistic = Statistic::Quantile(p);
                        (
                            p,
                            budget_row(&q.budget, statistic).map_or(v, BudgetRow::estimate),
                        )
                    })
                    .filter(|(_, v)| *v >= lo && *v <= hi)
                    .map(|(p, v)| Circle::new((v, p), 5, QUANTILE.filled())),
            )
            .map_err(err)?
            .label("quantiles")
            .legend(|(x, y)| Circle::new((x + 11, y), 5, QUANTILE.filled()));
    }
    draw_thresholds(&mut chart, q, &on_scale, 1.0)?;
    configure_legend(&mut chart, SeriesLabelPosition::LowerRight)
}
