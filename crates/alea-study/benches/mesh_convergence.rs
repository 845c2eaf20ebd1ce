//! Mesh convergence of the thesis examples' quantities of interest (issue 10): each example's
//! model is solved at a few parameter points on its shipped mesh and on meshes whose cell
//! counts (every `n_*` generator parameter) are multiplied by the given factors; the table
//! gives each quantity per mesh and its change from the shipped mesh.
//!
//! `cargo bench -p alea-study --bench mesh_convergence` runs every case;
//! `cargo bench -p alea-study --bench mesh_convergence -- blade` only the cases whose name
//! contains `blade`. Runs are cold (no warm start) and parallel over points.

use std::path::Path;
use std::time::Instant;

use alea_latin::{LatinSolver, PointStatus};
use alea_study::Source;
use alea_study::runner::Study;
use rayon::prelude::*;

struct Case {
    name: &'static str,
    file: &'static str,
    points: Vec<Vec<f64>>,
    factors: Vec<f64>,
}

/// The study file's text with every `n_*` mesh count multiplied by `factor` (rounded).
fn refined(text: &str, factor: f64) -> String {
    let mut doc: toml::Table = toml::from_str(text).expect("example parses");
    if let Some(toml::Value::Table(params)) = doc
        .get_mut("mesh")
        .and_then(|m| m.as_table_mut())
        .and_then(|m| m.get_mut("params"))
    {
        for (k, v) in params.iter_mut() {
            if let (true, Some(n)) = (k.starts_with("n_"), v.as_integer()) {
                *v = toml::Value::Integer(((n as f64) * factor).round().max(1.0) as i64);
            }
        }
    }
    toml::to_string(&doc).expect("serialises")
}

fn run_case(case: &Case) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(case.file);
    let text = std::fs::read_to_string(&path).expect("example file");
    println!("\n## {} ({})", case.name, case.file);
    // values[mesh][point][quantity], plus stick/slip counts of the first interface
    let mut values = Vec::new();
    let mut names = Vec::new();
    let mut dofs = Vec::new();
    let mut status = Vec::new();
    for &f in &case.factors {
        let src = Source::from_text(&path.to_string_lossy(), &refined(&text, f));
        let study = Study::from_source(src).expect("study builds");
        names = study.qois.iter().map(|q| q.name.clone()).collect();
        dofs.push(study.field_values());
        let t0 = Instant::now();
        let solver = LatinSolver::new(study.model.assembly.clone(), study.model.options.clone())
            .expect("solver set-up");
        let rows: Vec<(Vec<f64>, String)> = case
            .points
            .par_iter()
            .map(|p| {
                let input = study.model.parametric.run_input(p);
                let res = solver.run_shared(&input).expect("run");
                let q = study
                    .qois
                    .iter()
                    .map(|q| q.eval(&solver, &res).unwrap_or(f64::NAN))
                    .collect();
                let st = res
                    .interfaces
                    .iter()
                    .filter(|it| it.law != "perfect")
                    .map(|it| {
                        let c = |s: PointStatus| it.status.iter().filter(|&&x| x == s).count();
                        format!(
                            "{}: {} open / {} stick / {} slip{}",
                            it.name,
                            c(PointStatus::Open),
                            c(PointStatus::Stick),
                            c(PointStatus::Slip),
                            if matches!(res.status, alea_latin::RunStatus::Converged) {
                                ""
                            } else {
                                " (NOT CONVERGED)"
                            }
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(", ");
                (q, st)
            })
            .collect();
        println!(
            "mesh x{f}: {} dof, {} points in {:.2} s",
            dofs.last().unwrap_or(&0),
            case.points.len(),
            t0.elapsed().as_secs_f64()
        );
        values.push(rows.iter().map(|r| r.0.clone()).collect::<Vec<_>>());
        status.push(rows.into_iter().map(|r| r.1).collect::<Vec<_>>());
    }
    for (qi, qn) in names.iter().enumerate() {
        println!("\n{qn}:");
        let mut head = String::from("| point |");
        for (f, d) in case.factors.iter().zip(&dofs) {
            head.push_str(&format!(" x{f} ({d} dof) |"));
        }
        for f in case.factors.iter().skip(1) {
            head.push_str(&format!(" x{f} vs x{} |", case.factors[0]));
        }
        println!("{head}");
        println!(
            "|{}",
            "---|".repeat(1 + case.factors.len() + case.factors.len() - 1)
        );
        for (pi, p) in case.points.iter().enumerate() {
            let mut row = format!("| {p:?} |");
            for m in &values {
                row.push_str(&format!(" {:.5e} |", m[pi][qi]));
            }
            let base = values[0][pi][qi];
            for m in values.iter().skip(1) {
                if base == 0.0 {
                    row.push_str(" - |");
                } else {
                    row.push_str(&format!(" {:+.2} % |", 100.0 * (m[pi][qi] / base - 1.0)));
                }
            }
            println!("{row}");
        }
    }
    println!("\ncontact status per point (first mesh, last mesh):");
    for (pi, p) in case.points.iter().enumerate() {
        println!(
            "  {p:?}: {} | {}",
            status[0][pi],
            status.last().map_or("", |s| s[pi].as_str())
        );
    }
}

fn main() {
    let filter: Option<String> = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    let mut blade_points = Vec::new();
    for mu in [0.1, 0.5, 0.9] {
        blade_points.push(vec![240e3, mu]);
    }
    blade_points.push(vec![210e3, 0.9]);
    blade_points.push(vec![270e3, 0.9]);
    blade_points.push(vec![240e3, 0.7]);
    let turbine_points = vec![
        vec![0.0, 0.0],
        vec![0.5, 0.5],
        vec![1.0, 0.0],
        vec![0.0, 1.0],
        vec![1.0, 1.0],
    ];
    let turbine_3d_points = vec![
        vec![0.5, 0.5, 0.5, 0.5],
        vec![0.0, 0.0, 0.0, 0.0],
        vec![1.0, 1.0, 1.0, 1.0],
        vec![0.0, 1.0, 0.0, 1.0],
        vec![1.0, 0.0, 1.0, 0.0],
    ];
    let cases = vec![
        Case {
            name: "blade-root",
            file: "examples/blade-root-simple.toml",
            points: blade_points,
            factors: vec![1.0, 2.0],
        },
        Case {
            name: "turbine",
            file: "examples/turbine-2d-wear.toml",
            points: turbine_points,
            factors: vec![1.0, 2.0],
        },
        Case {
            name: "turbine-3d",
            file: "examples/turbine-3d-wear.toml",
            points: turbine_3d_points,
            factors: vec![1.0, 2.0],
        },
    ];
    for c in &cases {
        if filter.as_ref().is_none_or(|f| c.name.contains(f.as_str())) {
            run_case(c);
        }
    }
}
