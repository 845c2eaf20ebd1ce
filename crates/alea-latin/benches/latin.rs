//! LATIN benchmark: a 2D four-substructure frictional assembly (dovetail blade root in a disk
//! sector, both split in halves on x = 0: two Coulomb contact interfaces on the flanks, two
//! perfect interfaces on x = 0), ~23 000 dof, and Hertz's cylinder on a block at three mesh
//! sizes.
//!
//! Measures, for the two-scale LATIN (coarse problem, `k = 3 E / L`, the defaults) and the
//! single-scale one it replaces (no coarse problem, `k = 0.5 E / L`, the dovetail's best):
//! - set-up (assembly + factorisation of the four operators, + the macro responses);
//! - iterations to tolerance 1e-6 at the nominal point, and the time per iteration against the
//!   raw triangular solves of that iteration (`RunTimings`);
//! - a 5 x 5 parameter series (mu in [0.1, 0.9] x root Young's-modulus factor in
//!   [0.875, 1.125]): cold runs (a new solver per run: set-up + iterations from zero, the
//!   thesis's "restart a code per run"), cold iterations only (one solver, no warm start) and
//!   warm runs (one solver, each run started from the nearest finished one);
//! - Hertz (`alea_latin::samples::hertz_cylinder_on_block`, flat faces with node-to-node pairing
//!   and the true curved cylinder with mortar pairing) at n = 25, 50, 100 cells across the
//!   contact strip: iterations and time per run for the single-scale LATIN (k = E / L, plain
//!   and accelerated) and the two-scale one (k = 3 and 10 E / L).
//!
//! Run: `CARGO_TARGET_DIR=/work/target-latin cargo bench -p alea-latin --bench latin`
//! (results in `crates/alea-latin/BENCHMARKS.md`). `LATIN_BENCH_THREADS` (default `1,2`),
//! `LATIN_BENCH_HERTZ_N` (default `25,50,100`), `LATIN_BENCH_PART` (`dovetail` or `hertz`:
//! one part only), `LATIN_BENCH_REFINE=n` (dovetail mesh density, default 6). Diagnostics
//! instead: `LATIN_BENCH_SCAN=1` (iterations vs the search-direction factor, with and without
//! the coarse problem), `LATIN_BENCH_HIST=1` (residual histories of cold and warm runs, and of
//! the all-perfect assembly).

use std::time::Instant;

use alea_latin::samples::{four_part_dovetail_options, four_part_dovetail_single_scale_options};
use alea_latin::{
    Assembly, LatinOptions, LatinSolver, RunInput, RunResult, RunStatus, SearchDirection, constant,
};

fn assembly(refine: usize) -> Assembly {
    alea_latin::samples::four_part_dovetail(refine).expect("the sample assembly builds")
}

fn env_list(name: &str, default: &[usize]) -> Vec<usize> {
    std::env::var(name)
        .ok()
        .map(|v| v.split(',').filter_map(|t| t.trim().parse().ok()).collect())
        .unwrap_or_else(|| default.to_vec())
}

/// The 5 x 5 grid in snake order (each point next to the previous one) with its normalised
/// parameters.
fn grid() -> Vec<(f64, f64, Vec<f64>)> {
    let mut pts = Vec::new();
    for i in 0..5 {
        let ef = 0.875 + 0.0625 * i as f64;
        for jj in 0..5 {
            let j = if i % 2 == 0 { jj } else { 4 - jj };
            let mu = 0.1 + 0.2 * j as f64;
            pts.push((mu, ef, vec![j as f64 / 4.0, i as f64 / 4.0]));
        }
    }
    pts
}

/// The dovetail's input at `(mu, ef)`, started from `start` (`None`: cold).
fn input(mu: f64, ef: f64, start: Option<&RunResult>) -> RunInput {
    RunInput {
        young_factors: vec![ef, ef, 1.0, 1.0],
        mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
        initial: start.map(|r| std::sync::Arc::new(r.end_state())),
        ..Default::default()
    }
}

#[derive(Default)]
struct Series {
    seconds: f64,
    iterations: usize,
    results: Vec<RunResult>,
}

