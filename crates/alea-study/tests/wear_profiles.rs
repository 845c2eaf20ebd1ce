//! The thesis's 2D turbine example (`examples/turbine-2d-wear.toml`, thesis 5.2.3-5.2.4).
//!
//! - `examples/turbine-2d-wear-reference.toml` holds the same model (only its study title and
//!   methods differ).
//! - The wear profiles (5.1)-(5.2) written in the study language have the properties the
//!   thesis states for them (SEED-NOTES 5.2): with x in [La, Lb] = [0.7, 1.5] cm along the
//!   contact line, df(La) = 3a, df(Lb) = 3b, df(1.1) = 0.6 (a + b) + 1.8 micrometres,
//!   mu(La) ~ 0.2 + 0.6 a, mu(Lb) ~ 0.2 + 0.6 b; the left line mirrors the right one.
//! - On a coarsened copy of the mesh (every cell count halved, about 6 000 dof): the model is
//!   mirror-symmetric with (a, b) swapped (the D1 fillet at (a, b) is the D2 fillet at
//!   (b, a)), so the one-sided quantity is not symmetric in (a, b); the D2 fillet is the most
//!   stressed place of D2, its maximum is never on a corner (no corner warning); wear at the
//!   b end of I2 (next to the D2 fillet) raises it and wear at the a end lowers it; a 3 x 3
//!   study converges everywhere.

use alea_latin::LatinSolver;
use alea_study::Source;
use alea_study::qoi::warnings::corner_warnings;
use alea_study::runner::{NoProgress, Study, run_study};

fn example_text() -> String {
    std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/turbine-2d-wear.toml"),
    )
    .unwrap()
}

/// The example with every mesh count halved (`n_fillet` kept even), a 3 x 3 grid for the
/// methods, and `extra` TOML appended.
fn coarsened(extra: &str) -> Study {
    let mut doc: toml::Table = toml::from_str(&example_text()).unwrap();
    let params = doc["mesh"]["params"].as_table().unwrap().clone();
    let mut p2 = toml::Table::new();
    for (k, v) in params {
        let v = match (k.starts_with("n_"), v.as_integer()) {
            (true, Some(n)) if k == "n_fillet" => toml::Value::Integer((n / 4).max(1) * 2),
            (true, Some(n)) => toml::Value::Integer((n / 2).max(1)),
            _ => v,
        };
        p2.insert(k, v);
    }
    doc["mesh"]
        .as_table_mut()
        .unwrap()
        .insert("params".into(), toml::Value::Table(p2));
    for m in doc["method"].as_array_mut().unwrap() {
        let m = m.as_table_mut().unwrap();
        m.insert("points_per_dim".into(), toml::Value::Integer(3));
        if m.contains_key("degree") {
            m.insert("degree".into(), toml::Value::Integer(2));
        }
    }
    let text = format!("{}\n{extra}", toml::to_string(&doc).unwrap());
    Study::from_source(Source::from_text("turbine.toml", &text)).unwrap()
}

#[test]
fn the_reference_file_holds_the_same_model() {
    let strip = |text: &str| {
        let mut t: toml::Table = toml::from_str(text).unwrap();
        t.remove("study");
        t.remove("method");
        t
    };
    let reference = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/turbine-2d-wear-reference.toml"),
    )
    .unwrap();
    assert_eq!(strip(&example_text()), strip(&reference));
}

