//! Per-run cost of the deterministic error estimate against the warm-started LATIN solve it
//! follows (issue 9: "per run, the estimate costs <= 1.5x the accelerated LATIN solve"; the
//! thesis: 1.5x). The solver is set up once (factorisations shared, as in a study); a run at a
//! first parameter point is solved cold, then a neighbouring point is solved warm-started from
//! it (`RunInput::initial`, so that every repetition starts from the same state) and estimated.
//!
//! Cases:
//! - `blade`: the simple blade root study (`examples/blade-root-simple.toml`, Q4, 11.5k dof),
//!   E2 = 240 GPa, mu = 0.5 -> E2 = 245 GPa, mu = 0.55, estimated as a study does
//!   (`CreSetup::estimate_run`: the study's `LatinEstimator` plus the phase-2 coefficients of
//!   every cell); the direct path (`estimate_latin_direct`) is timed for comparison.
//! - `dovetail`: the four-part dovetail of `alea_latin::samples` (refinement 6, Q4, 23k dof):
//!   factors 1 -> Young's factors [1.1, 1.1, 0.95, 0.95] and load factor 1.2 on the root
//!   halves, estimated with a `LatinEstimator` built once (loads scaled by the factor); the
//!   direct path is timed for comparison.
//!
//! Run: `cargo bench -p alea-study --bench cre_run` (both cases, 1 and 2 threads);
//! `cargo bench -p alea-study --bench cre_run -- blade` for one case. Prints the best of
//! `CRE_RUN_REPS` (default 5) wall times and the CPU time of the process's threads.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use alea_cre::{CreOptions, LatinEstimator, LoadData, estimate_latin_direct};
use alea_latin::samples::{PULL, SHEAR};
use alea_latin::{LatinSolver, LocalState, RunInput, RunResult, RunStatus};
use alea_study::Source;
use alea_study::cre::CreSetup;
use alea_study::runner::Study;

#[path = "../../../benches/support/timing.rs"]
mod timing;
use timing::{cpu_seconds, with_threads};

fn state_of(r: &RunResult) -> Arc<LocalState> {
    Arc::new(LocalState {
        what: r.interfaces.iter().map(|i| i.what.clone()).collect(),
        fhat: r.interfaces.iter().map(|i| i.fhat.clone()).collect(),
    })
}

/// Best wall and CPU seconds of `reps` calls of `f`, and the last value.
fn best_of<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    let mut last = None;
    for _ in 0..reps {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        let v = f();
        wall = wall.min(t0.elapsed().as_secs_f64());
        cpu = cpu.min(cpu_seconds() - c0);
        last = Some(v);
    }
    (wall, cpu, last.expect("at least one repetition"))
}

/// Phase 1 and phase 2 seconds of an estimate (summed over the substructures).
fn phases(est: &alea_cre::CreResult) -> (f64, f64) {
    (
        est.substructures.iter().map(|d| d.seconds[0]).sum(),
        est.substructures.iter().map(|d| d.seconds[1]).sum(),
    )
}

/// Prints the context's set-up time and size and the direct path's time for one run.
fn extra(setup: f64, bytes: usize, cells: usize, direct: (f64, f64), est: f64) {
    println!(
        "    context set-up {setup:.3} s, cache {:.1} MB ({} bytes per cell, {cells} cells); direct path {:.4} s ({:.4} CPU): context {:.1}x faster",
        bytes as f64 / 1e6,
        bytes / cells.max(1),
        direct.0,
        direct.1,
        direct.0 / est
    );
}

/// One table row (warm solve and estimate, wall and CPU seconds) and the estimate's
/// `(theta, relative)` with the cold run's iteration count under it.
fn report(
    name: &str,
    threads: usize,
    (iterations, cold_iterations): (usize, usize),
    solve: (f64, f64),
    est: (f64, f64),
    (theta, relative): (f64, f64),
) {
    println!(
        "| {name} | {threads} | {iterations} | {:.4} s ({:.4} CPU) | {:.4} s ({:.4} CPU) | {:.2} | {:.2} |",
        solve.0,
        solve.1,
        est.0,
        est.1,
        est.0 / solve.0,
        est.1 / solve.1
    );
    println!(
        "    theta = {theta:.6e}, relative {relative:.4e}, cold run {cold_iterations} iterations"
    );
}

