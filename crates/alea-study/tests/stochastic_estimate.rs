//! The stochastic error estimate of studies (thesis 3.2, 4.1) against what it must reduce to.
//!
//! Two stacked blocks (generator `stacked_blocks`, plane stress, coarse mesh) joined by a
//! **perfect** interface; the base is clamped, the upper block carries a traction. Everything is
//! linear, so:
//! - with a **random load factor** `P ~ U(0.5, 1.5)` only, every field scales with `P`, every
//!   surrogate reproduces `P` exactly (affine), and the stochastic admissible solution at `P` is
//!   `P` times the deterministic one at `P = 1`: `e~^2 = E[P^2] e_det^2` with `e_det` the
//!   deterministic CRE (computed here independently with `alea_cre::estimate_latin`), and
//!   `I_sto = 0` to round-off for chaos (regression and projection), standard polynomial and
//!   piecewise-linear surrogates;
//! - with a Young's modulus of **vanishing variance** the estimate is the deterministic one;
//! - with a **random Young's modulus** `E ~ U(50e3, 150e3)` of both blocks, the stresses do not
//!   depend on `E` and the displacements go as `1/E`: the stochastic part is the interpolation
//!   error of `1/E`, so `i_sto` falls like `h^2` on a piecewise-linear stochastic mesh (slope
//!   fitted over the three finer of four meshes) while `i_geo` stays put.

use alea_cre::{CreOptions, LoadData, estimate_latin};
use alea_latin::{LatinSolver, RunStatus};
use alea_study::Source;
use alea_study::estimate::{MethodEstimateInput, error_settings, estimate_method};
use alea_study::method::MethodKind;
use alea_study::runner::{NoProgress, Study, run_study};
use alea_study::store::{Store, point_key};

const BASE: &str = r#"
[study]
seed = 3

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "stacked_blocks"
kind = "quad4"
params = { width = 40.0, h_lower = 20.0, h_upper = 20.0, n_x = 6, n_lower = 3, n_upper = 3 }

[analysis]
type = "plane_stress"
thickness = 1.0

PARAMETERS

[[substructure]]
name = "base"
cells = "lower"
young = YOUNG
poisson = 0.3
constraint = [ { group = "lower_bottom", x = 0.0, y = 0.0 } ]

[[substructure]]
name = "block"
cells = "upper"
young = YOUNG
poisson = 0.3
load = [ { group = "upper_top", traction = [4.0, -10.0], factor = FACTOR } ]

[[interface]]
name = "joint"
side1 = ["base", "lower_top"]
side2 = ["block", "upper_bottom"]
law = "perfect"

[[quantity]]
name = "ux"
kind = "displacement"
substructure = "block"
point = [40.0, 20.0]
component = 0
unit = "mm"

METHODS

[error]

[statistics]
samples = 2000

[solver]
tolerance = 1e-11
max_iterations = 20000
"#;

