//! CSV in and out (bit-exact round trip, errors naming line and column) and saving / loading a
//! fitted chaos with its run data (identical evaluations, statistics and errors after loading).

use alea_uq::basis::PcBasis;
use alea_uq::design::{Design, latin_hypercube};
use alea_uq::io::{read_csv, write_csv};
use alea_uq::joint::Independent;
use alea_uq::law::{Marginal, Normal, TruncatedNormal, Uniform};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::{LinearSurrogate, PcSurrogate, RunData};
use std::sync::Arc;

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("alea-uq-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn csv_round_trip_and_errors() {
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(1.0, 0.3).unwrap()),
        Arc::new(Uniform::new(-2.0, 5.0).unwrap()),
    ];
    let law = Independent::new(m).unwrap();
    let d = latin_hypercube(&law, 50, 3);
    let p = tmp("design.csv");
    d.to_csv(&p, &["E", "mu"]).unwrap();
    let (back, names) = Design::from_csv(&p).unwrap();
    assert_eq!(back, d);
    assert_eq!(names, ["E", "mu"]);
    write_csv(&p, &["a", "b"], &[1.0, 2.5, -3e-300, 4.0]).unwrap();
    let t = read_csv(&p).unwrap();
    assert_eq!(t.column("b").unwrap(), vec![2.5, 4.0]);
    std::fs::write(&p, "# comment\na,b\n1,2\n3,x\n").unwrap();
    let e = read_csv(&p).unwrap_err().to_string();
    assert!(
        e.contains("line 4") && e.contains("column \"b\"") && e.contains("design.csv"),
        "{e}"
    );
    std::fs::write(&p, "a,b\n1,2,3\n").unwrap();
    assert!(
        read_csv(&p)
            .unwrap_err()
            .to_string()
            .contains("3 fields, expected 2")
    );
    assert!(read_csv(tmp("missing.csv")).is_err());
    let e = write_csv(&p, &["a", "b"], &[1.0, 2.0, 3.0, f64::NAN])
        .unwrap_err()
        .to_string();
    assert!(e.contains("row 2, column \"b\""), "{e}");
}

#[test]
fn saved_chaos_evaluates_identically() {
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(1.0, 0.5).unwrap()),
        Arc::new(TruncatedNormal::new(0.0, 1.0, -1.0, 2.0).unwrap()),
    ];
    let law = Independent::new(m.clone()).unwrap();
    let design = latin_hypercube(&law, 40, 1);
    let f = |x: &[f64]| (x[0] * x[1]).sin() + x[1];
    let g = |x: &[f64]| x[0] * x[0];
    // Two values per run: a field of 2 components.
    let values: Vec<f64> = design.iter().flat_map(|x| [f(x), g(x)]).collect();
    let y: Vec<f64> = design.evaluate(f);
    let pc =
        PcSurrogate::regression(PcBasis::total_degree(&m, 4).unwrap(), design.points()).unwrap();
    let runs = RunData {
        points: design.points().to_vec(),
        values: values.clone(),
        values_per_run: 2,
    };
    let p = tmp("pc.json");
    pc.save_json(&p, &runs).unwrap();
    let (back, r) = PcSurrogate::load_json(&p).unwrap();
    assert_eq!(r, runs);
    for x in [[0.7, 0.1], [1.9, -0.9], [0.0, 1.5]] {
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        pc.eval_field(&x, &values, &mut a);
        back.eval_field(&x, &r.values, &mut b);
        assert_eq!(a, b);
    }
    assert_eq!(pc.loo_error(&y).unwrap(), back.loo_error(&y).unwrap());
    assert_eq!(
        pc.corrected_loo_error(&y).unwrap(),
        back.corrected_loo_error(&y).unwrap()
    );
    assert_eq!(
        pc.expansion(&y).unwrap().sobol_total(),
        back.expansion(&y).unwrap().sobol_total()
    );
    // Projection surrogates too.
    let rule = QuadratureRule::tensor_gauss(&m, &[4, 4]).unwrap();
    let pj = PcSurrogate::projection(PcBasis::total_degree(&m, 3).unwrap(), &rule).unwrap();
    let yq: Vec<f64> = (0..rule.len()).map(|q| f(rule.node(q))).collect();
    let runs = RunData {
        points: rule.nodes().to_vec(),
        values: yq.clone(),
        values_per_run: 1,
    };
    pj.save_json(&p, &runs).unwrap();
    let (back, _) = PcSurrogate::load_json(&p).unwrap();
    assert_eq!(back.eval(&[0.3, 0.2], &yq), pj.eval(&[0.3, 0.2], &yq));
    // Wrong sizes and damaged files are refused with the path and the field.
    let bad = RunData {
        points: vec![0.0; 3],
        values: yq,
        values_per_run: 1,
    };
    assert!(
        pj.save_json(&p, &bad)
            .unwrap_err()
            .to_string()
            .contains("do not match")
    );
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replace("\"runs\":16", "\"runs\":15");
    std::fs::write(&p, text).unwrap();
    let e = PcSurrogate::load_json(&p).unwrap_err().to_string();
    assert!(e.contains("pc.json") && e.contains("\"map\""), "{e}");
}
