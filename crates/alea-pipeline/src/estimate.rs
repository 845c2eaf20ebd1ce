//! The error estimates of a study's methods (the estimate of every method with a surrogate;
//! adaptive methods reuse their last step); `result.rs` gives them their place in the study's result.

use std::path::Path;

use alea_estimate::density::PairMap;
use alea_estimate::{EntityEstimate, Estimate};
use alea_study::StudyError;
use alea_study::analysis::MethodResult;
use alea_study::estimate::{
    ErrorSettings, MethodEstimateInput, SurrogateEstimate, density_maps, error_settings,
    estimate_method, write_error_fields,
};
use alea_study::method::{Method, MethodKind};
use alea_study::runner::{Study, StudyRuns};
use alea_study::store::Store;

use super::results::converged_runs;
use crate::Console;

/// The error estimate of one method.
pub(super) struct MethodEstimate {
    /// Method index.
    pub method: usize,
    /// The estimate (or why there is none).
    pub result: Result<SurrogateEstimate, String>,
    /// Density maps (main method only).
    pub maps: Vec<PairMap>,
    /// The ParaView file of the mean error density per cell (main method only).
    pub vtu: Option<std::path::PathBuf>,
}

/// Estimates the error of every method with a surrogate; `main` (the method that answers) also
/// gets its density maps.
pub(super) fn estimate_all(
    study: &Study,
    runs: &StudyRuns,
    results: &[MethodResult],
    dir: &Path,
    main: Option<usize>,
    console: &dyn Console,
) -> Result<(ErrorSettings, Vec<MethodEstimate>), StudyError> {
    let settings = error_settings(study)?;
    let Some(setup) = &runs.cre else {
        return Ok((settings, Vec::new()));
    };
    let store = Store::open(dir, &study.hash, false)?;
    let mut out = Vec::new();
    for (m, method) in runs.methods.iter().enumerate() {
        if method.kind == MethodKind::MonteCarlo {
            continue;
        }
        let adaptive = runs.adaptive.iter().find(|a| a.method == m);
        let used = used_points(method, runs);
        let sur = method.surrogate(&study.params, &used);
        let input = sur.as_ref().map(|sur| MethodEstimateInput {
            study,
            setup,
            solver: &runs.solver,
            store: &store,
            method,
            points: &used,
            sur,
            settings: &settings,
        });
        let computed =
            (|| -> Result<(Option<alea_estimate::Estimator>, SurrogateEstimate), String> {
                if let Some(a) = adaptive {
                    let last = a.steps.last().ok_or("the adaptive loop made no estimate")?;
                    return Ok((a.estimator.clone(), last.error.clone()));
                }
                if results[m].qois.is_empty() {
                    return Err(results[m]
                        .account
                        .error
                        .clone()
                        .unwrap_or_else(|| "no statistics".into()));
                }
                let input = input.as_ref().map_err(|e| e.to_string())?;
                let (est, merr) = estimate_method(input).map_err(|e| e.to_string())?;
                Ok((Some(est), merr))
            })();
        let (result, maps, vtu) = match computed {
            Ok((est, merr)) => {
                let (mut maps, mut vtu) = (Vec::new(), None);
                if let (true, Ok(input)) = (Some(m) == main, &input) {
                    if let (Some(est), true) = (&est, study.params.names.len() >= 2) {
                        maps = density_maps(study, &runs.solver, est, input.sur, &settings)
                            .unwrap_or_default();
                    }
                    vtu = write_error_fields(input, est.as_ref(), dir)?;
                }
                (Ok(merr), maps, vtu)
            }
            Err(e) => (Err(e), Vec::new(), None),
        };
        if let Some(p) = &vtu {
            console.line(&format!(
                "mean error densities (cells, interface nodes): {}",
                p.display()
            ));
        }
        out.push(MethodEstimate {
            method: m,
            result,
            maps,
            vtu,
        });
    }
    Ok((settings, out))
}

/// The converged runs of a method, in its point order (the surrogate's run order).
fn used_points(method: &Method, runs: &StudyRuns) -> Vec<Vec<f64>> {
    converged_runs(&method.points, &runs.records)
        .into_iter()
        .map(|(p, _)| p.clone())
        .collect()
}

/// The entity that carries the largest part of `part(entity)`, with its share.
pub(super) fn dominant(est: &Estimate, part: impl Fn(&EntityEstimate) -> f64) -> (String, f64) {
    let subs = est.subs.iter().map(|e| ("substructure", e, part(e)));
    let interfaces = est.interfaces.iter().map(|e| ("interface", e, part(e)));
    largest_share(
        subs.chain(interfaces)
            .map(|(kind, e, v)| (kind, e.name.as_str(), v)),
    )
}

/// Among `(kind, name, part)` (substructures first, then interfaces), the entity that carries
/// the largest part (`kind 'name'`), with its share of the sum of the parts (negative ones
/// counted as 0).
pub(super) fn largest_share<'a>(
    parts: impl Iterator<Item = (&'a str, &'a str, f64)>,
) -> (String, f64) {
    let parts: Vec<(&str, &str, f64)> = parts.collect();
    let total: f64 = parts.iter().map(|p| p.2.max(0.0)).sum();
    let mut best = (String::new(), 0.0);
    for (kind, name, v) in parts {
        let v = v.max(0.0);
        if v > best.1 {
            best = (format!("{kind} '{name}'"), v);
        }
    }
    (best.0, if total > 0.0 { best.1 / total } else { 0.0 })
}