fn series(asm: &Assembly, opts: &LatinOptions, mode: &str) -> Series {
    let mut s = Series::default();
    let mut shared = (mode != "cold").then(|| LatinSolver::new(asm.clone(), opts.clone()).unwrap());
    let t0 = Instant::now();
    for (mu, ef, _) in grid() {
        // Warm: from the previous point of the snake-ordered grid, its nearest neighbour.
        let start = if mode == "warm" {
            s.results.last()
        } else {
            None
        };
        let r = match shared.as_mut() {
            Some(solver) => solver.run(&input(mu, ef, start)).unwrap(),
            None => {
                let mut solver = LatinSolver::new(asm.clone(), opts.clone()).unwrap();
                solver.run(&input(mu, ef, start)).unwrap()
            }
        };
        assert_eq!(r.status, RunStatus::Converged, "{mode} mu {mu} ef {ef}");
        s.iterations += r.iterations;
        s.results.push(r);
    }
    s.seconds = t0.elapsed().as_secs_f64();
    s
}

fn dovetail(asm: &Assembly, label: &str, opts: &LatinOptions) {
    println!("\n### {label}");
    let mut solver = LatinSolver::new(asm.clone(), opts.clone()).unwrap();
    let setup = solver.setup_seconds;
    let r = solver.run(&input(0.5, 1.0, None)).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    let it = r.iterations as f64;
    let tm = r.timings;
    let counts: Vec<[usize; 4]> = r.interfaces.iter().map(|i| i.status_counts()).collect();
    println!("set-up: {setup:.3} s");
    println!(
        "nominal run (mu 0.5, E factor 1): {} iterations to 1e-6, run {:.3} s; statuses [perfect, open, stick, slip] {counts:?}",
        r.iterations, tm.total
    );
    println!(
        "per iteration: total {:.3} ms = linear {:.3} ms (of which triangular solves {:.3} ms, summed over substructures) + local {:.3} ms; (linear + local) / solves = {:.2}",
        1e3 * tm.total / it,
        1e3 * tm.linear / it,
        1e3 * tm.triangular_solves / it,
        1e3 * tm.local / it,
        (tm.linear + tm.local) / tm.triangular_solves
    );
    let cold = series(asm, opts, "cold");
    let iters = series(asm, opts, "iters");
    let warm = series(asm, opts, "warm");
    // Same answers (to the tolerance): friction work of both flanks.
    let mut worst = 0.0f64;
    for (a, b) in warm.results.iter().zip(&iters.results) {
        for k in 0..2 {
            let (wa, wb) = (a.interfaces[k].work(), b.interfaces[k].work());
            let scale = a.interfaces[k]
                .resultant()
                .iter()
                .map(|v| v.abs())
                .fold(0.0, f64::max);
            worst = worst.max((wa - wb).abs() / (scale * 1e-3 + wb.abs()));
        }
    }
    println!(
        "25 runs: cold (new solver per run) {:.3} s ({} iterations); cold iterations only {:.3} s ({} iterations); warm {:.3} s ({} iterations)",
        cold.seconds,
        cold.iterations,
        iters.seconds,
        iters.iterations,
        warm.seconds,
        warm.iterations
    );
    println!(
        "warm vs cold: {:.2}x; warm vs cold iterations only: {:.2}x; worst relative difference of the friction work warm vs cold: {worst:.1e}",
        cold.seconds / warm.seconds,
        iters.seconds / warm.seconds
    );
}

/// Hertz at several mesh sizes: iterations and time per run.
fn hertz_scaling() {
    let ns = env_list("LATIN_BENCH_HERTZ_N", &[25, 50, 100]);
    let configs: [(&str, bool, f64, usize); 6] = [
        ("single-scale k=1 plain", false, 1.0, 0),
        ("single-scale k=1 Anderson", false, 1.0, 5),
        ("two-scale k=3 plain", true, 3.0, 0),
        ("two-scale k=3 Anderson", true, 3.0, 5),
        ("two-scale k=10 plain", true, 10.0, 0),
        ("two-scale k=10 Anderson", true, 10.0, 5),
    ];
    for curved in [false, true] {
        println!(
            "\n### Hertz, {}",
            if curved {
                "true curved cylinder, mortar pairing"
            } else {
                "flat faces, curvature in g0, node-to-node pairing"
            }
        );
        for &n in &ns {
            let case = alea_latin::samples::hertz_cylinder_on_block(n, curved).unwrap();
            let ndof: usize = case
                .assembly
                .subs
                .iter()
                .map(|s| 2 * s.model.mesh.num_nodes())
                .sum();
            let mut line = format!("n {n} ({ndof} dof):");
            for (label, coarse, factor, acc) in configs {
                let opts = LatinOptions {
                    tolerance: 1e-7,
                    max_iterations: 5000,
                    acceleration: Some(acc),
                    coarse,
                    search_direction: SearchDirection::Auto { factor },
                    ..Default::default()
                };
                let mut solver = LatinSolver::new(case.assembly.clone(), opts).unwrap();
                let r = solver.run(&RunInput::default()).unwrap();
                let mark = if r.status == RunStatus::Converged {
                    ""
                } else {
                    " (not converged)"
                };
                line += &format!(
                    " | {label}: {}{mark} it, {:.3} s (+ set-up {:.3} s)",
                    r.iterations, r.timings.total, solver.setup_seconds
                );
            }
            println!("{line}");
        }
    }
}

