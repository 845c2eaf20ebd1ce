//! Invalid, degenerate and serialised inputs.

use super::super::plots::SIZE;
use super::super::*;
use super::fixtures::*;

#[test]
fn nan_is_an_error_naming_the_field() {
    let mut input = synthetic();
    input.qois[0].samples[3] = f64::NAN;
    let dir = out_dir("nan");
    let e = write_report(&dir, &input).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("qois[0] \"friction work\".samples[3]"),
        "message: {msg}"
    );
    assert!(!dir.join("report.html").exists());

    let mut input = synthetic();
    input.comparison.as_mut().unwrap().rows[1].std = f64::INFINITY;
    let msg = validate(&input).unwrap_err().to_string();
    assert!(
        msg.contains("comparison.rows[1]") && msg.contains(".std"),
        "{msg}"
    );

    let mut input = synthetic();
    input.qois[0].failure[0].probability = 1.5;
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("failure[0].probability"), "{msg}");

    let mut input = synthetic();
    input.qois[0].surface.as_mut().unwrap().values.pop();
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("surface.values"), "{msg}");

    let mut input = synthetic();
    input.runs[2].params.push(1.0);
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("runs[2].params"), "{msg}");
}

#[test]
fn degenerate_inputs_give_a_report() {
    // One run, one sample, no KDE, no history, no comparison, no timings, no notes.
    let input = ReportInput {
        title: String::new(),
        study_file: "one.toml".into(),
        units: vec![],
        method: "Monte Carlo on the model, 1 run".into(),
        parameters: vec![ParamInfo {
            name: "E".into(),
            law: "normal (200e3, 10e3)".into(),
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        }],
        runs: vec![RunInfo {
            params: vec![200e3],
            status: "converged".into(),
            iterations: 1,
            seconds: 0.0,
            qois: vec![0.0],
        }],
        residual_histories: vec![("run 1".into(), vec![0.0])],
        qois: vec![QoiReport {
            name: "compliance".into(),
            unit: String::new(),
            what: String::new(),
            samples: vec![0.0],
            mean: 0.0,
            std: 0.0,
            skewness: 0.0,
            quantiles: vec![],
            kde: vec![],
            atoms: vec![],
            failure: vec![FailureInfo {
                threshold: 0.0,
                probability: 1.0,
                ci_low: 1.0,
                ci_high: 1.0,
            }],
            surface: None,
            budget: vec![],
            budget_basis: vec![],
            sobol: vec![],
            sobol_basis: String::new(),
        }],
        comparison: Some(Comparison {
            qoi: "compliance".into(),
            rows: vec![],
        }),
        timings: vec![],
        notes: vec![],
        error: None,
        reliability: vec![],
    };
    let dir = out_dir("degenerate");
    let files = write_report(&dir, &input).unwrap();
    // PDF and CDF only: the history has no positive value, the comparison no curve.
    assert_eq!(files.plots.len(), 4);
    for stem in ["pdf_compliance", "cdf_compliance"] {
        check_png(&dir.join(format!("{stem}.png")), SIZE);
        check_svg(
            &dir.join(format!("{stem}.svg")),
            SIZE,
            &["polyline", "text"],
        );
    }
    let html = std::fs::read_to_string(&files.html).unwrap();
    assert!(html.contains("alea study report"));
    assert!(html.contains("−∞") && html.contains("∞"));
    assert!(!html.contains("NaN") && !html.contains("id=\"warnings\""));
    std::fs::remove_dir_all(&dir).unwrap();

    // No run, no QoI at all.
    let empty = ReportInput {
        runs: vec![],
        qois: vec![],
        parameters: vec![],
        residual_histories: vec![],
        comparison: None,
        ..input
    };
    let dir = out_dir("empty");
    let files = write_report(&dir, &empty).unwrap();
    assert!(files.plots.is_empty());
    assert!(
        std::fs::read_to_string(&files.html)
            .unwrap()
            .contains("No run recorded")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn json_round_trip_keeps_infinite_bounds() {
    let mut input = synthetic();
    input.parameters[0].hi = f64::INFINITY;
    input.parameters[1].lo = f64::NEG_INFINITY;
    input.qois[0].samples.truncate(100);
    let dir = out_dir("json");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("report-input.json");
    input.save_json(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("\"hi\": \"inf\"") && text.contains("\"lo\": \"-inf\""));
    let back = ReportInput::load_json(&path).unwrap();
    assert_eq!(back.parameters[0].hi, f64::INFINITY);
    assert_eq!(back.parameters[1].lo, f64::NEG_INFINITY);
    assert_eq!(back.parameters[0].lo, 210e3);
    assert_eq!(back.runs.len(), input.runs.len());
    assert_eq!(back.title, input.title);
    for (a, b) in back.qois[0].samples.iter().zip(&input.qois[0].samples) {
        assert!((a - b).abs() <= 1e-14 * b.abs());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
