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
use alea_study::estimate::{error_settings, estimate_method};
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
        let (_, est) = estimate_method(
            &s,
            &setup,
            &runs.solver,
            &store,
            m,
            &m.points,
            &sur,
            &settings,
        )
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