fn main() {
    let refine: usize = std::env::var("LATIN_BENCH_REFINE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6);
    let part = std::env::var("LATIN_BENCH_PART").unwrap_or_default();
    if std::env::var("LATIN_BENCH_HIST").is_ok() || std::env::var("LATIN_BENCH_SCAN").is_ok() {
        let asm = assembly(refine);
        diagnostics(&asm);
        return;
    }
    if part != "hertz" {
        let t = Instant::now();
        let asm = assembly(refine);
        let sizes: Vec<usize> = asm
            .subs
            .iter()
            .map(|s| 2 * s.model.mesh.num_nodes())
            .collect();
        println!(
            "dovetail refined x{refine}: {} dof in 4 substructures {sizes:?} (meshing {:.2}s)",
            sizes.iter().sum::<usize>(),
            t.elapsed().as_secs_f64()
        );
        for threads in env_list("LATIN_BENCH_THREADS", &[1, 2]) {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                println!("\n## {threads} thread(s)");
                dovetail(
                    &asm,
                    "two-scale (coarse problem, k = 3 E / L)",
                    &four_part_dovetail_options(),
                );
                dovetail(
                    &asm,
                    "single-scale (no coarse problem, k = 0.5 E / L)",
                    &four_part_dovetail_single_scale_options(),
                );
            });
        }
    }
    if part != "dovetail" {
        hertz_scaling();
    }
}

/// Residual histories (`LATIN_BENCH_HIST`) or a search-direction scan (`LATIN_BENCH_SCAN`).
fn diagnostics(asm: &Assembly) {
    for (label, base) in [
        ("two-scale", four_part_dovetail_options()),
        ("single-scale", four_part_dovetail_single_scale_options()),
    ] {
        if std::env::var("LATIN_BENCH_SCAN").is_ok() {
            for factor in [0.3, 0.5, 1.0, 3.0, 10.0] {
                let opts = LatinOptions {
                    search_direction: SearchDirection::Auto { factor },
                    ..base.clone()
                };
                let mut solver = LatinSolver::new(asm.clone(), opts).unwrap();
                let r = solver.run(&input(0.5, 1.0, None)).unwrap();
                println!(
                    "{label}, k factor {factor}: {:?} after {} iterations ({:.2} s)",
                    r.status, r.iterations, r.timings.total
                );
            }
            continue;
        }
        let mut solver = LatinSolver::new(asm.clone(), base.clone()).unwrap();
        let show = |name: &str, r: &RunResult| {
            let h: Vec<String> = r
                .residuals
                .iter()
                .enumerate()
                .filter(|(i, _)| i % 10 == 0)
                .map(|(i, v)| format!("{i}:{v:.1e}"))
                .collect();
            println!(
                "{label} {name}: {} iterations; {}",
                r.iterations,
                h.join(" ")
            );
        };
        let r03 = solver.run(&input(0.3, 1.0, None)).unwrap();
        show("cold mu 0.3", &r03);
        let r05 = solver.run(&input(0.5, 1.0, Some(&r03))).unwrap();
        show("warm mu 0.5 from 0.3", &r05);
        let r = solver.run(&input(0.5, 1.0625, Some(&r05))).unwrap();
        show("warm E 1.0625 from 1", &r);
        let mut asm2 = asm.clone();
        for i in asm2.interfaces.iter_mut() {
            i.law = std::sync::Arc::new(alea_latin::Perfect);
        }
        let mut s2 = LatinSolver::new(asm2, base.clone()).unwrap();
        let r = s2.run(&input(0.5, 1.0, None)).unwrap();
        show("all perfect", &r);
    }
}
