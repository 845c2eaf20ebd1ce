//! The statistics table of `alea run` / `alea report`: every method's mean and std with their
//! total intervals (the estimates and intervals of the error budget's rows, issue 40, item 3)
//! and skewness per quantity, the error budget of the main method, and every method's failure
//! probabilities with their total and sampling-only intervals.

use alea_study::analysis::{MethodResult, QoiStats};
use alea_study::budget::{BudgetRow, Statistic};
use alea_study::runner::Study;

use crate::Console;
use alea_report::format::{num, prob};

/// Shows the table on `console` (the values themselves, at full precision, for a study without
/// random parameters).
pub(super) fn print_table(
    study: &Study,
    results: &[MethodResult],
    confidence: f64,
    console: &dyn Console,
) {
    if study.params.names.is_empty() {
        // One deterministic run: the values themselves, at full precision.
        console.line("");
        for (q, qoi) in study.qois.iter().enumerate() {
            if let Some(s) = results.first().and_then(|r| r.qois.get(q)) {
                console.line(&format!(
                    "{} = {:e} {}",
                    qoi.name, s.distribution.mean, qoi.unit
                ));
            }
        }
        console.line("");
        return;
    }
    for (q, qoi) in study.qois.iter().enumerate() {
        console.line(&format!("\n{} [{}]: {}", qoi.name, qoi.unit, qoi.what));
        // Six significant digits, fixed notation where it reads (831.002, not 8.310020e2),
        // the unit in the header.
        let unit = if qoi.unit.is_empty() {
            String::new()
        } else {
            format!(" [{}]", qoi.unit)
        };
        console.line(&format!(
            "  {:<34} {:>5} {:>12} {:>24} {:>12} {:>24} {:>9}",
            "method",
            "runs",
            format!("mean{unit}"),
            "total interval",
            format!("std{unit}"),
            "total interval",
            "skewness"
        ));
        for r in results {
            match r.qois.get(q) {
                Some(s) => {
                    let (mean, mean_interval) = read(s, Statistic::Mean, s.distribution.mean, 6);
                    let (std, std_interval) = read(s, Statistic::Std, s.distribution.std, 6);
                    console.line(&format!(
                        "  {:<34} {:>5} {mean:>12} {mean_interval:>24} {std:>12} {std_interval:>24} {:>9.3}",
                        r.account.label, r.account.runs_used, s.distribution.skewness
                    ));
                }
                None => console.line(&format!(
                    "  {:<34} {:>5} {:>12} {:>24} {:>12} {:>24} {:>9}",
                    r.account.label, r.account.runs_used, "-", "-", "-", "-", "-"
                )),
            }
        }
        if let Some((r, b)) = results
            .iter()
            .find_map(|r| r.qois.get(q).map(|s| (r, s)))
            .and_then(|(r, s)| Some((r, s.budget.as_ref()?)))
        {
            console.line(&format!("  error budget ({}):", r.account.label));
            for row in &b.rows {
                if let Statistic::Quantile(p) = row.statistic
                    && ![0.05, 0.5, 0.95].contains(&p)
                {
                    continue;
                }
                let unit = if row.statistic.is_probability() {
                    ""
                } else {
                    qoi.unit.as_str()
                };
                let part = |v: Option<f64>| {
                    v.map_or_else(
                        || "not estimated".to_string(),
                        |v| format!("+-{}", num(v, 3)),
                    )
                };
                let sliding = row
                    .sliding
                    .map_or_else(String::new, |v| format!(", sliding +-{}", num(v, 3)));
                let corrected = row.validation.as_ref().map_or_else(String::new, |v| {
                    if v.detected {
                        format!(
                            " (surrogate {}, corrected by {} validation runs)",
                            num(row.value, 6),
                            v.runs
                        )
                    } else {
                        format!(" ({} validation runs agree within their noise)", v.runs)
                    }
                });
                console.line(&format!(
                    "    {:<12} {:>13} {unit:<4} total +-{}: surrogate {}, sampling +-{}, mesh {}{sliding}{corrected}",
                    row.statistic,
                    num(row.estimate(), 6),
                    num(row.total, 3),
                    part(row.surrogate),
                    num(row.sampling, 3),
                    part(row.mesh)
                ));
            }
        }
        // Every method's failure probabilities: the total interval of the error budget first
        // (issue 40, item 3), the sampling interval alone labelled as such.
        let several = results.iter().filter(|r| r.qois.get(q).is_some()).count() > 1;
        for r in results {
            let Some(s) = r.qois.get(q) else { continue };
            for f in &s.failure {
                let row = budget_row(s, Statistic::Exceedance(f.threshold));
                let total_words = row.map_or_else(String::new, |row| {
                    let (lo, hi) = row.interval();
                    format!("total interval [{}, {}] (budget); ", prob(lo), prob(hi))
                });
                console.line(&format!(
                    "  {}P({} > {} {}) = {}  ({total_words}{:.0}% sampling-only interval [{}, {}])",
                    if several {
                        format!("{}: ", r.account.label)
                    } else {
                        String::new()
                    },
                    qoi.name,
                    num(f.threshold, 6),
                    qoi.unit,
                    prob(row.map_or(f.probability, BudgetRow::estimate)),
                    100.0 * confidence,
                    prob(f.ci_low),
                    prob(f.ci_high)
                ));
            }
        }
    }
    console.line("");
}

