//! The PDFs of several methods in one plot.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::Comparison;
use super::common::{
    DrawResult, PALETTE, axis_label, by_x, chart, configure_legend, err, extend, grid, line_legend,
    pad, ticks,
};

pub(super) fn draw_comparison<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    c: &Comparison,
    unit: &str,
) -> DrawResult {
    let mut xr = None;
    let mut ymax: f64 = 0.0;
    for row in &c.rows {
        if row.kde.len() >= 2 {
            for &(x, p) in &row.kde {
                extend(&mut xr, x);
                ymax = ymax.max(p);
            }
        }
    }
    let (x0, x1) = pad(xr.unwrap_or((0.0, 1.0)), 0.02);
    let ymax = if ymax > 0.0 { ymax * 1.15 } else { 1.0 };
    let mut chart = chart(
        root,
        format!("Probability density of {}: methods compared", c.qoi),
        x0..x1,
        0.0..ymax,
    )?;
    grid(&mut chart.configure_mesh())
        .x_desc(axis_label(&c.qoi, unit))
        .y_desc("probability density")
        .x_labels(8)
        .y_labels(7)
        .x_label_formatter(&ticks(x0, x1, 8))
        .y_label_formatter(&ticks(0.0, ymax, 7))
        .draw()
        .map_err(err)?;
    let mut k = 0;
    for row in &c.rows {
        if row.kde.len() < 2 {
            continue;
        }
        let reference = row.method.to_lowercase().contains("reference");
        let (color, width) = if reference {
            (RGBColor(0, 0, 0), 3)
        } else {
            k += 1;
            (PALETTE[(k - 1) % PALETTE.len()], 2)
        };
        // Labels often say their run count already ("chaos p=2 (9 runs)").
        let label = if row.method.contains("run") {
            row.method.clone()
        } else {
            format!("{} ({} runs)", row.method, row.runs)
        };
        if reference {
            chart
                .draw_series(DashedLineSeries::new(
                    by_x(&row.kde),
                    10,
                    5,
                    color.stroke_width(width),
                ))
                .map_err(err)?
                .label(label)
                .legend(line_legend(color, width));
        } else {
            chart
                .draw_series(LineSeries::new(by_x(&row.kde), color.stroke_width(width)))
                .map_err(err)?
                .label(label)
                .legend(line_legend(color, width));
        }
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}
