//! Gauss rules of every marginal (classical families and Stieltjes-generated ones) reproduce the
//! law's moments E[X^k], k <= 2n - 1, computed independently (closed forms or composite
//! Gauss-Legendre on the pdf); Smolyak projection gives exact PC coefficients.

use alea_uq::basis::{OrthoPoly, PcBasis, PolyKind};
use alea_uq::law::*;
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::PcSurrogate;
use std::sync::Arc;

/// E[X^k], k < kmax, by composite 10-point Gauss-Legendre on the (extended) support.
fn numeric_moments(law: &dyn Marginal, kmax: usize) -> Vec<f64> {
    // Support, or for an unbounded side the 1e-15 quantile pushed out by its distance to the
    // median (the far tails carry x^k f(x) for the high moments).
    let (lo, hi) = law.support();
    let med = law.quantile(0.5);
    let a = if lo.is_finite() {
        lo
    } else {
        2.0 * law.quantile(1e-15) - med
    };
    let b = if hi.is_finite() {
        hi
    } else {
        2.0 * law.quantile(1.0 - 1e-15) - med
    };
    let np = 4000;
    let mut m = vec![0.0; kmax];
    for i in 0..np {
        let lo = a + (b - a) * i as f64 / np as f64;
        let hi = a + (b - a) * (i + 1) as f64 / np as f64;
        let r = QuadratureRule::gauss_legendre_box(&[lo], &[hi], 10).unwrap();
        for q in 0..r.len() {
            let x = r.node(q)[0];
            let mut v = r.weights()[q] * law.pdf(x);
            for mk in m.iter_mut() {
                *mk += v;
                v *= x;
            }
        }
    }
    m
}

#[test]
fn gauss_rules_reproduce_moments() {
    let laws: Vec<(Box<dyn Marginal>, PolyKind)> = vec![
        (Box::new(Normal::new(1.0, 0.5).unwrap()), PolyKind::Hermite),
        (
            Box::new(Uniform::new(-1.0, 3.0).unwrap()),
            PolyKind::Legendre,
        ),
        (
            // Smooth pdf, so that the composite reference is accurate (closed forms below
            // cover non-integer shapes).
            Box::new(Beta::new(3.0, 4.0, 0.0, 2.0).unwrap()),
            PolyKind::Jacobi,
        ),
        (
            Box::new(Gamma::new(2.5, 0.5, 1.0).unwrap()),
            PolyKind::Laguerre,
        ),
        (
            Box::new(TruncatedNormal::new(0.0, 1.0, -0.5, 3.0).unwrap()),
            PolyKind::Stieltjes,
        ),
        (
            Box::new(LogNormal::new(0.0, 0.25).unwrap()),
            PolyKind::Stieltjes,
        ),
        (
            Box::new(Triangular::new(0.0, 0.3, 1.0).unwrap()),
            PolyKind::Stieltjes,
        ),
    ];
    let n = 8;
    for (law, kind) in &laws {
        let p = OrthoPoly::for_marginal(law.as_ref(), n).unwrap();
        assert_eq!(p.kind(), *kind);
        let (x, w) = p.gauss(n);
        let moments = numeric_moments(law.as_ref(), 2 * n);
        for k in 0..(2 * n as i32) {
            let g: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
            let e = moments[k as usize];
            assert!(
                (g - e).abs() < 1e-9 * e.abs().max(1.0),
                "{} k={k}: {g} vs {e}",
                law.name()
            );
        }
    }
    // Closed forms: Beta(a, b) on [0, 1]: E[X^k] = prod_{r<k} (a + r)/(a + b + r);
    // Gamma(k, theta): E[X^m] = theta^m Gamma(k + m)/Gamma(k).
    let beta = Beta::new(2.5, 1.5, 0.0, 1.0).unwrap();
    let (x, w) = OrthoPoly::for_marginal(&beta, 4).unwrap().gauss(4);
    for k in 0..8 {
        let g: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
        let e: f64 = (0..k)
            .map(|r| (2.5 + r as f64) / (4.0 + r as f64))
            .product();
        assert!((g - e).abs() < 1e-13, "beta k={k}");
    }
    let gam = Gamma::new(2.5, 0.5, 0.0).unwrap();
    let (x, w) = OrthoPoly::for_marginal(&gam, 4).unwrap().gauss(4);
    for k in 0..8 {
        let g: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(k)).sum();
        let e: f64 = (0..k).map(|r| 0.5 * (2.5 + r as f64)).product();
        assert!((g - e).abs() < 1e-12 * e, "gamma k={k}");
    }
}

#[test]
fn smolyak_projection_is_exact_for_polynomials() {
    // Level l = d + p integrates total degree 2p + 1, so products of degree-p basis functions
    // are exact and the projection recovers a degree-p polynomial exactly.
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Uniform::new(0.0, 1.0).unwrap()),
        Arc::new(Beta::new(2.0, 3.0, -1.0, 1.0).unwrap()),
    ];
    let f = |x: &[f64]| 2.0 + x[0] * x[1] - x[2].powi(3) + x[0].powi(2) * x[2];
    let rule = QuadratureRule::smolyak(&m, 6).unwrap();
    let tensor = QuadratureRule::tensor_gauss(&m, &[4, 4, 4]).unwrap();
    let y: Vec<f64> = (0..rule.len()).map(|q| f(rule.node(q))).collect();
    let yt: Vec<f64> = (0..tensor.len()).map(|q| f(tensor.node(q))).collect();
    let basis = PcBasis::total_degree(&m, 3).unwrap();
    let es = PcSurrogate::projection(basis.clone(), &rule)
        .unwrap()
        .expansion(&y)
        .unwrap();
    let et = PcSurrogate::projection(basis, &tensor)
        .unwrap()
        .expansion(&yt)
        .unwrap();
    for (a, b) in es.coefficients().iter().zip(et.coefficients()) {
        assert!((a - b).abs() < 1e-11, "{a} vs {b}");
    }
    let x = [0.3, 0.6, -0.2];
    assert!((es.eval(&x) - f(&x)).abs() < 1e-11);
    eprintln!("Smolyak nodes {} vs tensor {}", rule.len(), tensor.len());
}
