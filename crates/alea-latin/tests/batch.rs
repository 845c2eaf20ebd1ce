//! Batched runs (`LatinSolver::run_batch`, issue 20 item 1) against the same runs one at a time
//! on the four-part dovetail (two Coulomb flanks, two perfect cuts, coarse problem, tolerance
//! 1e-6): a batch of one is bitwise the single run; in a batch of four (different friction
//! coefficients and Young's-modulus factors, so the runs converge at different iterations and
//! leave the batch one by one) every run converges, with the single run's iteration count to
//! within a few iterations and its displacements to within 1e-4 of their largest value (two
//! solutions both within the stopping tolerance 1e-6 of the indicator, differing by the
//! rounding of the multi-column solves that the iteration carries along, none with this
//! model's simplicial factors: there the batched runs are the single ones bit for bit); and the
//! batch gives the same bits on 1 and 2 threads.

use alea_latin::samples::{four_part_dovetail, four_part_dovetail_options};
use alea_latin::{LatinSolver, RunInput, RunResult, RunStatus, constant};

fn input(mu: f64, ef: f64) -> RunInput {
    RunInput {
        young_factors: vec![ef, ef, 1.0, 1.0],
        mu: vec![Some(constant(mu)), Some(constant(mu)), None, None],
        ..Default::default()
    }
}

fn max_abs(r: &RunResult) -> f64 {
    r.displacements
        .iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(v.abs()))
}

fn max_diff(a: &RunResult, b: &RunResult) -> f64 {
    a.displacements
        .iter()
        .flatten()
        .zip(b.displacements.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn batched_runs_match_single_runs() {
    let asm = four_part_dovetail(2).unwrap();
    let solver = LatinSolver::new(asm, four_part_dovetail_options()).unwrap();
    let points = [(0.2, 0.9), (0.4, 1.0), (0.6, 1.05), (0.9, 1.1)];
    // This 2D model's factors are simplicial (`alea_fem::FactorKind::Auto`).
    let simplicial = (0..solver.num_subs()).all(|s| !solver.factor_summary(s).2);
    assert!(simplicial);
    let single: Vec<RunResult> = points
        .iter()
        .map(|&(mu, ef)| solver.run_shared(&input(mu, ef)).unwrap())
        .collect();
    // A batch of one: the single run, bit for bit.
    let one = solver.run_batch(&[input(0.4, 1.0)]);
    let one = one[0].as_ref().unwrap();
    assert_eq!(one.residuals, single[1].residuals);
    assert_eq!(one.displacements, single[1].displacements);
    // A batch of four on 1 and 2 threads.
    let inputs: Vec<RunInput> = points.iter().map(|&(mu, ef)| input(mu, ef)).collect();
    let on = |threads: usize| -> Vec<RunResult> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                solver
                    .run_batch(&inputs)
                    .into_iter()
                    .map(|r| r.unwrap())
                    .collect()
            })
    };
    let batch = on(1);
    let batch2 = on(2);
    let mut distinct = std::collections::BTreeSet::new();
    for (k, (b, s)) in batch.iter().zip(&single).enumerate() {
        assert_eq!(b.status, RunStatus::Converged, "run {k}");
        assert_eq!(s.status, RunStatus::Converged, "run {k}");
        let rel = max_diff(b, s) / max_abs(s);
        println!(
            "run {k}: iterations single {} batch {}, displacement difference {rel:.2e} of the largest",
            s.iterations, b.iterations
        );
        assert!(b.iterations.abs_diff(s.iterations) <= 5, "run {k}");
        assert!(rel < 1e-4, "run {k}: {rel:e}");
        assert_eq!(b.displacements, batch2[k].displacements, "run {k}: threads");
        assert_eq!(b.residuals, batch2[k].residuals, "run {k}: threads");
        if simplicial {
            // Simplicial factors: the multi-column solve is the single ones, bit for bit.
            assert_eq!(b.residuals, s.residuals, "run {k}");
            assert_eq!(b.displacements, s.displacements, "run {k}");
        }
        distinct.insert(b.iterations);
    }
    assert!(
        distinct.len() >= 2,
        "the runs must leave the batch at different iterations"
    );
}
