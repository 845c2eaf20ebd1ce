//! Young's modulus from a random field over a substructure's cells (`[[field]] substructure =
//! ...`, the field's mean over each cell in the substructure's `young`).
//!
//! The plate of `examples/plate-random-E.toml` (100 x 20 mm, plane stress, nu = 0, traction
//! `200 P` MPa on its right end) meshed with one row of 10 cells: with `E` constant over each
//! cell and every cell spanning the plate's height, the stress is `200 P` everywhere and the
//! Quad4 solution is exact, so each run's tip displacement is `200 P sum_c L_c / E_c` (cells of
//! length `L_c = 10` mm) whatever the field - checked run by run with `E_c` recomputed here from
//! the field's nodal values (the mean of the P1 field over a rectangle split along its first
//! diagonal: `(2 u_0 + u_1 + 2 u_2 + u_3) / 6`). The same holds for the 3D bar of 10 Hex8
//! cells (the field on the cells' corners, each hexahedron split into 6 tetrahedra), and for
//! fields on a 5-box grid in 2D and 3D (each cell's modulus the field at its centroid, located
//! here by the field's own nearest-simplex search). The mean / std fields see the same uniform
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

/// How the test recomputes a cell's modulus from the field's nodal values.
enum CellValue {
    /// Mean of the P1 field over a rectangle split along its first diagonal.
    RectangleMean,
    /// Mean of the P1 field over a Hex8 split into Kuhn's 6 tetrahedra along its diagonal from
    /// VTK corner 0 to 6 (in all 6 tetrahedra: weight 1/4 each; the other 6 corners in 2 each:
    /// 1/12).
    HexMean,
    /// The P1 field at the cell's centroid, located by the field's own nearest-cell search.
    AtCentroid,
}

