//! Batched LATIN runs (`LatinSolver::run_batch`, issue 20 item 1) against the same runs one at
//! a time, on the four-part dovetail (`LATIN_BENCH_REFINE`, default 6: ~23 000 dof, the 2D
//! turbine's size): 8 runs (friction coefficient 0.1-0.8, Young's-modulus factor 0.9-1.1 on the
//! root), cold starts, one thread. Prints the iterations of each run both ways, the largest
//! displacement difference, and the CPU cost of an iteration per run in the batch against one
//! alone (the target: <= 0.4x).
//!
//! Run: `cargo bench -p alea-latin --bench batch`.

use std::time::Instant;

use alea_latin::samples::{four_part_dovetail, four_part_dovetail_options};
use alea_latin::{LatinSolver, RunInput, RunResult, constant};

fn input(mu: f64, ef: f64) -> RunInput {
    RunInput {
        young_factors: vec![ef, ef, 1.0, 1.0],
        mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
        ..Default::default()
    }
}

fn main() {
    let refine = std::env::var("LATIN_BENCH_REFINE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    pool.install(|| {
        let solver =
            LatinSolver::new(four_part_dovetail(refine).unwrap(), four_part_dovetail_options())
                .unwrap();
        let inputs: Vec<RunInput> = (0..8)
            .map(|k| input(0.1 + 0.1 * k as f64, 0.9 + 0.2 * (k % 4) as f64 / 3.0))
            .collect();
        let dof: usize = (0..solver.num_subs())
            .map(|s| 2 * solver.model(s).mesh.num_nodes())
            .sum();
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
            let per_single = t_single / it_single as f64;
            let per_batch = t_batch / it_batch as f64;
            println!(
                "round {round}: {} dof; iterations single {:?}, batch {:?}; largest displacement difference {worst:.1e} of the largest value; 8 runs one at a time {t_single:.3} s ({:.3} ms per iteration), batched {t_batch:.3} s ({:.3} ms per run-iteration): ratio {:.2}",
                dof,
                single.iter().map(|r| r.iterations).collect::<Vec<_>>(),
                batch.iter().map(|r| r.iterations).collect::<Vec<_>>(),
                1e3 * per_single,
                1e3 * per_batch,
                per_batch / per_single
            );
        }
    });
}