/// The budget row of `statistic` of a quantity's statistics, if estimated.
fn budget_row(s: &QoiStats, statistic: Statistic) -> Option<&BudgetRow> {
    s.budget
        .as_ref()?
        .rows
        .iter()
        .find(|r| r.statistic == statistic)
}

/// What a user reads of `statistic`: its estimate (the budget's, else `value`) and its total
/// interval (`-` when not estimated), with `sig` significant digits.
fn read(s: &QoiStats, statistic: Statistic, value: f64, sig: usize) -> (String, String) {
    match budget_row(s, statistic) {
        Some(row) => {
            let (lo, hi) = row.interval();
            (
                num(row.estimate(), sig),
                format!("[{}, {}]", num(lo, sig - 2), num(hi, sig - 2)),
            )
        }
        None => (num(value, sig), "-".to_string()),
    }
}

/// The `[[reliability]]` results: the probability by each algorithm, with its interval and
/// cost.
pub(super) fn print_reliability(
    results: &[alea_study::reliability::ReliabilityResult],
    console: &dyn Console,
) {
    for r in results {
        console.line(&format!(
            "\nP({} > {}) on the surrogate of '{}':",
            r.quantity, r.threshold, r.method
        ));
        if let Some(f) = r.design_points.first() {
            console.line(&format!(
                "  FORM                 {:.4e}  beta {:.3}, {} design point(s), {} evaluations",
                f.pf,
                f.beta,
                r.design_points.len(),
                r.form_evaluations
            ));
        }
        if let Some(s) = &r.sorm {
            console.line(&format!(
                "  SORM                 {:.4e}  (Tvedt {:.4e}), {} evaluations",
                s.pf_breitung, s.pf_tvedt, s.evaluations
            ));
        }
        for (name, e) in [
            ("importance sampling", &r.importance),
            ("subset simulation", &r.subset),
        ] {
            if let Some(e) = e {
                console.line(&format!(
                    "  {name:<20} {:.4e}  [{:.4e}, {:.4e}], {} evaluations",
                    e.pf, e.lower, e.upper, e.evaluations
                ));
            }
        }
        if let Some(c) = &r.solver {
            console.line(&format!(
                "  on the solver        {:.4e}  [{:.4e}, {:.4e}], {} runs (importance sampling at beta {:.3}){}",
                c.pf,
                c.lower,
                c.upper,
                c.runs,
                c.beta,
                if c.failed > 0 {
                    format!("; {} runs missing or not converged, left out", c.failed)
                } else {
                    String::new()
                }
            ));
        }
    }
}
