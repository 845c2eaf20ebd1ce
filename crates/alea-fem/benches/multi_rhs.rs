//! What a batch of LATIN runs would gain per linear stage (issue 20, item 1): the cost per
//! right-hand side of one triangular solve `L L^T x = b` with `k` columns at once (one pass over
//! the factor for all of them) against `k` single-column solves, with the same factor, for
//! substructure-sized plane-strain Q8 models (a quarter of the 2D turbine, ~5 600 dofs, and
//! the whole of it, ~22 000 dofs) and a 3D Hex8 box of ~59 000 dofs.
//!
//! Run (release; prints a Markdown table):
//!
//! ```text
//! cargo bench -p alea-fem --bench multi_rhs
//! ```
//! One thread; each timing is the fastest of several repetitions (the machine may be shared);
//! the ratio column (per-column time of the `k`-column solve over the single solve) is the
//! robust figure. Every solve's relative residual is checked.
//!
//! A second table compares, for the 3D boxes, the factor stored in single precision (module
//! `single` of alea-fem): one refinement step from a nearby solution (`solve_near`, what a
//! LATIN linear stage makes) and the solve refined to full accuracy (`solve_with`), each
//! against the double-precision solve of the same columns, timed in the same process.
//!
//! A third table streams: 32 single-precision factors of a turbine-part-sized box (more bytes
//! than the caches hold, as the parts of a large model), one refinement step on each over 2
//! threads, and the bytes a pass reads per second (against `scripts/read_bandwidth.c`).

#[path = "support/cantilever.rs"]
mod support;

use std::time::Instant;

use alea_fem::{
    Analysis, Cholesky, DofMap, FactorKind, Material, Model, Ordering, SolveScratch,
    assemble_stiffness,
};
use alea_mesh::{CellType, generate};

/// Fastest of `reps` runs of `f`, in seconds.
fn best(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t_best = f64::INFINITY;
    for _ in 0..reps {
        let t0 = Instant::now();
        f();
        t_best = t_best.min(t0.elapsed().as_secs_f64());
    }
    t_best
}

fn case(name: &str, model: &Model, reps: usize, kinds: &[FactorKind]) {
    for &kind in kinds {
        case_kind(name, model, reps, kind);
    }
}

fn case_kind(name: &str, model: &Model, reps: usize, kind: FactorKind) {
    let (cons, loads) = support::cantilever(model);
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let asm = assemble_stiffness(model, &dofs).unwrap();
    let blocks = dofs.node_of_dof();
    let auto = Cholesky::new(&asm.k, Ordering::Metis, Some(&blocks)).unwrap();
    let mut chol = Cholesky::with_kind(&asm.k, Ordering::Metis, Some(&blocks), kind).unwrap();
    let t_factor = best(reps.min(5), || chol.factorize(&asm.k).unwrap());
    let label = format!(
        "{name} | {kind:?}{} | {:.2}",
        if auto.is_supernodal() == (kind == FactorKind::Supernodal) {
            " (auto)"
        } else {
            ""
        },
        t_factor * 1e3
    );
    let b = dofs.reduce(&loads.f);
    let n = b.len();
    // Columns: the load scaled differently, so no two are equal.
    let columns = |k: usize| -> Vec<f64> {
        (0..k)
            .flat_map(|j| b.iter().map(move |v| v * (1.0 + 0.1 * j as f64)))
            .collect()
    };
    let mut scratch: SolveScratch = chol.solve_scratch(16);
    let single = {
        let x0 = columns(1);
        let mut x = x0.clone();
        best(reps, || {
            x.copy_from_slice(&x0);
            chol.solve_with(&mut x, &mut scratch);
        })
    };
    for k in [1usize, 2, 4, 8, 16] {
        let x0 = columns(k);
        let mut x = x0.clone();
        let t = best(reps, || {
            x.copy_from_slice(&x0);
            chol.solve_with(&mut x, &mut scratch);
        });
        let mut worst: f64 = 0.0;
        for j in 0..k {
            let xj = &x[j * n..(j + 1) * n];
            let mut ax = vec![0.0; n];
            asm.k.mul_vec(xj, &mut ax);
            let bj = &x0[j * n..(j + 1) * n];
            let num: f64 = ax.iter().zip(bj).map(|(a, c)| (a - c).powi(2)).sum::<f64>();
            let den: f64 = bj.iter().map(|c| c * c).sum::<f64>();
            worst = worst.max((num / den).sqrt());
        }
        assert!(worst < 1e-8, "{name}: residual {worst:e}");
        println!(
            "| {label} | {n} | {k} | {:.3} | {:.3} | {:.2} | {worst:.0e} |",
            t * 1e3,
            t * 1e3 / k as f64,
            t / k as f64 / single
        );
    }
}

