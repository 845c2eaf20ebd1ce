//! The report's error section from the study's result (the indicators of every method, the
//! main method's entities, the adaptive steps) and from the error estimates (the main
//! method's density map and error fields).

use alea_study::estimate::ErrorSettings;
use alea_study::runner::{Study, StudyRuns};

use super::estimate::{MethodEstimate, largest_share};
use super::result::{AdaptiveLoop, ErrorEstimate, StudyResult, SurrogateError};
use alea_report::{AdaptiveReport, EntityRow, ErrorReport, ErrorRow, StepRow, Surface};

/// The report's error section: indicators per method, the main method's entities, adaptive
/// steps, the first density map.
pub(super) fn report_error(
    study: &Study,
    runs: &StudyRuns,
    result: &StudyResult,
    settings: &ErrorSettings,
    estimates: &[MethodEstimate],
) -> Option<ErrorReport> {
    if estimates.is_empty() {
        return None;
    }
    let methods = result
        .methods
        .iter()
        .filter_map(|m| {
            let e = estimated(&m.error_estimate)?;
            let (who, share) = largest_share(
                e.entities
                    .iter()
                    .map(|x| (x.kind.as_str(), x.name.as_str(), x.e2)),
            );
            Some(ErrorRow {
                method: m.account.label.clone(),
                runs: e.runs,
                relative: e.relative,
                i_geo: e.i_geo,
                i_sto: e.i_sto,
                dominant: format!("{who}: {:.0} %", 100.0 * share),
                violation: e.violation_probability.clamp(0.0, 1.0),
            })
        })
        .collect();
    let main = estimates
        .iter()
        .find(|me| me.result.is_ok() && (!me.maps.is_empty() || me.vtu.is_some()))
        .or_else(|| estimates.iter().find(|me| me.result.is_ok()));
    let (main_label, entities, map, vtu) = match main {
        Some(me) => {
            let m = &result.methods[me.method];
            let e = estimated(&m.error_estimate)?;
            let entities = e
                .entities
                .iter()
                .map(|x| EntityRow {
                    entity: x.name.clone(),
                    kind: x.kind.clone(),
                    relative: x.relative,
                    i_geo: x.i_geo,
                    i_sto: x.i_sto,
                    mean_share: (x.kind == "substructure" && x.e2 > 0.0)
                        .then(|| (x.mean2 / x.e2).clamp(0.0, 1.0)),
                })
                .collect();
            let map = me.maps.iter().find(|m| m.axes == [0, 1]).map(|m| {
                let method = &runs.methods[me.method];
                let floor = m.sto.iter().copied().fold(f64::INFINITY, f64::min).max(0.0);
                Surface {
                    param_names: [study.params.names[0].clone(), study.params.names[1].clone()],
                    x: m.x.clone(),
                    y: m.y.clone(),
                    values: m.sto.iter().map(|v| v.max(0.0)).collect(),
                    points: method.points.iter().map(|p| [p[0], p[1], floor]).collect(),
                }
            });
            (
                m.account.label.clone(),
                entities,
                map,
                me.vtu.as_ref().map(|p| p.display().to_string()),
            )
        }
        None => (String::new(), Vec::new(), None, None),
    };
    let qoi = study
        .qois
        .first()
        .map_or("-".to_string(), |q| q.name.clone());
    // In the order the loops ran.
    let adaptive = runs
        .adaptive
        .iter()
        .filter_map(|a| {
            let m = &result.methods[a.method];
            Some(adaptive_report(
                &m.account.label,
                m.adaptive.as_ref()?,
                &qoi,
            ))
        })
        .collect();
    Some(ErrorReport {
        warn: settings.warn,
        methods,
        main: main_label,
        entities,
        adaptive,
        map,
        vtu,
    })
}

/// The estimate of a method that has one.
fn estimated(e: &Option<ErrorEstimate>) -> Option<&SurrogateError> {
    match e {
        Some(ErrorEstimate::Estimated(e)) => Some(e),
        _ => None,
    }
}

/// The steps of the adaptive method `label`, with the statistics of the first quantity `qoi`.
fn adaptive_report(label: &str, a: &AdaptiveLoop, qoi: &str) -> AdaptiveReport {
    AdaptiveReport {
        method: label.to_string(),
        stop: a.stop.clone(),
        qoi: qoi.to_string(),
        steps: a
            .steps
            .iter()
            .map(|s| {
                let q = s.qois.first();
                StepRow {
                    runs: s.runs,
                    new_runs: s.new_runs,
                    i_sto: s.estimate.i_sto,
                    i_geo: s.estimate.i_geo,
                    relative: s.estimate.relative,
                    mean: q.map_or(0.0, |q| q.mean),
                    std: q.map_or(0.0, |q| q.std),
                    failure: q.and_then(|q| q.failure.first().copied()),
                    cost: s.thesis_cost,
                }
            })
            .collect(),
    }
}
