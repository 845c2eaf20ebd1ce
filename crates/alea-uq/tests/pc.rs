//! Polynomial chaos verification: exactness on polynomials of the basis degree, Ishigami
//! statistics (Ishigami & Homma 1990; exact values from `samples::Ishigami`, e.g.
//! mean 3.5, variance 13.8446, S1 0.3139, S2 0.4424, S3 0), regression vs projection, fast LOO
//! vs brute-force LOO, sparse LARS, and the monomial response surface.

use alea_uq::basis::{MultiIndexSet, PcBasis};
use alea_uq::design::{latin_hypercube, pc_collocation, sobol};
use alea_uq::joint::Independent;
use alea_uq::law::{Marginal, Normal, TruncatedNormal, Uniform};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::samples::Ishigami;
use alea_uq::surrogate::{LinearSurrogate, MonomialSurface, PcSurrogate};
use std::f64::consts::PI;
use std::sync::Arc;

fn ishigami_marginals() -> Vec<Arc<dyn Marginal>> {
    (0..3)
        .map(|_| Arc::new(Uniform::new(-PI, PI).unwrap()) as Arc<dyn Marginal>)
        .collect()
}

#[test]
fn pc_is_exact_on_polynomials_of_its_degree() {
    // Mixed marginals, degree 3: f is in the span, so regression reproduces it exactly.
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(1.0, 0.5).unwrap()),
        Arc::new(Uniform::new(0.0, 2.0).unwrap()),
        Arc::new(TruncatedNormal::new(0.0, 1.0, -1.0, 2.5).unwrap()),
    ];
    let f = |x: &[f64]| 1.0 + x[0] * x[1] * x[2] - 2.0 * x[0].powi(3) + x[2].powi(2) * x[1];
    let basis = PcBasis::total_degree(&m, 3).unwrap();
    assert_eq!(basis.len(), 20); // (3 + 3)! / (3! 3!)
    let law = Independent::new(m.clone()).unwrap();
    let design = latin_hypercube(&law, 60, 3);
    let y = design.evaluate(f);
    let pc = PcSurrogate::regression(basis.clone(), design.points()).unwrap();
    let x = [0.7, 1.3, 0.4];
    assert!((pc.eval(&x, &y) - f(&x)).abs() < 1e-10);
    // Projection on a 4-point Gauss rule per variable is exact too.
    let rule = QuadratureRule::tensor_gauss(&m, &[4, 4, 4]).unwrap();
    let yq: Vec<f64> = (0..rule.len()).map(|q| f(rule.node(q))).collect();
    let pj = PcSurrogate::projection(basis, &rule).unwrap();
    assert!((pj.eval(&x, &yq) - f(&x)).abs() < 1e-10);
    // Mean from the coefficients: E[x0 x1 x2] = 1 * 1 * E[x2] ; E[x0^3] = mu^3 + 3 mu s^2.
    let tn = TruncatedNormal::new(0.0, 1.0, -1.0, 2.5).unwrap();
    let e2 = tn.std().powi(2) + tn.mean().powi(2);
    let exact = 1.0 + tn.mean() - 2.0 * (1.0 + 3.0 * 0.25) + e2 * 1.0;
    let mean = pc.expansion(&y).unwrap().mean();
    assert!((mean - exact).abs() < 1e-10, "{mean} vs {exact}");
}

