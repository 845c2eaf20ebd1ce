//! LATIN benchmark: a 2D four-substructure frictional assembly (dovetail blade root in a disk
//! sector, both split in halves on x = 0: two Coulomb contact interfaces on the flanks, two
//! perfect interfaces on x = 0), ~22 000 dof.
//!
//! Measures, with 1 and 2 threads:
//! - set-up (assembly + factorisation of the four operators);
//! - iterations to tolerance 1e-6 at the nominal point, and the time per iteration against the
//!   raw triangular solves of that iteration (`RunTimings`);
//! - a 5 x 5 parameter series (mu in [0.1, 0.9] x root Young's-modulus factor in
//!   [0.875, 1.125]): cold runs (a new solver per run: set-up + iterations from zero, the
//!   thesis's "restart a code per run"), cold iterations only (one solver, no warm start) and
//!   warm runs (one solver, each run started from the nearest finished one).
//!
//! Run: `CARGO_TARGET_DIR=/work/target-latin cargo bench -p alea-latin --bench latin`
//! (results in `crates/alea-latin/BENCHMARKS.md`). Diagnostics instead of the benchmark:
//! `LATIN_BENCH_SCAN=1` (iterations vs the search-direction factor), `LATIN_BENCH_SCAN2=1`
//! (separate factors for contact and perfect interfaces), `LATIN_BENCH_HIST=1` (residual
//! histories of cold and warm runs, and of the all-perfect assembly); `LATIN_BENCH_REFINE=n`
//! changes the mesh density (default 6).

use std::time::Instant;

use alea_latin::samples::YOUNG as E;
use alea_latin::{
    Assembly, LatinOptions, LatinSolver, RunInput, RunResult, RunStatus, SearchDirection, constant,
};

fn assembly(refine: usize) -> Assembly {
    alea_latin::samples::four_part_dovetail(refine).expect("the sample assembly builds")
}

fn options() -> LatinOptions {
    let mut o = alea_latin::samples::four_part_dovetail_options();
    if let Some(v) = env_usize("LATIN_BENCH_COARSE") {
        o.coarse = v != 0;
    }
    if let Some(v) = env_usize("LATIN_BENCH_ACC") {
        o.acceleration = v;
    }
    if let Some(v) = std::env::var("LATIN_BENCH_RELAX")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        o.relaxation = v;
    }
    if let Some(v) = std::env::var("LATIN_BENCH_K")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        o.search_direction = SearchDirection::Auto { factor: v };
    }
    o
}

