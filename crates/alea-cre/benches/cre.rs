//! CRE benchmark: one estimate on the LATIN benchmark assembly (dovetail blade root in a disk
//! sector, each split in halves on x = 0: four substructures, two Coulomb contact interfaces on
//! the flanks, two perfect interfaces on x = 0, Q4, ~22 000 dof; built as in
//! `crates/alea-latin/benches/latin.rs`) against one cold deterministic LATIN solve (set-up +
//! iterations to 1e-6) of the same assembly, with 1 and 2 threads. The thesis quotes an
//! estimate at 1.5x a deterministic run. "CRE estimate" is the one-run entry point
//! `estimate_latin` (it builds the multiresolution context, then estimates); the per-run cost
//! in a study (context built once, warm-started runs) is measured by
//! `cargo bench -p alea-study --bench cre_run`.
//!
//! Run: `CARGO_TARGET_DIR=/work/target-cre cargo bench -p alea-cre --bench cre`
//! (results in `crates/alea-cre/BENCHMARKS.md`). `CRE_BENCH_REFINE` changes the refinement
//! (default 6).
//!
//! 3D case (`CRE_BENCH_CASE=3d`): the same four-part assembly with each substructure's mesh
//! (refinement `CRE_BENCH_REFINE`, default 2) extruded along z into `CRE_BENCH_LAYERS`
//! (default 8) layers of Hex8 over 20 mm, out-of-plane displacement blocked on `z = 0`, the
//! same loads (Coulomb flanks and perfect cuts become face interfaces).

use std::time::Instant;

use alea_cre::{CreOptions, LoadData, estimate_latin};
use alea_latin::samples::{PULL, SHEAR};
use alea_latin::{Assembly, LatinOptions, LatinSolver, RunInput, RunStatus};

#[path = "../../../benches/support/timing.rs"]
mod timing;
use timing::{cpu_seconds, with_threads};

fn assembly(refine: usize) -> Assembly {
    alea_latin::samples::four_part_dovetail(refine).expect("the sample assembly builds")
}

fn options() -> LatinOptions {
    alea_latin::samples::four_part_dovetail_options()
}

/// The 3D case: every substructure of the 2D assembly extruded into Hex8.
fn assembly_3d(refine: usize, layers: usize) -> Assembly {
    use alea_fem::{Analysis, Constraints, Loads, Model};
    let flat = assembly(refine);
    let subs = flat
        .subs
        .into_iter()
        .map(|s| {
            let mesh = alea_mesh::generate::extrude(&s.model.mesh, layers, 20.0).unwrap();
            let mut m = Model::new(mesh, Analysis::Solid).unwrap();
            m.set_material_all(*s.model.material(0).unwrap());
            let mut c = Constraints::new();
            c.fix_component(&m.mesh, "zmin", 2, 0.0).unwrap();
            let mut l = Loads::new(&m);
            if s.name.starts_with("disk") {
                let side = s.name.replace("disk_", "disk_side_");
                c.fix_normal(&m.mesh, &side, 0.0).unwrap();
            } else {
                l.traction(&m, "root_top", |_, _| [SHEAR, PULL, 0.0])
                    .unwrap();
            }
            alea_latin::Substructure {
                name: s.name,
                model: m,
                constraints: c,
                load_cases: vec![l.f],
            }
        })
        .collect();
    Assembly {
        subs,
        interfaces: flat.interfaces,
    }
}

fn loads() -> Vec<LoadData> {
    let root = LoadData::new().traction("root_top", |_, _| [SHEAR, PULL, 0.0]);
    vec![root.clone(), root, LoadData::new(), LoadData::new()]
}

fn main() {
    let solid = std::env::var("CRE_BENCH_CASE").is_ok_and(|v| v == "3d");
    let env = |k: &str, d: usize| -> usize {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let refine = env("CRE_BENCH_REFINE", if solid { 2 } else { 6 });
    let layers = env("CRE_BENCH_LAYERS", 8);
    let asm = if solid {
        assembly_3d(refine, layers)
    } else {
        assembly(refine)
    };
    let dim = asm.subs[0].model.mesh.dim;
    let ndof: usize = asm
        .subs
        .iter()
        .map(|s| dim * s.model.mesh.num_nodes())
        .sum();
    let ncell: usize = asm.subs.iter().map(|s| s.model.mesh.num_cells()).sum();
    if solid {
        println!(
            "3D dovetail refined x{refine}, {layers} Hex8 layers: {ndof} dof, {ncell} cells in 4 substructures"
        );
    } else {
        println!("dovetail refined x{refine}: {ndof} dof, {ncell} cells in 4 substructures");
    }
    let data = loads();
    for threads in [1, 2] {
        with_threads(threads, || {
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
                    est.interfaces
                        .iter()
                        .map(|i| i.violations)
                        .collect::<Vec<_>>()
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