#[test]
fn wear_gap_and_friction_profiles_match_the_thesis() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-2d-wear.toml");
    let study = Study::load(&path).unwrap();
    // Right contact line (I2): from the neck A (x = La) to the root's bottom corner B (x = Lb),
    // 8 mm at 35 degrees from the blade axis; the left one (I1) is its mirror image.
    let ya = (200.0f64 * 200.0 - 64.0).sqrt();
    let (s, c) = 35f64.to_radians().sin_cos();
    let right_top = [8.0, ya, 0.0];
    let right_bottom = [8.0 + 8.0 * s, ya - 8.0 * c, 0.0];
    let right_mid = [8.0 + 4.0 * s, ya - 4.0 * c, 0.0];
    let left_top = [-8.0, ya, 0.0];
    let left_bottom = [-right_bottom[0], right_bottom[1], 0.0];
    let e = (-(0.8f64 * 0.8) / 0.13).exp(); // the other bump's tail at the far end
    let names: Vec<&str> = study
        .model
        .assembly
        .interfaces
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    let (i1, i2) = (
        names.iter().position(|&n| n == "I1").unwrap(),
        names.iter().position(|&n| n == "I2").unwrap(),
    );
    for (a, b) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.3, 0.7), (1.0, 1.0)] {
        let input = study.model.parametric.run_input(&[a, b]);
        let (mu_l, mu_r) = (input.mu[i1].clone().unwrap(), input.mu[i2].clone().unwrap());
        let (g_l, g_r) = (
            input.gap[i1].clone().unwrap(),
            input.gap[i2].clone().unwrap(),
        );
        let um = 1e-3; // micrometres in mm
        // The thesis's coefficients are rounded to 4 decimals: 3 x 5e-5 micrometres.
        assert!(
            (g_r(right_top) - 3.0 * a * um).abs() < 1e-3 * um,
            "df(La) = 3a"
        );
        assert!(
            (g_r(right_bottom) - 3.0 * b * um).abs() < 1e-3 * um,
            "df(Lb) = 3b"
        );
        assert!(
            (g_r(right_mid) - (0.6 * (a + b) + 1.8) * um).abs() < 1e-3 * um,
            "df(1.1)"
        );
        assert!((mu_r(right_top) - (0.2 + 0.6 * (a + b * e))).abs() < 1e-12);
        assert!((mu_r(right_bottom) - (0.2 + 0.6 * (a * e + b))).abs() < 1e-12);
        // I1 mirrors I2: its top varies like the bottom of I2.
        assert!((g_l(left_top) - g_r(right_bottom)).abs() < 1e-15);
        assert!((g_l(left_bottom) - g_r(right_top)).abs() < 1e-15);
        assert!((mu_l(left_top) - mu_r(right_bottom)).abs() < 1e-15);
    }
}

#[test]
fn one_sided_fillet_stress_is_mirror_symmetric_smooth_and_follows_the_wear() {
    let extra = r#"
[[quantity]]
name = "vm_fillet_D1"
kind = "max_von_mises"
substructure = "D1"
group = "D1_fillet"

[[quantity]]
name = "vm_D2"
kind = "max_von_mises"
substructure = "D2"
"#;
    let study = coarsened(extra);
    let q = |n: &str| study.qois.iter().position(|q| q.name == n).unwrap();
    let (d2, d1, all) = (q("vm_fillet"), q("vm_fillet_D1"), q("vm_D2"));
    let solver =
        LatinSolver::new(study.model.assembly.clone(), study.model.options.clone()).unwrap();
    let run = |a: f64, b: f64| {
        let res = solver
            .run_shared(&study.model.parametric.run_input(&[a, b]))
            .unwrap();
        assert_eq!(res.status, alea_latin::RunStatus::Converged);
        let v: Vec<f64> = study
            .qois
            .iter()
            .map(|q| q.eval(&solver, &res).unwrap())
            .collect();
        v
    };
    let (p, m) = (run(0.2, 0.9), run(0.9, 0.2));
    // Mirror symmetry: D1 at (a, b) is D2 at (b, a) (up to the solver tolerance); the
    // quantity on one side is therefore not symmetric in (a, b).
    assert!(
        (p[d1] - m[d2]).abs() < 1e-3 * p[d1],
        "{} vs {}",
        p[d1],
        m[d2]
    );
    assert!((p[d2] - m[d1]).abs() < 1e-3 * p[d2]);
    assert!(
        (p[d2] - m[d2]).abs() > 0.05 * p[d2],
        "{} vs {}",
        p[d2],
        m[d2]
    );
    // The fillet is where D2 is most stressed.
    for v in [&p, &m] {
        assert!(
            (v[all] - v[d2]).abs() <= 1e-12 * v[d2],
            "{} vs {}",
            v[all],
            v[d2]
        );
    }
    // Wear at the b end (next to the D2 fillet) raises its stress, at the a end lowers it.
    let (v00, v01, v10) = (run(0.0, 0.0)[d2], run(0.0, 1.0)[d2], run(1.0, 0.0)[d2]);
    assert!(v01 > 1.05 * v00 && v10 < 0.95 * v00, "{v00} {v01} {v10}");
}

#[test]
fn turbine_study_converges_and_its_fillet_maximum_is_never_on_a_corner() {
    let study = coarsened("");
    let dir = std::env::temp_dir().join(format!("alea-turbine-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    // 9 design runs and 5 validation runs.
    assert_eq!(runs.records.len(), 14);
    assert!(runs.records.iter().all(|r| r.converged()));
    assert!(
        runs.records
            .iter()
            .all(|r| r.qois.iter().all(|v| v.is_finite()))
    );
    assert!(
        corner_warnings(&study, &runs.records, &dir)
            .unwrap()
            .is_empty()
    );
    let _ = std::fs::remove_dir_all(&dir);
}
