//! Designs: Latin hypercube stratification (also maximin, which must not lower the minimal
//! distance), Sobol' through a law, tensor grids, corners + centre, Monte Carlo reproducibility.

use alea_uq::design::{
    Design, corners_and_centre, latin_hypercube, latin_hypercube_maximin, monte_carlo, sobol,
    tensor_grid,
};
use alea_uq::joint::{Independent, JointLaw};
use alea_uq::law::{Marginal, Normal, Uniform};
use std::sync::Arc;

fn law() -> Independent {
    Independent::new(vec![
        Arc::new(Uniform::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>,
        Arc::new(Normal::new(5.0, 2.0).unwrap()),
        Arc::new(Uniform::new(-1.0, 1.0).unwrap()),
    ])
    .unwrap()
}

fn strata_hit_once(law: &Independent, d: &Design) {
    let n = d.len();
    for j in 0..3 {
        let mut hit = vec![0; n];
        for x in d.iter() {
            let mut u = [0.0; 3];
            law.x_to_unit(x, &mut u);
            hit[((u[j] * n as f64) as usize).min(n - 1)] += 1;
        }
        assert!(hit.iter().all(|&h| h == 1), "direction {j}");
    }
}

fn min_dist(law: &Independent, d: &Design) -> f64 {
    let u: Vec<[f64; 3]> = d
        .iter()
        .map(|x| {
            let mut u = [0.0; 3];
            law.x_to_unit(x, &mut u);
            u
        })
        .collect();
    let mut m = f64::INFINITY;
    for i in 0..u.len() {
        for k in 0..i {
            m = m.min((0..3).map(|j| (u[i][j] - u[k][j]).powi(2)).sum::<f64>());
        }
    }
    m
}

#[test]
fn latin_hypercube_is_stratified() {
    let law = law();
    let d = latin_hypercube(&law, 37, 5);
    strata_hit_once(&law, &d);
    let dm = latin_hypercube_maximin(&law, 37, 5, 20);
    strata_hit_once(&law, &dm);
    // Candidate 0 of the maximin search is the plain LHS with the same seed.
    assert!(min_dist(&law, &dm) >= min_dist(&law, &d));
}

#[test]
fn sobol_design_has_low_discrepancy_mean() {
    let law = law();
    let d = sobol(&law, 1024, Some(3)).unwrap();
    let m1 = d.iter().map(|x| x[1]).sum::<f64>() / 1024.0;
    // QMC error of the mean of N(5, 2^2) is far below the MC standard error 2/32 = 0.0625.
    assert!((m1 - 5.0).abs() < 0.01, "{m1}");
    assert!(
        sobol(&law, 10, None)
            .unwrap()
            .iter()
            .all(|x| x.iter().all(|v| v.is_finite()))
    );
}

#[test]
fn grids_and_corners() {
    let g = tensor_grid(&[0.0, 10.0], &[1.0, 20.0], &[3, 2]).unwrap();
    assert_eq!(g.len(), 6);
    assert_eq!(g.point(0), &[0.0, 10.0]);
    assert_eq!(g.point(1), &[0.0, 20.0]);
    assert_eq!(g.point(5), &[1.0, 20.0]);
    let c = corners_and_centre(&[0.0, 0.0, 0.0], &[1.0, 2.0, 3.0]).unwrap();
    assert_eq!(c.len(), 9);
    assert_eq!(c.point(8), &[0.5, 1.0, 1.5]);
    assert!(tensor_grid(&[0.0], &[1.0], &[0]).is_err());
    assert!(tensor_grid(&[0.0], &[1.0, 2.0], &[2]).is_err());
}

#[test]
fn monte_carlo_is_reproducible_and_seed_dependent() {
    let law = law();
    let a = monte_carlo(&law, 10_000, 1);
    let b = monte_carlo(&law, 10_000, 1);
    let c = monte_carlo(&law, 10_000, 2);
    assert_eq!(a, b);
    assert_ne!(a, c);
    // A prefix of a longer run is the shorter run (chunks are fixed).
    let long = monte_carlo(&law, 20_000, 1);
    assert_eq!(&long.points()[..30_000], a.points());
}
