//! The mesh part of the error budget (issue 19) against the TRUE mesh error: Kirsch's plate
//! with a hole (Quad4, a deliberately coarse mesh), remote traction `100 P` MPa with
//! `P ~ N(1, 0.1^2)`, quantity the maximum von Mises stress on the hole. The response is
//! exactly linear in `P` on every mesh (linear elasticity), `q_h = K_h P`, so a chaos is
//! exact (degree 2 on 10 runs: its degree-1 and degree-3 comparisons equal it, so the surrogate
//! part is 0) and every error of the statistics is the mesh's (plus sampling): with `K` the value on
//! an 8x finer mesh (the reference),
//! mean `K`, std `0.1 K`, quantile `K (1 + 0.1 z_p)`, `P(q > t) = 1 - Phi((t / K - 1) / 0.1)`.
//!
//! `[budget] refined_mesh` doubles the mesh; the budget's total must cover the true error of
//! each statistic and stay within 10x of it.

use alea_study::Source;
use alea_study::analysis::AnalysisSettings;
use alea_study::budget::Statistic;
use alea_study::runner::{NoProgress, Study, run_study};

/// The plate on an `n x n` mesh of `kind`; `refined`: the `[budget] refined_mesh` value.
fn study(n: usize, kind: &str, refined: Option<&str>) -> Study {
    let refined = refined.map_or(String::new(), |r| format!("[budget]\nrefined_mesh = {r}\n"));
    let text = format!(
        r#"
[study]
title = "Kirsch plate, mesh budget"
seed = 5

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "plate_with_hole"
kind = "{kind}"
params = {{ radius = 10.0, half_width = 100.0, n_arc = {n}, n_radial = {n}, grading = 6.0 }}

[analysis]
type = "plane_stress"

[[parameter]]
name = "P"
law = "normal"
mean = 1.0
std = 0.1

[[substructure]]
name = "plate"
young = 210e3
poisson = 0.3
constraint = [ {{ group = "xsym", x = 0.0 }}, {{ group = "ysym", y = 0.0 }} ]
load = [ {{ group = "right", traction = [100.0, 0.0], factor = "P" }} ]

[[quantity]]
name = "vm_hole"
kind = "max_von_mises"
substructure = "plate"
group = "hole"
unit = "MPa"
thresholds = [330.0]

[[method]]
type = "pc_regression"
degree = 2
design = "lhs"
runs = 10

[statistics]
samples = 100000

{refined}"#
    );
    Study::from_source(Source::from_text("kirsch.toml", &text)).unwrap()
}

fn norm_cdf(x: f64) -> f64 {
    alea_uq::special::norm_cdf(x)
}

#[test]
fn mesh_part_covers_the_true_mesh_error_of_every_statistic() {
    let refined = "{ params = { n_arc = 12, n_radial = 12 } }";
    check_mesh_budget(
        "generator",
        study(48, "quad4", None),
        study(6, "quad4", Some(refined)),
    );
}

/// The same check with the refined mesh made by splitting every cell (`refined_mesh = { split =
/// 1 }`, the way that works for any mesh, Gmsh files included). Quad8 cells: their children keep
/// the hole's quadratic arcs, so the split mesh converges to (nearly) the true geometry; split
/// Quad4 cells would keep the coarse mesh's chords, an error no refinement of that mesh sees.
#[test]
fn split_mesh_part_covers_the_true_mesh_error_of_every_statistic() {
    check_mesh_budget(
        "split",
        study(32, "quad8", None),
        study(4, "quad8", Some("{ split = 1 }")),
    );
}

/// Runs `reference` (one converged run gives `K = q / P`) and `coarse` (with its budget), and
/// checks the budget of each statistic of `coarse` against the exact one.
fn check_mesh_budget(case: &str, reference: Study, coarse: Study) {
    let dir = std::env::temp_dir().join(format!("alea-mesh-budget-{case}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&reference, &dir.join("ref"), false, &NoProgress).unwrap();
    let r = runs
        .records
        .iter()
        .find(|r| r.converged())
        .expect("a reference run");
    let k = r.qois[0] / r.params[0];
    let s = coarse;
    let runs = run_study(&s, &dir.join("coarse"), false, &NoProgress).unwrap();
    let settings = AnalysisSettings {
        samples: 100_000,
        bandwidth: alea_uq::kde::Bandwidth::Silverman,
        kde_points: 64,
        confidence: 0.95,
    };
    let results = alea_pipeline::analyse_all(&s, &runs, &settings);
    let stats = &results[0].qois[0];
    let budget = stats.budget.as_ref().unwrap();
    assert!(
        budget.mesh_basis.starts_with("paired solves"),
        "{}",
        budget.mesh_basis
    );
    let z95 = 1.644_853_626_951_472_2;
    let truth = |statistic: Statistic| -> Option<f64> {
        match statistic {
            Statistic::Mean => Some(k),
            Statistic::Std => Some(0.1 * k),
            Statistic::Quantile(0.5) => Some(k),
            Statistic::Quantile(0.95) => Some(k * (1.0 + 0.1 * z95)),
            Statistic::Exceedance(330.0) => Some(1.0 - norm_cdf((330.0 / k - 1.0) / 0.1)),
            _ => None,
        }
    };
    let mut checked = 0;
    for row in &budget.rows {
        let Some(t) = truth(row.statistic) else {
            continue;
        };
        let actual = (row.estimate() - t).abs();
        eprintln!(
            "{case} {:<10} value {:.5e} true {:.5e} error {:.3e} total {:.3e} (mesh {:.3e}, surrogate {:.3e}, sampling {:.3e})",
            row.statistic,
            row.value,
            t,
            actual,
            row.total,
            row.mesh.unwrap_or(f64::NAN),
            row.surrogate.unwrap_or(f64::NAN),
            row.sampling
        );
        assert!(
            row.total >= actual,
            "{case} {}: total {} < true error {actual}",
            row.statistic,
            row.total
        );
        assert!(
            row.total <= 10.0 * actual.max(row.sampling),
            "{case} {}: total {} > 10x true error {actual}",
            row.statistic,
            row.total
        );
        checked += 1;
    }
    assert_eq!(checked, 5);
    // The mesh error is large here (coarse meshes around the hole).
    let mean = &budget.rows[0];
    assert!(
        (mean.value - k).abs() > 0.01 * k,
        "mean {} vs {k}",
        mean.value
    );
    let _ = std::fs::remove_dir_all(&dir);
}
