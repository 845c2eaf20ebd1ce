//! Verification of the marginal laws: `cdf(quantile(p)) = p`, moments against closed forms
//! (numerical integration of the pdf), sampling moments within their confidence interval, and
//! error messages that name the law and the field.

use alea_uq::law::*;
use alea_uq::quadrature::QuadratureRule;
use alea_uq::rng::chunk_rng;

fn laws() -> Vec<(Box<dyn Marginal>, f64, f64)> {
    // (law, exact mean, exact std) from closed forms written independently of the code.
    let tn_mean = {
        // N(1, 2^2) on [0, 4]: alpha = -0.5, beta = 1.5
        let (a, b) = (-0.5f64, 1.5f64);
        let phi = |t: f64| (-0.5 * t * t).exp() / (2.0 * std::f64::consts::PI).sqrt();
        // Phi(1.5) - Phi(-0.5) = 0.9331927987311419 - 0.3085375387259869
        let z = 0.933_192_798_731_141_9 - 0.308_537_538_725_986_9;
        let m = 1.0 + 2.0 * (phi(a) - phi(b)) / z;
        let v = 4.0 * (1.0 + (a * phi(a) - b * phi(b)) / z - ((phi(a) - phi(b)) / z).powi(2));
        (m, v.sqrt())
    };
    vec![
        (
            Box::new(Uniform::new(-1.0, 3.0).unwrap()),
            1.0,
            4.0 / 12f64.sqrt(),
        ),
        (Box::new(Normal::new(2.0, 0.5).unwrap()), 2.0, 0.5),
        (
            Box::new(TruncatedNormal::new(1.0, 2.0, 0.0, 4.0).unwrap()),
            tn_mean.0,
            tn_mean.1,
        ),
        (
            Box::new(TruncatedNormal::new(0.0, 1.0, 3.0, f64::INFINITY).unwrap()),
            // Mills ratio: E = phi(3)/(1 - Phi(3))
            0.004_431_848_411_938_008 / 0.001_349_898_031_630_094_6,
            {
                let l = 0.004_431_848_411_938_008 / 0.001_349_898_031_630_094_6;
                (1.0f64 + 3.0 * l - l * l).sqrt()
            },
        ),
        (
            Box::new(LogNormal::new(0.1, 0.4).unwrap()),
            (0.1f64 + 0.08).exp(),
            (((0.16f64).exp() - 1.0) * (0.2f64 + 0.16).exp()).sqrt(),
        ),
        (
            Box::new(Beta::new(2.0, 5.0, 1.0, 3.0).unwrap()),
            1.0 + 2.0 * 2.0 / 7.0,
            2.0 * (10.0f64 / (49.0 * 8.0)).sqrt(),
        ),
        (
            Box::new(Gamma::new(3.0, 2.0, 1.0).unwrap()),
            7.0,
            3f64.sqrt() * 2.0,
        ),
        (
            Box::new(Triangular::new(0.0, 1.0, 4.0).unwrap()),
            5.0 / 3.0,
            ((16.0 + 1.0 - 4.0) / 18.0f64).sqrt(),
        ),
        (
            // Triangle (0,0)-(1,2)-(2,0) tabulated: same as triangular(0, 1, 2).
            Box::new(Tabulated::new(vec![0.0, 1.0, 2.0], vec![0.0, 5.0, 0.0]).unwrap()),
            1.0,
            (1.0 / 6.0f64).sqrt(),
        ),
    ]
}

#[test]
fn cdf_of_quantile_is_identity() {
    for (law, _, _) in laws() {
        for i in 1..200 {
            let p = i as f64 / 200.0;
            let x = law.quantile(p);
            assert!(
                (law.cdf(x) - p).abs() < 1e-11,
                "{}: p = {p}, cdf = {}",
                law.name(),
                law.cdf(x)
            );
        }
        for &p in &[1e-9, 1e-5, 1.0 - 1e-5] {
            let x = law.quantile(p);
            assert!(
                (law.cdf(x) - p).abs() < 1e-11 * p.max(1e-3),
                "{}: p = {p}",
                law.name()
            );
        }
        assert!(law.quantile(-0.1).is_nan() && law.quantile(1.1).is_nan());
    }
}

#[test]
fn moments_match_closed_forms() {
    for (law, mean, std) in laws() {
        assert!(
            (law.mean() - mean).abs() < 1e-12 * (1.0 + mean.abs()),
            "{} mean",
            law.name()
        );
        assert!(
            (law.std() - std).abs() < 1e-12 * std,
            "{} std {} vs {}",
            law.name(),
            law.std(),
            std
        );
        // Numerical moments of the pdf on [q(1e-15), q(1 - 1e-15)] in 400 panels.
        let (a, b) = (law.quantile(1e-15), law.quantile(1.0 - 1e-15));
        let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
        let np = 400;
        for k in 0..np {
            let lo = a + (b - a) * k as f64 / np as f64;
            let hi = a + (b - a) * (k + 1) as f64 / np as f64;
            let r = QuadratureRule::gauss_legendre_box(&[lo], &[hi], 8).unwrap();
            m0 += r.integrate(|x| law.pdf(x[0]));
            m1 += r.integrate(|x| x[0] * law.pdf(x[0]));
            m2 += r.integrate(|x| x[0] * x[0] * law.pdf(x[0]));
        }
        assert!((m0 - 1.0).abs() < 1e-7, "{} mass {m0}", law.name());
        assert!(
            (m1 - mean).abs() < 1e-7 * (1.0 + mean.abs()),
            "{} m1 {m1}",
            law.name()
        );
        let s = (m2 - m1 * m1).sqrt();
        assert!(
            (s - std).abs() < 1e-6 * std,
            "{} std {s} vs {std}",
            law.name()
        );
    }
}

