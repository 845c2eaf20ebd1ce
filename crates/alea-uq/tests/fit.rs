//! Maximum-likelihood fitting: estimates within their asymptotic standard errors, the right
//! family ranked first by BIC, goodness-of-fit statistics that reject a wrong family, and the
//! digamma/trigamma functions against known values.

use alea_uq::fit::{Family, digamma, fit, fit_best, trigamma};
use alea_uq::law::*;
use alea_uq::rng::chunk_rng;

fn draws(law: &dyn Marginal, n: usize, seed: u64) -> Vec<f64> {
    let mut rng = chunk_rng(seed, 0);
    (0..n).map(|_| law.sample(&mut rng)).collect()
}

#[test]
fn digamma_and_trigamma_known_values() {
    let euler = 0.577_215_664_901_532_9;
    assert!((digamma(1.0) + euler).abs() < 1e-14);
    assert!((digamma(0.5) + euler + 2.0 * 2f64.ln()).abs() < 1e-14);
    assert!(
        (digamma(10.0) - (-euler + (1..10).map(|k| 1.0 / k as f64).sum::<f64>())).abs() < 1e-14
    );
    let pi2_6 = std::f64::consts::PI.powi(2) / 6.0;
    assert!((trigamma(1.0) - pi2_6).abs() < 1e-13);
    assert!((trigamma(0.5) - 3.0 * pi2_6).abs() < 1e-13);
}

#[test]
fn maximum_likelihood_recovers_parameters() {
    let n = 4000;
    // Normal: sd(mean) = s / sqrt n.
    let x = draws(&Normal::new(3.0, 2.0).unwrap(), n, 1);
    let f = fit(&x, Family::Normal).unwrap();
    assert!((f.parameters[0].1 - 3.0).abs() < 4.5 * 2.0 / (n as f64).sqrt());
    assert!((f.parameters[1].1 - 2.0).abs() < 4.5 * 2.0 / (2.0 * n as f64).sqrt());
    // Gamma(2.5, 1.3): var(k^) = k / (n (k psi'(k) - 1)).
    let x = draws(&Gamma::new(2.5, 1.3, 0.0).unwrap(), n, 2);
    let f = fit(&x, Family::Gamma).unwrap();
    let sd = (2.5 / (n as f64 * (2.5 * trigamma(2.5) - 1.0))).sqrt();
    assert!(
        (f.parameters[0].1 - 2.5).abs() < 4.5 * sd,
        "{:?}",
        f.parameters
    );
    // The MLE maximises the likelihood: nearby parameters do worse.
    let (k, t) = (f.parameters[0].1, f.parameters[1].1);
    for (dk, dt) in [(1.01, 1.0), (0.99, 1.0), (1.0, 1.01), (1.0, 0.99)] {
        let g = Gamma::new(k * dk, t * dt, 0.0).unwrap();
        assert!(x.iter().map(|&v| g.pdf(v).ln()).sum::<f64>() < f.log_likelihood);
    }
    // Beta(2, 5) on [1, 3].
    let x = draws(&Beta::new(2.0, 5.0, 1.0, 3.0).unwrap(), n, 3);
    let f = fit(&x, Family::Beta { a: 1.0, b: 3.0 }).unwrap();
    assert!(
        (f.parameters[0].1 - 2.0).abs() < 0.15 && (f.parameters[1].1 - 5.0).abs() < 0.4,
        "{:?}",
        f.parameters
    );
    for (da, db) in [(1.01, 1.0), (1.0, 0.99)] {
        let g = Beta::new(f.parameters[0].1 * da, f.parameters[1].1 * db, 1.0, 3.0).unwrap();
        assert!(x.iter().map(|&v| g.pdf(v).ln()).sum::<f64>() < f.log_likelihood);
    }
}

#[test]
fn bic_picks_the_family_and_ks_rejects_a_wrong_one() {
    let x = draws(&LogNormal::new(0.0, 0.5).unwrap(), 2000, 4);
    let ranked = fit_best(
        &x,
        &[
            Family::Normal,
            Family::LogNormal,
            Family::Gamma,
            Family::Uniform,
        ],
    )
    .unwrap();
    assert_eq!(ranked[0].family, Family::LogNormal);
    let normal = ranked.iter().find(|f| f.family == Family::Normal).unwrap();
    assert!(normal.ks_pvalue < 1e-3, "{}", normal.ks_pvalue);
    assert!(ranked[0].ks_pvalue > 0.01 && ranked[0].anderson_darling < normal.anderson_darling);
    let e = fit(&[-1.0, 2.0, 3.0], Family::LogNormal).unwrap_err();
    assert!(e.to_string().contains("> 0"), "{e}");
}