/// The single-precision factor of a 3D model against its double-precision one.
fn case_single(name: &str, model: &Model, reps: usize) {
    let (cons, loads) = support::cantilever(model);
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let asm = assemble_stiffness(model, &dofs).unwrap();
    let blocks = dofs.node_of_dof();
    let double = supernodal_factor(&asm.k, &blocks);
    let mut single = supernodal_factor(&asm.k, &blocks);
    assert!(
        single.store_single(&asm.k),
        "{name}: kept in double precision"
    );
    let b = dofs.reduce(&loads.f);
    let n = b.len();
    for k in [1usize, 2, 4, 8] {
        let x0: Vec<f64> = (0..k)
            .flat_map(|j| b.iter().map(move |v| v * (1.0 + 0.1 * j as f64)))
            .collect();
        let (mut s64, mut s32) = (double.solve_scratch(k), single.solve_scratch(k));
        let mut exact = x0.clone();
        let t64 = best(reps, || {
            exact.copy_from_slice(&x0);
            double.solve_with(&mut exact, &mut s64);
        });
        // A nearby solution: the exact one off by 1e-3 relative.
        let previous: Vec<f64> = exact
            .iter()
            .enumerate()
            .map(|(i, v)| v * (1.0 + 1e-3 * ((i % 7) as f64 - 3.0)))
            .collect();
        let columns: Vec<&[f64]> = previous.chunks_exact(n).collect();
        let mut x = x0.clone();
        let t_near = best(reps, || {
            x.copy_from_slice(&x0);
            single.solve_near(&mut x, &columns, &mut s32);
        });
        let rel = |a: &[f64]| {
            let num: f64 = a.iter().zip(&exact).map(|(p, q)| (p - q).powi(2)).sum();
            let den: f64 = exact.iter().map(|q| q * q).sum();
            (num / den).sqrt()
        };
        let e_near = rel(&x);
        let t_refined = best(reps, || {
            x.copy_from_slice(&x0);
            single.solve_with(&mut x, &mut s32);
        });
        let e_refined = rel(&x);
        assert!(e_refined < 1e-10, "{name}: refined error {e_refined:e}");
        println!(
            "| {name} | {n} | {} | {:.1e} | {k} | {:.3} | {:.3} ({:.2}x, error {e_near:.0e}) | {:.3} ({:.2}x, error {e_refined:.0e}) |",
            double.nnz_factor(),
            single.refinement_rate().unwrap(),
            t64 * 1e3,
            t_near * 1e3,
            t_near / t64,
            t_refined * 1e3,
            t_refined / t64
        );
    }
}

