//! The PDFs of several methods in one plot: each method's density (of the samples off its
//! atoms, scaled by their share), its probability atoms as stems ending in a dot (height: the
//! probability, the top of the frame standing for 1) and the total interval of its mean as a
//! horizontal error bar near the axis (issue 40, item 3).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::format::prob;
use super::super::{Comparison, Statistic};
use super::common::{
    DrawResult, PALETTE, axis_label, by_x, chart, configure_legend, err, extend, grid, line_legend,
    pad, ticks,
};
use super::marks::{clipped_interval, draw_atoms, error_bar};

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
        for a in &row.atoms {
            extend(&mut xr, a.value);
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
    let top = ymax / 1.15;
    let mut k = 0;
    for (i, row) in c.rows.iter().enumerate() {
        if row.kde.len() < 2 && row.atoms.is_empty() {
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
        let mut label = if row.method.contains("run") {
            row.method.clone()
        } else {
            format!("{} ({} runs)", row.method, row.runs)
        };
        for a in &row.atoms {
            label.push_str(&format!(
                ", P(q = {}) = {}",
                ticks(x0, x1, 8)(&a.value),
                prob(a.probability)
            ));
        }
        // The mean's total interval, one height per method near the axis.
        if let Some(b) = clipped_interval(&row.budget, Statistic::Mean, (x0, x1)) {
            let y = top * (0.03 + 0.03 * i as f64);
            chart
                .draw_series(std::iter::once(error_bar(y, b, color)))
                .map_err(err)?;
        }
        draw_atoms(&mut chart, &row.atoms, top, color, None)?;
        if row.kde.len() < 2 {
            // Atoms only: the legend entry on a dot.
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(err)?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 11, y), 6, color.filled()));
            continue;
        }
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
