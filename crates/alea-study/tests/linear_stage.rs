//! `[solver] linear_stage` (issue 41): `"condensed"` and `"volume"` give the same run of a
//! study's model (Lame's shrink fit, frictionless contact; the same iteration count, the contact
//! pressure to round-off), `"auto"` condenses this small-interface model, the load-time estimate
//! of the interface unknowns is the solver's count for node-to-node interfaces, and a bad value
//! is refused at its line.

use alea_latin::{LatinSolver, RunResult, RunStatus};
use alea_study::spec::ModelFile;
use alea_study::{BuiltModel, Source, build_model, build_params};

fn build(src: &Source) -> Result<BuiltModel, alea_study::StudyError> {
    let file: ModelFile = src.parse()?;
    let params = build_params(src, &file)?;
    build_model(src, &file, &params)
}

fn shrink_fit(stage: &str) -> Source {
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
linear_stage = "{stage}"
"#
    );
    Source::from_text("shrink-fit-stage.toml", &text)
}

fn solve(built: &BuiltModel) -> (RunResult, LatinSolver) {
    let solver = LatinSolver::new(built.assembly.clone(), built.options.clone()).unwrap();
    let input = built.parametric.run_input(&[]);
    (solver.run_shared(&input).unwrap(), solver)
}

#[test]
fn condensed_and_volume_runs_agree_and_bad_values_are_refused() {
    let mut runs = Vec::new();
    for stage in ["volume", "condensed", "auto"] {
        let built = build(&shrink_fit(stage)).unwrap();
        let (r, solver) = solve(&built);
        assert_eq!(r.status, RunStatus::Converged, "{stage}");
        let summary = solver.linear_stage_summary();
        let condensed = summary.iter().filter(|s| s.condensed).count();
        assert_eq!(condensed, if stage == "volume" { 0 } else { 2 }, "{stage}");
        let estimate = alea_study::limits::interface_unknowns(&built.assembly);
        let actual: Vec<usize> = summary.iter().map(|s| s.interface_unknowns).collect();
        assert_eq!(estimate, actual);
        runs.push(r);
    }
    let pressure = |r: &RunResult| r.interfaces[0].resultant();
    for r in &runs[1..] {
        assert_eq!(r.iterations, runs[0].iterations);
        let (a, b) = (pressure(&runs[0]), pressure(r));
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() <= 1e-9 * a[0].abs().max(a[1].abs()));
        }
    }
    let Err(e) = build(&shrink_fit("sparse")) else {
        panic!("a bad linear_stage must be refused");
    };
    let msg = e.to_string();
    assert!(
        msg.contains("solver.linear_stage") && msg.contains("\"volume\""),
        "{msg}"
    );
}
