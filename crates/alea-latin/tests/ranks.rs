//! One run spread over ranks (module `alea_latin::ranks`, [`LatinSolver::with_ranks`]): ranks
//! simulated by threads ([`ThreadExchange`]), each factorising only the substructures it owns,
//! give **bitwise** the results of the one-process solver at 1, 2 and 4 ranks - displacements,
//! interface fields of both stages, contact status, residual history, equilibrium checks - on a
//! frictional contact between two bodies cut into 5 substructures by METIS (`Split`; 2D node to
//! node, 3D mortar; the block's parts float and are held by the contact alone), for a batch of
//! runs with different moduli and loads, a warm-started run, a run whose modulus varies from
//! cell to cell, and the condensed linear stage.
//!
//! ```text
//!        traction on top
//!          +-----------+
//!          |   block   |      block cut in 2 parts
//!    +-----+-----------+-----+   Coulomb contact, mu = 0.3 (partial slip)
//!    |          base         |   base cut in 3 parts
//!    +-----------------------+
//!          clamped
//! ```

mod common;

use std::sync::Arc;
use std::time::Duration;

use alea_latin::split::Split;
use alea_latin::{
    Assembly, LatinOptions, LatinSolver, LinearStage, RankExchange, RunInput, RunResult, RunStatus,
    ThreadExchange,
};

fn options(linear_stage: LinearStage) -> LatinOptions {
    LatinOptions {
        tolerance: 1e-8,
        max_iterations: 4000,
        linear_stage,
        ..Default::default()
    }
}

/// `options` with every substructure cut into subdomains of about 150 unknowns by the solver
/// itself (`LatinOptions::subdomains`).
fn cut_options(linear_stage: LinearStage) -> LatinOptions {
    LatinOptions {
        subdomains: alea_latin::Subdomains::Always,
        subdomain_dofs: 150,
        ..options(linear_stage)
    }
}

/// The two bodies in contact of `tests/split.rs`, cut into 3 + 2 substructures when `cut`
/// (then paired by mortar: the contact's pieces do not match node to node), else paired node
/// to node in 2D.
fn press_and_shear(dim: usize, cut: bool) -> Assembly {
    let asm = common::press_and_shear(dim, cut);
    match cut {
        true => Split::new(&asm, &[3, 2]).unwrap().inner,
        false => asm,
    }
}

/// The runs: a batch of two (moduli and loads changed), a run warm-started from the first's
/// end, and a run whose block parts' moduli vary from cell to cell.
fn inputs(asm: &Assembly, first: Option<&RunResult>) -> Vec<RunInput> {
    let n = asm.subs.len();
    let loads: Vec<Vec<f64>> = asm
        .subs
        .iter()
        .map(|s| vec![1.3; s.load_cases.len()])
        .collect();
    let mut out = vec![
        RunInput::default(),
        RunInput {
            young_factors: (0..n).map(|s| 1.0 + 0.2 * s as f64).collect(),
            load_factors: loads,
            ..RunInput::default()
        },
    ];
    if let Some(r) = first {
        out.push(RunInput {
            initial: Some(Arc::new(r.end_state())),
            young_factors: vec![1.05; n],
            ..RunInput::default()
        });
        out.push(RunInput {
            cell_young: asm
                .subs
                .iter()
                .map(|s| {
                    let cells = s.model.mesh.num_cells();
                    Some(Arc::new(
                        (0..cells).map(|c| 0.8 + 0.4 * (c % 3) as f64).collect(),
                    ))
                })
                .collect(),
            ..RunInput::default()
        });
    }
    out
}

/// Every run: the batch of the first two, then the others one by one.
fn solve_all(solver: &LatinSolver, asm: &Assembly) -> Vec<RunResult> {
    let mut out: Vec<RunResult> = solver
        .run_batch(&inputs(asm, None))
        .into_iter()
        .map(Result::unwrap)
        .collect();
    for input in inputs(asm, Some(&out[0])).into_iter().skip(2) {
        out.push(solver.run_shared(&input).unwrap());
    }
    out
}

fn bits(v: impl IntoIterator<Item = f64>) -> Vec<u64> {
    v.into_iter().map(f64::to_bits).collect()
}