fn study(params: &str, young: &str, factor: &str, methods: &str) -> Study {
    let text = BASE
        .replace("PARAMETERS", params)
        .replace("YOUNG", young)
        .replace("FACTOR", factor)
        .replace("METHODS", methods);
    Study::from_source(Source::from_text("stochastic_estimate.toml", &text)).unwrap()
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("alea-stoest-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// `e_det^2 = theta^2 / 2` of the deterministic run at parameter point `theta_point`, by
/// `alea_cre::estimate_latin` on a fresh solver (traction `[4, -10] factor` on the block).
fn deterministic_e2(s: &Study, theta_point: &[f64], factor: f64) -> f64 {
    let solver = LatinSolver::new(s.model.assembly.clone(), s.model.options.clone()).unwrap();
    let input = s.model.parametric.run_input(theta_point);
    let run = solver.run_shared(&input).unwrap();
    assert_eq!(run.status, RunStatus::Converged);
    let loads = vec![
        LoadData::new(),
        LoadData::new().traction("upper_top", move |_, _| [4.0 * factor, -10.0 * factor, 0.0]),
    ];
    let est = estimate_latin(&s.model.assembly, &loads, &run, &CreOptions::default()).unwrap();
    0.5 * est.theta * est.theta
}

/// The estimate of every method of a study run in `dir`.
fn estimates(s: &Study, dir: &std::path::Path) -> Vec<(String, alea_estimate::Estimate)> {
    let runs = run_study(s, dir, false, &NoProgress).unwrap();
    let setup = runs.cre.clone().expect("[error] turns estimation on");
    let store = Store::open(dir, &s.hash, false).unwrap();
    let settings = error_settings(s).unwrap();
    let mut out = Vec::new();
    for m in &runs.methods {
        if m.kind == MethodKind::MonteCarlo {
            continue;
        }
        let used: Vec<Vec<f64>> = m
            .points
            .iter()
            .filter(|p| {
                runs.records
                    .iter()
                    .any(|r| point_key(&r.params) == point_key(p) && r.converged())
            })
            .cloned()
            .collect();
        assert_eq!(
            used.len(),
            m.points.len(),
            "{}: every run converged",
            m.label
        );
        let sur = m.surrogate(&s.params, &used).unwrap();
        let (_, e) = estimate_method(&MethodEstimateInput {
            study: s,
            setup: &setup,
            solver: &runs.solver,
            store: &store,
            method: m,
            points: &used,
            sur: &sur,
            settings: &settings,
        })
        .unwrap();
        out.push((m.label.clone(), e.estimate));
    }
    drop(runs);
    let _ = std::fs::remove_dir_all(dir);
    out
}

#[test]
fn a_random_load_factor_has_no_stochastic_error_for_any_surrogate() {
    let s = study(
        "[[parameter]]\nname = \"P\"\nlaw = \"uniform\"\nlo = 0.5\nhi = 1.5",
        "70e3",
        "\"P\"",
        r#"
[[method]]
type = "pc_regression"
degree = 2

[[method]]
type = "pc_projection"
degree = 2

[[method]]
type = "polynomial"
degree = 2
design = "grid"
points_per_dim = 3

[[method]]
type = "piecewise_linear"
points_per_dim = 3
"#,
    );
    let e_det2 = deterministic_e2(&s, &[1.0], 1.0);
    let ep2 = 1.0 + 1.0 / 12.0; // E[P^2] for U(0.5, 1.5)
    let all = estimates(&s, &scratch("load"));
    assert_eq!(all.len(), 4);
    for (label, e) in &all {
        assert!(
            (e.e2 - ep2 * e_det2).abs() < 1e-6 * e.e2,
            "{label}: e~^2 = {} against E[P^2] e_det^2 = {}",
            e.e2,
            ep2 * e_det2
        );
        assert!(
            e.sto2.abs() <= 1e-12 * e.e2,
            "{label}: I_sto^2 = {}",
            e.sto2
        );
        assert!((e.i_geo() - e.relative()).abs() < 1e-9, "{label}");
        assert!(e.relative() > 0.0 && e.relative() < 1.0, "{label}");
        assert_eq!(e.violation_probability, 0.0, "{label}");
    }
}

#[test]
fn vanishing_variance_reduces_to_the_deterministic_estimate() {
    let s = study(
        "[[parameter]]\nname = \"E\"\nlaw = \"uniform\"\nlo = 70e3\nhi = 70.00000007e3",
        "\"E\"",
        "1.0",
        "[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = 2\n",
    );
    let e_det2 = deterministic_e2(&s, &[70e3], 1.0);
    let all = estimates(&s, &scratch("det"));
    let (_, e) = &all[0];
    assert!(
        (e.e2 - e_det2).abs() < 1e-6 * e_det2,
        "e~^2 = {} against the deterministic {e_det2}",
        e.e2
    );
    assert!(e.sto2.abs() < 1e-6 * e.e2, "I_sto^2 = {}", e.sto2);
}

#[test]
fn stochastic_error_of_a_random_young_modulus_falls_like_h_squared() {
    let (mut hs, mut isto, mut igeo) = (Vec::new(), Vec::new(), Vec::new());
    for n in [2usize, 3, 5, 9] {
        let s = study(
            "[[parameter]]\nname = \"E\"\nlaw = \"uniform\"\nlo = 50e3\nhi = 150e3",
            "\"E\"",
            "1.0",
            &format!("[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = {n}\n"),
        );
        let all = estimates(&s, &scratch(&format!("rate{n}")));
        let (_, e) = &all[0];
        hs.push(1.0 / (n - 1) as f64);
        isto.push(e.i_sto());
        igeo.push(e.i_geo());
    }
    // Slope over the three finer meshes (two cells and more: the asymptotic range of linear
    // interpolation; the one-cell mesh only has the corners).
    let k = (hs.len() - 1) as f64;
    let lx: Vec<f64> = hs[1..].iter().map(|h| h.ln()).collect();
    let ly: Vec<f64> = isto[1..].iter().map(|v| v.ln()).collect();
    let (mx, my) = (lx.iter().sum::<f64>() / k, ly.iter().sum::<f64>() / k);
    let slope = lx
        .iter()
        .zip(&ly)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / lx.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
    assert!(
        (slope - 2.0).abs() < 0.15,
        "i_sto {isto:?} against h {hs:?}: slope {slope}"
    );
    for g in &igeo {
        assert!((g - igeo[0]).abs() < 1e-6 * igeo[0], "i_geo {igeo:?}");
    }
}
