//! Batched LATIN runs on the 2D turbine (issue 20, item 1: "per-run cost of an iteration inside
//! a batch of 8 <= 0.4x the single-run iteration"). The model of `examples/turbine-2d-wear.toml`
//! (four substructures, Quad8, ~22 000 dof), 8 points of its 5 x 5 design, each started from
//! the converged state of the design's centre (as the study's schedule starts a generation
//! from its parents): the 8 runs one at a time ([`LatinSolver::run_shared`]) against the same 8
//! as one batch ([`LatinSolver::run_batch`]), one thread, five rounds in one process, timed by
//! the thread's CPU time (Linux; wall time elsewhere). Prints
//! each substructure's factor (kind, size), the iterations both ways, the largest displacement
//! difference and the CPU per run-iteration.
//!
//! Run: `cargo bench -p alea-study --bench batch_turbine` (`ALEA_BATCH_COLD=1`: cold starts;
//! `ALEA_BATCH_ONLY=1`: only the batches, for a profiler).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use alea_latin::{LatinSolver, RunInput, RunResult};
use alea_study::Source;
use alea_study::runner::Study;

/// CPU seconds of the calling thread (`/proc/thread-self/schedstat`: on-CPU nanoseconds, so
/// other processes of a shared machine do not count), or `None` off Linux.
fn thread_cpu() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// Seconds of `f`: the thread's CPU time where available, else wall time.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let (c0, t0) = (thread_cpu(), Instant::now());
    let out = f();
    let t = match (c0, thread_cpu()) {
        (Some(a), Some(b)) => b - a,
        _ => t0.elapsed().as_secs_f64(),
    };
    (out, t)
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("examples/turbine-2d-wear.toml");
    let text = std::fs::read_to_string(&path).expect("examples/turbine-2d-wear.toml");
    let study =
        Study::from_source(Source::from_text(path.to_str().expect("utf-8"), &text)).expect("study");
    let cold = std::env::var("ALEA_BATCH_COLD").is_ok_and(|v| v == "1");
    let batch_only = std::env::var("ALEA_BATCH_ONLY").is_ok_and(|v| v == "1");
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
        let input = |theta: &[f64]| study.model.parametric.run_input(theta);
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
        let (mut best_single, mut best_batch) = (f64::INFINITY, f64::INFINITY);
        for round in 0..5 {
            if batch_only {
                let (_, t) = timed(|| solver.run_batch(&inputs));
                println!("round {round}: batch only, {t:.3} s");
                continue;
            }
            let (single, t_single) = timed(|| {
                inputs
                    .iter()
                    .map(|i| solver.run_shared(i).unwrap())
                    .collect::<Vec<RunResult>>()
            });
            let (batch, t_batch) = timed(|| {
                solver
                    .run_batch(&inputs)
                    .into_iter()
                    .map(|r| r.unwrap())
                    .collect::<Vec<RunResult>>()
            });
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
            best_single = best_single.min(per_single);
            best_batch = best_batch.min(per_batch);
            println!(
                "round {round} ({}): iterations single {:?}, batch {:?}; largest displacement difference {worst:.1e} of the largest value",
                if cold { "cold starts" } else { "started from the centre run" },
                single.iter().map(|r| r.iterations).collect::<Vec<_>>(),
                batch.iter().map(|r| r.iterations).collect::<Vec<_>>(),
            );
            println!(
                "  one at a time {t_single:.3} s ({:.3} ms per iteration); batched {t_batch:.3} s ({:.3} ms per run-iteration; mean width {:.2}): ratio {:.2}",
                1e3 * per_single,
                1e3 * per_batch,
                it_batch as f64 / batch.iter().map(|r| r.iterations).max().unwrap_or(1) as f64,
                per_batch / per_single
            );
        }
        if best_batch.is_finite() {
            println!(
                "fastest of the rounds: {:.3} ms per iteration alone, {:.3} ms per run-iteration batched: ratio {:.2}",
                1e3 * best_single,
                1e3 * best_batch,
                best_batch / best_single
            );
        }
    });
}
