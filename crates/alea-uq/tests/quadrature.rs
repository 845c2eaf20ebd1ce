//! Gauss rules of every marginal (classical families and Stieltjes-generated ones) reproduce the
//! law's moments E[X^k], k <= 2n - 1, computed independently (closed forms or composite
//! Gauss-Legendre on the pdf); Smolyak projection gives exact PC coefficients.

use alea_uq::basis::{OrthoPoly, PcBasis, PolyKind};
use alea_uq::law::*;
use alea_uq::quadrature::{
    GENZ_KEISTER_LEVELS, QuadratureRule, clenshaw_curtis, clenshaw_curtis_size, genz_keister,
    genz_keister_size,
};
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

/// `sum_q w_q p_k(x_q)` for the orthonormal polynomials `p_k` of `poly`, k = 0..=kmax.
fn orthonormal_moments(poly: &OrthoPoly, x: &[f64], w: &[f64], kmax: usize) -> Vec<f64> {
    let mut v = vec![0.0; kmax + 1];
    let mut s = vec![0.0; kmax + 1];
    for (xq, wq) in x.iter().zip(w) {
        poly.eval_all(*xq, &mut v);
        for (sk, vk) in s.iter_mut().zip(&v) {
            *sk += wq * vk;
        }
    }
    s
}

#[test]
fn nested_rules_have_their_degree_of_exactness() {
    // Clenshaw-Curtis with m nodes: exact to degree m - 1 (m for odd m), not beyond.
    let leg = OrthoPoly::legendre(70, -1.0, 1.0);
    for level in 0..6 {
        let (x, w) = clenshaw_curtis(level);
        assert_eq!(x.len(), clenshaw_curtis_size(level));
        let deg = if x.len() == 1 { 1 } else { x.len() };
        let s = orthonormal_moments(&leg, &x, &w, deg + 1);
        for (k, sk) in s.iter().enumerate().take(deg + 1) {
            let e = if k == 0 { 1.0 } else { 0.0 };
            assert!((sk - e).abs() < 1e-13, "CC level {level} k={k}: {sk}");
        }
        assert!(
            s[deg + 1].abs() > 1e-6,
            "CC level {level} exact beyond {deg}"
        );
        // Nested: the nodes of level l are among those of level l + 1.
        let (xn, _) = clenshaw_curtis(level + 1);
        for v in &x {
            assert!(xn.iter().any(|u| (u - v).abs() < 1e-15), "CC not nested");
        }
    }
    // Genz-Keister: sizes 1, 3, 9, 19, 35 and degrees 1, 5, 15, 29, 51 (Genz & Keister 1996).
    let he = OrthoPoly::hermite(60, 0.0, 1.0);
    for (level, (n, deg)) in [(1, 1), (3, 5), (9, 15), (19, 29), (35, 51)]
        .iter()
        .enumerate()
    {
        let (x, w) = genz_keister(level).unwrap();
        assert_eq!((x.len(), genz_keister_size(level)), (*n, *n));
        let s = orthonormal_moments(&he, &x, &w, deg + 3);
        for (k, sk) in s.iter().enumerate().take(deg + 1) {
            let e = if k == 0 { 1.0 } else { 0.0 };
            assert!((sk - e).abs() < 1e-12, "GK level {level} k={k}: {sk}");
        }
        // Not exact at deg + 1: 0.71, 0.22, 7.4e-3, 7.9e-5, 2.1e-8 (>> the 1e-12 tolerance).
        assert!(
            s[deg + 1].abs() > 1e-9,
            "GK level {level} exact beyond {deg}: {}",
            s[deg + 1]
        );
        if level + 1 < GENZ_KEISTER_LEVELS {
            let (xn, _) = genz_keister(level + 1).unwrap();
            for v in &x {
                assert!(xn.iter().any(|u| (u - v).abs() < 1e-14), "GK not nested");
            }
        }
    }
    assert!(genz_keister(GENZ_KEISTER_LEVELS).is_err());
}

/// Size of a nested Smolyak grid: `sum_{|l| <= L} prod_j (m_j(l_j) - m_j(l_j - 1))`.
fn nested_size(growth: &[fn(usize) -> usize], big_l: usize) -> usize {
    let d = growth.len();
    let mut total = 0;
    let mut l = vec![0usize; d];
    loop {
        if l.iter().sum::<usize>() <= big_l {
            total += (0..d)
                .map(|j| growth[j](l[j]) - if l[j] == 0 { 0 } else { growth[j](l[j] - 1) })
                .product::<usize>();
        }
        let mut j = 0;
        loop {
            if j == d {
                return total;
            }
            l[j] += 1;
            if l[j] <= big_l {
                break;
            }
            l[j] = 0;
            j += 1;
        }
    }
}

