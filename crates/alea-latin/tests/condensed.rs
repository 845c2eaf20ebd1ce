//! The interface-condensed linear stage (issue 41, `LinearStage::Condensed`) against volume
//! solves (`LinearStage::Volume`) on the same set-ups: the condensed iterates are the volume
//! ones up to the rounding of the dense product `W = w0 + H v` (module `solver::condensed`), so
//! every run must take the same number of iterations, end with the same status, and give the
//! same interface fields and displacements to round-off carried by the iteration (bounded here
//! by 1e-7 of the largest value, two orders below the stopping tolerance's effect): a perfect
//! interface and frictional contact, 2D and 3D, floating substructures (whose rigid motion the
//! condensed stage measures from interface values), Young's-modulus and load factors, and the
//! runs of a batch, bitwise those of the runs alone.

mod common;

use std::sync::Arc;

use alea_fem::{Constraints, Loads};
use alea_latin::samples::{four_part_dovetail, four_part_dovetail_options};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, LinearStage, RunInput, RunResult,
    RunStatus, constant,
};
use alea_mesh::CellType;
use common::*;

/// Largest difference of two runs' displacements and interface fields (`W`, `F`, `W_hat`,
/// `F_hat`), each relative to the largest value of its kind.
fn difference(a: &RunResult, b: &RunResult) -> [f64; 2] {
    let rel = |x: Vec<f64>, y: Vec<f64>| {
        let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300);
        x.iter()
            .zip(&y)
            .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
            / scale
    };
    let u = rel(
        a.displacements.iter().flatten().copied().collect(),
        b.displacements.iter().flatten().copied().collect(),
    );
    let fields = |r: &RunResult| -> Vec<f64> {
        let mut v = Vec::new();
        for i in &r.interfaces {
            for s in 0..2 {
                for arr in [&i.w[s], &i.f[s], &i.what[s], &i.fhat[s]] {
                    v.extend(arr.iter().flatten());
                }
            }
        }
        v
    };
    [u, rel(fields(a), fields(b))]
}

/// Solves `inputs` on the set-up with the volume and the condensed stage; checks that the
/// condensed one condenses `expect_condensed` substructures and that every run agrees.
fn compare(asm: Assembly, options: LatinOptions, inputs: &[RunInput], expect_condensed: usize) {
    let volume = LatinSolver::new(
        asm.clone(),
        LatinOptions {
            linear_stage: LinearStage::Volume,
            ..options.clone()
        },
    )
    .unwrap();
    let condensed = LatinSolver::new(
        asm,
        LatinOptions {
            linear_stage: LinearStage::Condensed,
            ..options
        },
    )
    .unwrap();
    assert!(volume.linear_stage_summary().iter().all(|s| !s.condensed));
    let summary = condensed.linear_stage_summary();
    assert_eq!(
        summary.iter().filter(|s| s.condensed).count(),
        expect_condensed,
        "{summary:?}"
    );
    for (k, input) in inputs.iter().enumerate() {
        let v = volume.run_shared(input).unwrap();
        let c = condensed.run_shared(input).unwrap();
        let [du, df] = difference(&v, &c);
        println!(
            "run {k}: {:?} after {} iterations (condensed {:?} after {}); displacements {du:.1e}, interface fields {df:.1e}",
            v.status, v.iterations, c.status, c.iterations
        );
        assert_eq!(v.status, RunStatus::Converged, "run {k}");
        assert_eq!(c.status, v.status, "run {k}");
        assert_eq!(c.iterations, v.iterations, "run {k}");
        assert!(du < 1e-7 && df < 1e-7, "run {k}: {du:e} {df:e}");
        let statuses: std::collections::BTreeSet<u8> = c
            .interfaces
            .iter()
            .flat_map(|i| i.status.iter().map(|s| s.code()))
            .collect();
        println!("  point statuses {statuses:?}");
        for (e, f) in v.equilibrium.iter().zip(&c.equilibrium) {
            assert!((e.relative_rigid_motion - f.relative_rigid_motion).abs() < 1e-9);
        }
    }
}

/// 2D: the four-part dovetail (two Coulomb flanks, two perfect cuts, a floating root, coarse
/// problem), runs with different friction and Young's-modulus factors.
#[test]
fn dovetail_2d_condensed_matches_volume() {
    let asm = four_part_dovetail(1).unwrap();
    let inputs: Vec<RunInput> = [(0.2, 0.9), (0.6, 1.05), (0.9, 1.1)]
        .iter()
        .map(|&(mu, ef)| RunInput {
            young_factors: vec![ef, ef, 1.0, 1.0],
            mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
            ..Default::default()
        })
        .collect();
    compare(asm, four_part_dovetail_options(), &inputs, 4);
}

