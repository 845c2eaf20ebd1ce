//! The error estimates in words: the indicators of every method, the adaptive steps, and the
//! warnings they raise.

use alea_study::adaptive::AdaptiveOutcome;
use alea_study::analysis::MethodResult;
use alea_study::estimate::ErrorSettings;
use alea_study::runner::{Study, StudyRuns};

use super::estimate::{MethodEstimate, dominant};
use crate::Console;

/// A fraction as a percentage with 2 decimals.
fn pct(v: f64) -> String {
    format!("{:.2} %", 100.0 * v)
}

/// Shows the indicators of every method, the adaptive steps, and the warnings; returns the
/// warnings (for the report's notes).
pub(super) fn print_estimates(
    study: &Study,
    runs: &StudyRuns,
    settings: &ErrorSettings,
    estimates: &[MethodEstimate],
    results: &[MethodResult],
    console: &dyn Console,
) -> Vec<String> {
    let mut warnings = Vec::new();
    if estimates.is_empty() {
        return warnings;
    }
    let all_admissible = estimates.iter().all(|e| {
        e.result
            .as_ref()
            .map_or(true, |r| r.substructures_estimated)
    });
    console.line(&format!(
        "error estimate (constitutive-relation error, thesis 3.2 / 4.1; relative to the energy of the {}):",
        if all_admissible {
            "admissible stresses"
        } else {
            "admissible stresses, FE stresses where there are none (3D: interface part only)"
        }
    ));
    console.line(&format!(
        "  {:<34} {:>5} {:>9} {:>9} {:>9}  largest part",
        "method", "runs", "e~", "i_geo", "i_sto"
    ));
    for me in estimates {
        let label = &runs.methods[me.method].label;
        match &me.result {
            Ok(e) => {
                let est = &e.estimate;
                let (who, share) = dominant(est, |x| x.e2);
                console.line(&format!(
                    "  {:<34} {:>5} {:>9} {:>9} {:>9}  {who}: {:.0} % of e~^2",
                    label,
                    e.runs,
                    pct(est.relative()),
                    pct(est.i_geo()),
                    pct(est.i_sto()),
                    100.0 * share
                ));
                if let Some(line) = results.get(me.method).and_then(validation_line) {
                    console.line(&line);
                }
                // The indicators above the warning threshold, with the entity to act on.
                type Part = fn(&alea_estimate::EntityEstimate) -> f64;
                let indicators: [(&str, &str, f64, Part, &str, &str); 2] = [
                    (
                        "i_geo",
                        "I_geo",
                        est.i_geo(),
                        |x| x.geo2,
                        "the space mesh is too coarse for this answer",
                        " (refine it)",
                    ),
                    (
                        "i_sto",
                        "I_sto",
                        est.i_sto(),
                        |x| x.sto2,
                        "the surrogate needs more runs",
                        "",
                    ),
                ];
                for (name, energy, value, part, why, advice) in indicators {
                    if value > settings.warn {
                        let (w, s) = dominant(est, part);
                        warnings.push(format!(
                            "method '{label}': {name} = {} exceeds {}: {why}; {w} carries {:.0} % of {}^2{advice}",
                            pct(value),
                            pct(settings.warn),
                            100.0 * s,
                            energy,
                        ));
                    }
                }
                for part in est.negative_parts() {
                    warnings.push(format!(
                        "method '{label}': {part}: a part of the error estimate is negative (a defect of the split, reported with its sign)"
                    ));
                }
                if est.violation_probability > 0.0 {
                    warnings.push(format!(
                        "method '{label}': the interpolated interface fields leave the admissible set (negative gap or normal force) with probability {:.3}: they are brought onto it and the correction is charged to I_sto",
                        est.violation_probability
                    ));
                }
                if e.load_defect > 1e-6 {
                    warnings.push(format!(
                        "method '{label}': the surrogate reproduces the load factors only to {:.1e}: the interpolated stresses are not exactly admissible",
                        e.load_defect
                    ));
                }
                if !e.substructures_estimated {
                    warnings.push(format!(
                        "method '{label}': 3D substructures: interface part of the error only (as the thesis's 3D study), relative indicators normalised by the FE energy; e~ is not a bound of the total error"
                    ));
                }
            }
            Err(why) => console.line(&format!("  {label:<34} no estimate: {why}")),
        }
    }
    for a in &runs.adaptive {
        print_adaptive(study, runs, a, console);
        if let Some(e) = &a.error {
            warnings.push(format!("method '{}': {e}", runs.methods[a.method].label));
        }
    }
    for w in &warnings {
        console.warning(w);
    }
    warnings
}

/// The surrogate's relative RMS error at the validation runs, per quantity, to read beside
/// `i_sto` (both relative to the size of what they measure: `i_sto` to the solution's energy,
/// this to the quantity's root mean square; `None` without validation runs).
fn validation_line(r: &MethodResult) -> Option<String> {
    let parts: Vec<String> = r
        .qois
        .iter()
        .filter_map(|s| {
            let e = s.budget.as_ref()?.validation_errors.as_ref()?;
            Some(format!("{} {}", s.name, pct(e.relative)))
        })
        .collect();
    let runs = r.qois.iter().find_map(|s| {
        s.budget
            .as_ref()?
            .validation_errors
            .as_ref()
            .map(|e| e.runs)
    })?;
    Some(format!(
        "  {:<34} the surrogate's RMS error at {runs} validation runs, relative to each quantity's: {}",
        "",
        parts.join(", ")
    ))
}

fn print_adaptive(study: &Study, runs: &StudyRuns, a: &AdaptiveOutcome, console: &dyn Console) {
    let label = &runs.methods[a.method].label;
    console.line(&format!("adaptive method '{label}': stopped: {}", a.stop));
    let q = study.qois.first();
    let qname = q.map_or("-".to_string(), |q| q.name.clone());
    console.line(&format!(
        "  {:>4} {:>5} {:>4} {:>9} {:>9} {:>9} {:>13} {:>13} {:>7} {:>8}",
        "step",
        "runs",
        "new",
        "i_sto",
        "i_geo",
        "e~",
        format!("mean {qname}"),
        format!("std {qname}"),
        "cost",
        "seconds"
    ));
    for (i, s) in a.steps.iter().enumerate() {
        let est = &s.error.estimate;
        let (mean, std) = s
            .qois
            .first()
            .map_or((f64::NAN, f64::NAN), |q| (q.mean, q.std));
        console.line(&format!(
            "  {:>4} {:>5} {:>4} {:>9} {:>9} {:>9} {:>13.5e} {:>13.5e} {:>7.1} {:>8.2}",
            i,
            s.runs,
            s.new_runs,
            pct(est.i_sto()),
            pct(est.i_geo()),
            pct(est.relative()),
            mean,
            std,
            s.thesis_cost,
            s.solve_seconds + s.estimate_seconds
        ));
    }
}