/// Runs the study of `text` and checks every run's tip displacement against the series
/// formula `200 P sum_c 10 / E_c`; returns the runs' compliances `tip / P`.
fn series_check(text: &str, value: CellValue, tag: &str) -> (Study, Vec<f64>) {
    let study = load(text).unwrap();
    let field = study.params.fields[0].clone();
    let fmesh = field.field.kl().mesh();
    let dir = std::env::temp_dir().join(format!("alea-young-field-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let model = runs.solver.model(0);
    // The field node at each mesh corner (matched by coordinates).
    let node_of = |g: usize| {
        let x = model.mesh.coords[g];
        (0..fmesh.num_nodes())
            .find(|&i| (0..3).all(|k| (fmesh.nodes()[i][k] - x[k]).abs() < 1e-9))
            .unwrap()
    };
    let mut compliances = Vec::new();
    for r in &runs.records {
        assert!(r.converged());
        let nodal = field.at_nodes(&r.params);
        let mut compliance = 0.0;
        for c in 0..model.mesh.num_cells() {
            let e = match value {
                CellValue::RectangleMean => {
                    let u: Vec<f64> = model.mesh.cell_nodes(c)[..4]
                        .iter()
                        .map(|&g| nodal[node_of(g)])
                        .collect();
                    (2.0 * u[0] + u[1] + 2.0 * u[2] + u[3]) / 6.0
                }
                CellValue::HexMean => {
                    let u: Vec<f64> = model.mesh.cell_nodes(c)[..8]
                        .iter()
                        .map(|&g| nodal[node_of(g)])
                        .collect();
                    (3.0 * (u[0] + u[6]) + u[1] + u[2] + u[3] + u[4] + u[5] + u[7]) / 12.0
                }
                CellValue::AtCentroid => {
                    let xs = model.cell_coords(c);
                    let mut x = [0.0; 3];
                    for p in &xs {
                        for d in 0..3 {
                            x[d] += p[d] / xs.len() as f64;
                        }
                    }
                    field.interpolate(&nodal, x)
                }
            };
            compliance += 10.0 / e;
        }
        let exact = 200.0 * r.params[0] * compliance;
        assert!(
            (r.qois[0] - exact).abs() < 1e-8 * exact,
            "{tag}: run at {:?}: tip {} vs {exact}",
            r.params,
            r.qois[0]
        );
        compliances.push(r.qois[0] / r.params[0]);
    }
    // The field matters: the compliance varies by more than 10 % between runs.
    let (lo, hi) = compliances
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
    assert!(hi > 1.1 * lo, "{tag}: compliance range [{lo}, {hi}]");
    let _ = std::fs::remove_dir_all(&dir);
    (study, compliances)
}

/// The same plate in 3D: a 100 x 20 x 20 mm bar of 10 Hex8 cells in a row.
fn bar_3d(grid: &str) -> String {
    STUDY
        .replace(
            "generator = \"rectangle\"\nkind = \"quad4\"\nsize = [100.0, 20.0]\ncells = [10, 1]",
            "generator = \"box\"\nkind = \"hex8\"\nsize = [100.0, 20.0, 20.0]\ncells = [10, 1, 1]",
        )
        .replace("type = \"plane_stress\"\nthickness = 1.0", "type = \"solid\"")
        .replace(
            "constraint = [ { group = \"xmin\", x = 0.0 }, { group = \"ymin\", y = 0.0 } ]",
            "constraint = [ { group = \"xmin\", x = 0.0 }, { group = \"ymin\", y = 0.0 }, { group = \"zmin\", z = 0.0 } ]",
        )
        .replace("traction = [200.0, 0.0]", "traction = [200.0, 0.0, 0.0]")
        .replace("point = [100.0, 20.0]", "point = [100.0, 20.0, 20.0]")
        .replace("modes = 4", &format!("modes = 4\n{grid}"))
}

#[test]
fn every_run_is_the_series_formula_of_its_cells_moduli() {
    let (study, _) = series_check(STUDY, CellValue::RectangleMean, "corners");
    assert_eq!(study.params.names, ["P", "EF_1", "EF_2", "EF_3", "EF_4"]);
    // On a grid coarser than the mesh (5 boxes along the plate), in 2D and in 3D.
    let grid_2d = STUDY.replace("modes = 4", "modes = 4\ngrid = [5, 1]");
    series_check(&grid_2d, CellValue::AtCentroid, "grid2d");
    series_check(&bar_3d("grid = [5, 1, 1]"), CellValue::AtCentroid, "grid3d");
    // On the 3D cells' corners (each Hex8 split into 6 tetrahedra).
    let (bar, _) = series_check(&bar_3d(""), CellValue::HexMean, "corners3d");
    assert_eq!(bar.params.fields[0].field.kl().mesh().num_nodes(), 44);
}

#[test]
fn mean_std_fields_rebuild_each_run_with_its_cells_moduli() {
    let study = load(STUDY).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-young-field-ms-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let model = runs.solver.model(0);
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
    let cases: [(&str, &str, &str, &str); 7] = [
        (
            "modes = 4",
            "modes = 4\ngrid = [100, 100]",
            "field[0].grid",
            "at most 2000",
        ),
        (
            "modes = 4",
            "modes = 4\ngrid = [5, 1, 1]",
            "field[0].grid",
            "needs 2 box counts",
        ),
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

/// `examples/blade-root-simple-young-field.toml` (examples double as tests) on the generator's
/// cell counts divided by 3 and fewer runs: it loads, its field has the 6 KL modes of its
/// header (the grid does not depend on the mesh), and every run converges.
#[test]
fn the_blade_root_example_runs_on_a_coarse_mesh() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/blade-root-simple-young-field.toml");
    let mut text = std::fs::read_to_string(path).unwrap();
    for (from, to) in [
        (
            "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27",
            "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9",
        ),
        ("runs = 60", "runs = 16"),
        ("runs = 100", "runs = 4"),
    ] {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let study = load(&text).unwrap();
    assert_eq!(study.params.names.len(), 7);
    let f = &study.params.fields[0];
    assert_eq!(f.num_variables(), 6);
    assert!(f.description.contains("24 x 16 grid"), "{}", f.description);
    let dir = std::env::temp_dir().join(format!("alea-young-field-ex-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    // 16 + 4 design runs and 5 validation runs.
    assert_eq!(runs.records.len(), 25);
    assert!(runs.records.iter().all(|r| r.converged()));
    let _ = std::fs::remove_dir_all(&dir);
}
