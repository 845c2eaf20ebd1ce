//! CRE benchmark: one estimate on the LATIN benchmark assembly (dovetail blade root in a disk
//! sector, each split in halves on x = 0: four substructures, two Coulomb contact interfaces on
//! the flanks, two perfect interfaces on x = 0, Q4, ~22 000 dof; built as in
//! `crates/alea-latin/benches/latin.rs`) against one deterministic LATIN solve (set-up +
//! iterations to 1e-6) of the same assembly, with 1 and 2 threads. The thesis quotes an
//! estimate at 1.5x a deterministic run.
//!
//! Run: `CARGO_TARGET_DIR=/work/target-cre cargo bench -p alea-cre --bench cre`
//! (results in `crates/alea-cre/BENCHMARKS.md`). `CRE_BENCH_REFINE` changes the refinement
//! (default 6).

use std::time::Instant;

use alea_cre::{CreOptions, LoadData, estimate_latin};
use alea_latin::samples::{PULL, SHEAR};
use alea_latin::{Assembly, LatinOptions, LatinSolver, RunInput, RunStatus};

fn assembly(refine: usize) -> Assembly {
    alea_latin::samples::four_part_dovetail(refine).expect("the sample assembly builds")
}

fn options() -> LatinOptions {
    alea_latin::samples::four_part_dovetail_options()
}

/// CPU seconds used so far by all threads of the process (sum of `/proc/self/task/*/schedstat`
/// run times; threads that have exited are not counted, rayon's pool threads persist).
fn cpu_seconds() -> f64 {
    let Ok(dir) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    dir.filter_map(|e| e.ok())
        .filter_map(|e| std::fs::read_to_string(e.path().join("schedstat")).ok())
        .filter_map(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .sum::<f64>()
        * 1e-9
}

fn loads() -> Vec<LoadData> {
    let root = LoadData::new().traction("root_top", |_, _| [SHEAR, PULL, 0.0]);
    vec![root.clone(), root, LoadData::new(), LoadData::new()]
}

fn main() {
    let refine: usize = std::env::var("CRE_BENCH_REFINE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6);
    let asm = assembly(refine);
    let ndof: usize = asm.subs.iter().map(|s| 2 * s.model.mesh.num_nodes()).sum();
    let ncell: usize = asm.subs.iter().map(|s| s.model.mesh.num_cells()).sum();
    println!("dovetail refined x{refine}: {ndof} dof, {ncell} cells in 4 substructures");
    let data = loads();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut best = [f64::INFINITY; 3];
            let mut summary = String::new();
            for _ in 0..3 {
                let t0 = Instant::now();
                let c0 = cpu_seconds();
                let mut solver = LatinSolver::new(asm.clone(), options()).unwrap();
                let setup = t0.elapsed().as_secs_f64();
                let r = solver.run(&RunInput::default()).unwrap();
                let solve = t0.elapsed().as_secs_f64();
                let solve_cpu = cpu_seconds() - c0;
                assert_eq!(r.status, RunStatus::Converged);
                let t1 = Instant::now();
                let c1 = cpu_seconds();
                let est = estimate_latin(&asm, &data, &r, &CreOptions::default()).unwrap();
                let cre = t1.elapsed().as_secs_f64();
                let cpu = cpu_seconds() - c1;
                best = [best[0].min(setup), best[1].min(solve), best[2].min(cre)];
                let p1: f64 = est.substructures.iter().map(|d| d.seconds[0]).sum();
                let p2: f64 = est.substructures.iter().map(|d| d.seconds[1]).sum();
                println!(
                    "  solve {solve:.3} s (CPU {solve_cpu:.3} s); estimate {cre:.3} s (CPU {cpu:.3} s, {:.2} cores busy): phase 1 {p1:.3} s, phase 2 {p2:.3} s; CPU ratio {:.2}",
                    cpu / cre,
                    cpu / solve_cpu
                );
                summary = format!(
                    "{} iterations; theta = {:.4e}, relative {:.3e}, substructures {:?}, interface terms {:?}, compatibility defect {:.1e}, violations {:?}",
                    r.iterations,
                    est.theta,
                    est.relative,
                    est.substructure_theta()
                        .iter()
                        .map(|t| format!("{t:.3e}"))
                        .collect::<Vec<_>>(),
                    est.interfaces
                        .iter()
                        .map(|i| format!("{:.2e}", i.term))
                        .collect::<Vec<_>>(),
                    est.compatibility_defect(),
                    est.interfaces.iter().map(|i| i.violations).collect::<Vec<_>>()
                );
            }
            println!("\n## {threads} thread(s) (best of 3)");
            println!("{summary}");
            println!(
                "| LATIN set-up | LATIN solve (set-up + iterations) | CRE estimate | CRE / solve |"
            );
            println!("|---|---|---|---|");
            println!(
                "| {:.3} s | {:.3} s | {:.3} s | {:.2} |",
                best[0],
                best[1],
                best[2],
                best[2] / best[1]
            );
        });
    }
}
