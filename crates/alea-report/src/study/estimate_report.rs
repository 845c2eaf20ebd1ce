//! The report's error section from the error estimates.

use alea_study::estimate::ErrorSettings;
use alea_study::runner::{Study, StudyRuns};

use super::estimate::{MethodEstimate, dominant};
use crate::report::{AdaptiveReport, EntityRow, ErrorReport, ErrorRow, StepRow, Surface};

/// The report's error section: indicators per method, the main method's entities, adaptive
/// steps, the first density map.
pub(super) fn report_error(
    study: &Study,
    runs: &StudyRuns,
    settings: &ErrorSettings,
    estimates: &[MethodEstimate],
) -> Option<ErrorReport> {
    if estimates.is_empty() {
        return None;
    }
    let methods = estimates
        .iter()
        .filter_map(|me| {
            let e = me.result.as_ref().ok()?;
            let est = &e.estimate;
            let (who, share) = dominant(est, |x| x.e2);
            Some(ErrorRow {
                method: runs.methods[me.method].label.clone(),
                runs: e.runs,
                relative: est.relative(),
                i_geo: est.i_geo(),
                i_sto: est.i_sto(),
                dominant: format!("{who}: {:.0} %", 100.0 * share),
                violation: est.violation_probability.clamp(0.0, 1.0),
            })
        })
        .collect();
    let main = estimates
        .iter()
        .find(|me| me.result.is_ok() && (!me.maps.is_empty() || me.vtu.is_some()))
        .or_else(|| estimates.iter().find(|me| me.result.is_ok()));
    let (main_label, entities, map, vtu) = match main {
        Some(me) => {
            let e = me.result.as_ref().ok()?;
            let est = &e.estimate;
            let entities = est
                .subs
                .iter()
                .map(|x| (x, "substructure"))
                .chain(est.interfaces.iter().map(|x| (x, "interface")))
                .map(|(x, kind)| EntityRow {
                    entity: x.name.clone(),
                    kind: kind.into(),
                    relative: est.relative_of(x.e2),
                    i_geo: est.relative_of(x.geo2),
                    i_sto: est.relative_of(x.sto2),
                    mean_share: (kind == "substructure" && x.e2 > 0.0)
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
                runs.methods[me.method].label.clone(),
                entities,
                map,
                me.vtu.as_ref().map(|p| p.display().to_string()),
            )
        }
        None => (String::new(), Vec::new(), None, None),
    };
    let qoi = study.qois.first();
    let adaptive = runs
        .adaptive
        .iter()
        .map(|a| AdaptiveReport {
            method: runs.methods[a.method].label.clone(),
            stop: a.stop.clone(),
            qoi: qoi.map_or("-".to_string(), |q| q.name.clone()),
            steps: a
                .steps
                .iter()
                .map(|s| {
                    let est = &s.error.estimate;
                    let q = s.qois.first();
                    StepRow {
                        runs: s.runs,
                        new_runs: s.new_runs,
                        i_sto: est.i_sto(),
                        i_geo: est.i_geo(),
                        relative: est.relative(),
                        mean: q.map_or(0.0, |q| q.mean),
                        std: q.map_or(0.0, |q| q.std),
                        failure: q.and_then(|q| q.failure.first().copied()),
                        cost: s.thesis_cost,
                    }
                })
                .collect(),
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