#[test]
fn sample_moments_within_confidence_interval() {
    let n = 40_000;
    for (law, mean, std) in laws() {
        let mut rng = chunk_rng(17, 0);
        let x: Vec<f64> = (0..n).map(|_| law.sample(&mut rng)).collect();
        let m = x.iter().sum::<f64>() / n as f64;
        // 4.5 standard errors: a false alarm has probability 7e-6 for a given seed.
        assert!(
            (m - mean).abs() < 4.5 * std / (n as f64).sqrt(),
            "{}: {m} vs {mean}",
            law.name()
        );
        let v = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1) as f64;
        assert!((v.sqrt() - std).abs() < 0.05 * std, "{}", law.name());
    }
}

#[test]
fn invalid_laws_name_law_and_field() {
    let e = TruncatedNormal::new(0.0, -1.0, 0.0, 1.0).unwrap_err();
    assert_eq!(e.to_string(), "truncated normal: std must be > 0, got -1");
    // Far tails are valid (log space).
    assert!(TruncatedNormal::new(0.0, 1.0, 40.0, 41.0).is_ok());
    let e = TruncatedNormal::new(0.0, 1.0, 2.0, 1.0).unwrap_err();
    assert!(e.to_string().starts_with("truncated normal: hi"), "{e}");
    assert!(
        Normal::new(0.0, 0.0)
            .unwrap_err()
            .to_string()
            .contains("normal: std")
    );
    assert!(
        Beta::new(0.0, 1.0, 0.0, 1.0)
            .unwrap_err()
            .to_string()
            .contains("beta: alpha")
    );
    assert!(Uniform::new(1.0, 1.0).is_err());
    assert!(Triangular::new(0.0, 2.0, 1.0).is_err());
    assert!(Tabulated::new(vec![0.0, 1.0], vec![0.0, 0.0]).is_err());
    assert!(Tabulated::new(vec![1.0, 0.0], vec![1.0, 1.0]).is_err());
}

/// Moments of `N(0, 1)` truncated to `[a, b]` in the upper tail by composite Gauss-Legendre on
/// the rescaled density `exp(-(t^2 - a^2)/2)` (no underflow, independent of the law's code).
fn tail_moments(a: f64, b: f64) -> (f64, f64) {
    let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
    let np = 200;
    for k in 0..np {
        let lo = a + (b - a) * k as f64 / np as f64;
        let hi = a + (b - a) * (k + 1) as f64 / np as f64;
        let r = QuadratureRule::gauss_legendre_box(&[lo], &[hi], 10).unwrap();
        let f = |t: f64| (-(t * t - a * a) / 2.0).exp();
        m0 += r.integrate(|x| f(x[0]));
        m1 += r.integrate(|x| x[0] * f(x[0]));
        m2 += r.integrate(|x| x[0] * x[0] * f(x[0]));
    }
    let m = m1 / m0;
    (m, (m2 / m0 - m * m).sqrt())
}

