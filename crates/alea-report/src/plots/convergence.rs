//! The LATIN error indicator per iteration, one line per run.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    DrawResult, PALETTE, configure_legend, count_log_chart, err, extend, line_legend,
};

/// Legend entries at most in the convergence plot.
const MAX_LEGEND: usize = 12;

pub(super) fn draw_convergence<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    histories: &[(&str, Vec<(f64, f64)>)],
) -> DrawResult {
    let mut xr = None;
    let mut yr = None;
    for (_, h) in histories {
        for &(i, v) in h {
            extend(&mut xr, i);
            extend(&mut yr, v);
        }
    }
    let (x0, x1) = xr.unwrap_or((1.0, 1.0));
    let (x0, x1) = if x1 > x0 {
        (x0 - 0.02 * (x1 - x0), x1 + 0.02 * (x1 - x0))
    } else {
        (x0 - 0.5, x1 + 0.5)
    };
    let mut chart = count_log_chart(
        root,
        "Convergence of the LATIN iterations",
        x0..x1,
        yr.unwrap_or((0.1, 1.0)),
        1.6,
        ("iteration", "LATIN error indicator"),
    )?;
    for (k, (label, h)) in histories.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let series = chart
            .draw_series(LineSeries::new(h.iter().copied(), color.stroke_width(2)))
            .map_err(err)?;
        if k < MAX_LEGEND {
            series.label(*label).legend(line_legend(color, 2));
        } else if k == MAX_LEGEND {
            series
                .label(format!("... {} more", histories.len() - MAX_LEGEND))
                .legend(line_legend(color, 2));
        }
        if h.len() <= 25 {
            chart
                .draw_series(h.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(err)?;
        }
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}