fn main() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    pool.install(|| {
        println!(
            "| model | factor | factorisation ms | dofs | columns k | solve ms | ms per column | per column / single solve | worst residual |"
        );
        println!("|---|---|---|---|---|---|---|---|---|");
        let q8 = |nx: usize, ny: usize| {
            let mesh = generate::rectangle(2.0, 1.0, nx, ny, CellType::Quad8).unwrap();
            let mut m = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
            m.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
            m
        };
        let both = [FactorKind::Simplicial, FactorKind::Supernodal];
        case("2D Q8 (turbine quarter)", &q8(42, 21), 30, &both);
        case("2D Q8 (turbine whole)", &q8(84, 42), 20, &both);
        let m = hex_model([26; 3]);
        case("3D Hex8", &m, 3, &[FactorKind::Supernodal]);
        println!();
        println!(
            "| model | dofs | factor entries | refinement rate | columns k | f64 solve ms | f32 one step from 1e-3 ms | f32 refined ms |"
        );
        println!("|---|---|---|---|---|---|---|---|");
        case_single("3D Hex8 (a turbine part)", &hex_model([18, 18, 18]), 10);
        case_single("3D Hex8", &m, 3);
    });
    streamed(&hex_model([18, 18, 18]), 32);
}

/// The supernodal factorisation of `k` (METIS ordering on the node blocks).
fn supernodal_factor(k: &alea_fem::SymCsc, blocks: &[usize]) -> Cholesky {
    let mut c =
        Cholesky::with_kind(k, Ordering::Metis, Some(blocks), FactorKind::Supernodal).unwrap();
    c.factorize(k).unwrap();
    c
}

fn hex_model(cells: [usize; 3]) -> Model {
    let mesh = generate::box_mesh([1.0; 3], cells, CellType::Hex8).unwrap();
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    m
}

/// `parts` single-precision factors of `model` (more bytes than the caches hold, as the parts
/// of a large model; each a copy of the same factor), one refinement step (`solve_near`) on
/// each, over 2 threads, for 1 and 2 columns: the bytes a pass reads (the factor twice, forward
/// and backward, the matrix once) per second, against what this machine streams
/// (`scripts/read_bandwidth.c`).
fn streamed(model: &Model, parts: usize) {
    use rayon::prelude::*;
    let (cons, loads) = support::cantilever(model);
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let asm = assemble_stiffness(model, &dofs).unwrap();
    let blocks = dofs.node_of_dof();
    let factors: Vec<Cholesky> = (0..parts)
        .map(|_| {
            let mut c = supernodal_factor(&asm.k, &blocks);
            assert!(c.store_single(&asm.k));
            c
        })
        .collect();
    let b = dofs.reduce(&loads.f);
    let n = b.len();
    let factor_bytes = 4.0 * factors[0].nnz_factor() as f64 * parts as f64;
    let matrix_bytes = 12.0 * asm.k.nnz() as f64 * parts as f64;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    println!();
    println!(
        "| parts | dofs each | f32 factors | matrices | threads | columns | one step, all parts ms | GB/s read |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for k in [1usize, 2] {
        let x0: Vec<f64> = (0..k)
            .flat_map(|j| b.iter().map(move |v| v * (1.0 + 0.1 * j as f64)))
            .collect();
        let mut exact = x0.clone();
        factors[0].solve_with(&mut exact, &mut factors[0].solve_scratch(k));
        let previous: Vec<f64> = exact.iter().map(|v| v * (1.0 + 1e-3)).collect();
        let columns: Vec<&[f64]> = previous.chunks_exact(n).collect();
        let mut xs: Vec<Vec<f64>> = vec![x0.clone(); parts];
        let mut scratch: Vec<_> = factors.iter().map(|f| f.solve_scratch(k)).collect();
        let t = pool.install(|| {
            best(5, || {
                xs.par_iter_mut()
                    .zip(&mut scratch)
                    .zip(&factors)
                    .for_each(|((x, s), f)| {
                        x.copy_from_slice(&x0);
                        f.solve_near(x, &columns, s);
                    })
            })
        });
        println!(
            "| {parts} | {n} | {:.2} GB | {:.2} GB | 2 | {k} | {:.1} | {:.1} |",
            factor_bytes / 1e9,
            matrix_bytes / 1e9,
            t * 1e3,
            (2.0 * factor_bytes + matrix_bytes) / t / 1e9
        );
    }
}
