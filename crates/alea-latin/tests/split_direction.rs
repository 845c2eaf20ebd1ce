//! The split search direction (`SearchDirection::Split`: `k_n` along the normal of contact
//! points, `k_t = ratio k_n` across it) changes the iteration, not its fixed point: on the
//! four-part dovetail (two Coulomb flanks, two perfect cuts, coarse problem, Anderson depth 5)
//! solved to 1e-10, runs with Young's-modulus factors and friction coefficients away from the
//! set-up's give the isotropic direction's displacements and contact statuses; a batch of
//! split runs is the same runs one at a time bit for bit (simplicial factors) and the same on
//! 1 and 2 threads; a ratio <= 0 is refused.

use alea_latin::samples::{four_part_dovetail, four_part_dovetail_options};
use alea_latin::{LatinOptions, LatinSolver, RunInput, RunResult, RunStatus, SearchDirection};

fn input(mu: f64, ef: f64) -> RunInput {
    RunInput {
        young_factors: vec![ef, ef, 1.0, 1.0],
        mu: vec![
            Some(alea_latin::constant(mu)),
            Some(alea_latin::constant(mu)),
            None,
            None,
        ],
        ..Default::default()
    }
}

fn options(search_direction: SearchDirection) -> LatinOptions {
    LatinOptions {
        tolerance: 1e-10,
        search_direction,
        ..four_part_dovetail_options()
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
fn split_direction_has_the_isotropic_fixed_point() {
    let iso = LatinSolver::new(
        four_part_dovetail(0).unwrap(),
        options(SearchDirection::Auto { factor: 3.0 }),
    )
    .unwrap();
    let split = LatinSolver::new(
        four_part_dovetail(0).unwrap(),
        options(SearchDirection::Split {
            factor: 3.0,
            tangential: 0.25,
        }),
    )
    .unwrap();
    for (mu, ef) in [(0.5, 1.0), (0.2, 1.3), (0.8, 0.7)] {
        let a = iso.run_shared(&input(mu, ef)).unwrap();
        let b = split.run_shared(&input(mu, ef)).unwrap();
        assert_eq!(a.status, RunStatus::Converged);
        assert_eq!(b.status, RunStatus::Converged);
        let rel = max_diff(&a, &b) / max_abs(&a);
        println!(
            "mu {mu}, E factor {ef}: iterations isotropic {} split {}, displacement difference {rel:.2e}",
            a.iterations, b.iterations
        );
        assert!(rel < 1e-6, "{rel}");
        for (ia, ib) in a.interfaces.iter().zip(&b.interfaces) {
            let (sa, sb) = (ia.status_counts(), ib.status_counts());
            // Statuses may differ only at points on the edge between two branches.
            for k in 0..4 {
                assert!(sa[k].abs_diff(sb[k]) <= 1, "{}: {sa:?} {sb:?}", ia.name);
            }
        }
    }
    // Batched split runs: the runs alone, bit for bit, on 1 and 2 threads.
    let inputs = [input(0.2, 1.3), input(0.8, 0.7)];
    let single: Vec<RunResult> = inputs
        .iter()
        .map(|i| split.run_shared(i).unwrap())
        .collect();
    for threads in [1, 2] {
        let batch: Vec<RunResult> = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| split.run_batch(&inputs))
            .into_iter()
            .map(|r| r.unwrap())
            .collect();
        for (b, s) in batch.iter().zip(&single) {
            assert_eq!(b.residuals, s.residuals);
            assert_eq!(b.displacements, s.displacements);
        }
    }
}

#[test]
fn a_tangential_ratio_that_is_not_positive_is_refused() {
    for tangential in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let r = LatinSolver::new(
            four_part_dovetail(0).unwrap(),
            options(SearchDirection::Split {
                factor: 3.0,
                tangential,
            }),
        );
        assert!(r.is_err(), "{tangential}");
    }
}