#[test]
fn ishigami_projection_statistics() {
    let ish = Ishigami::default();
    let m = ishigami_marginals();
    let basis = PcBasis::total_degree(&m, 16).unwrap();
    let rule = QuadratureRule::tensor_gauss(&m, &[18, 18, 18]).unwrap();
    let y: Vec<f64> = (0..rule.len()).map(|q| ish.eval(rule.node(q))).collect();
    let e = PcSurrogate::projection(basis, &rule)
        .unwrap()
        .expansion(&y)
        .unwrap();
    let s = e.sobol_first();
    let st = e.sobol_total();
    let (ex, et) = (ish.sobol_first(), ish.sobol_total());
    eprintln!(
        "projection: mean {:.6} var {:.6} S {:?} ST {:?}",
        e.mean(),
        e.variance(),
        s,
        st
    );
    // The issue asks for 1e-3 relative; degree 16 on 18^3 Gauss points reaches 1e-5.
    assert!((e.mean() - 3.5).abs() < 1e-5 * 3.5, "mean {}", e.mean());
    assert!(
        (e.variance() - ish.variance()).abs() < 1e-5 * ish.variance(),
        "var {}",
        e.variance()
    );
    assert!((ish.variance() - 13.8446).abs() < 1e-4);
    assert!(
        (s[0] - ex[0]).abs() < 1e-5 * ex[0] && (ex[0] - 0.3139).abs() < 1e-4,
        "S1 {}",
        s[0]
    );
    assert!(
        (s[1] - ex[1]).abs() < 1e-5 * ex[1] && (ex[1] - 0.4424).abs() < 1e-4,
        "S2 {}",
        s[1]
    );
    assert!(s[2].abs() < 1e-10, "S3 {}", s[2]);
    // Interaction indices: only S13 = b^2 pi^8 (1/18 - 1/50) / Var is non-zero.
    let v13 = ish.b.powi(2) * PI.powi(8) * (1.0 / 18.0 - 1.0 / 50.0) / ish.variance();
    assert!(
        (e.sobol_index(&[0, 2]) - v13).abs() < 1e-5 * v13,
        "S13 {}",
        e.sobol_index(&[0, 2])
    );
    let s2 = e.sobol_second_order();
    assert!(s2[1].abs() < 1e-10 && s2[5].abs() < 1e-10 && (s2[2] - s2[6]).abs() < 1e-15);
    assert!(e.sobol_index(&[0, 1, 2]).abs() < 1e-10);
    let groups: [&[usize]; 7] = [&[0], &[1], &[2], &[0, 1], &[0, 2], &[1, 2], &[0, 1, 2]];
    let total: f64 = groups.iter().map(|g| e.sobol_index(g)).sum();
    assert!((total - 1.0).abs() < 1e-12);
    assert!((e.sobol_closed(&[0, 2]) - (s[0] + s[2] + v13)).abs() < 1e-5);
    assert!((e.sobol_index(&[0]) - s[0]).abs() < 1e-15);
    for i in 0..3 {
        assert!(
            (st[i] - et[i]).abs() < 1e-5 * et[i],
            "ST{} {} vs {}",
            i + 1,
            st[i],
            et[i]
        );
    }
}

#[test]
fn ishigami_regression_agrees_with_projection() {
    let ish = Ishigami::default();
    let m = ishigami_marginals();
    let law = Independent::new(m.clone()).unwrap();
    let basis = PcBasis::total_degree(&m, 12).unwrap(); // 455 terms
    let design = sobol(&law, 2048, Some(11)).unwrap();
    let y = design.evaluate(|x| ish.eval(x));
    let reg = PcSurrogate::regression(basis.clone(), design.points()).unwrap();
    assert!(reg.warnings().is_empty(), "{:?}", reg.warnings());
    let er = reg.expansion(&y).unwrap();
    let rule = QuadratureRule::tensor_gauss(&m, &[14, 14, 14]).unwrap();
    let yq: Vec<f64> = (0..rule.len()).map(|q| ish.eval(rule.node(q))).collect();
    let ep = PcSurrogate::projection(basis, &rule)
        .unwrap()
        .expansion(&yq)
        .unwrap();
    let (sr, sp) = (er.sobol_first(), ep.sobol_first());
    eprintln!(
        "regression: mean {:.6} var {:.6} S {:?}; LOO {:.2e}",
        er.mean(),
        er.variance(),
        sr,
        reg.loo_error(&y).unwrap()
    );
    assert!(
        (er.mean() - ep.mean()).abs() < 1e-4 * 3.5,
        "{} {}",
        er.mean(),
        ep.mean()
    );
    assert!((er.variance() - ep.variance()).abs() < 1e-4 * ep.variance());
    for i in 0..3 {
        assert!(
            (sr[i] - sp[i]).abs() < 1e-4,
            "S{}: {} vs {}",
            i + 1,
            sr[i],
            sp[i]
        );
    }
    // And both are within 1e-3 relative of the exact values (absolute for S3).
    let ex = ish.sobol_first();
    for i in 0..3 {
        assert!(
            (sr[i] - ex[i]).abs() < 1e-3 * ex[i].max(1.0),
            "S{} = {}",
            i + 1,
            sr[i]
        );
    }
    assert!(reg.loo_error(&y).unwrap() < 1e-3);
}