/// The same bits in every quantity a run reports (timings aside).
fn assert_identical(a: &RunResult, b: &RunResult, what: &str) {
    assert_eq!(a.status, b.status, "{what}");
    assert_eq!(a.iterations, b.iterations, "{what}");
    assert_eq!(
        bits(a.residuals.iter().copied()),
        bits(b.residuals.iter().copied()),
        "{what}"
    );
    assert_eq!(a.displacements.len(), b.displacements.len());
    for (s, (x, y)) in a.displacements.iter().zip(&b.displacements).enumerate() {
        assert!(
            !x.is_empty(),
            "{what}: substructure {s} has no displacement"
        );
        assert_eq!(
            bits(x.iter().copied()),
            bits(y.iter().copied()),
            "{what}: u of {s}"
        );
    }
    for (i, (x, y)) in a.interfaces.iter().zip(&b.interfaces).enumerate() {
        for (f, g) in [
            (&x.w, &y.w),
            (&x.f, &y.f),
            (&x.what, &y.what),
            (&x.fhat, &y.fhat),
            (&x.what_prev, &y.what_prev),
        ] {
            for side in 0..2 {
                assert_eq!(
                    bits(f[side].iter().flatten().copied()),
                    bits(g[side].iter().flatten().copied()),
                    "{what}: interface {i}"
                );
            }
        }
        assert_eq!(x.status, y.status, "{what}: interface {i}");
    }
    assert_eq!(a.equilibrium, b.equilibrium, "{what}");
}

fn compare(dim: usize, cut: bool, stage: LinearStage) {
    compare_with(dim, cut, stage, options);
}

fn compare_with(
    dim: usize,
    cut: bool,
    stage: LinearStage,
    options: fn(LinearStage) -> LatinOptions,
) {
    let asm = press_and_shear(dim, cut);
    let single = LatinSolver::new(asm.clone(), options(stage)).unwrap();
    let reference = solve_all(&single, &asm);
    assert!(
        reference.iter().all(|r| r.status == RunStatus::Converged),
        "{:?}",
        reference.iter().map(|r| r.status).collect::<Vec<_>>()
    );
    let slipping = reference[0]
        .interfaces
        .iter()
        .any(|i| i.status.contains(&alea_latin::PointStatus::Slip));
    assert!(slipping, "the case has slip");
    let nsub = single.num_solved_subs();
    let total: usize = (0..nsub).map(|s| single.factor_summary(s).1).sum();
    let summary = single.linear_stage_summary();
    for np in [1, 2, 4] {
        let group = ThreadExchange::group_with_timeout(np, Some(Duration::from_secs(60)));
        let per_rank: Vec<(Vec<RunResult>, Vec<bool>, Vec<usize>)> = std::thread::scope(|sc| {
            let handles: Vec<_> = group
                .iter()
                .map(|ex| {
                    let asm = asm.clone();
                    let ex: Arc<dyn RankExchange> = ex.clone();
                    let summary = &summary;
                    sc.spawn(move || {
                        let solver =
                            LatinSolver::with_ranks(asm.clone(), options(stage), ex).unwrap();
                        assert_eq!(&solver.linear_stage_summary(), summary);
                        let held = (0..nsub).map(|s| solver.holds_factor(s)).collect();
                        (solve_all(&solver, &asm), held, solver.substructure_owners())
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let owners = &per_rank[0].2;
        let mut held_entries = vec![0; np];
        for (rank, (results, held, own)) in per_rank.iter().enumerate() {
            assert_eq!(own, owners, "the same owners on every rank");
            for s in 0..nsub {
                assert_eq!(held[s], owners[s] == rank, "{np} ranks: factor of {s}");
                if held[s] {
                    held_entries[rank] += single.factor_summary(s).1;
                }
            }
            for (k, (r, x)) in results.iter().zip(&reference).enumerate() {
                assert_identical(r, x, &format!("{dim}D, {np} ranks, rank {rank}, run {k}"));
            }
        }
        // Every factor entry held once, and by one rank only: the memory per rank falls.
        assert_eq!(held_entries.iter().sum::<usize>(), total);
        if np > 1 {
            assert!(held_entries.iter().all(|&e| e < total), "{held_entries:?}");
            let busy = held_entries.iter().filter(|&&e| e > 0).count();
            assert_eq!(busy, np.min(nsub), "{held_entries:?}");
        }
        eprintln!(
            "{dim}D {stage:?}, {np} ranks: factor entries per rank {held_entries:?} of {total}"
        );
    }
}

#[test]
fn runs_over_ranks_are_bitwise_the_single_process_runs_in_2d() {
    compare(2, true, LinearStage::Volume);
}

#[test]
fn runs_over_ranks_are_bitwise_the_single_process_runs_in_3d() {
    compare(3, true, LinearStage::Volume);
}

#[test]
fn condensed_runs_over_ranks_are_bitwise_the_single_process_runs() {
    compare(2, true, LinearStage::Condensed);
}

/// Two substructures paired node to node on 4 ranks: two ranks own nothing and still take
/// part in every exchange.
#[test]
fn ranks_without_substructures_follow_the_run() {
    compare(2, false, LinearStage::Auto);
}

/// The solver cuts the model into subdomains by itself and spreads them over the ranks: the
/// runs are bitwise the single process's, each rank holding the factors of its subdomains.
#[test]
fn subdomains_cut_by_the_solver_are_spread_over_ranks() {
    let single = LatinSolver::new(press_and_shear(3, false), cut_options(LinearStage::Volume));
    assert!(single.unwrap().num_solved_subs() >= 6);
    compare_with(3, false, LinearStage::Volume, cut_options);
}
