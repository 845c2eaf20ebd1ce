//! Analysis verification: KDE integrates to one and converges to the true density (Silverman
//! and ISJ), failure probability of a known law inside its confidence interval, Monte Carlo
//! Sobol' indices of Ishigami, summary statistics against exact moments, and reproducibility of
//! every seeded routine with 1 and 2 rayon threads.

use alea_uq::design::{latin_hypercube_maximin, monte_carlo, sobol};
use alea_uq::joint::{GaussianCopula, Independent};
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::law::{Marginal, Normal, Uniform};
use alea_uq::samples::Ishigami;
use alea_uq::sobol::sobol_indices;
use alea_uq::special::{norm_pdf, norm_sf};
use alea_uq::stats::{Summary, failure_probability, quantile, sample_model};
use std::f64::consts::PI;
use std::sync::Arc;

fn normal_law() -> Independent {
    Independent::new(vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>
    ])
    .unwrap()
}

fn normal_sample(n: usize, seed: u64) -> Vec<f64> {
    sample_model(&normal_law(), n, seed, |x| x[0])
}

/// Integral of the KDE by the trapezoidal rule on [-8, 8] and its L2 distance to phi.
fn kde_mass_and_l2(k: &Kde) -> (f64, f64) {
    let n = 4001;
    let xs: Vec<f64> = (0..n)
        .map(|i| -8.0 + 16.0 * i as f64 / (n - 1) as f64)
        .collect();
    let f = k.eval(&xs);
    let h = 16.0 / (n - 1) as f64;
    let mass = h * (f.iter().sum::<f64>() - 0.5 * (f[0] + f[n - 1]));
    let l2 = (h * xs
        .iter()
        .zip(&f)
        .map(|(x, v)| (v - norm_pdf(*x)).powi(2))
        .sum::<f64>())
    .sqrt();
    (mass, l2)
}

#[test]
fn kde_integrates_to_one_and_converges() {
    let mut last = (f64::INFINITY, f64::INFINITY);
    for &n in &[1_000, 10_000, 100_000] {
        let x = normal_sample(n, 42);
        let ks = Kde::new(&x, Bandwidth::Silverman).unwrap();
        let ki = Kde::new(&x, Bandwidth::Isj).unwrap();
        let (ms, ls) = kde_mass_and_l2(&ks);
        let (mi, li) = kde_mass_and_l2(&ki);
        eprintln!(
            "n {n}: Silverman h {:.4} L2 {ls:.2e}; ISJ h {:.4} L2 {li:.2e}",
            ks.bandwidth(),
            ki.bandwidth()
        );
        assert!(
            (ms - 1.0).abs() < 1e-9 && (mi - 1.0).abs() < 1e-9,
            "{ms} {mi}"
        );
        assert!(ls < last.0 && li < last.1, "no convergence at n = {n}");
        // For normal data both rules approach the AMISE-optimal 1.06 sigma n^-1/5.
        let h_opt = (4.0f64 / 3.0).powf(0.2) * (n as f64).powf(-0.2);
        assert!((ks.bandwidth() / h_opt - 0.9 / 1.06).abs() < 0.05);
        assert!(
            (ki.bandwidth() / h_opt - 1.0).abs() < 0.15,
            "ISJ h {}",
            ki.bandwidth()
        );
        assert!(ki.bandwidth() != ks.bandwidth()); // ISJ found its own root
        last = (ls, li);
    }
    assert!(last.0 < 5e-3 && last.1 < 5e-3);
}

#[test]
fn isj_beats_silverman_on_bimodal_data() {
    // 0.5 N(-3, 0.5^2) + 0.5 N(3, 0.5^2): Silverman's rule oversmooths (it sees sigma ~ 3).
    let x = normal_sample(20_000, 11);
    let y: Vec<f64> = x
        .iter()
        .enumerate()
        .map(|(i, v)| {
            if i % 2 == 0 {
                -3.0 + 0.5 * v
            } else {
                3.0 + 0.5 * v
            }
        })
        .collect();
    let pdf = |t: f64| 0.5 * (norm_pdf((t + 3.0) / 0.5) + norm_pdf((t - 3.0) / 0.5)) / 0.5;
    let pts: Vec<f64> = (0..801).map(|i| -6.0 + 12.0 * i as f64 / 800.0).collect();
    let err = |k: &Kde| {
        let f = k.eval(&pts);
        (pts.iter()
            .zip(&f)
            .map(|(t, v)| (v - pdf(*t)).powi(2))
            .sum::<f64>()
            * 0.015)
            .sqrt()
    };
    let es = err(&Kde::new(&y, Bandwidth::Silverman).unwrap());
    let ei = err(&Kde::new(&y, Bandwidth::Isj).unwrap());
    eprintln!("bimodal L2: Silverman {es:.3e}, ISJ {ei:.3e}");
    assert!(ei < 0.5 * es, "ISJ {ei} vs Silverman {es}");
}

#[test]
fn kde_binned_matches_direct() {
    let x = normal_sample(50_000, 7);
    let k = Kde::new(&x, Bandwidth::Silverman).unwrap();
    let pts: Vec<f64> = (0..64).map(|i| -4.0 + 8.0 * i as f64 / 63.0).collect();
    let a = k.eval(&pts);
    let b = k.eval_binned(&pts);
    for (u, v) in a.iter().zip(&b) {
        assert!((u - v).abs() < 1e-4 * 0.4, "{u} {v}");
    }
}