fn env_usize(name: &str) -> Option<usize> {
    std::env::var(name).ok().and_then(|v| v.parse().ok())
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

fn input(mu: f64, ef: f64, params: Vec<f64>) -> RunInput {
    RunInput {
        young_factors: vec![ef, ef, 1.0, 1.0],
        mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
        params,
        ..Default::default()
    }
}

#[derive(Default)]
struct Series {
    seconds: f64,
    iterations: usize,
    results: Vec<RunResult>,
}

fn series(asm: &Assembly, mode: &str) -> Series {
    let mut s = Series::default();
    let mut shared = (mode != "cold").then(|| LatinSolver::new(asm.clone(), options()).unwrap());
    let t0 = Instant::now();
    for (mu, ef, params) in grid() {
        let params = if mode == "warm" { params } else { vec![] };
        let r = match shared.as_mut() {
            Some(solver) => solver.run(&input(mu, ef, params)).unwrap(),
            None => {
                let mut solver = LatinSolver::new(asm.clone(), options()).unwrap();
                solver.run(&input(mu, ef, params)).unwrap()
            }
        };
        assert_eq!(r.status, RunStatus::Converged, "{mode} mu {mu} ef {ef}");
        s.iterations += r.iterations;
        s.results.push(r);
    }
    s.seconds = t0.elapsed().as_secs_f64();
    s
}

/// Hertz at three mesh sizes: iterations and time per run, plain and accelerated, with and
/// without the coarse problem.
fn hertz_scaling() {
    let ns: Vec<usize> = std::env::var("LATIN_BENCH_HERTZ_N")
        .ok()
        .map(|v| v.split(',').filter_map(|t| t.parse().ok()).collect())
        .unwrap_or_else(|| vec![25, 50, 100]);
    for curved in [false, true] {
        for &n in &ns {
            let case = alea_latin::samples::hertz_cylinder_on_block(n, curved).unwrap();
            let ndof: usize = case
                .assembly
                .subs
                .iter()
                .map(|s| 2 * s.model.mesh.num_nodes())
                .sum();
            let accs: Vec<usize> = std::env::var("LATIN_BENCH_HERTZ_ACC")
                .ok()
                .map(|v| v.split(',').filter_map(|t| t.parse().ok()).collect())
                .unwrap_or_else(|| vec![0, 5]);
            for &acc in &accs {
                for coarse in [false, true] {
                    let opts = LatinOptions {
                        tolerance: 1e-7,
                        max_iterations: 20000,
                        acceleration: acc,
                        coarse,
                        ..Default::default()
                    };
                    let mut solver = LatinSolver::new(case.assembly.clone(), opts).unwrap();
                    let r = solver.run(&RunInput::default()).unwrap();
                    println!(
                        "hertz {} n {n} ({ndof} dof): acceleration {acc}, coarse {coarse}: {:?} in {} iterations, {:.3} s (set-up {:.3} s)",
                        if curved { "curved/mortar" } else { "flat/node" },
                        r.status,
                        r.iterations,
                        r.timings.total,
                        solver.setup_seconds
                    );
                }
            }
        }
    }
}

fn main() {
    let refine: usize = std::env::var("LATIN_BENCH_REFINE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6);
    let t = Instant::now();
    let asm = assembly(refine);
    let ndof: usize = asm.subs.iter().map(|s| 2 * s.model.mesh.num_nodes()).sum();
    let sizes: Vec<usize> = asm
        .subs
        .iter()
        .map(|s| 2 * s.model.mesh.num_nodes())
        .collect();
    println!(
        "dovetail refined x{refine}: {ndof} dof in 4 substructures {sizes:?} (meshing {:.2}s)",
        t.elapsed().as_secs_f64()
    );
    if std::env::var("LATIN_BENCH_HERTZ").is_ok() {
        hertz_scaling();
        return;
    }
    if std::env::var("LATIN_BENCH_HIST").is_ok() {
        let mut solver = LatinSolver::new(asm.clone(), options()).unwrap();
        let show = |name: &str, r: &RunResult| {
            let h: Vec<String> = r
                .residuals
                .iter()
                .enumerate()
                .filter(|(i, _)| i % 50 == 0)
                .map(|(i, v)| format!("{i}:{v:.1e}"))
                .collect();
            println!("{name}: {} iterations; {}", r.iterations, h.join(" "));
        };
        let r = solver.run(&input(0.3, 1.0, vec![0.25, 0.5])).unwrap();
        show("cold mu 0.3", &r);
        let r = solver.run(&input(0.5, 1.0, vec![0.5, 0.5])).unwrap();
        show("warm mu 0.5 from 0.3", &r);
        let r = solver.run(&input(0.5, 1.0625, vec![0.5, 0.75])).unwrap();
        show("warm E 1.0625 from 1", &r);
        let r = solver.run(&input(0.5, 1.0, vec![0.5, 0.5])).unwrap();
        show("warm same point", &r);
        let mut asm2 = asm.clone();
        for i in asm2.interfaces.iter_mut() {
            i.law = std::sync::Arc::new(alea_latin::Perfect);
        }
        let mut s2 = LatinSolver::new(asm2, options()).unwrap();
        let r = s2.run(&input(0.5, 1.0, vec![])).unwrap();
        show("all perfect", &r);
        return;
    }
    if std::env::var("LATIN_BENCH_SCAN2").is_ok() {
        // Separate factors for the contact and the perfect interfaces.
        let lens: Vec<f64> = asm
            .interfaces
            .iter()
            .map(|i| {
                let m = &asm.subs[i.sub1].model.mesh;
                alea_latin::interface::side_geometry(m, &i.group1, 1.0)
                    .unwrap()
                    .weights
                    .iter()
                    .sum::<f64>()
            })
            .collect();
        println!("interface lengths {lens:?}");
        for (fc, fp) in [
            (0.5, 0.5),
            (0.5, 2.0),
            (0.5, 5.0),
            (0.5, 0.2),
            (1.0, 2.0),
            (0.2, 2.0),
        ] {
            let k: Vec<[f64; 2]> = lens
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let f = if i < 2 { fc } else { fp };
                    [f * E / l, f * E / l]
                })
                .collect();
            let mut opts = options();
            opts.search_direction = SearchDirection::Fixed(k);
            let mut solver = LatinSolver::new(asm.clone(), opts).unwrap();
            let r = solver.run(&input(0.5, 1.0, vec![])).unwrap();
            println!(
                "contact {fc}, perfect {fp}: {:?} after {} iterations ({:.2} s)",
                r.status, r.iterations, r.timings.total
            );
        }
        return;
    }
    if std::env::var("LATIN_BENCH_SCAN").is_ok() {
        // Search-direction scan at the nominal point (iterations only).
        for factor in [0.1, 0.2, 0.3, 0.5, 1.0, 3.0] {
            let mut opts = options();
            opts.search_direction = SearchDirection::Auto { factor };
            let mut solver = LatinSolver::new(asm.clone(), opts).unwrap();
            let r = solver.run(&input(0.5, 1.0, vec![])).unwrap();
            println!(
                "k factor {factor}: {:?} after {} iterations ({:.2} s)",
                r.status, r.iterations, r.timings.total
            );
        }
        return;
    }
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            println!("\n## {threads} thread(s)");
            // Nominal point: set-up, iterations, per-iteration cost.
            let mut solver = LatinSolver::new(asm.clone(), options()).unwrap();
            let setup = solver.setup_seconds;
            let r = solver.run(&input(0.5, 1.0, vec![])).unwrap();
            assert_eq!(r.status, RunStatus::Converged);
            let it = r.iterations as f64;
            let tm = r.timings;
            let counts: Vec<[usize; 4]> =
                r.interfaces.iter().map(|i| i.status_counts()).collect();
            println!("set-up (assembly + factorisation): {:.3} s", setup);
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
            let cold = series(&asm, "cold");
            let iters = series(&asm, "iters");
            let warm = series(&asm, "warm");
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
                "25 runs: cold (new solver per run) {:.3} s ({} iterations, {:.3} s/run); cold iterations only {:.3} s ({} iterations); warm {:.3} s ({} iterations, {:.3} s/run)",
                cold.seconds,
                cold.iterations,
                cold.seconds / 25.0,
                iters.seconds,
                iters.iterations,
                warm.seconds,
                warm.iterations,
                warm.seconds / 25.0
            );
            println!(
                "speed-up warm vs cold: {:.2}x; warm vs cold iterations only: {:.2}x; worst relative difference of the friction work warm vs cold: {worst:.1e}",
                cold.seconds / warm.seconds,
                iters.seconds / warm.seconds
            );
        });
    }
}
