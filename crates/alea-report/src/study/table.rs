//! The statistics table of `alea run` / `alea report`: every method's mean, std and skewness
//! per quantity, the failure probabilities of the main method.

use alea_study::analysis::MethodResult;
use alea_study::runner::Study;

use crate::Console;

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
        console.line(&format!(
            "  {:<34} {:>5} {:>14} {:>14} {:>10}",
            "method", "runs", "mean", "std", "skewness"
        ));
        for r in results {
            match r.qois.get(q) {
                Some(s) => console.line(&format!(
                    "  {:<34} {:>5} {:>14.6e} {:>14.6e} {:>10.3}",
                    r.label, r.runs_used, s.mean, s.std, s.skewness
                )),
                None => console.line(&format!(
                    "  {:<34} {:>5} {:>14} {:>14} {:>10}",
                    r.label, r.runs_used, "-", "-", "-"
                )),
            }
        }
        if let Some(s) = results.iter().find_map(|r| r.qois.get(q)) {
            for f in &s.failure {
                console.line(&format!(
                    "  P({} > {}) = {:.4e}  ({:.0}% interval [{:.4e}, {:.4e}])",
                    qoi.name,
                    f.threshold,
                    f.probability,
                    100.0 * confidence,
                    f.ci_low,
                    f.ci_high
                ));
            }
        }
    }
    console.line("");
}
