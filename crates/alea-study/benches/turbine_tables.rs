//! The thesis's tables 5.1 - 5.3 on the 2D turbine (`cargo bench -p alea-study --bench
//! turbine_tables`; `ALEA_TABLE53_COLD=N` solves only the first `N` chaining runs and
//! extrapolates, `ALEA_THREADS` sets the worker threads, default 2).
//!
//! One model: `examples/turbine-2d-wear-adaptive.toml` (four substructures, Quad8, ~22 000
//! dof). Measured in one process, one after the other, so that the ratios hold on a shared
//! machine:
//! 1. **chaining** (the thesis's "commercial chaining" baseline): the 225 runs of the 15 x 15
//!    grid, each with a new solver (new factorisations) and a zero start, `threads` at a time;
//! 2. **multiresolution**: the same 225 runs through the study runner (one set-up, every run
//!    warm-started from the nearest finished one), the study's piecewise-linear 15 x 15;
//! 3. **adaptive**: the study's own adaptive method (5 runs to start, improved criterion, until
//!    the example's stopping rule, `i_sto <= 7 %`), runs and error estimates;
//!
//! and tables 5.1 / 5.2: per adaptive step the runs, `i_sto`, `i_geo`, mean, std and
//! `P(vm_fillet > threshold)`, against the 225-run reference statistics (piecewise linear
//! 15 x 15, its Monte Carlo draws).

use std::path::PathBuf;
use std::time::Instant;

use alea_study::runner::{NoProgress, Study, run_study};
use alea_study::{Source, StudyError};
use rayon::prelude::*;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn adaptive_text() -> String {
    std::fs::read_to_string(root().join("examples/turbine-2d-wear-adaptive.toml"))
        .expect("examples/turbine-2d-wear-adaptive.toml")
}

/// The same model with the 15 x 15 piecewise-linear grid as its only method (no estimate).
fn grid_text() -> String {
    let text = adaptive_text();
    let head = &text[..text.find("[[method]]").expect("a method")];
    let tail = &text[text.find("[solver]").expect("a [solver] table")..];
    format!(
        "{head}[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = 15\nlabel = \"reference 15 x 15\"\n\n{tail}"
    )
}

fn load(name: &str, text: &str) -> Study {
    let path = root().join("examples").join(name);
    Study::from_source(Source::from_text(path.to_str().expect("utf-8 path"), text)).expect("study")
}

fn secs(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

fn main() -> Result<(), StudyError> {
    let threads: usize = std::env::var("ALEA_THREADS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .expect("thread pool");
    let grid = load("turbine-table53-grid.toml", &grid_text());
    let adaptive = load("turbine-2d-wear-adaptive.toml", &adaptive_text());
    let points = grid.methods[0].points.clone();
    let dofs: usize = grid
        .model
        .assembly
        .subs
        .iter()
        .map(|s| s.model.mesh.num_nodes() * s.model.mesh.dim)
        .sum();
    println!(
        "2D turbine, {} substructures, {dofs} dof, {} grid runs, {threads} threads",
        grid.model.assembly.subs.len(),
        points.len()
    );

    // 1. Chaining: a new solver and a zero start per run.
    let cold_n: usize = std::env::var("ALEA_TABLE53_COLD")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(points.len())
        .min(points.len());
    let t = Instant::now();
    let cold: Vec<(usize, bool)> = points[..cold_n]
        .par_iter()
        .map(|p| {
            let solver = grid.model.solver().expect("solver");
            let r = solver
                .run_shared(&grid.model.parametric.run_input(p))
                .expect("run");
            (r.iterations, r.status == alea_latin::RunStatus::Converged)
        })
        .collect();
    let cold_s = secs(t);
    let cold_total = cold_s * points.len() as f64 / cold_n as f64;
    let cold_it: usize = cold.iter().map(|c| c.0).sum();
    let cold_ok = cold.iter().filter(|c| c.1).count();
    println!(
        "chaining: {cold_n} runs in {cold_s:.2} s ({:.0} iterations per run, {cold_ok} converged){}",
        cold_it as f64 / cold_n as f64,
        if cold_n < points.len() {
            format!(
                ", {cold_total:.1} s for {} runs (extrapolated)",
                points.len()
            )
        } else {
            String::new()
        }
    );

    // 2. Multiresolution: the study runner on the same grid.
    let dir = std::env::temp_dir().join(format!("alea-table53-grid-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let t = Instant::now();
    let runs = run_study(&grid, &dir, true, &NoProgress)?;
    let multi_s = secs(t);
    let multi_it: usize = runs.records.iter().map(|r| r.iterations).sum();
    println!(
        "multiresolution: {} runs in {multi_s:.2} s (set-up {:.2} s, {:.0} iterations per run)",
        runs.records.len(),
        runs.setup_seconds,
        multi_it as f64 / runs.records.len() as f64
    );
    let settings = alea_study::analysis::analysis_settings(&grid)?;
    let reference =
        alea_study::analysis::analyse_method(&grid, &runs.methods[0], &runs.records, &settings);
    drop(runs);
    let _ = std::fs::remove_dir_all(&dir);

    // 3. Adaptive, with the error estimates.
    let dir = std::env::temp_dir().join(format!("alea-table53-adaptive-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let t = Instant::now();
    let runs = run_study(&adaptive, &dir, true, &NoProgress)?;
    let adaptive_s = secs(t);
    println!(
        "adaptive: {} runs in {adaptive_s:.2} s (solves {:.2} s, estimates {:.2} s)",
        runs.records.len(),
        runs.solve_seconds,
        runs.estimate_seconds
    );
    println!(
        "table 5.3: chaining {cold_total:.1} s, multiresolution {multi_s:.2} s ({:.1}x), \
         multiresolution + adaptive {adaptive_s:.2} s ({:.1}x overall)",
        cold_total / multi_s,
        cold_total / adaptive_s
    );

    // Tables 5.1 / 5.2.
    let threshold = adaptive.qois[0].thresholds.first().copied();
    println!("\ntables 5.1 / 5.2 (vm_fillet [MPa]; P(vm_fillet > {threshold:?}))");
    println!("| step | runs | i_sto | i_geo | mean | std | P_f |");
    println!("|---|---|---|---|---|---|---|");
    for outcome in &runs.adaptive {
        for (s, step) in outcome.steps.iter().enumerate() {
            let q = &step.qois[0];
            println!(
                "| {s} | {} | {:.2} % | {:.2} % | {:.1} | {:.2} | {} |",
                step.runs,
                100.0 * step.error.estimate.i_sto(),
                100.0 * step.error.estimate.i_geo(),
                q.mean,
                q.std,
                q.failure
                    .first()
                    .map_or("-".into(), |p| format!("{:.2} %", 100.0 * p))
            );
        }
        println!("stop: {}", outcome.stop);
    }
    let m = &reference;
    let q = &m.qois[0];
    println!(
        "| reference | {} | - | - | {:.1} | {:.2} | {} |",
        m.account.runs_used,
        q.distribution.mean,
        q.distribution.std,
        q.failure
            .first()
            .map_or("-".into(), |f| format!("{:.2} %", 100.0 * f.probability))
    );
    drop(runs);
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
