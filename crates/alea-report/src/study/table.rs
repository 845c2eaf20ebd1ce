//! The statistics table of `alea run` / `alea report`: every method's mean, std and skewness
//! per quantity, the failure probabilities of the main method.

use alea_study::analysis::MethodResult;
use alea_study::runner::Study;

use crate::Console;
use crate::report::format::{num, prob};

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
                console.line(&format!("{} = {:e} {}", qoi.name, s.mean, qoi.unit));
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
            "  {:<34} {:>5} {:>14} {:>14} {:>10}",
            "method",
            "runs",
            format!("mean{unit}"),
            format!("std{unit}"),
            "skewness"
        ));
        for r in results {
            match r.qois.get(q) {
                Some(s) => console.line(&format!(
                    "  {:<34} {:>5} {:>14} {:>14} {:>10.3}",
                    r.label,
                    r.runs_used,
                    num(s.mean, 6),
                    num(s.std, 6),
                    s.skewness
                )),
                None => console.line(&format!(
                    "  {:<34} {:>5} {:>14} {:>14} {:>10}",
                    r.label, r.runs_used, "-", "-", "-"
                )),
            }
        }
        if let Some((r, s)) = results.iter().find_map(|r| r.qois.get(q).map(|s| (r, s))) {
            if let Some(b) = &s.budget {
                console.line(&format!("  error budget ({}):", r.label));
                for row in &b.rows {
                    if row.statistic.starts_with('q')
                        && !["q0.05", "q0.5", "q0.95"].contains(&row.statistic.as_str())
                    {
                        continue;
                    }
                    let unit = if row.statistic.starts_with('P') {
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
                    console.line(&format!(
                        "    {:<12} {:>13} {unit:<4} total +-{}: surrogate {}, sampling +-{}, mesh {}{sliding}",
                        row.statistic,
                        num(row.value, 6),
                        num(row.total, 3),
                        part(row.surrogate),
                        num(row.sampling, 3),
                        part(row.mesh)
                    ));
                }
            }
            for f in &s.failure {
                // The total interval of the error budget first (issue 40, item 3); the sampling
                // interval alone labelled as such.
                let total = s.budget.as_ref().and_then(|b| {
                    b.rows
                        .iter()
                        .find(|r| r.statistic == format!("P(> {})", f.threshold))
                        .map(|r| r.total)
                });
                let total_words = total.map_or_else(String::new, |t| {
                    format!(
                        "total interval [{}, {}] (budget, parts above); ",
                        prob((f.probability - t).max(0.0)),
                        prob((f.probability + t).min(1.0))
                    )
                });
                console.line(&format!(
                    "  P({} > {} {}) = {}  ({total_words}{:.0}% sampling interval [{}, {}])",
                    qoi.name,
                    num(f.threshold, 6),
                    qoi.unit,
                    prob(f.probability),
                    100.0 * confidence,
                    prob(f.ci_low),
                    prob(f.ci_high)
                ));
            }
        }
    }
    console.line("");
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
