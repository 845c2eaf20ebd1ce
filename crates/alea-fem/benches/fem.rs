//! Timing of the linear-elastic pipeline: assembly, symbolic analysis (ordering + elimination
//! structure), numeric Cholesky factorisation, refactorisation on the same pattern, and the
//! triangular solves, for a 2D Q4 model of ~22k dofs, a 2D Q4 model of ~200k dofs and a 3D Hex8
//! model of ~80k dofs, with METIS and AMD orderings, on 1 and 2 rayon threads.
//!
//! Run (release; prints a Markdown table):
//!
//! ```text
//! CARGO_TARGET_DIR=/work/target-fem cargo bench -p alea-fem --bench fem
//! ```
//! Each phase is run `reps` times and the fastest time is kept (the machine may be shared).
//! Set-up: unit-density steel-like material, plane stress (2D), `xmin` clamped, uniform traction
//! on `xmax`; the mesh and the load vector are built outside the timed region.

#[path = "support/cantilever.rs"]
mod support;

use std::time::Instant;

use alea_fem::{
    Analysis, Cholesky, Constraints, DofMap, Loads, Material, Model, Ordering, assemble_stiffness,
};
use alea_mesh::{CellType, generate};

struct Case {
    name: &'static str,
    model: Model,
    cons: Constraints,
    loads: Loads,
    reps: usize,
}

fn case_2d(name: &'static str, n: usize, reps: usize) -> Case {
    let mesh = generate::rectangle(2.0, 1.0, 2 * n, n, CellType::Quad4).unwrap();
    let mut model = Model::new(mesh, Analysis::PlaneStress { thickness: 1.0 }).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    finish(name, model, reps)
}

fn case_3d(name: &'static str, n: usize, reps: usize) -> Case {
    let mesh = generate::box_mesh([1.0; 3], [n; 3], CellType::Hex8).unwrap();
    let mut model = Model::new(mesh, Analysis::Solid).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    finish(name, model, reps)
}

fn finish(name: &'static str, model: Model, reps: usize) -> Case {
    let (cons, loads) = support::cantilever(&model);
    Case {
        name,
        model,
        cons,
        loads,
        reps,
    }
}

/// Fastest of `reps` runs of `f`, in seconds, and the last result.
fn best<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut t_best = f64::INFINITY;
    let mut out = None;
    for _ in 0..reps {
        let t0 = Instant::now();
        let r = f();
        t_best = t_best.min(t0.elapsed().as_secs_f64());
        out = Some(r);
    }
    (t_best, out.unwrap())
}

fn run(case: &Case, ordering: Ordering, threads: usize) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let (t_asm, (dofs, asm)) = best(case.reps, || {
            let dofs = DofMap::for_mesh(&case.model.mesh, &case.cons).unwrap();
            let asm = assemble_stiffness(&case.model, &dofs).unwrap();
            (dofs, asm)
        });
        let blocks = dofs.node_of_dof();
        let (t_sym, mut chol) = best(case.reps, || {
            Cholesky::new(&asm.k, ordering, Some(&blocks)).unwrap()
        });
        let t0 = Instant::now();
        chol.factorize(&asm.k).unwrap();
        let t_num = t0.elapsed().as_secs_f64();
        let (t_refac, ()) = best(case.reps, || chol.factorize(&asm.k).unwrap());
        let rhs0 = dofs.reduce(&case.loads.f);
        let (t_solve, x) = best(case.reps, || {
            let mut x = rhs0.clone();
            chol.solve_in_place(&mut x);
            x
        });
        // Relative residual, so a wrong result cannot hide behind a fast time.
        let mut ax = vec![0.0; x.len()];
        asm.k.mul_vec(&x, &mut ax);
        let num: f64 = ax.iter().zip(&rhs0).map(|(a, b)| (a - b) * (a - b)).sum();
        let den: f64 = rhs0.iter().map(|b| b * b).sum();
        println!(
            "| {} | {} | {:?}, {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.4} | {:.1} | {:.0e} |",
            case.name,
            dofs.num_free(),
            ordering,
            if chol.is_supernodal() {
                "supernodal"
            } else {
                "simplicial"
            },
            threads,
            t_asm,
            t_sym,
            t_num,
            t_refac,
            t_solve,
            chol.nnz_factor() as f64 / 1e6,
            (num / den).sqrt()
        );
    });
}

/// Splits the 1-thread assembly into its parts: dof map, sparsity pattern, element kernels
/// alone (`K_e` of every cell, no scatter), and the rest (reduction + scatter).
fn assembly_breakdown(case: &Case) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    pool.install(|| {
        let (t_dofs, dofs) = best(case.reps, || {
            DofMap::for_mesh(&case.model.mesh, &case.cons).unwrap()
        });
        let (t_pat, _) = best(case.reps, || {
            alea_fem::assembly::stiffness_pattern(&case.model, &dofs)
        });
        let (t_ke, _) = best(case.reps, || {
            let mut ke = Vec::new();
            let mut s = 0.0;
            for c in 0..case.model.mesh.num_cells() {
                alea_fem::assembly::element_stiffness(&case.model, c, &mut ke).unwrap();
                s += ke[0];
            }
            s
        });
        let (t_all, _) = best(case.reps, || assemble_stiffness(&case.model, &dofs).unwrap());
        println!(
            "| {} | dof map {:.3} | pattern {:.3} | element kernels {:.3} | reduce + scatter {:.3} | assembly total {:.3} |",
            case.name,
            t_dofs,
            t_pat,
            t_ke,
            (t_all - t_pat - t_ke).max(0.0),
            t_all + t_dofs
        );
    });
}

fn main() {
    let filter: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    println!(
        "| case | free dofs | ordering, factor | threads | assembly s | symbolic s | numeric s | \
         refactor s | solve s | nnz(L) M | residual |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    type MakeCase = fn() -> Case;
    let cases: [(&str, MakeCase); 3] = [
        ("2d-22k", || case_2d("2D Q4 22k", 74, 3)),
        ("2d-200k", || case_2d("2D Q4 200k", 224, 1)),
        ("3d-80k", || case_3d("3D Hex8 80k", 29, 1)),
    ];
    let mut built = Vec::new();
    for (key, make) in cases {
        if !filter.is_empty() && !filter.iter().any(|f| key.contains(f.as_str())) {
            continue;
        }
        let case = make();
        for ordering in [Ordering::Metis, Ordering::Amd] {
            for threads in [1, 2] {
                run(&case, ordering, threads);
            }
        }
        built.push(case);
    }
    println!("\nAssembly breakdown, 1 thread (seconds):\n");
    println!("| case | | | | | |\n|---|---|---|---|---|---|");
    for case in &built {
        assembly_breakdown(case);
    }
}
