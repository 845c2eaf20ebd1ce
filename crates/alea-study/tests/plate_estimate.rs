//! The stochastic error estimate where the stochastic error comes from a **random Young's
//! modulus over a wide range** (issue 18, acceptance (a)), against the true error computed from
//! the closed-form response - nothing of the estimator's machinery.
//!
//! A bar-like plate (100 x 20 mm, plane stress, Poisson 0, Q4) clamped axially at `x = 0`, a
//! traction of 200 MPa on `x = 100`, `E ~ U(20e3, 400e3)`: the FE solution is exact (uniform
//! stress), the tip displacement is `u(E) = F L / (E A) = 2e4 / E` and the displacement error
//! field of a surrogate is linear in `x`, so its squared energy norm is
//! `E A / L (u~_tip - u_tip)^2` with `u~_tip = sum_k w_k(E) 2e4 / E_k`. The true error is
//! `(E_xi[E A / L (u~_tip - u_tip)^2])^(1/2)`, integrated by 64-point Gauss rules on 64 cells.
//! The CRE of the stochastic solution measures `1/2` of that square (the admissible stress is
//! exact here, Prager-Synge with equality): asserted `|I_sto - true / sqrt(2)| <= 5 %` of
//! `true / sqrt(2)` for piecewise-linear K = 2 / 3 / 5 / 9, polynomial and chaos surrogates.

use alea_estimate::Weights;
use alea_study::Source;
use alea_study::estimate::{MethodEstimateInput, error_settings, estimate_method};
use alea_study::method::MethodKind;
use alea_study::runner::{NoProgress, Study, run_study};
use alea_study::store::Store;
use alea_uq::quadrature::QuadratureRule;

const TEXT: &str = r#"
[study]
seed = 7

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [100.0, 20.0]
cells = [10, 2]

[analysis]
type = "plane_stress"
thickness = 1.0

[[parameter]]
name = "E"
law = "uniform"
lo = 20e3
hi = 400e3

