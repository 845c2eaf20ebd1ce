//! The empirical CDF of a QoI with its quantiles.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::QoiReport;
use super::super::format::{count, num};
use super::common::{
    DrawResult, GRID_BOLD, GRID_LIGHT, KDE, MEAN, QUANTILE, axis_label, configure_legend, err,
    font, line_legend, ticks,
};
use super::qoi::{draw_thresholds, qoi_x_range};

/// Points drawn at most for the empirical CDF.
const CDF_POINTS: usize = 2000;
pub(super) fn draw_cdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    q: &QoiReport,
    sorted: &[f64],
) -> DrawResult {
    let ((lo, hi), on_scale) = qoi_x_range(q, sorted);
    let mut chart = ChartBuilder::on(root)
        .caption(format!("Cumulative distribution of {}", q.name), font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(lo..hi, -0.02..1.04)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(axis_label(&q.name, &q.unit))
        .y_desc("probability")
        .x_labels(8)
        .y_labels(11)
        .x_label_formatter(&ticks(lo, hi, 8))
        .y_label_formatter(&ticks(0.0, 1.0, 10))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
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
    chart
        .draw_series(DashedLineSeries::new(
            [(q.mean, 0.0), (q.mean, 1.0)],
            9,
            6,
            MEAN.stroke_width(2),
        ))
        .map_err(err)?
        .label(format!("mean = {}", num(q.mean, 4)))
        .legend(line_legend(MEAN, 2));
    if !q.quantiles.is_empty() {
        chart
            .draw_series(
                q.quantiles
                    .iter()
                    .filter(|(_, v)| *v >= lo && *v <= hi)
                    .map(|&(p, v)| Circle::new((v, p), 5, QUANTILE.filled())),
            )
            .map_err(err)?
            .label("quantiles")
            .legend(|(x, y)| Circle::new((x + 11, y), 5, QUANTILE.filled()));
    }
    draw_thresholds(&mut chart, q, &on_scale, 1.0)?;
    configure_legend(&mut chart, SeriesLabelPosition::LowerRight)
}
