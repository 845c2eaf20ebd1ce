//! The thesis's wear profiles (5.1)-(5.2) written in the study language
//! (`examples/turbine-2d-wear.toml`) have the properties the thesis states for them
//! (SEED-NOTES 5.2): with x in [La, Lb] = [0.7, 1.5] cm along the contact line,
//! df(La) = 3a, df(Lb) = 3b, df(1.1) = 0.6 (a + b) + 1.8 micrometres, mu(La) ~ 0.2 + 0.6 a,
//! mu(Lb) ~ 0.2 + 0.6 b; the left flank mirrors the right one. The study itself runs with every
//! run converged.

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

fn example() -> Study {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-2d-wear.toml");
    Study::load(&path).unwrap()
}

#[test]
fn wear_gap_and_friction_profiles_match_the_thesis() {
    let study = example();
    let ya = (200.0f64 * 200.0 - 64.0).sqrt();
    // Right flank (I2): top (neck) is x = La, bottom is x = Lb; left flank mirrored.
    let right_top = [8.0, ya, 0.0];
    let right_bottom = [16.0, ya - 12.0, 0.0];
    let right_mid = [12.0, ya - 6.0, 0.0];
    let left_top = [-8.0, ya, 0.0];
    let left_bottom = [-16.0, ya - 12.0, 0.0];
    let e = (-(0.8f64 * 0.8) / 0.13).exp(); // the other bump's tail at the far end
    for (a, b) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.3, 0.7), (1.0, 1.0)] {
        let input = study.model.parametric.run_input(&[a, b], vec![]);
        let (mu_l, mu_r) = (input.mu[0].clone().unwrap(), input.mu[1].clone().unwrap());
        let (g_l, g_r) = (input.gap[0].clone().unwrap(), input.gap[1].clone().unwrap());
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
fn the_turbine_study_runs_with_every_run_converged() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/turbine-2d-wear.toml"),
    )
    .unwrap()
    .replace("points_per_dim = 5", "points_per_dim = 3")
    .replace("degree = 3", "degree = 2");
    let study = Study::from_source(Source::from_text("turbine.toml", &text)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-turbine-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert_eq!(runs.records.len(), 9);
    assert!(runs.records.iter().all(|r| r.converged()));
    assert!(
        runs.records
            .iter()
            .all(|r| r.qois.iter().all(|v| v.is_finite()))
    );
    let _ = std::fs::remove_dir_all(&dir);
}