#[test]
fn fast_loo_matches_brute_force() {
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Uniform::new(-1.0, 1.0).unwrap()),
    ];
    let law = Independent::new(m.clone()).unwrap();
    let f = |x: &[f64]| (x[0] + 0.5 * x[1]).sin() + x[1].powi(4);
    let design = latin_hypercube(&law, 30, 8);
    let y = design.evaluate(f);
    let basis = PcBasis::total_degree(&m, 3).unwrap();
    let fast = PcSurrogate::regression(basis.clone(), design.points())
        .unwrap()
        .loo_error(&y)
        .unwrap();
    let n = design.len();
    let mut sum = 0.0;
    for i in 0..n {
        let pts: Vec<f64> = (0..n)
            .filter(|&k| k != i)
            .flat_map(|k| design.point(k).to_vec())
            .collect();
        let yy: Vec<f64> = (0..n).filter(|&k| k != i).map(|k| y[k]).collect();
        let pc = PcSurrogate::regression(basis.clone(), &pts).unwrap();
        let r = y[i] - pc.eval(design.point(i), &yy);
        sum += r * r;
    }
    let mean = y.iter().sum::<f64>() / n as f64;
    let var = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let brute = sum / n as f64 / var;
    assert!((fast - brute).abs() < 1e-10 * brute, "{fast} vs {brute}");
}

#[test]
fn weights_interpolate_fields_like_scalars() {
    // Linear in the data: eval_field of a 2-component field equals two scalar evals.
    let m = ishigami_marginals();
    let law = Independent::new(m.clone()).unwrap();
    let design = latin_hypercube(&law, 80, 2);
    let pc =
        PcSurrogate::regression(PcBasis::total_degree(&m, 3).unwrap(), design.points()).unwrap();
    let a = design.evaluate(|x| x[0].sin());
    let b = design.evaluate(|x| x[1] * x[2]);
    let field: Vec<f64> = a.iter().zip(&b).flat_map(|(u, v)| [*u, *v]).collect();
    let xi = [0.3, -1.0, 2.0];
    let mut out = [0.0; 2];
    pc.eval_field(&xi, &field, &mut out);
    assert!((out[0] - pc.eval(&xi, &a)).abs() < 1e-12);
    assert!((out[1] - pc.eval(&xi, &b)).abs() < 1e-12);
    // Sum of weights = 1 because the constant is in the basis.
    let mut w = Vec::new();
    pc.weights(&xi, &mut w);
    assert!((w.iter().map(|e| e.1).sum::<f64>() - 1.0).abs() < 1e-12);
}

#[test]
fn pc_collocation_points_and_hermite_chaos() {
    // Collocation at roots of the next-degree Hermite polynomial; y = exp(x0/2) x1.
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Normal::new(2.0, 1.0).unwrap()),
    ];
    let design = pc_collocation(&m, 6, 49).unwrap();
    // Root of He_7 nearest to the mode is 0 (odd degree).
    assert!(design.point(0)[0].abs() < 1e-12 && (design.point(0)[1] - 2.0).abs() < 1e-12);
    let y = design.evaluate(|x| (0.5 * x[0]).exp() * x[1]);
    let pc =
        PcSurrogate::regression(PcBasis::total_degree(&m, 6).unwrap(), design.points()).unwrap();
    let e = pc.expansion(&y).unwrap();
    // E = exp(1/8) * 2 ; E[y^2] = exp(1/2) * (4 + 1)
    let mean = (0.125f64).exp() * 2.0;
    let var = 0.5f64.exp() * 5.0 - mean * mean;
    assert!((e.mean() - mean).abs() < 1e-4 * mean, "{}", e.mean());
    assert!(
        (e.variance() - var).abs() < 1e-3 * var,
        "{} vs {var}",
        e.variance()
    );
}

#[test]
fn lars_finds_sparse_expansion() {
    let m = ishigami_marginals();
    let law = Independent::new(m.clone()).unwrap();
    // A sparse function of the Legendre basis: 2 + 3 P1(x0) + P2(x1) P1(x2) (orthonormal).
    let design = latin_hypercube(&law, 60, 4);
    let f = |x: &[f64]| {
        let (t0, t1, t2) = (x[0] / PI, x[1] / PI, x[2] / PI);
        2.0 + 3.0 * 3f64.sqrt() * t0 + 5f64.sqrt() * 0.5 * (3.0 * t1 * t1 - 1.0) * 3f64.sqrt() * t2
    };
    let y = design.evaluate(f);
    let basis = PcBasis::total_degree(&m, 5).unwrap(); // 56 candidates for 60 points
    let pc = PcSurrogate::lars(basis, design.points(), &y).unwrap();
    assert!(pc.basis().len() <= 10, "selected {}", pc.basis().len());
    let e = pc.expansion(&y).unwrap();
    assert!((e.mean() - 2.0).abs() < 1e-9 && (e.variance() - 10.0).abs() < 1e-8);
}

