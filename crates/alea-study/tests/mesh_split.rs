//! `[mesh] split = n`: any mesh refined uniformly `n` times (`alea_mesh::Mesh::refined`), held to
//! closed forms.
//!
//! - **Convergence rate on a contact problem with a closed form**: Lame's shrink fit (the case of
//!   `examples/shrink-fit.toml` on a coarse Quad8 mesh, frictionless contact with an interference
//!   `delta`): the error of the mean contact pressure against Lame's
//!   `E delta (b^2 - a^2)(c^2 - b^2) / (2 b^3 (c^2 - a^2))` must fall by at least 4x per split
//!   (second order; measured 8.1x then 6.7x, from 4.4e-4 unsplit to 8.0e-6 after two splits).
//! - **A Gmsh mesh split**: the 3D block on a plane of `examples/block-on-plane-3d.toml` (two Hex8
//!   boxes with coincident but distinct nodes on the contact): split once it has 8x the cells, the
//!   two sides stay separate bodies, and the normal resultant is still `p A = 20 N` (equilibrium).
//! - **Bad values** are refused at load, at `mesh.split`.

use std::path::PathBuf;

use alea_latin::contact::contact_rows;
use alea_latin::{LatinSolver, RunResult, RunStatus};
use alea_study::spec::ModelFile;
use alea_study::{BuiltModel, Source, build_model, build_params};

fn build(src: &Source) -> Result<BuiltModel, alea_study::StudyError> {
    let file: ModelFile = src.parse()?;
    let params = build_params(src, &file)?;
    build_model(src, &file, &params)
}

fn solve(built: &BuiltModel) -> RunResult {
    let solver = LatinSolver::new(built.assembly.clone(), built.options.clone()).unwrap();
    let input = built.parametric.run_input(&[]);
    solver.run_shared(&input).unwrap()
}

fn shrink_fit(split: usize) -> Source {
    let text = format!(
        r#"
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "concentric_rings"
kind = "quad8"
params = {{ r_in = 50.0, r_contact = 80.0, r_out = 120.0, angle_deg = 90.0, n_inner = 3, n_outer = 3, n_theta = 8 }}
split = {split}

[analysis]
type = "plane_stress"
thickness = 1.0

[[substructure]]
name = "shaft"
cells = "inner"
young = 210e3
poisson = 0.3
constraint = [ {{ group = "inner_side0", y = 0.0 }}, {{ group = "inner_side1", x = 0.0 }} ]

[[substructure]]
name = "hub"
cells = "outer"
young = 210e3
poisson = 0.3
constraint = [ {{ group = "outer_side0", y = 0.0 }}, {{ group = "outer_side1", x = 0.0 }} ]

[[interface]]
name = "fit"
side1 = ["shaft", "inner_contact"]
side2 = ["hub", "outer_contact"]
law = "coulomb"
mu = 0.0
gap = -0.05

[solver]
tolerance = 1e-10
max_iterations = 5000
"#
    );
    Source::from_text("shrink-fit-split.toml", &text)
}

#[test]
fn split_meshes_converge_to_lames_pressure_at_second_order() {
    let (a, b, c, delta, e) = (50.0f64, 80.0f64, 120.0f64, 0.05, 210e3);
    let lame = e * delta * (b * b - a * a) * (c * c - b * b) / (2.0 * b.powi(3) * (c * c - a * a));
    let mut errors = Vec::new();
    let mut nodes = Vec::new();
    for split in 0..3 {
        let built = build(&shrink_fit(split)).unwrap();
        nodes.push(
            built
                .assembly
                .subs
                .iter()
                .map(|s| s.model.mesh.num_nodes())
                .sum::<usize>(),
        );
        let res = solve(&built);
        assert_eq!(res.status, RunStatus::Converged, "split {split}");
        let rows = contact_rows(&res.interfaces[0]);
        let (pm, m) = rows.iter().fold((0.0, 0.0), |(pm, m), r| {
            (pm + r.weight * r.pressure, m + r.weight)
        });
        errors.push((pm / m - lame).abs() / lame);
    }
    eprintln!("shrink fit: nodes {nodes:?}, relative errors of the mean pressure {errors:?}");
    assert!(
        errors[0] > 2e-4,
        "the coarse mesh must have a visible error"
    );
    for k in 1..3 {
        // Quad8 nodes grow about 3.5x per split in 2D (4x the cells, shared nodes).
        assert!(nodes[k] > 3 * nodes[k - 1], "{nodes:?}");
        assert!(
            errors[k - 1] / errors[k] >= 4.0,
            "split {k}: error {} after {} (ratio {})",
            errors[k],
            errors[k - 1],
            errors[k - 1] / errors[k]
        );
    }
}

fn block_on_plane(split: &str) -> Source {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/block-on-plane-3d.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace(
        "file = \"block-on-plane-3d.msh\"",
        &format!("file = \"block-on-plane-3d.msh\"\n{split}"),
    );
    Source { path, text }
}

#[test]
fn a_split_gmsh_mesh_keeps_its_bodies_separate_and_its_resultant() {
    let coarse = build(&block_on_plane("")).unwrap();
    let fine = build(&block_on_plane("split = 1")).unwrap();
    for (c, f) in coarse.assembly.subs.iter().zip(&fine.assembly.subs) {
        assert_eq!(f.model.mesh.num_cells(), 8 * c.model.mesh.num_cells());
    }
    let res = solve(&fine);
    assert_eq!(res.status, RunStatus::Converged);
    let rows = contact_rows(&res.interfaces[0]);
    // The refined interface is pressed by p A = 20 N (equilibrium of the block).
    let fz: f64 = rows.iter().map(|r| r.weight * r.pressure).sum();
    assert!((fz - 20.0).abs() < 1e-6 * 20.0, "Fz = {fz}");
    let coarse_points = contact_rows(&solve(&coarse).interfaces[0]).len();
    // (2 nx + 1)(2 ny + 1) points against (nx + 1)(ny + 1): 45 against 15.
    assert!(
        2 * rows.len() > 5 * coarse_points,
        "{} vs {coarse_points}",
        rows.len()
    );
}

#[test]
fn bad_split_values_are_refused_at_load() {
    for (value, wanted) in [
        ("4", "expected 0 to 3"),
        ("-1", "expected 0 to 3"),
        ("1.5", "split"),
    ] {
        let err = build(&block_on_plane(&format!("split = {value}")))
            .err()
            .unwrap_or_else(|| panic!("split = {value} accepted"))
            .to_string();
        assert!(err.contains("split"), "{value}: {err}");
        assert!(err.contains(wanted), "{value}: {err}");
        assert!(
            err.contains("block-on-plane-3d.toml:"),
            "{value}: no file:line in {err}"
        );
    }
}