#[test]
fn failure_probability_of_known_law_within_ci() {
    // q ~ N(0, 1): P(q > 2) = 0.0227501319...
    let exact = norm_sf(2.0);
    assert!((exact - 0.022_750_131_948_179_2).abs() < 1e-15);
    let mut inside = 0;
    for seed in 0..20 {
        let q = normal_sample(20_000, seed);
        let fp = failure_probability(&q, 2.0, 0.95);
        assert!(fp.lower < fp.p && fp.p < fp.upper);
        if fp.lower <= exact && exact <= fp.upper {
            inside += 1;
        }
    }
    // 95 % intervals: P(fewer than 15 of 20 cover) = 0.3 %.
    assert!(inside >= 15, "coverage {inside}/20");
    // No failure observed: the interval is still informative.
    let q = normal_sample(1000, 1);
    let fp = failure_probability(&q, 10.0, 0.95);
    assert_eq!(fp.failures, 0);
    assert!(fp.upper > 0.0 && fp.upper < 0.01);
    // Exactly 0 (not a rounding residue); Wilson upper bound for zero failures is
    // z^2 / (N + z^2).
    assert_eq!(fp.lower, 0.0);
    let z2 = 1.959_963_984_540_054f64.powi(2);
    assert!((fp.upper - z2 / (1000.0 + z2)).abs() < 1e-15);
    let all = failure_probability(&q, -10.0, 0.95);
    assert_eq!((all.upper, all.failures), (1.0, 1000));
    assert!((all.lower - 1000.0 / (1000.0 + z2)).abs() < 1e-15);
}

#[test]
fn summary_statistics_match_exact_moments() {
    // Uniform(0, 1): mean 1/2, variance 1/12, skewness 0, excess kurtosis -6/5.
    let law = Independent::new(vec![
        Arc::new(Uniform::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>
    ])
    .unwrap();
    let x = sample_model(&law, 400_000, 3, |x| x[0]);
    let s = Summary::of(&x);
    assert!((s.mean - 0.5).abs() < 4.5 * s.mean_ci_half_width(0.6827));
    assert!((s.variance - 1.0 / 12.0).abs() < 1e-3);
    assert!(s.skewness.abs() < 0.01 && (s.kurtosis + 1.2).abs() < 0.01);
    assert!((quantile(&x, 0.9) - 0.9).abs() < 3e-3);
    assert!(quantile(&x, 1.5).is_nan());
}

#[test]
fn sobol_mc_on_ishigami() {
    let ish = Ishigami::default();
    let law = Independent::new(
        (0..3)
            .map(|_| Arc::new(Uniform::new(-PI, PI).unwrap()) as Arc<dyn Marginal>)
            .collect(),
    )
    .unwrap();
    let r = sobol_indices(&law, 50_000, 2024, |x| ish.eval(x)).unwrap();
    let (s, st) = (ish.sobol_first(), ish.sobol_total());
    eprintln!(
        "MC Sobol': S {:?} +- {:?}; ST {:?} +- {:?}",
        r.first, r.first_se, r.total, r.total_se
    );
    for i in 0..3 {
        assert!(
            (r.first[i] - s[i]).abs() < 4.5 * r.first_se[i],
            "S{}",
            i + 1
        );
        assert!(
            (r.total[i] - st[i]).abs() < 4.5 * r.total_se[i],
            "ST{}",
            i + 1
        );
        assert!(r.first_se[i] < 0.02);
    }
    assert_eq!(r.evaluations, 250_000);
    // Dependent inputs are rejected.
    let cop = GaussianCopula::new(
        vec![
            Arc::new(Normal::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>,
            Arc::new(Normal::new(0.0, 1.0).unwrap()),
        ],
        vec![1.0, 0.5, 0.5, 1.0],
    )
    .unwrap();
    assert!(sobol_indices(&cop, 100, 1, |x| x[0]).is_err());
}

#[test]
fn results_do_not_depend_on_thread_count() {
    let ish = Ishigami::default();
    let law = Independent::new(
        (0..3)
            .map(|_| Arc::new(Uniform::new(-PI, PI).unwrap()) as Arc<dyn Marginal>)
            .collect(),
    )
    .unwrap();
    let run = || {
        let d = monte_carlo(&law, 20_000, 99);
        let q = sample_model(&law, 30_000, 5, |x| ish.eval(x));
        let s = sobol_indices(&law, 10_000, 3, |x| ish.eval(x)).unwrap();
        let m = Summary::of(&q);
        let l = latin_hypercube_maximin(&law, 50, 4, 5);
        let so = sobol(&law, 1000, Some(8)).unwrap();
        let k = Kde::new(&q, Bandwidth::Isj)
            .unwrap()
            .eval_binned(&[0.0, 3.5, 7.0]);
        (d, q, s, m.mean.to_bits(), m.variance.to_bits(), l, so, k)
    };
    let p1 = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let p2 = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = p1.install(run);
    let b = p2.install(run);
    assert!(a == b, "results differ between 1 and 2 threads");
}