[[substructure]]
name = "plate"
young = "E"
poisson = 0.0
constraint = [ { group = "xmin", x = 0.0 }, { group = "ymin", y = 0.0 } ]
load = [ { group = "xmax", traction = [200.0, 0.0] } ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [100.0, 20.0]
component = 0
unit = "mm"

[[method]]
type = "piecewise_linear"
points_per_dim = 2
label = "pl2"

[[method]]
type = "piecewise_linear"
points_per_dim = 3
label = "pl3"

[[method]]
type = "piecewise_linear"
points_per_dim = 5
label = "pl5"

[[method]]
type = "piecewise_linear"
points_per_dim = 9
label = "pl9"

[[method]]
type = "polynomial"
degree = 2
design = "grid"
points_per_dim = 3
label = "poly2"

[[method]]
type = "polynomial"
degree = 4
design = "grid"
points_per_dim = 5
label = "poly4"

[[method]]
type = "pc_regression"
degree = 3
label = "pc3"

[error]
cells_per_dim = 64
points_per_cell = 8

[statistics]
samples = 1000
"#;

#[test]
fn wide_range_young_modulus_estimate_is_the_true_error_over_sqrt_two() {
    let s = Study::from_source(Source::from_text("plate_estimate.toml", TEXT)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-plate-est-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&s, &dir, false, &NoProgress).unwrap();
    let setup = runs.cre.clone().unwrap();
    let store = Store::open(&dir, &s.hash, false).unwrap();
    let settings = error_settings(&s).unwrap();
    let (lo, hi) = (20e3, 400e3);
    let (area, length) = (20.0, 100.0);
    let tip = |e: f64| 2e4 / e;
    for m in &runs.methods {
        if m.kind == MethodKind::MonteCarlo {
            continue;
        }
        let sur = m.surrogate(&s.params, &m.points).unwrap();
        let (_, est) = estimate_method(&MethodEstimateInput {
            study: &s,
            setup: &setup,
            solver: &runs.solver,
            store: &store,
            method: m,
            points: &m.points,
            sur: &sur,
            settings: &settings,
        })
        .unwrap();
        let est = est.estimate;
        // The true error from the closed form, on 64 cells x 64 Gauss points.
        let run_tips: Vec<f64> = m.points.iter().map(|p| tip(p[0])).collect();
        let mut true2 = 0.0;
        let mut w = Vec::new();
        let cells = 64;
        let h = (hi - lo) / cells as f64;
        for c in 0..cells {
            let a = lo + h * c as f64;
            let rule = QuadratureRule::gauss_legendre_box(&[a], &[a + h], 64).unwrap();
            for q in 0..rule.len() {
                let e = rule.node(q)[0];
                Weights::weights(&sur, &[e], &mut w);
                let interp: f64 = w.iter().map(|&(k, wk)| wk * run_tips[k]).sum();
                let energy = e * area / length * (interp - tip(e)).powi(2);
                // Uniform law: density 1 / (hi - lo).
                true2 += rule.weights()[q] / (hi - lo) * energy;
            }
        }
        let expected = (true2 / 2.0).sqrt();
        let i_sto = est.sto2.sqrt();
        assert!(
            (i_sto - expected).abs() <= 0.05 * expected,
            "{}: I_sto {i_sto:.5e} against true / sqrt(2) = {expected:.5e} ({:+.2} %)",
            m.label,
            100.0 * (i_sto / expected - 1.0)
        );
        eprintln!(
            "{}: I_sto {i_sto:.5e}, true / sqrt(2) {expected:.5e} ({:+.2} %), i_sto {:.2} %",
            m.label,
            100.0 * (i_sto / expected - 1.0),
            100.0 * est.i_sto()
        );
    }
    drop(runs);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same plate with a random load factor too, `P ~ U(0.8, 1.2)`: the response `2e4 P / E`
/// bends in `E` only. Both adaptive criteria, from the corners and the centre, must reach the
/// regular 9 x 9 grid's `i_sto` with fewer runs than its 81, and their true error (closed form)
/// must then be below the grid's.
#[test]
fn adaptive_criteria_beat_the_regular_grid_on_a_response_bending_in_one_parameter() {
    let two = |methods: &str| {
        let text = TEXT
            .replace(
                "[[substructure]]",
                "[[parameter]]\nname = \"P\"\nlaw = \"uniform\"\nlo = 0.8\nhi = 1.2\n\n[[substructure]]",
            )
            .replace(
                "traction = [200.0, 0.0] }",
                "traction = [200.0, 0.0], factor = \"P\" }",
            );
        let head = &text[..text.find("[[method]]").unwrap()];
        let tail = &text[text.find("[error]").unwrap()..];
        Study::from_source(Source::from_text(
            "plate_adaptive.toml",
            &format!("{head}{methods}\n{tail}"),
        ))
        .unwrap()
    };
    // True error of a surrogate on `points`, closed form, 16 x 16 cells of 8 x 8 Gauss points.
    let true_error = |s: &Study, m: &alea_study::method::Method| -> f64 {
        let sur = m.surrogate(&s.params, &m.points).unwrap();
        let tips: Vec<f64> = m.points.iter().map(|p| 2e4 * p[1] / p[0]).collect();
        let (lo, hi) = ([20e3, 0.8], [400e3, 1.2]);
        let mut w = Vec::new();
        let mut t2 = 0.0;
        let n = 16;
        for i in 0..n {
            for j in 0..n {
                let a = [
                    lo[0] + (hi[0] - lo[0]) * i as f64 / n as f64,
                    lo[1] + (hi[1] - lo[1]) * j as f64 / n as f64,
                ];
                let b = [
                    a[0] + (hi[0] - lo[0]) / n as f64,
                    a[1] + (hi[1] - lo[1]) / n as f64,
                ];
                let rule = QuadratureRule::gauss_legendre_box(&a, &b, 8).unwrap();
                for q in 0..rule.len() {
                    let x = rule.node(q);
                    Weights::weights(&sur, x, &mut w);
                    let interp: f64 = w.iter().map(|&(k, wk)| wk * tips[k]).sum();
                    let energy = x[0] * 20.0 / 100.0 * (interp - 2e4 * x[1] / x[0]).powi(2);
                    t2 += rule.weights()[q] / ((hi[0] - lo[0]) * (hi[1] - lo[1])) * energy;
                }
            }
        }
        t2.sqrt()
    };
    let dir = std::env::temp_dir().join(format!("alea-plate-adapt-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let s = two("[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = 9\nlabel = \"grid\"\n");
    let runs = run_study(&s, &dir, false, &NoProgress).unwrap();
    let setup = runs.cre.clone().unwrap();
    let store = Store::open(&dir, &s.hash, false).unwrap();
    let settings = error_settings(&s).unwrap();
    let grid = &runs.methods[0];
    let sur = grid.surrogate(&s.params, &grid.points).unwrap();
    let (_, e) = estimate_method(&MethodEstimateInput {
        study: &s,
        setup: &setup,
        solver: &runs.solver,
        store: &store,
        method: grid,
        points: &grid.points,
        sur: &sur,
        settings: &settings,
    })
    .unwrap();
    let target = e.estimate.i_sto();
    let grid_true = true_error(&s, grid);
    drop((runs, store));
    let _ = std::fs::remove_dir_all(&dir);
    for criterion in ["improved", "max_error"] {
        let s = two(&format!(
            "[[method]]\ntype = \"adaptive\"\ncriterion = \"{criterion}\"\ntarget = {target}\nmax_runs = 81\nlabel = \"{criterion}\"\n"
        ));
        let runs = run_study(&s, &dir, false, &NoProgress).unwrap();
        let a = &runs.adaptive[0];
        let last = a.steps.last().unwrap();
        let t = true_error(&s, &runs.methods[0]);
        eprintln!(
            "{criterion}: {} runs, i_sto {:.2} % (grid 81 runs: {:.2} %), true {t:.4e} (grid {grid_true:.4e}); stop: {}",
            last.runs,
            100.0 * last.error.estimate.i_sto(),
            100.0 * target,
            a.stop
        );
        assert!(
            last.error.estimate.i_sto() <= target && last.runs < 81,
            "{criterion}: {} runs, i_sto {} against the grid's {target}; stop: {}",
            last.runs,
            last.error.estimate.i_sto(),
            a.stop
        );
        assert!(
            t <= grid_true,
            "{criterion}: true error {t} above the grid's {grid_true}"
        );
        drop(runs);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
