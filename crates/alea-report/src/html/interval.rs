//! What a statistic reads as on the page (issue 40, item 3): its estimate
//! ([`BudgetRow::estimate`]: corrected by the validation runs where there are some) and its
//! total interval ([`BudgetRow::interval`]: every estimated part of the error budget), from
//! the statistic's budget row; the sampling-only interval is never shown without its label.

use super::super::format::{num, prob};
use super::super::{BudgetRow, Statistic, budget_row};

/// The value users read of `statistic`: the budget row's estimate, else `value` (no budget).
pub(super) fn estimate(rows: &[BudgetRow], statistic: Statistic, value: f64) -> f64 {
    budget_row(rows, statistic).map_or(value, BudgetRow::estimate)
}

/// How a bound is written: a probability, or a number with its significant digits.
#[derive(Clone, Copy)]
pub(super) enum Style {
    Prob,
    Num(usize),
}

impl Style {
    pub(super) fn text(self, v: f64) -> String {
        match self {
            Style::Prob => prob(v),
            Style::Num(sig) => num(v, sig),
        }
    }
}

/// `[lo, hi]`, the total interval of `statistic`, or `None` when it has no budget row.
pub(super) fn total(rows: &[BudgetRow], statistic: Statistic, style: Style) -> Option<String> {
    let (lo, hi) = budget_row(rows, statistic)?.interval();
    Some(format!("[{}, {}]", style.text(lo), style.text(hi)))
}

/// A table cell's text: the estimate of `statistic` followed by its total interval in a
/// `ci` span (`value` alone when not estimated).
pub(super) fn with_total(
    rows: &[BudgetRow],
    statistic: Statistic,
    value: f64,
    style: Style,
) -> String {
    let e = style.text(estimate(rows, statistic, value));
    match total(rows, statistic, style) {
        Some(t) => format!("{e} <span class=\"ci\">{t}</span>"),
        None => e,
    }
}
