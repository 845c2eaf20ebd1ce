//! The thesis's adaptive 2D turbine study (`examples/turbine-2d-wear-adaptive.toml`, tables
//! 5.1 / 5.2), on a copy with every mesh count divided by four (about 1 500 dof).
//!
//! Checked, as the example's header states them: the study starts from the 4 corners and the
//! centre of [0, 1]^2 and every run converges; the Young's moduli are deterministic, so the
//! substructures carry no stochastic error and all of `I_sto` comes from the contact
//! interfaces (the thesis: 99.9 %), the perfect interfaces carry none; the contact interfaces'
//! stochastic part is positive from the start (the interpolation between runs of different
//! contact status; it was 0 under the thesis's split (4.4)-(4.5)); the loop stops on its
//! criterion (`i_sto <= 7 %`) within its budget; the statistics are those of a non-degenerate
//! response (std > 0, P_f in [0, 1]).

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

fn coarse_copy() -> Study {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-2d-wear-adaptive.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut doc: toml::Table = toml::from_str(&text).unwrap();
    let params = doc["mesh"]["params"].as_table().unwrap().clone();
    let mut coarse = toml::Table::new();
    for (k, v) in params {
        let v = match (k.starts_with("n_"), v.as_integer()) {
            (true, Some(n)) if k == "n_fillet" => toml::Value::Integer((n / 8).max(1) * 2),
            (true, Some(n)) => toml::Value::Integer((n / 4).max(2)),
            _ => v,
        };
        coarse.insert(k, v);
    }
    doc["mesh"]
        .as_table_mut()
        .unwrap()
        .insert("params".into(), toml::Value::Table(coarse));
    doc.insert(
        "statistics".into(),
        toml::Value::Table(toml::from_str("samples = 20000").unwrap()),
    );
    let text = toml::to_string(&doc).unwrap();
    Study::from_source(Source::from_text(path.to_str().unwrap(), &text)).unwrap()
}

#[test]
fn adaptive_turbine_study_on_a_coarse_mesh() {
    let study = coarse_copy();
    let dir = std::env::temp_dir().join(format!("alea-turbine-adaptive-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, true, &NoProgress).unwrap();
    assert!(runs.records.iter().all(|r| r.converged()));
    let outcome = &runs.adaptive[0];
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    let steps = &outcome.steps;
    assert_eq!(steps[0].runs, 5, "4 corners and the centre");
    for step in steps {
        let e = &step.error.estimate;
        assert!(e.geo2 > 0.0 && e.sto2 >= -1e-12 * e.e2);
        for s in &e.subs {
            assert!(s.sto2.abs() <= 1e-12 * s.e2.abs(), "{}: {s:?}", s.name);
        }
        let contact_sto: f64 = e.interfaces[..2].iter().map(|i| i.sto2).sum();
        assert!(contact_sto > 1e-3 * e.e2, "{e:?}");
        assert!((contact_sto - e.sto2).abs() <= 1e-12 * e.e2);
        for i in &e.interfaces[2..] {
            assert!(i.sto2.abs() <= 1e-12 * e.e2, "{}: {i:?}", i.name);
            assert!(
                i.e2.abs() <= 1e-9 * e.e2,
                "perfect interface {}: {i:?}",
                i.name
            );
        }
        let q = &step.qois[0];
        assert!(q.std > 0.0 && q.failure.iter().all(|p| (0.0..=1.0).contains(p)));
    }
    for step in steps {
        let e = &step.error.estimate;
        eprintln!(
            "{} runs: i_geo {:.4}, i_sto {:.5}, mean {:.1}, std {:.2}",
            step.runs,
            e.i_geo(),
            e.i_sto(),
            step.qois[0].mean,
            step.qois[0].std
        );
    }
    let last = steps.last().unwrap().error.estimate.clone();
    assert!(
        last.i_sto() <= 0.07,
        "stopped with i_sto {} > 7 % ({})",
        last.i_sto(),
        outcome.stop
    );
    drop(runs);
    let _ = std::fs::remove_dir_all(&dir);
}
