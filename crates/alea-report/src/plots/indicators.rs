//! The error indicators of the adaptive steps.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::AdaptiveReport;
use super::common::{
    DrawResult, PALETTE, configure_legend, count_log_chart, err, extend, line_legend, pad,
};

/// `i_sto` (solid) and `i_geo` (dashed) of each adaptive method against its number of runs
/// (log scale), with the thesis's stopping rule `i_sto <= i_geo` where the lines cross.
pub(super) fn draw_indicators<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    adaptive: &[AdaptiveReport],
) -> DrawResult {
    let mut xr = None;
    let mut yr = None;
    for a in adaptive {
        for s in &a.steps {
            extend(&mut xr, s.runs as f64);
            for v in [s.i_sto, s.i_geo] {
                if v > 0.0 {
                    extend(&mut yr, 100.0 * v);
                }
            }
        }
    }
    let (x0, x1) = pad(xr.unwrap_or((0.0, 1.0)), 0.05);
    let mut chart = count_log_chart(
        root,
        "Error indicators of the adaptive steps",
        x0..x1,
        yr.unwrap_or((0.1, 100.0)),
        1.5,
        ("runs", "indicator (% of the admissible energy)"),
    )?;
    for (k, a) in adaptive.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts = |f: fn(&super::super::StepRow) -> f64| -> Vec<(f64, f64)> {
            a.steps
                .iter()
                .filter(|s| f(s) > 0.0)
                .map(|s| (s.runs as f64, 100.0 * f(s)))
                .collect()
        };
        let sto = pts(|s| s.i_sto);
        let geo = pts(|s| s.i_geo);
        chart
            .draw_series(LineSeries::new(sto.iter().copied(), color.stroke_width(2)))
            .map_err(err)?
            .label(format!("i_sto, {}", a.method))
            .legend(line_legend(color, 2));
        chart
            .draw_series(sto.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(err)?;
        chart
            .draw_series(DashedLineSeries::new(
                geo.iter().copied(),
                8,
                5,
                color.stroke_width(2),
            ))
            .map_err(err)?
            .label(format!("i_geo, {}", a.method))
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (8, 0)], color.stroke_width(2))
                    + PathElement::new(vec![(12, 0), (20, 0)], color.stroke_width(2))
            });
        chart
            .draw_series(geo.iter().map(|&p| Cross::new(p, 4, color.stroke_width(2))))
            .map_err(err)?;
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}
