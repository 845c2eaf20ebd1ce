//! `alea run`'s error-estimate outputs: the estimate of every method with a surrogate (adaptive
//! methods reuse their last step), the CLI table and warnings, and the JSON for `summary.json`.

use std::path::Path;

use alea_estimate::Estimate;
use alea_estimate::density::PairMap;
use alea_study::adaptive::AdaptiveOutcome;
use alea_study::analysis::MethodResult;
use alea_study::estimate::{
    ErrorSettings, SurrogateEstimate, density_maps, error_settings, estimate_method,
};
use alea_study::method::{Method, MethodKind};
use alea_study::runner::{Study, StudyRuns};
use alea_study::store::{Store, point_key};
use anyhow::Result;

/// The error estimate of one method.
pub struct MethodEstimate {
    /// Method index.
    pub method: usize,
    /// The estimate (or why there is none).
    pub result: std::result::Result<SurrogateEstimate, String>,
    /// Density maps (main method only).
    pub maps: Vec<PairMap>,
    /// The ParaView file of the mean error density per cell (main method only).
    pub vtu: Option<std::path::PathBuf>,
}

/// Estimates the error of every method with a surrogate; `main` (the method that answers) also
/// gets its density maps.
pub fn estimate_all(
    study: &Study,
    runs: &StudyRuns,
    results: &[MethodResult],
    dir: &Path,
    main: Option<usize>,
) -> Result<(ErrorSettings, Vec<MethodEstimate>)> {
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
        let computed =
            (|| -> std::result::Result<(Option<alea_estimate::Estimator>, SurrogateEstimate), String> {
                if let Some(a) = adaptive {
                    let last = a.steps.last().ok_or("the adaptive loop made no estimate")?;
                    return Ok((a.estimator.clone(), last.error.clone()));
                }
                if results[m].qois.is_empty() {
                    return Err(results[m]
                        .error
                        .clone()
                        .unwrap_or_else(|| "no statistics".into()));
                }
                let used = used_points(method, runs);
                let sur = method.surrogate(&study.params, &used)?;
                let (est, merr) = estimate_method(
                    study,
                    setup,
                    &runs.solver,
                    &store,
                    method,
                    &used,
                    &sur,
                    &settings,
                )
                .map_err(|e| e.to_string())?;
                Ok((Some(est), merr))
            })();
        let (result, maps, vtu) = match computed {
            Ok((est, merr)) => {
                let (mut maps, mut vtu) = (Vec::new(), None);
                if Some(m) == main {
                    let used = used_points(method, runs);
                    if let Ok(sur) = method.surrogate(&study.params, &used) {
                        if let (Some(est), true) = (&est, study.params.names.len() >= 2) {
                            maps = density_maps(study, &runs.solver, est, &sur, &settings)
                                .unwrap_or_default();
                        }
                        vtu = alea_study::estimate::write_error_fields(
                            study,
                            setup,
                            &runs.solver,
                            &store,
                            method,
                            &used,
                            &sur,
                            &settings,
                            est.as_ref(),
                            dir,
                        )?;
                    }
                }
                (Ok(merr), maps, vtu)
            }
            Err(e) => (Err(e), Vec::new(), None),
        };
        if let Some(p) = &vtu {
            println!(
                "mean error densities (cells, interface nodes): {}",
                p.display()
            );
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
    let by_key: std::collections::HashMap<String, &alea_study::store::RunRecord> = runs
        .records
        .iter()
        .map(|r| (point_key(&r.params), r))
        .collect();
    method
        .points
        .iter()
        .filter(|p| by_key.get(&point_key(p)).is_some_and(|r| r.converged()))
        .cloned()
        .collect()
}

fn pct(v: f64) -> String {
    format!("{:.2} %", 100.0 * v)
}

/// The entity that carries the largest part of `part(entity)`, with its share.
fn dominant(est: &Estimate, part: impl Fn(&alea_estimate::EntityEstimate) -> f64) -> (String, f64) {
    let total: f64 = est
        .subs
        .iter()
        .chain(&est.interfaces)
        .map(|e| part(e).max(0.0))
        .sum();
    let mut best = (String::new(), 0.0);
    for (kind, list) in [("substructure", &est.subs), ("interface", &est.interfaces)] {
        for e in list.iter() {
            let v = part(e).max(0.0);
            if v > best.1 {
                best = (format!("{kind} '{}'", e.name), v);
            }
        }
    }
    (best.0, if total > 0.0 { best.1 / total } else { 0.0 })
}

/// Prints the indicators of every method, the adaptive steps, and the warnings; returns the
/// warnings (for the report's notes).
pub fn print(
    study: &Study,
    runs: &StudyRuns,
    settings: &ErrorSettings,
    estimates: &[MethodEstimate],
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
    println!(
        "error estimate (constitutive-relation error, thesis 3.2 / 4.1; relative to the energy of the {}):",
        if all_admissible {
            "admissible stresses"
        } else {
            "admissible stresses, FE stresses where there are none (3D: interface part only)"
        }
    );
    println!(
        "  {:<34} {:>5} {:>9} {:>9} {:>9}  largest part",
        "method", "runs", "e~", "i_geo", "i_sto"
    );
    for me in estimates {
        let label = &runs.methods[me.method].label;
        match &me.result {
            Ok(e) => {
                let est = &e.estimate;
                let (who, share) = dominant(est, |x| x.e2);
                println!(
                    "  {:<34} {:>5} {:>9} {:>9} {:>9}  {who}: {:.0} % of e~^2",
                    label,
                    e.runs,
                    pct(est.relative()),
                    pct(est.i_geo()),
                    pct(est.i_sto()),
                    100.0 * share
                );
                if est.i_geo() > settings.warn {
                    let (w, s) = dominant(est, |x| x.geo2);
                    warnings.push(format!(
                        "method '{label}': i_geo = {} exceeds {}: the space mesh is too coarse for this answer; {w} carries {:.0} % of I_geo^2 (refine it)",
                        pct(est.i_geo()),
                        pct(settings.warn),
                        100.0 * s
                    ));
                }
                if est.i_sto() > settings.warn {
                    let (w, s) = dominant(est, |x| x.sto2);
                    warnings.push(format!(
                        "method '{label}': i_sto = {} exceeds {}: the surrogate needs more runs; {w} carries {:.0} % of I_sto^2",
                        pct(est.i_sto()),
                        pct(settings.warn),
                        100.0 * s
                    ));
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
            Err(why) => println!("  {label:<34} no estimate: {why}"),
        }
    }
    for a in &runs.adaptive {
        print_adaptive(study, runs, a);
        if let Some(e) = &a.error {
            warnings.push(format!("method '{}': {e}", runs.methods[a.method].label));
        }
    }
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    warnings
}

fn print_adaptive(study: &Study, runs: &StudyRuns, a: &AdaptiveOutcome) {
    let label = &runs.methods[a.method].label;
    println!("adaptive method '{label}': stopped: {}", a.stop);
    let q = study.qois.first();
    let qname = q.map_or("-".to_string(), |q| q.name.clone());
    println!(
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
    );
    for (i, s) in a.steps.iter().enumerate() {
        let est = &s.error.estimate;
        let (mean, std) = s
            .qois
            .first()
            .map_or((f64::NAN, f64::NAN), |q| (q.mean, q.std));
        println!(
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
        );
    }
}

fn entity_json(e: &alea_estimate::EntityEstimate, kind: &str, est: &Estimate) -> serde_json::Value {
    serde_json::json!({
        "name": e.name, "kind": kind,
        "e2": e.e2, "geo2": e.geo2, "sto2": e.sto2, "mean2": e.mean2, "std2": e.std2,
        "relative": est.relative_of(e.e2), "i_geo": est.relative_of(e.geo2),
        "i_sto": est.relative_of(e.sto2),
    })
}

/// The JSON of one method's estimate.
pub fn error_json(e: &SurrogateEstimate) -> serde_json::Value {
    let est = &e.estimate;
    let entities: Vec<serde_json::Value> = est
        .subs
        .iter()
        .map(|x| entity_json(x, "substructure", est))
        .chain(
            est.interfaces
                .iter()
                .map(|x| entity_json(x, "interface", est)),
        )
        .collect();
    serde_json::json!({
        "relative": est.relative(), "i_geo": est.i_geo(), "i_sto": est.i_sto(),
        "e2": est.e2, "geo2": est.geo2, "sto2": est.sto2, "norm2": est.norm2,
        "runs": e.runs, "rule_points": e.rule_points, "load_defect": e.load_defect,
        "violation_probability": est.violation_probability, "max_violation": est.max_violation,
        "substructures_estimated": e.substructures_estimated,
        "negative_parts": est.negative_parts(),
        "entities": entities,
    })
}

/// The JSON of an adaptive loop.
pub fn adaptive_json(a: &AdaptiveOutcome) -> serde_json::Value {
    let steps: Vec<serde_json::Value> = a
        .steps
        .iter()
        .map(|s| {
            serde_json::json!({
                "runs": s.runs, "new_runs": s.new_runs, "thesis_cost": s.thesis_cost,
                "estimate": error_json(&s.error),
                "qois": s.qois.iter().map(|q| serde_json::json!({
                    "mean": q.mean, "std": q.std, "failure": q.failure,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    serde_json::json!({
        "stop": a.stop, "error": a.error, "steps": steps,
        "runs": (0..a.mesh.num_runs()).map(|r| a.mesh.run_point(r).to_vec()).collect::<Vec<_>>(),
    })
}

/// The report's error section: indicators per method, the main method's entities, adaptive
/// steps, the first density map.
pub fn report_error(
    study: &Study,
    runs: &StudyRuns,
    settings: &ErrorSettings,
    estimates: &[MethodEstimate],
) -> Option<crate::report::ErrorReport> {
    use crate::report::{AdaptiveReport, EntityRow, ErrorReport, ErrorRow, StepRow, Surface};
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