/// 2D batches: the runs of a batch on the condensed stage are the runs alone, bit for bit
/// (each column of the dense product is summed in the same order), on 1 and 2 threads.
#[test]
fn condensed_batches_are_the_runs_alone() {
    let asm = four_part_dovetail(1).unwrap();
    let solver = LatinSolver::new(
        asm,
        LatinOptions {
            linear_stage: LinearStage::Condensed,
            ..four_part_dovetail_options()
        },
    )
    .unwrap();
    let inputs: Vec<RunInput> = [(0.2, 0.9), (0.4, 1.0), (0.9, 1.1)]
        .iter()
        .map(|&(mu, ef)| RunInput {
            young_factors: vec![ef, ef, 1.0, 1.0],
            mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
            ..Default::default()
        })
        .collect();
    let single: Vec<RunResult> = inputs
        .iter()
        .map(|i| solver.run_shared(i).unwrap())
        .collect();
    for threads in [1, 2] {
        let batch: Vec<RunResult> = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| solver.run_batch(&inputs))
            .into_iter()
            .map(Result::unwrap)
            .collect();
        for (b, s) in batch.iter().zip(&single) {
            assert_eq!(b.residuals, s.residuals);
            assert_eq!(b.displacements, s.displacements);
            assert_eq!(b.equilibrium, s.equilibrium);
        }
    }
}

/// A 3D block `[0, 1] x [0, 1] x [z0, z0 + 1/2]` of Hex8 cells.
fn block(name: &str, z0: f64, n: usize) -> alea_latin::Substructure {
    let m = solid(
        cuboid(
            [0.0, 0.0, z0],
            [1.0, 1.0, 0.5],
            [n, n, n.div_ceil(2)],
            CellType::Hex8,
        ),
        210e3,
        0.3,
    );
    sub(name, m, Constraints::new())
}

/// 3D: a block on a clamped block, pressed and sheared on its top (two load cases), through a
/// perfect interface and through Coulomb contact (the upper block floats: its rigid motion is
/// checked from interface values).
#[test]
fn blocks_3d_condensed_matches_volume() {
    let n = 4;
    let lower = {
        let mut s = block("lower", -0.5, n);
        s.constraints.clamp(&s.model.mesh, "zmin").unwrap();
        s
    };
    let upper = {
        let s = block("upper", 0.0, n);
        let s = with_load(s, |m, l: &mut Loads| {
            l.traction(m, "zmax", |_, _| [0.0, 0.0, -100.0]).unwrap();
        });
        with_load(s, |m, l: &mut Loads| {
            l.traction(m, "zmax", |x, _| [20.0, 10.0 * x[1], 0.0])
                .unwrap();
        })
    };
    let options = LatinOptions {
        tolerance: 1e-7,
        max_iterations: 5000,
        ..Default::default()
    };
    let inputs: Vec<RunInput> = [(1.0, 0.5), (1.0, 1.0), (0.8, 1.1)]
        .iter()
        .map(|&(ef, shear)| RunInput {
            young_factors: vec![1.0, ef],
            load_factors: vec![vec![], vec![1.0, shear]],
            ..Default::default()
        })
        .collect();
    let perfect = InterfaceSpec::perfect("glue", 0, "zmax", 1, "zmin");
    compare(
        Assembly {
            subs: vec![lower.clone(), upper.clone()],
            interfaces: vec![perfect],
        },
        options.clone(),
        &inputs,
        2,
    );
    let mut contact = InterfaceSpec::coulomb("contact", 0, "zmax", 1, "zmin", 0.3);
    contact.gap = Arc::new(|x: [f64; 3]| 1e-5 * ((x[0] - 0.5).powi(2) + (x[1] - 0.5).powi(2)));
    compare(
        Assembly {
            subs: vec![lower, upper],
            interfaces: vec![contact],
        },
        options,
        &inputs,
        2,
    );
}

/// Runs whose modulus varies from cell to cell: the changed substructure is solved by volume
/// solves on its own operator, the others stay condensed; the run agrees with the volume one.
#[test]
fn cell_young_runs_keep_the_volume_path_where_the_operator_changes() {
    let asm = four_part_dovetail(1).unwrap();
    let cells = asm.subs[2].model.mesh.num_cells();
    let factors: Vec<f64> = (0..cells)
        .map(|c| 0.8 + 0.4 * (c % 7) as f64 / 6.0)
        .collect();
    let input = RunInput {
        cell_young: vec![None, None, Some(Arc::new(factors)), None],
        ..Default::default()
    };
    let solver = |stage| {
        LatinSolver::new(
            asm.clone(),
            LatinOptions {
                linear_stage: stage,
                ..four_part_dovetail_options()
            },
        )
        .unwrap()
    };
    let condensed = solver(LinearStage::Condensed);
    let derived = condensed.with_cell_young(&input.cell_young).unwrap();
    let flags: Vec<bool> = derived
        .linear_stage_summary()
        .iter()
        .map(|s| s.condensed)
        .collect();
    assert_eq!(flags, [true, true, false, true]);
    let v = solver(LinearStage::Volume).run_shared(&input).unwrap();
    let c = condensed.run_shared(&input).unwrap();
    let [du, df] = difference(&v, &c);
    assert_eq!(v.status, RunStatus::Converged);
    assert_eq!((c.status, c.iterations), (v.status, v.iterations));
    assert!(du < 1e-7 && df < 1e-7, "{du:e} {df:e}");
}
