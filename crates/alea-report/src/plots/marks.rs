//! Marks the density and distribution plots share (issue 40, item 3): probability atoms as
//! stems ending in a dot (height: the probability, the top of the frame standing for 1), the
//! total interval of a statistic as a horizontal error bar or a shaded band, and the
//! samples that are not atoms.

use plotters::coord::types::RangedCoordf64;
use plotters::element::ErrorBarOrientH;
use plotters::prelude::*;

use super::super::format::{num, prob};
use super::super::{Atom, BudgetRow, Statistic, budget_row};
use super::common::{DrawResult, err, font};

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// `sorted` without the values of `atoms` (exact equality: the atoms are values samples take
/// exactly).
pub(super) fn without_atoms(sorted: &[f64], atoms: &[Atom]) -> Vec<f64> {
    if atoms.is_empty() {
        return sorted.to_vec();
    }
    sorted
        .iter()
        .copied()
        .filter(|v| !atoms.iter().any(|a| a.value == *v))
        .collect()
}

/// The legend text of an atom: `P(q = v) = p` and its sampling-only interval.
pub(super) fn atom_label(a: &Atom) -> String {
    format!(
        "atom P(q = {}) = {} [{}, {}] (sampling only)",
        num(a.value, 4),
        prob(a.probability),
        prob(a.ci_low),
        prob(a.ci_high)
    )
}

/// Draws each atom as a stem from 0 to `probability * top` ending in a dot, with `label` in
/// the legend and `P = p` written beside the dot (`None`: neither, the caller's legend says it).
pub(super) fn draw_atoms<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    atoms: &[Atom],
    top: f64,
    color: RGBColor,
    label: Option<String>,
) -> DrawResult {
    for (k, a) in atoms.iter().enumerate() {
        let h = a.probability * top;
        chart
            .draw_series(LineSeries::new(
                [(a.value, 0.0), (a.value, h)],
                color.stroke_width(3),
            ))
            .map_err(err)?;
        let dots = chart
            .draw_series(std::iter::once(Circle::new(
                (a.value, h),
                6,
                color.filled(),
            )))
            .map_err(err)?;
        if k == 0
            && let Some(l) = &label
        {
            dots.label(l.clone())
                .legend(move |(x, y)| Circle::new((x + 11, y), 6, color.filled()));
        }
        if label.is_some() {
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((a.value, h))
                        + Text::new(
                            format!("P = {}", prob(a.probability)),
                            (10, -18),
                            font(15.0).color(&color),
                        ),
                ))
                .map_err(err)?;
        }
    }
    Ok(())
}

/// The total interval of `statistic` clipped to the x range `(x0, x1)`, with the estimate:
/// `(lo, estimate, hi)`; `None` without a budget row or wholly off the range.
pub(super) fn clipped_interval(
    rows: &[BudgetRow],
    statistic: Statistic,
    (x0, x1): (f64, f64),
) -> Option<(f64, f64, f64)> {
    let row = budget_row(rows, statistic)?;
    let (lo, hi) = row.interval();
    (hi >= x0 && lo <= x1).then(|| (lo.max(x0), row.estimate(), hi.min(x1)))
}

/// A horizontal error bar at height `y` over `(lo, hi)` with a dot at `mid` (plotters'
/// `ErrorBar`: caps of 10 pixels).
pub(super) fn error_bar(
    y: f64,
    (lo, mid, hi): (f64, f64, f64),
    color: RGBColor,
) -> ErrorBar<f64, f64, ErrorBarOrientH<f64, f64>> {
    ErrorBar::new_horizontal(y, lo, mid, hi, color.stroke_width(2), 10)
}

/// The total interval of the mean as a shaded band over the full height `top`, labelled.
pub(super) fn draw_mean_band<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    rows: &[BudgetRow],
    range: (f64, f64),
    top: f64,
    color: RGBColor,
) -> DrawResult {
    let Some((lo, _, hi)) = clipped_interval(rows, Statistic::Mean, range) else {
        return Ok(());
    };
    let Some((a, b)) = budget_row(rows, Statistic::Mean).map(BudgetRow::interval) else {
        return Ok(());
    };
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(lo, 0.0), (hi, top)],
            color.mix(0.13).filled(),
        )))
        .map_err(err)?
        .label(format!(
            "mean's total interval [{}, {}]",
            num(a, 4),
            num(b, 4)
        ))
        .legend(move |(x, y)| {
            Rectangle::new([(x, y - 6), (x + 22, y + 6)], color.mix(0.3).filled())
        });
    Ok(())
}
