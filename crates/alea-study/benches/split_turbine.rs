//! Automatic subdomains (module `alea_latin::split`, issue 38) on the 3D turbine: the model of
//! `examples/turbine-3d-wear.toml` with `[mesh] split = ALEA_SPLIT_MESH` (default 1: every
//! cell split in 8, about 660 000 dof), its substructures undivided (`ALEA_SPLIT_TARGET=0`) or
//! each split into `ceil(dof / ALEA_SPLIT_TARGET)` parts; set-up time, then `ALEA_SPLIT_RUNS`
//! runs (default 2: the middle design point, then the first warm-started from it; the study's
//! tolerance or `ALEA_SPLIT_TOL`), their
//! iterations and times, and a checksum of the displacements (per substructure, the root mean
//! square and the largest component) to compare the configurations (`ALEA_SPLIT_KEEP_CUTS=1`:
//! the warm start is the split assembly's own end state, cuts included, not the user-level
//! one), which run in separate
//! processes so that each one's peak memory can be read (`/usr/bin/time -f %M`).
//!
//! `ALEA_SPLIT_TARGET=40000 /usr/bin/time -f "%e s %M kB" cargo bench -p alea-study --bench
//! split_turbine` (BENCHMARKS.md "Automatic subdomains").

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use alea_latin::split::Split;
use alea_latin::{LatinSolver, RunInput, RunResult};
use alea_study::Source;
use alea_study::runner::Study;

fn env(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("examples/turbine-3d-wear.toml");
    let text = std::fs::read_to_string(&path).expect("examples/turbine-3d-wear.toml");
    let mut doc: toml::Table = toml::from_str(&text).expect("toml");
    doc.remove("budget");
    let level = env("ALEA_SPLIT_MESH", 1);
    if level > 0 {
        doc["mesh"]
            .as_table_mut()
            .expect("[mesh]")
            .insert("split".into(), toml::Value::Integer(level as i64));
    }
    let target = env("ALEA_SPLIT_TARGET", 0);
    let runs = env("ALEA_SPLIT_RUNS", 2);
    let text = toml::to_string(&doc).expect("toml");
    let study =
        Study::from_source(Source::from_text("turbine-3d-wear.toml", &text)).expect("study");
    let asm = &study.model.assembly;
    let dofs: Vec<usize> = asm
        .subs
        .iter()
        .map(|s| s.model.mesh.num_nodes() * s.model.mesh.dim)
        .collect();
    let parts: Vec<usize> = dofs
        .iter()
        .map(|&n| if target == 0 { 1 } else { n.div_ceil(target) })
        .collect();
    println!(
        "mesh split {level}: {} dof in {:?}; parts {parts:?}",
        dofs.iter().sum::<usize>(),
        dofs
    );
    let mut options = study.model.options.clone();
    if let Some(tol) = std::env::var("ALEA_SPLIT_TOL")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        options.tolerance = tol;
    }
    let t0 = Instant::now();
    let split = (target > 0).then(|| Split::new(asm, &parts).expect("split"));
    let solver: LatinSolver = match &split {
        Some(s) => s.solver(options.clone()).expect("solver"),
        None => LatinSolver::new(asm.clone(), options.clone()).expect("solver"),
    };
    println!("set-up {:.2} s", t0.elapsed().as_secs_f64());
    for part in solver.linear_stage_summary() {
        println!(
            "  {}: {} dof, {} factor entries, {} interface unknowns, condensed {}",
            part.name, part.dofs, part.factor_entries, part.interface_unknowns, part.condensed
        );
    }
    let points = &study.methods[0].points;
    let thetas: Vec<Vec<f64>> = std::iter::once(points[points.len() / 2].clone())
        .chain(points.iter().cloned())
        .take(runs)
        .collect();
    let mut start: Option<Arc<alea_latin::LocalState>> = None;
    let mut next: Option<Arc<alea_latin::LocalState>> = None;
    let keep_cuts = std::env::var("ALEA_SPLIT_KEEP_CUTS").is_ok_and(|v| v == "1");
    for theta in &thetas {
        let mut input = study.model.parametric.run_input(theta);
        input.initial = start.clone();
        let t = Instant::now();
        let r: RunResult = match &split {
            Some(s) => {
                let inner: RunInput = s.input(&solver, &input).expect("input");
                let res = solver.run_shared(&inner).expect("run");
                let inner_end = Arc::new(res.end_state());
                let merged = s.merge(&input, res);
                if keep_cuts {
                    next = Some(inner_end);
                }
                merged
            }
            None => solver.run_shared(&input).expect("run"),
        };
        let checksum: Vec<String> = r
            .displacements
            .iter()
            .map(|u| {
                let rms = (u.iter().map(|x| x * x).sum::<f64>() / u.len() as f64).sqrt();
                let max = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                format!("{rms:.9e}/{max:.9e}")
            })
            .collect();
        println!(
            "run {theta:?}: {:?}, {} iterations, {:.2} s; displacements {checksum:?}",
            r.status,
            r.iterations,
            t.elapsed().as_secs_f64()
        );
        start = next.take().or_else(|| Some(Arc::new(r.end_state())));
    }
}
