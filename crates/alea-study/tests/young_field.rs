//! Young's modulus from a random field over a substructure's cells (`[[field]] substructure =
//! ...`, the field's mean over each cell in the substructure's `young`).
//!
//! The plate of `examples/plate-random-E.toml` (100 x 20 mm, plane stress, nu = 0, traction
//! `200 P` MPa on its right end) meshed with one row of 10 cells: with `E` constant over each
//! cell and every cell spanning the plate's height, the stress is `200 P` everywhere and the
//! Quad4 solution is exact, so each run's tip displacement is `200 P sum_c L_c / E_c` (cells of
//! length `L_c = 10` mm) whatever the field - checked run by run with `E_c` recomputed here from
//! the field's nodal values (the mean of the P1 field over a rectangle split along its first
//! diagonal: `(2 u_0 + u_1 + 2 u_2 + u_3) / 6`). The mean / std fields see the same uniform
//! stress (von Mises `200 P` at every node, whatever each cell's modulus: mean 200, std 10 MPa); the field changes
//! the answer (the tip's spread exceeds the load's alone); and every combination the field
//! cannot serve is refused at load with the file, the line and the field.

use alea_study::analysis::{AnalysisSettings, analyse_method};
use alea_study::runner::{NoProgress, Study, run_study};
use alea_study::{Source, StudyError};
use alea_uq::kde::Bandwidth;

const STUDY: &str = r#"
[study]
title = "plate with E a random field"
seed = 3

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [100.0, 20.0]
cells = [10, 1]

[analysis]
type = "plane_stress"
thickness = 1.0

[[parameter]]
name = "P"
law = "normal"
mean = 1.0
std = 0.05

[[field]]
name = "EF"
substructure = "plate"
covariance = "exponential"
correlation_length = 40.0
transform = "lognormal"
mean = 200e3
std = 40e3
modes = 4
unit = "MPa"

[[substructure]]
name = "plate"
young = "EF"
poisson = 0.0
constraint = [ { group = "xmin", x = 0.0 }, { group = "ymin", y = 0.0 } ]
load = [ { group = "xmax", traction = [200.0, 0.0], factor = "P" } ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [100.0, 20.0]
component = 0
unit = "mm"

[[method]]
type = "pc_regression"
degree = 2
design = "lhs"
runs = 30

[solver]
tolerance = 1e-10
"#;

fn load(text: &str) -> Result<Study, StudyError> {
    Study::from_source(Source::from_text("young_field.toml", text))
}

#[test]
fn every_run_is_the_series_formula_of_its_cells_moduli() {
    let study = load(STUDY).unwrap();
    assert_eq!(study.params.names, ["P", "EF_1", "EF_2", "EF_3", "EF_4"]);
    let field = &study.params.fields[0];
    let fmesh = field.field.kl().mesh();
    let dir = std::env::temp_dir().join(format!("alea-young-field-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert_eq!(runs.records.len(), 30);
    let model = runs.solver.model(0);
    // The field node at each mesh corner (matched by coordinates).
    let node_of = |g: usize| {
        let x = model.mesh.coords[g];
        (0..fmesh.num_nodes())
            .find(|&i| (0..3).all(|k| (fmesh.nodes()[i][k] - x[k]).abs() < 1e-9))
            .unwrap()
    };
    let mut tips = Vec::new();
    for r in &runs.records {
        assert!(r.converged());
        let nodal = field.at_nodes(&r.params);
        let mut compliance = 0.0;
        for c in 0..model.mesh.num_cells() {
            let u: Vec<f64> = model.mesh.cell_nodes(c)[..4]
                .iter()
                .map(|&g| nodal[node_of(g)])
                .collect();
            let e = (2.0 * u[0] + u[1] + 2.0 * u[2] + u[3]) / 6.0;
            compliance += 10.0 / e;
        }
        let exact = 200.0 * r.params[0] * compliance;
        assert!(
            (r.qois[0] - exact).abs() < 1e-8 * exact,
            "run at {:?}: tip {} vs {exact}",
            r.params,
            r.qois[0]
        );
        tips.push(r.qois[0] / r.params[0]);
    }
    // The field matters: tip / P (the compliance) varies by more than 10 % between runs.
    let (lo, hi) = tips
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
    assert!(hi > 1.1 * lo, "compliance range [{lo}, {hi}]");

    // Mean / std fields rebuild each run's stress with its own cells' moduli: uniform 200 P.
    let settings = AnalysisSettings {
        samples: 20_000,
        bandwidth: Bandwidth::Silverman,
        kde_points: 64,
        confidence: 0.95,
    };
    let res = analyse_method(&study, &study.methods[0], &runs.records, &settings);
    let fields = alea_study::fields::mean_std_fields(&study, &runs, &dir, 0, &res.points).unwrap();
    for n in 0..model.mesh.num_nodes() {
        let (m, s) = (fields[0].von_mises_mean[n], fields[0].von_mises_std[n]);
        assert!((m - 200.0).abs() < 1.0, "node {n}: von Mises mean {m}");
        assert!((s - 10.0).abs() < 0.5, "node {n}: von Mises std {s}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every setting a field over cells cannot serve is refused at load, naming the line.
#[test]
fn what_a_cell_field_cannot_serve_is_refused_at_load() {
    let cases: [(&str, &str, &str, &str); 5] = [
        (
            "substructure = \"plate\"\ncovariance",
            "substructure = \"nope\"\ncovariance",
            "field[0].substructure",
            "unknown substructure 'nope'",
        ),
        (
            "substructure = \"plate\"\ncovariance",
            "covariance",
            "field[0].interface",
            "a field needs interface",
        ),
        (
            "[solver]",
            "[error]\n\n[solver]",
            "field[0].substructure",
            "error estimate",
        ),
        (
            "[solver]",
            "[budget]\nrefined_mesh = { split = 1 }\n\n[solver]",
            "field[0].substructure",
            "refined_mesh",
        ),
        (
            "young = \"EF\"",
            "young = \"EF * UNKNOWN\"",
            "substructure[0].young",
            "UNKNOWN",
        ),
    ];
    for (from, to, field, message) in cases {
        assert!(STUDY.contains(from), "{from}");
        let text = STUDY.replacen(from, to, 1);
        match load(&text) {
            Err(StudyError::Input {
                field: f,
                message: m,
                line,
                ..
            }) => {
                assert_eq!(f, field, "{to}: {m}");
                assert!(m.contains(message), "{to}: {m}");
                assert!(line > 0, "{to}: no line");
            }
            other => panic!("{to}: expected an input error, got {:?}", other.err()),
        }
    }
}
