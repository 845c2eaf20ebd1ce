//! Factors stored in single precision (`LatinOptions::factor_precision`, module `precision` of
//! the solver): each linear stage makes one refinement step from the previous iterate, the
//! set-up and the final recovery refine to full accuracy. The converged answer must be the
//! double-precision one: measured against the TRUE answer (the same model at tolerance 1e-11
//! in double precision), the error of a single-precision run at the study tolerance 1e-6 is
//! that of the double-precision run at the same tolerance (at most 2x, plus 1e-9), in about the
//! same number of iterations (at most 10 % + 2 more).
//!
//! ```text
//!        traction (25, 10, -100) MPa on top
//!          +-----------+
//!          |   block   |      E = 70 000 MPa, floating (held by the contact only)
//!    +-----+-----------+-----+   Coulomb contact, mu = 0.3 (partial slip), mortar
//!    |          base         |   E = 200 000 MPa
//!    +-----------------------+
//!          clamped
//! ```
//!
//! Three configurations: volume solves of the two bodies, volume solves of the bodies cut into
//! 8 subdomains (perfect interfaces inside each body), and condensed linear stages (the
//! factor then serves the set-up's solves and the recovery only). Two runs solved together
//! (load factors 1 and 0.6), so that the multi-column refinement is exercised.

mod common;

use alea_latin::{
    FactorPrecision, LatinOptions, LatinSolver, LinearStage, RunInput, RunResult, RunStatus,
    Subdomains,
};
use common::press_and_shear;

fn inputs() -> Vec<RunInput> {
    [1.0, 0.6]
        .into_iter()
        .map(|l| RunInput {
            load_factors: vec![vec![], vec![l]],
            ..RunInput::default()
        })
        .collect()
}

fn solve(options: LatinOptions) -> (Vec<RunResult>, Vec<bool>) {
    let solver = LatinSolver::new(press_and_shear(3, false), options).unwrap();
    let single = solver
        .linear_stage_summary()
        .iter()
        .map(|s| s.single_precision)
        .collect();
    let results = solver
        .run_batch(&inputs())
        .into_iter()
        .map(|r| {
            let r = r.unwrap();
            assert_eq!(r.status, RunStatus::Converged);
            r
        })
        .collect();
    (results, single)
}

/// Largest relative error, over the runs, of the displacements of both bodies and of the
/// contact tractions.
fn error(runs: &[RunResult], reference: &[RunResult]) -> f64 {
    let rel = |a: &[f64], b: &[f64]| {
        let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
        let den: f64 = b.iter().map(|y| y * y).sum();
        (num / den).sqrt()
    };
    let flat = |v: &[[f64; 3]]| v.iter().flatten().copied().collect::<Vec<_>>();
    let mut worst = 0.0f64;
    for (r, t) in runs.iter().zip(reference) {
        for s in 0..2 {
            worst = worst.max(rel(&r.displacements[s], &t.displacements[s]));
        }
        let (a, b) = (&r.interfaces[0], &t.interfaces[0]);
        worst = worst.max(rel(&flat(&a.fhat[0]), &flat(&b.fhat[0])));
    }
    worst
}

#[test]
fn single_precision_factors_give_the_double_precision_answer() {
    let configurations: [(&str, LinearStage, Subdomains); 3] = [
        ("volume", LinearStage::Volume, Subdomains::Never),
        (
            "volume, 8 subdomains",
            LinearStage::Volume,
            Subdomains::Always,
        ),
        ("condensed", LinearStage::Condensed, Subdomains::Never),
    ];
    for (name, linear_stage, subdomains) in configurations {
        let options = |precision, tolerance| LatinOptions {
            tolerance,
            max_iterations: 4000,
            linear_stage,
            subdomains,
            subdomain_dofs: 150,
            factor_precision: precision,
            ..LatinOptions::default()
        };
        let (truth, _) = solve(options(FactorPrecision::Double, 1e-11));
        let (double, stored) = solve(options(FactorPrecision::Double, 1e-6));
        assert!(stored.iter().all(|s| !s), "{name}: {stored:?}");
        let (single, stored) = solve(options(FactorPrecision::Single, 1e-6));
        assert!(stored.iter().all(|s| *s), "{name}: {stored:?}");
        // The default keeps these small factors (< 1e6 entries) in double precision.
        let (_, stored) = solve(options(FactorPrecision::Auto, 1e-6));
        assert!(stored.iter().all(|s| !s), "{name}: {stored:?}");

        let (e_double, e_single) = (error(&double, &truth), error(&single, &truth));
        let iterations = |r: &[RunResult]| r.iter().map(|r| r.iterations).collect::<Vec<_>>();
        eprintln!(
            "{name}: true error double {e_double:.2e}, single {e_single:.2e}; iterations {:?} / {:?}",
            iterations(&double),
            iterations(&single)
        );
        assert!(
            e_single <= 2.0 * e_double + 1e-9,
            "{name}: {e_single:e} against {e_double:e}"
        );
        assert!(e_double < 1e-4, "{name}: {e_double:e}");
        for (d, s) in double.iter().zip(&single) {
            assert!(
                s.iterations as f64 <= 1.1 * d.iterations as f64 + 2.0,
                "{name}: {} against {} iterations",
                s.iterations,
                d.iterations
            );
        }
    }
}
