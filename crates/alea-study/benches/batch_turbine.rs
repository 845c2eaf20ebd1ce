//! Batched LATIN runs on the 2D turbine (issue 20, item 1: "per-run cost of an iteration inside
//! a batch of 8 <= 0.4x the single-run iteration"). The model of `examples/turbine-2d-wear.toml`
//! (four substructures, Quad8, ~22 000 dof), 8 points of its 5 x 5 design, each started from
//! the converged state of the design's centre (as the study's schedule starts a generation
//! from its parents): the 8 runs one at a time ([`LatinSolver::run_shared`]) against the same 8
//! as one batch ([`LatinSolver::run_batch`]), one thread, two rounds in one process. Prints
//! each substructure's factor (kind, size), the iterations both ways, the largest displacement
//! difference, the CPU per run-iteration and the share of it in the triangular solves.
//!
//! Run: `cargo bench -p alea-study --bench batch_turbine` (`ALEA_BATCH_COLD=1`: cold starts).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use alea_latin::{LatinSolver, RunInput, RunResult};
use alea_study::Source;
use alea_study::runner::Study;

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("examples/turbine-2d-wear.toml");
    let text = std::fs::read_to_string(&path).expect("examples/turbine-2d-wear.toml");
    let study =
        Study::from_source(Source::from_text(path.to_str().expect("utf-8"), &text)).expect("study");
    let cold = std::env::var("ALEA_BATCH_COLD").is_ok_and(|v| v == "1");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    pool.install(|| {
        let solver: LatinSolver = study.model.solver().expect("solver");
        for s in 0..solver.num_subs() {
            let (n, nnz, supernodal) = solver.factor_summary(s);
            println!(
                "substructure '{}': {n} dof, {nnz} factor entries, {}",
                solver.sub_name(s),
                if supernodal { "supernodal" } else { "simplicial" }
            );
        }
        let points = &study.methods[0].points;
        let input = |theta: &[f64]| study.model.parametric.run_input(theta, vec![]);
        let centre = solver
            .run_shared(&input(&points[points.len() / 2]))
            .expect("centre run");
        let start = Arc::new(centre.end_state());
        let inputs: Vec<RunInput> = [0, 2, 4, 6, 8, 10, 14, 16]
            .iter()
            .map(|&i| {
                let mut inp = input(&points[i]);
                if !cold {
                    inp.initial = Some(start.clone());
                }
                inp
            })
            .collect();
        for round in 0..2 {
            let t0 = Instant::now();
            let single: Vec<RunResult> = inputs
                .iter()
                .map(|i| solver.run_shared(i).unwrap())
                .collect();
            let t_single = t0.elapsed().as_secs_f64();
            let t1 = Instant::now();
            let batch: Vec<RunResult> = solver
                .run_batch(&inputs)
                .into_iter()
                .map(|r| r.unwrap())
                .collect();
            let t_batch = t1.elapsed().as_secs_f64();
            let it_single: usize = single.iter().map(|r| r.iterations).sum();
            let it_batch: usize = batch.iter().map(|r| r.iterations).sum();
            let mut worst: f64 = 0.0;
            for (a, b) in single.iter().zip(&batch) {
                let scale = a
                    .displacements
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                let d = a
                    .displacements
                    .iter()
                    .flatten()
                    .zip(b.displacements.iter().flatten())
                    .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
                worst = worst.max(d / scale);
            }
            let solves = |r: &[RunResult]| r.iter().map(|r| r.timings.triangular_solves).sum::<f64>();
            let per_single = t_single / it_single as f64;
            let per_batch = t_batch / it_batch as f64;
            println!(
                "round {round} ({}): iterations single {:?}, batch {:?}; largest displacement difference {worst:.1e} of the largest value",
                if cold { "cold starts" } else { "started from the centre run" },
                single.iter().map(|r| r.iterations).collect::<Vec<_>>(),
                batch.iter().map(|r| r.iterations).collect::<Vec<_>>(),
            );
            println!(
                "  one at a time {t_single:.3} s ({:.3} ms per iteration, {:.0} % in solves); batched {t_batch:.3} s ({:.3} ms per run-iteration, {:.0} % in solves; mean width {:.2}): ratio {:.2}",
                1e3 * per_single,
                100.0 * solves(&single) / t_single,
                1e3 * per_batch,
                100.0 * solves(&batch) / t_batch,
                it_batch as f64 / batch.iter().map(|r| r.iterations).max().unwrap_or(1) as f64,
                per_batch / per_single
            );
        }
    });
}