#[test]
fn nested_smolyak_node_counts_are_the_known_sizes() {
    let u = || Arc::new(Uniform::new(0.0, 2.0).unwrap()) as Arc<dyn Marginal>;
    let n = || Arc::new(Normal::new(1.0, 3.0).unwrap()) as Arc<dyn Marginal>;
    // Clenshaw-Curtis sparse grids (Novak & Ritter 1996; Burkardt's sparse_grid_cc tables).
    let cc2 = [1, 5, 13, 29, 65, 145, 321];
    let cc3 = [1, 7, 25, 69, 177, 441];
    for (l, &size) in cc2.iter().enumerate() {
        assert_eq!(
            QuadratureRule::smolyak_nested(&[u(), u()], l)
                .unwrap()
                .len(),
            size
        );
    }
    for (l, &size) in cc3.iter().enumerate() {
        assert_eq!(
            QuadratureRule::smolyak_nested(&[u(), u(), u()], l)
                .unwrap()
                .len(),
            size
        );
    }
    // The centre of the 3-D level-1 grid has weight 3 (2/3) - 2 = 0 and can be dropped.
    let r = QuadratureRule::smolyak_nested(&[u(), u(), u()], 1).unwrap();
    let (pruned, removed) = r.without_zero_weights(1e-14);
    assert_eq!((pruned.len(), removed), (6, 1));
    assert!((pruned.integrate(|x| x[0] * x[0] + x[1] * x[2]) - (4.0 / 3.0 + 1.0)).abs() < 1e-13);
    // d = 10, levels 1 and 2: 1 + 2d and 1 + 4d + 4 C(d, 2).
    let u10: Vec<_> = (0..10).map(|_| u()).collect();
    assert_eq!(QuadratureRule::smolyak_nested(&u10, 1).unwrap().len(), 21);
    assert_eq!(QuadratureRule::smolyak_nested(&u10, 2).unwrap().len(), 221);
    // Genz-Keister and mixed grids against the size formula of nested grids.
    let gk: fn(usize) -> usize = genz_keister_size;
    let cc: fn(usize) -> usize = clenshaw_curtis_size;
    for l in 0..5 {
        let r = QuadratureRule::smolyak_nested(&[n(), n(), n()], l).unwrap();
        assert_eq!(r.len(), nested_size(&[gk, gk, gk], l), "GK3 level {l}");
        let r = QuadratureRule::smolyak_nested(&[n(), u(), n(), u()], l).unwrap();
        assert_eq!(
            r.len(),
            nested_size(&[gk, cc, gk, cc], l),
            "mixed level {l}"
        );
    }
    assert!(QuadratureRule::smolyak_nested(&[n()], 5).is_err());
    let tn = Arc::new(TruncatedNormal::new(0.0, 1.0, -1.0, 1.0).unwrap()) as Arc<dyn Marginal>;
    let e = QuadratureRule::smolyak_nested(&[tn], 2).unwrap_err();
    assert!(e.to_string().contains("truncated normal"), "{e}");
}

#[test]
fn nested_smolyak_integrates_total_degree_2l_plus_1() {
    // Each 1-D rule of level l is exact to degree >= 2l + 1, so the level-L grid integrates
    // every monomial of total degree <= 2L + 1 exactly.
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Uniform::new(-1.0, 1.0).unwrap()),
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
    ];
    let big_l = 3;
    let r = QuadratureRule::smolyak_nested(&m, big_l).unwrap();
    let moment_n = |k: i32| -> f64 {
        if k % 2 == 1 {
            0.0
        } else {
            (1..k).step_by(2).map(|v| v as f64).product()
        }
    };
    let moment_u = |k: i32| -> f64 {
        if k % 2 == 1 {
            0.0
        } else {
            1.0 / (k + 1) as f64
        }
    };
    for a in 0..=7i32 {
        for b in 0..=(7 - a) {
            for c in 0..=(7 - a - b) {
                let v = r.integrate(|x| x[0].powi(a) * x[1].powi(b) * x[2].powi(c));
                let e = moment_n(a) * moment_u(b) * moment_n(c);
                assert!(
                    (v - e).abs() < 1e-11 * e.abs().max(1.0),
                    "{a} {b} {c}: {v} vs {e}"
                );
            }
        }
    }
}

#[test]
fn gauss_smolyak_has_no_duplicate_nodes() {
    // Independent count: label the j-th node of the n-point symmetric Gauss rule (n, j), except
    // the centre of odd rules, which is one node shared by all of them; count the distinct label
    // tuples of the active tensor grids (1 <= i_j, level - d < |i| <= level).
    fn count(d: usize, level: usize) -> usize {
        let maxn = level - d + 1;
        let mut set = std::collections::HashSet::new();
        let mut i = vec![1usize; d];
        loop {
            let s: usize = i.iter().sum();
            if s + d > level && s <= level {
                let total: usize = i.iter().product();
                for flat in 0..total {
                    let mut r = flat;
                    let key: Vec<(usize, usize)> = i
                        .iter()
                        .map(|&n| {
                            let j = r % n;
                            r /= n;
                            if n % 2 == 1 && j == n / 2 {
                                (0, 0)
                            } else {
                                (n, j)
                            }
                        })
                        .collect();
                    set.insert(key);
                }
            }
            let mut j = 0;
            loop {
                if j == d {
                    return set.len();
                }
                i[j] += 1;
                if i[j] <= maxn && i.iter().sum::<usize>() <= level {
                    break;
                }
                i[j] = 1;
                j += 1;
            }
        }
    }
    for (d, extra) in [(2, 8), (3, 6), (4, 5), (5, 4)] {
        let m: Vec<Arc<dyn Marginal>> = (0..d)
            .map(|k| {
                if k % 2 == 0 {
                    Arc::new(Normal::new(0.5, 2.0).unwrap()) as Arc<dyn Marginal>
                } else {
                    Arc::new(Uniform::new(-3.0, 1.0).unwrap())
                }
            })
            .collect();
        let r = QuadratureRule::smolyak(&m, d + extra).unwrap();
        assert_eq!(r.len(), count(d, d + extra), "d = {d}, level {}", d + extra);
        assert!((r.weights().iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
