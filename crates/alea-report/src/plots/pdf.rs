//! The PDF plot of a QoI: KDE over a normalised histogram, mean with the band of its total
//! interval, failure regions; probability atoms as stems (the histogram and the KDE are then
//! those of the other samples, scaled by their share: `alea_study::atoms`).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::super::QoiReport;
use super::super::format::{count, num};
use super::common::{
    DrawResult, HIST_EDGE, HIST_FILL, KDE, MEAN, THRESHOLD, axis_label, by_x, chart,
    configure_legend, err, grid, line_legend, ticks,
};
use super::marks::{atom_label, draw_atoms, draw_mean_band, without_atoms};
use super::qoi::{draw_mean, draw_thresholds, qoi_x_range};

/// The region under a curve (increasing x) right of `t`, as a closed polygon; `None` when the
/// curve ends before `t`.
fn tail_polygon(curve: &[(f64, f64)], t: f64) -> Option<Vec<(f64, f64)>> {
    let last = *curve.last()?;
    if last.0 <= t {
        return None;
    }
    let k = curve.partition_point(|p| p.0 <= t);
    let start = if k == 0 {
        curve[0]
    } else {
        let (a, b) = (curve[k - 1], curve[k]);
        let w = (t - a.0) / (b.0 - a.0);
        (t, a.1 + w * (b.1 - a.1))
    };
    let mut poly = vec![(start.0, 0.0), start];
    poly.extend_from_slice(&curve[k..]);
    poly.push((last.0, 0.0));
    Some(poly)
}

/// Freedman-Diaconis bins (10 to 80) of sorted samples, as (left, right, density), the
/// densities scaled by `share` (the samples' share of the law: 1 without atoms).
fn histogram(sorted: &[f64], share: f64) -> Vec<(f64, f64, f64)> {
    let n = sorted.len();
    if n < 2 {
        return Vec::new();
    }
    let (lo, hi) = (sorted[0], sorted[n - 1]);
    if !(hi > lo) {
        return Vec::new();
    }
    let iqr = sorted[(3 * (n - 1)) / 4] - sorted[(n - 1) / 4];
    let bins = if iqr > 0.0 {
        let h = 2.0 * iqr / (n as f64).cbrt();
        ((hi - lo) / h).ceil() as usize
    } else {
        (n as f64).sqrt().ceil() as usize
    }
    .clamp(10, 80);
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for &v in sorted {
        let b = (((v - lo) / width) as usize).min(bins - 1);
        counts[b] += 1;
    }
    counts
        .iter()
        .enumerate()
        .map(|(b, &c)| {
            let a = lo + b as f64 * width;
            (a, a + width, share * c as f64 / (n as f64 * width))
        })
        .collect()
}

pub(super) fn draw_pdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    q: &QoiReport,
    sorted: &[f64],
) -> DrawResult {
    let ((lo, hi), on_scale) = qoi_x_range(q, sorted);
    let rest = without_atoms(sorted, &q.atoms);
    let share = rest.len() as f64 / sorted.len().max(1) as f64;
    let bars = histogram(&rest, share);
    // A constant sample handed over without its atom: one line.
    let point_mass = !sorted.is_empty() && bars.is_empty() && q.atoms.is_empty();
    let ymax = bars
        .iter()
        .map(|b| b.2)
        .chain(q.kde.iter().map(|p| p.1))
        .fold(0.0, f64::max);
    let ymax = if ymax > 0.0 { ymax * 1.15 } else { 1.0 };
    let mut chart = chart(
        root,
        format!("Probability density of {}", q.name),
        lo..hi,
        0.0..ymax,
    )?;
    grid(&mut chart.configure_mesh())
        .x_desc(axis_label(&q.name, &q.unit))
        .y_desc("probability density")
        .x_labels(8)
        .y_labels(7)
        .x_label_formatter(&ticks(lo, hi, 8))
        .y_label_formatter(&ticks(0.0, ymax, 7))
        .draw()
        .map_err(err)?;
    let top = ymax / 1.15;
    draw_mean_band(&mut chart, &q.budget, (lo, hi), top, MEAN)?;
    if !bars.is_empty() {
        let what = if q.atoms.is_empty() {
            format!("histogram of {} samples", count(sorted.len()))
        } else {
            format!(
                "histogram of the {} samples off the atoms",
                count(rest.len())
            )
        };
        chart
            .draw_series(
                bars.iter()
                    .map(|&(a, b, d)| Rectangle::new([(a, 0.0), (b, d)], HIST_FILL.filled())),
            )
            .map_err(err)?
            .label(what)
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 22, y + 6)], HIST_FILL.filled()));
        chart
            .draw_series(
                bars.iter().map(|&(a, b, d)| {
                    Rectangle::new([(a, 0.0), (b, d)], HIST_EDGE.stroke_width(1))
                }),
            )
            .map_err(err)?;
    }
    if point_mass {
        let v = sorted[0];
        chart
            .draw_series(LineSeries::new(
                [(v, 0.0), (v, ymax / 1.15)],
                KDE.stroke_width(4),
            ))
            .map_err(err)?
            .label(format!("all {} samples = {}", sorted.len(), num(v, 5)))
            .legend(line_legend(KDE, 4));
    }
    if q.kde.len() >= 2 {
        // The failure region P(q > t) shaded under the KDE, for each threshold on scale.
        let kde = by_x(&q.kde);
        for (f, on) in q.failure.iter().zip(&on_scale) {
            if let (true, Some(tail)) = (*on, tail_polygon(&kde, f.threshold)) {
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        tail,
                        THRESHOLD.mix(0.14).filled(),
                    )))
                    .map_err(err)?;
            }
        }
        chart
            .draw_series(LineSeries::new(by_x(&q.kde), KDE.stroke_width(3)))
            .map_err(err)?
            .label(if q.atoms.is_empty() {
                "kernel density estimate"
            } else {
                "kernel density estimate off the atoms"
            })
            .legend(line_legend(KDE, 3));
    }
    for a in &q.atoms {
        draw_atoms(
            &mut chart,
            std::slice::from_ref(a),
            top,
            KDE,
            Some(atom_label(a)),
        )?;
    }
    draw_mean(&mut chart, q, top)?;
    draw_thresholds(&mut chart, q, &on_scale, top)?;
    let position = if q.mean > 0.5 * (lo + hi) {
        SeriesLabelPosition::UpperLeft
    } else {
        SeriesLabelPosition::UpperRight
    };
    configure_legend(&mut chart, position)
}