#[test]
fn truncated_normal_far_tails_in_log_space() {
    // TN(0, 1, [-40, -38]): mass 3e-316 (subnormal), scipy's truncnorm mean is -38.026.
    let tn = TruncatedNormal::new(0.0, 1.0, -40.0, -38.0).unwrap();
    let (m, s) = tail_moments(38.0, 40.0);
    assert!((tn.mean() + 38.026).abs() < 5e-4, "{}", tn.mean());
    assert!((tn.mean() + m).abs() < 1e-11 * m, "{} vs {}", tn.mean(), -m);
    assert!((tn.std() - s).abs() < 1e-7 * s, "{} vs {s}", tn.std());
    // Mirror image in the upper tail, shifted and scaled.
    let up = TruncatedNormal::new(2.0, 3.0, 2.0 + 3.0 * 38.0, 2.0 + 3.0 * 40.0).unwrap();
    assert!((up.mean() - (2.0 + 3.0 * m)).abs() < 1e-11 * up.mean());
    // cdf(quantile(p)) = p, also for p and 1 - p near 0, and the density integrates to 1.
    for law in [
        tn,
        up,
        TruncatedNormal::new(0.0, 1.0, 60.0, f64::INFINITY).unwrap(),
    ] {
        for &p in &[1e-12, 1e-6, 0.01, 0.3, 0.5, 0.9, 1.0 - 1e-9] {
            let x = law.quantile(p);
            assert!(
                (law.cdf(x) - p).abs() < 1e-9 * p.min(1.0 - p).max(1e-3),
                "p {p}"
            );
            assert!((law.sf(x) - (1.0 - p)).abs() < 1e-9 * p.min(1.0 - p).max(1e-3));
        }
        let (lo, hi) = (law.quantile(1e-15), law.quantile(1.0 - 1e-15));
        let r = QuadratureRule::gauss_legendre_box(&[lo], &[hi], 40).unwrap();
        let mass = r.integrate(|x| law.pdf(x[0]));
        assert!((mass - 1.0).abs() < 1e-9, "mass {mass}");
        let mut rng = chunk_rng(3, 0);
        for _ in 0..1000 {
            let x = law.sample(&mut rng);
            assert!(x >= law.support().0 && x <= law.support().1 && x.is_finite());
        }
    }
    // Half-infinite far tail: Mills ratio a + 1/a - 2/a^3 + 10/a^5 for a = 60.
    let far = TruncatedNormal::new(0.0, 1.0, 60.0, f64::INFINITY).unwrap();
    let a = 60.0f64;
    let mills = a + 1.0 / a - 2.0 / a.powi(3) + 10.0 / a.powi(5);
    assert!((far.mean() - mills).abs() < 1e-12 * a, "{}", far.mean());
}

#[test]
fn empirical_law_is_the_interpolated_sample_cdf() {
    // Data 0, 1, 3: cdf through (0, 0), (1, 1/2), (3, 1); mass 1/2 uniform on each gap.
    let e = Empirical::new(&[3.0, 0.0, 1.0]).unwrap();
    assert!((e.cdf(0.5) - 0.25).abs() < 1e-15 && (e.cdf(2.0) - 0.75).abs() < 1e-15);
    assert!((e.quantile(0.75) - 2.0).abs() < 1e-15 && (e.pdf(2.0) - 0.25).abs() < 1e-15);
    assert!((e.mean() - 1.25).abs() < 1e-15);
    assert!((e.std() - (7.0f64 / 3.0 - 1.5625).sqrt()).abs() < 1e-15);
    // Ties are a point mass: the cdf jumps at 1.
    let t = Empirical::new(&[0.0, 1.0, 1.0, 2.0]).unwrap();
    assert!((t.cdf(1.0) - 2.0 / 3.0).abs() < 1e-15 && (t.cdf(0.999_999) - 1.0 / 3.0).abs() < 1e-6);
    // The empirical law of 20 000 normal draws has the normal's moments and quantiles.
    let mut rng = chunk_rng(9, 0);
    let n = Normal::new(1.0, 2.0).unwrap();
    let data: Vec<f64> = (0..20_000).map(|_| n.sample(&mut rng)).collect();
    let e = Empirical::new(&data).unwrap();
    assert!((e.mean() - 1.0).abs() < 4.5 * 2.0 / (20_000f64).sqrt());
    assert!(
        (e.std() - 2.0).abs() < 0.05 && (e.quantile(0.975) - (1.0 + 2.0 * 1.959_964)).abs() < 0.1
    );
    for i in 1..100 {
        let p = i as f64 / 100.0;
        assert!((e.cdf(e.quantile(p)) - p).abs() < 1e-12);
    }
    assert!(Empirical::new(&[1.0]).is_err() && Empirical::new(&[2.0, 2.0]).is_err());
}

#[test]
fn kde_law_is_the_gaussian_mixture() {
    use alea_uq::kde::{Bandwidth, Kde};
    let k = KdeLaw::new(Kde::new(&[0.0, 1.0], Bandwidth::Fixed(0.5)).unwrap());
    let phi = |t: f64| alea_uq::special::norm_cdf(t);
    for &x in &[-1.0, 0.0, 0.3, 1.7] {
        let exact = 0.5 * (phi(x / 0.5) + phi((x - 1.0) / 0.5));
        assert!((k.cdf(x) - exact).abs() < 1e-15, "{x}");
    }
    assert!((k.mean() - 0.5).abs() < 1e-15 && (k.std() - 0.5f64.sqrt()).abs() < 1e-15);
    for &p in &[1e-6, 0.1, 0.5, 0.77, 1.0 - 1e-9] {
        assert!(
            (k.cdf(k.quantile(p)) - p).abs() < 1e-12 * p.max(1e-3),
            "p {p}"
        );
    }
    let r = QuadratureRule::gauss_legendre_box(&[-5.0], &[6.0], 60).unwrap();
    assert!((r.integrate(|x| k.pdf(x[0])) - 1.0).abs() < 1e-12);
    // Sampling x_J + h Z: moments within their confidence interval.
    let mut rng = chunk_rng(2, 0);
    let xs: Vec<f64> = (0..40_000).map(|_| k.sample(&mut rng)).collect();
    let m = xs.iter().sum::<f64>() / xs.len() as f64;
    assert!((m - 0.5).abs() < 4.5 * k.std() / 200.0);
}