#[test]
fn monomial_surface_exact_and_linear() {
    let law = Independent::new(vec![
        Arc::new(Uniform::new(0.0, 10.0).unwrap()),
        Arc::new(Uniform::new(-1.0, 1.0).unwrap()),
    ])
    .unwrap();
    let f = |x: &[f64]| 3.0 - x[0] + 0.5 * x[0] * x[1] + x[1].powi(2);
    let d = latin_hypercube(&law, 15, 1);
    let y = d.evaluate(f);
    let s = MonomialSurface::fit(2, 2, d.points()).unwrap();
    assert_eq!(s.indices().len(), 6);
    let x = [7.5, 0.25];
    assert!((s.eval(&x, &y) - f(&x)).abs() < 1e-10);
    let c = s.coefficients(&y).unwrap();
    assert!((s.eval_coefficients(&x, &c) - f(&x)).abs() < 1e-10);
    assert!(MonomialSurface::fit(2, 3, &d.points()[..8]).is_err()); // 4 points < 10 terms
}

#[test]
fn hyperbolic_basis_sizes() {
    let s = MultiIndexSet::hyperbolic(3, 12, 0.5).unwrap();
    assert!(s.len() < MultiIndexSet::total_degree(3, 12).unwrap().len());
}

#[test]
fn ill_conditioned_regression_is_reported() {
    // Points clustered in a tiny region: the degree-4 design matrix is numerically singular or
    // at least flagged as ill-conditioned.
    let m = ishigami_marginals();
    let pts: Vec<f64> = (0..100)
        .flat_map(|i| {
            let t = i as f64 * 1e-5;
            [0.1 + t, 0.2 + t * t, 0.3 - t]
        })
        .collect();
    match PcSurrogate::regression(PcBasis::total_degree(&m, 4).unwrap(), &pts) {
        Err(e) => assert!(e.to_string().contains("singular"), "{e}"),
        Ok(pc) => {
            assert!(pc.condition_estimate() > 1e8);
            assert!(pc.warnings().iter().any(|w| w.contains("ill-conditioned")));
        }
    }
    // Too few points for the basis.
    let e = PcSurrogate::regression(PcBasis::total_degree(&m, 4).unwrap(), &pts[..30]).unwrap_err();
    assert!(e.to_string().contains("at least as many points"), "{e}");
}

#[test]
fn dependent_inputs_through_the_nataf_map() {
    // x ~ Gaussian copula with N(1, 1) and N(0, 2^2) marginals, rho = 0.6; q = x0 + x1.
    // Var q = 1 + 4 + 2 * 0.6 * 2 = 7.4. The chaos is built in the independent y variables.
    use alea_uq::joint::{GaussianCopula, JointLaw};
    let marg: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(1.0, 1.0).unwrap()),
        Arc::new(Normal::new(0.0, 2.0).unwrap()),
    ];
    let law = GaussianCopula::new(marg, vec![1.0, 0.6, 0.6, 1.0]).unwrap();
    let std_normal: Vec<Arc<dyn Marginal>> =
        vec![Arc::new(Normal::standard()), Arc::new(Normal::standard())];
    let design = pc_collocation(&std_normal, 2, 9).unwrap();
    let y = design.evaluate(|yv| {
        let mut x = [0.0; 2];
        law.standard_normal_to_x(yv, &mut x);
        x[0] + x[1]
    });
    let e = PcSurrogate::regression(
        PcBasis::total_degree(&std_normal, 2).unwrap(),
        design.points(),
    )
    .unwrap()
    .expansion(&y)
    .unwrap();
    assert!((e.mean() - 1.0).abs() < 1e-12 && (e.variance() - 7.4).abs() < 1e-12);
}

#[test]
fn weight_moments_give_mean_and_variance() {
    let m = ishigami_marginals();
    let law = Independent::new(m.clone()).unwrap();
    let ish = Ishigami::default();
    let design = latin_hypercube(&law, 120, 5);
    let y = design.evaluate(|x| ish.eval(x));
    let pc =
        PcSurrogate::regression(PcBasis::total_degree(&m, 4).unwrap(), design.points()).unwrap();
    let e = pc.expansion(&y).unwrap();
    let ew = pc.expected_weights();
    let mean: f64 = ew.iter().zip(&y).map(|(a, b)| a * b).sum();
    let mm = pc.weight_second_moments();
    let k = y.len();
    let m2: f64 = (0..k)
        .map(|i| y[i] * (0..k).map(|j| mm[i * k + j] * y[j]).sum::<f64>())
        .sum();
    assert!((mean - e.mean()).abs() < 1e-10);
    assert!((m2 - mean * mean - e.variance()).abs() < 1e-9 * e.variance());
}