fn blade(reps: usize, threads: usize) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/blade-root-simple.toml");
    let text = std::fs::read_to_string(&path).expect("example file");
    let study = Study::from_source(Source::from_text(&path.to_string_lossy(), &text))
        .expect("study builds");
    let solver = LatinSolver::new(study.model.assembly.clone(), study.model.options.clone())
        .expect("solver set-up");
    let t0 = Instant::now();
    let setup = CreSetup::new(&study, &solver).expect("estimator set-up");
    let setup_seconds = t0.elapsed().as_secs_f64();
    let (a, b) = ([240e3, 0.5], [245e3, 0.55]);
    let first = solver
        .run_shared(&study.model.parametric.run_input(&a))
        .expect("first run");
    assert_eq!(first.status, RunStatus::Converged);
    let mut input = study.model.parametric.run_input(&b);
    input.initial = Some(state_of(&first));
    let (sw, sc, res) = best_of(reps, || solver.run_shared(&input).expect("warm run"));
    assert_eq!(res.status, RunStatus::Converged);
    let (ew, ec, rec) = best_of(reps, || {
        setup
            .estimate_run(&study, &solver, &b, &res)
            .expect("estimate")
    });
    report(
        "blade root (11.5k dof)",
        threads,
        (res.iterations, first.iterations),
        (sw, sc),
        (ew, ec),
        (rec.theta, rec.relative),
    );
    // The same estimate through the direct path (loads of the study: no load factors here).
    let ctx = LatinEstimator::new(&study.model.assembly, &setup.options).expect("context");
    let asm = &study.model.assembly;
    let loads = blade_loads(&study);
    let (dw, dc, direct) = best_of(reps.min(3), || {
        estimate_latin_direct(asm, &loads, &res, &setup.options).expect("direct")
    });
    let (_, _, mine) = best_of(reps, || {
        ctx.estimate(&loads, &res).expect("context estimate")
    });
    let (p1, p2) = phases(&mine);
    println!("    context estimate: phase 1 {p1:.4} s, phase 2 {p2:.4} s (last repetition)");
    println!(
        "    substructures {:?}, interface terms {:?}, compatibility defect {:.1e}, balance defect {:.1e}",
        mine.substructure_theta(),
        mine.interfaces.iter().map(|i| i.term).collect::<Vec<_>>(),
        mine.compatibility_defect(),
        mine.substructures
            .iter()
            .fold(0.0f64, |m, d| m.max(d.balance_defect))
    );
    assert!((mine.theta - direct.theta).abs() <= 1e-9 * direct.theta);
    assert!((rec.theta - direct.theta).abs() <= 1e-9 * direct.theta);
    let cells: usize = asm.subs.iter().map(|s| s.model.mesh.num_cells()).sum();
    extra(setup_seconds, ctx.cache_bytes(), cells, (dw, dc), ew);
}

/// The blade root's loads as the estimator takes them: the pressures of the root S2.
fn blade_loads(study: &Study) -> Vec<LoadData> {
    let mut out = Vec::new();
    for sub in &study.file.substructure {
        let mut d = LoadData::new();
        for l in &sub.load {
            let group = l.group.as_ref().expect("load group").get_ref().clone();
            let p = *l.pressure.as_ref().expect("pressure load").get_ref();
            d = d.traction(&group, move |_, n| [-p * n[0], -p * n[1], -p * n[2]]);
        }
        out.push(d);
    }
    out
}

fn dovetail_loads(factor: f64) -> Vec<LoadData> {
    let root =
        LoadData::new().traction("root_top", move |_, _| [factor * SHEAR, factor * PULL, 0.0]);
    vec![root.clone(), root, LoadData::new(), LoadData::new()]
}

fn dovetail(reps: usize, threads: usize) {
    let asm = alea_latin::samples::four_part_dovetail(6).expect("sample assembly");
    let solver = LatinSolver::new(
        asm.clone(),
        alea_latin::samples::four_part_dovetail_options(),
    )
    .expect("solver set-up");
    let first = solver.run_shared(&RunInput::default()).expect("first run");
    assert_eq!(first.status, RunStatus::Converged);
    let lf = 1.2;
    let input = RunInput {
        young_factors: vec![1.1, 1.1, 0.95, 0.95],
        load_factors: vec![vec![lf], vec![lf], vec![1.0], vec![1.0]],
        initial: Some(state_of(&first)),
        ..Default::default()
    };
    let (sw, sc, res) = best_of(reps, || solver.run_shared(&input).expect("warm run"));
    assert_eq!(res.status, RunStatus::Converged);
    let loads = dovetail_loads(lf);
    let options = CreOptions::default();
    let t0 = Instant::now();
    let ctx = LatinEstimator::new(&asm, &options).expect("context");
    let setup_seconds = t0.elapsed().as_secs_f64();
    let (ew, ec, est) = best_of(reps, || ctx.estimate(&loads, &res).expect("estimate"));
    report(
        "four-part dovetail (23k dof)",
        threads,
        (res.iterations, first.iterations),
        (sw, sc),
        (ew, ec),
        (est.theta, est.relative),
    );
    let (p1, p2) = phases(&est);
    println!("    context estimate: phase 1 {p1:.4} s, phase 2 {p2:.4} s (last repetition)");
    let (dw, dc, direct) = best_of(reps.min(3), || {
        estimate_latin_direct(&asm, &loads, &res, &options).expect("direct")
    });
    assert!((est.theta - direct.theta).abs() <= 1e-9 * direct.theta);
    let cells: usize = asm.subs.iter().map(|s| s.model.mesh.num_cells()).sum();
    extra(setup_seconds, ctx.cache_bytes(), cells, (dw, dc), ew);
}

fn main() {
    let filter: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let wanted = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f));
    let reps = std::env::var("CRE_RUN_REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5);
    println!(
        "| case | threads | warm iterations | warm LATIN solve | estimate | ratio (wall) | ratio (CPU) |"
    );
    println!("|---|---|---|---|---|---|---|");
    for threads in [1, 2] {
        with_threads(threads, || {
            if wanted("blade") {
                blade(reps, threads);
            }
            if wanted("dovetail") {
                dovetail(reps, threads);
            }
        });
    }
}
