//! Rare events against closed forms: FORM on limit states linear in the standard normal space
//! (`P_f = Phi(-beta)` exactly), SORM on a parabolic limit state (Breitung's formula and the
//! exact probability by quadrature), importance sampling and subset simulation within their
//! intervals, the four-branch series system (Waarts 2000; Echard et al. 2011, `P_f = 4.416e-3`
//! for k = 6 by 10^6 Monte Carlo draws), and goal-oriented refinement of a chaos for a
//! `P_f ~ 1e-5`. Draws used are compared with the Monte Carlo size `(1 - P)/(P delta^2)` at the
//! same coefficient of variation.

use alea_uq::basis::PcBasis;
use alea_uq::design::latin_hypercube;
use alea_uq::joint::Independent;
use alea_uq::law::{Marginal, Normal};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::reliability::*;
use alea_uq::special::{norm_cdf, norm_pdf};
use alea_uq::surrogate::PcSurrogate;
use std::sync::Arc;

fn std_normals(d: usize) -> Independent {
    Independent::new(
        (0..d)
            .map(|_| Arc::new(Normal::standard()) as Arc<dyn Marginal>)
            .collect(),
    )
    .unwrap()
}

/// `int_a^b f` by composite 20-point Gauss-Legendre on 200 panels.
fn integrate(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let np = 200;
    (0..np)
        .map(|i| {
            let lo = a + (b - a) * i as f64 / np as f64;
            let hi = a + (b - a) * (i + 1) as f64 / np as f64;
            QuadratureRule::gauss_legendre_box(&[lo], &[hi], 20)
                .unwrap()
                .integrate(|x| f(x[0]))
        })
        .sum()
}

#[test]
fn form_is_exact_on_linear_limit_states() {
    // R - S, R ~ N(5, 0.5), S ~ N(2, 0.6): beta = 3 / sqrt(0.5^2 + 0.6^2).
    let law = Independent::new(vec![
        Arc::new(Normal::new(5.0, 0.5).unwrap()) as Arc<dyn Marginal>,
        Arc::new(Normal::new(2.0, 0.6).unwrap()),
    ])
    .unwrap();
    let ls = LimitState::new(&law, |x| x[0] - x[1]);
    let f = form(&ls, &FormOptions::default()).unwrap();
    let beta = 3.0 / 0.61f64.sqrt();
    assert!((f.beta - beta).abs() < 1e-7, "{} vs {beta}", f.beta);
    assert!((f.pf - norm_cdf(-beta)).abs() < 1e-9 * norm_cdf(-beta));
    assert!(
        (f.x_star[0] - f.x_star[1]).abs() < 1e-6,
        "design point on g = 0"
    );
    let imp = f.importance_factors();
    assert!((imp[0] - 0.25 / 0.61).abs() < 1e-6 && (imp.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    eprintln!(
        "FORM R - S: beta {:.8}, {} iterations, {} evaluations",
        f.beta, f.iterations, f.evaluations
    );
    // 6 standard normals, g = 4.5 - a.u / |a|: beta = 4.5, P_f = 3.4e-6.
    let law6 = std_normals(6);
    let a = [1.0, -2.0, 0.5, 3.0, 0.0, 1.5];
    let na = a.iter().map(|v| v * v).sum::<f64>().sqrt();
    let ls = LimitState::new(&law6, |u| {
        4.5 - u.iter().zip(&a).map(|(x, y)| x * y).sum::<f64>() / na
    });
    let f = form(&ls, &FormOptions::default()).unwrap();
    assert!((f.beta - 4.5).abs() < 1e-7 && (f.pf / norm_cdf(-4.5) - 1.0).abs() < 1e-6);
    for (al, ai) in f.alpha.iter().zip(&a) {
        assert!((al - ai / na).abs() < 1e-6);
    }
    // Origin in the failure domain: negative beta.
    let ls = LimitState::new(&law6, |u| -1.0 + u[0]);
    let f = form(&ls, &FormOptions::default()).unwrap();
    assert!((f.beta + 1.0).abs() < 1e-7 && (f.pf - norm_cdf(1.0)).abs() < 1e-9);
}

/// Exact `P(u3 >= beta + (k1 u1^2 + k2 u2^2)/2)` by tensor Gauss-Hermite on (u1, u2).
fn parabolic_exact(beta: f64, k: [f64; 2]) -> f64 {
    let m: Vec<Arc<dyn Marginal>> =
        vec![Arc::new(Normal::standard()), Arc::new(Normal::standard())];
    QuadratureRule::tensor_gauss(&m, &[60, 60])
        .unwrap()
        .integrate(|u| norm_cdf(-(beta + 0.5 * (k[0] * u[0] * u[0] + k[1] * u[1] * u[1]))))
}

#[test]
fn sorm_on_a_parabolic_limit_state() {
    let law = std_normals(3);
    let (beta, k) = (3.0, [0.2, -0.1]);
    let ls = LimitState::new(&law, |u| {
        beta + 0.5 * (k[0] * u[0] * u[0] + k[1] * u[1] * u[1]) - u[2]
    });
    let s = sorm(&ls, &FormOptions::default()).unwrap();
    assert!((s.form.beta - beta).abs() < 1e-7);
    assert!(
        (s.curvatures[0] + 0.1).abs() < 1e-5 && (s.curvatures[1] - 0.2).abs() < 1e-5,
        "{:?}",
        s.curvatures
    );
    let breitung = norm_cdf(-beta) / ((1.0 + beta * k[0]) * (1.0 + beta * k[1])).sqrt();
    assert!((s.pf_breitung - breitung).abs() < 1e-6 * breitung);
    let exact = parabolic_exact(beta, k);
    let rel = |v: f64| (v / exact - 1.0).abs();
    eprintln!(
        "parabola: exact {exact:.6e}, FORM {:.6e} ({:.1} %), Breitung {:.6e} ({:.2} %), Tvedt {:.6e} ({:.3} %), {} evaluations",
        s.form.pf,
        100.0 * rel(s.form.pf),
        s.pf_breitung,
        100.0 * rel(s.pf_breitung),
        s.pf_tvedt,
        100.0 * rel(s.pf_tvedt),
        s.evaluations
    );
    assert!(rel(s.pf_tvedt) < 0.01 && rel(s.pf_tvedt) < rel(s.pf_breitung));
    assert!(rel(s.pf_breitung) < rel(s.form.pf));
    // Tvedt is exact for a single curvature as beta grows; Breitung is its asymptote: check
    // both formulas on a second case by quadrature.
    let (pb, pt) = breitung_tvedt(2.0, &[0.3, 0.3]);
    let e2 = parabolic_exact(2.0, [0.3, 0.3]);
    assert!((pt / e2 - 1.0).abs() < 0.02 && (pt / e2 - 1.0).abs() < (pb / e2 - 1.0).abs());
}

#[test]
fn importance_sampling_and_subset_simulation_cover_the_exact_value() {
    // Linear limit state, beta = 4.265 (P_f = 1e-5).
    let law = std_normals(4);
    let beta = 4.264_890_793_922_602;
    let exact = norm_cdf(-beta);
    assert!((exact / 1e-5 - 1.0).abs() < 1e-6);
    let g = |u: &[f64]| beta - (u[0] + u[1] - u[2] + u[3]) / 2.0;
    let ls = LimitState::new(&law, g);
    let f = form(&ls, &FormOptions::default()).unwrap();
    eprintln!(
        "FORM beta 4.265: {:.4e}, {} evaluations",
        f.pf, f.evaluations
    );
    assert!((f.pf / exact - 1.0).abs() < 1e-6);
    let is = importance_sampling(
        &ls,
        &f,
        &ImportanceOptions {
            target_cov: 0.05,
            ..Default::default()
        },
    )
    .unwrap();
    eprintln!(
        "IS: {:.4e} [{:.4e}, {:.4e}] cov {:.3}, {} evaluations (MC at the same cov: {:.2e})",
        is.p,
        is.lower,
        is.upper,
        is.cov,
        is.evaluations,
        is.mc_equivalent_draws()
    );
    assert!(is.cov <= 0.05 && (is.p - exact).abs() <= 3.0 * is.cov * exact);
    assert!((is.evaluations as f64) < 1e-3 * is.mc_equivalent_draws());
    let ls = LimitState::new(&law, g);
    let ss = subset_simulation(&ls, &SubsetOptions::default()).unwrap();
    eprintln!(
        "subset: {:.4e} [{:.4e}, {:.4e}] cov {:.3}, {} evaluations (MC at the same cov: {:.2e})",
        ss.p,
        ss.lower,
        ss.upper,
        ss.cov,
        ss.evaluations,
        ss.mc_equivalent_draws()
    );
    assert!(
        (ss.p / exact).ln().abs() <= 3.0 * ss.cov,
        "{} vs {exact}",
        ss.p
    );
    assert!(ss.cov < 0.5 && (ss.evaluations as f64) < 0.05 * ss.mc_equivalent_draws());
}

#[test]
fn four_branch_series_system() {
    // g = min{3 + 0.1 (x1 - x2)^2 -+ (x1 + x2)/sqrt2, +-(x1 - x2) + k/sqrt2}, x ~ N(0, I).
    // With a = (x1 + x2)/sqrt2, b = (x1 - x2)/sqrt2 (independent N(0, 1)), failure is
    // |a| >= 3 + 0.2 b^2 or |b| >= k/2, so
    // P_f = 2 Phi(-k/2) + 2 int_{-k/2}^{k/2} phi(b) Phi(-(3 + 0.2 b^2)) db.
    let law = std_normals(2);
    let k = 6.0f64;
    let exact = 2.0 * norm_cdf(-k / 2.0)
        + 2.0
            * integrate(-k / 2.0, k / 2.0, |b| {
                norm_pdf(b) * norm_cdf(-(3.0 + 0.2 * b * b))
            });
    // Published Monte Carlo value 4.416e-3 with 10^6 draws (cov 1.5 %).
    assert!((exact / 4.416e-3 - 1.0).abs() < 0.03, "{exact}");
    let s2 = std::f64::consts::SQRT_2;
    let g = move |x: &[f64]| {
        let (p, m) = (x[0] + x[1], x[0] - x[1]);
        [
            3.0 + 0.1 * m * m - p / s2,
            3.0 + 0.1 * m * m + p / s2,
            m + k / s2,
            -m + k / s2,
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min)
    };
    let ls = LimitState::new(&law, g);
    let ss = subset_simulation(
        &ls,
        &SubsetOptions {
            samples_per_level: 4000,
            ..Default::default()
        },
    )
    .unwrap();
    eprintln!(
        "four-branch: exact {exact:.4e}, subset {:.4e} [{:.4e}, {:.4e}] cov {:.3}, {} evaluations (MC at the same cov: {:.2e})",
        ss.p,
        ss.lower,
        ss.upper,
        ss.cov,
        ss.evaluations,
        ss.mc_equivalent_draws()
    );
    assert!((ss.p / exact).ln().abs() <= 3.0 * ss.cov);
    // FORM finds one of the four design points only (beta = 3 for the a-branches,
    // sqrt2 k/2 / sqrt2 = 3 for the b-branches): Phi(-3) is 4x too small, as expected.
    // The gradient vanishes at the origin by symmetry: FORM says so, and converges from
    // another start.
    let e = form(&LimitState::new(&law, g), &FormOptions::default()).unwrap_err();
    assert!(e.to_string().contains("gradient"), "{e}");
    let opts = FormOptions {
        start: Some(vec![0.5, 0.1]),
        ..Default::default()
    };
    let f = form(&LimitState::new(&law, g), &opts).unwrap();
    assert!((f.beta - 3.0).abs() < 1e-5, "{}", f.beta);
}

#[test]
fn rare_event_estimates_do_not_depend_on_the_thread_count() {
    let law = std_normals(3);
    let g = |u: &[f64]| 3.5 - u[0] - 0.3 * u[1] * u[1] + 0.1 * u[2];
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let ls = LimitState::new(&law, g);
            let ss = subset_simulation(&ls, &SubsetOptions::default()).unwrap();
            let f = form(&ls, &FormOptions::default()).unwrap();
            let is = importance_sampling(&ls, &f, &ImportanceOptions::default()).unwrap();
            (ss.p, is.p)
        })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn goal_oriented_refinement_of_a_chaos_for_a_small_failure_probability() {
    // q(x) = a + 0.3 sin(a) - 0.2 b^2, a = (x1 + x2)/sqrt2, b = (x1 - x2)/sqrt2, x ~ N(0, I);
    // P(q > 4) = int phi(b) Phi(-a*(b)) db with a*(b) + 0.3 sin a*(b) = 4 + 0.2 b^2.
    let law = std_normals(2);
    let s2 = std::f64::consts::SQRT_2;
    let q = move |x: &[f64]| {
        let (a, b) = ((x[0] + x[1]) / s2, (x[0] - x[1]) / s2);
        a + 0.3 * a.sin() - 0.2 * b * b
    };
    let threshold = 4.0;
    let a_star = |b: f64| {
        let t = threshold + 0.2 * b * b;
        let mut a = t;
        for _ in 0..50 {
            a -= (a + 0.3 * a.sin() - t) / (1.0 + 0.3 * a.cos());
        }
        a
    };
    let exact = integrate(-12.0, 12.0, |b| norm_pdf(b) * norm_cdf(-a_star(b)));
    let m: Vec<Arc<dyn Marginal>> =
        vec![Arc::new(Normal::standard()), Arc::new(Normal::standard())];
    let fit = |p: &[f64], _v: &[f64]| PcSurrogate::regression(PcBasis::total_degree(&m, 4)?, p);
    // P_f of a surrogate by importance sampling at its own design point (cov 2 %, cheap on a
    // surrogate); 0 if the surrogate has no failure domain (FORM does not converge).
    let pf_of = |pts: &[f64], vals: &[f64]| {
        let s = fit(pts, vals).unwrap();
        let ls = LimitState::exceedance(
            &law,
            |x| alea_uq::surrogate::LinearSurrogate::eval(&s, x, vals),
            threshold,
        );
        match form(&ls, &FormOptions::default()) {
            Ok(f) => {
                let o = ImportanceOptions {
                    target_cov: 0.02,
                    ..Default::default()
                };
                importance_sampling(&ls, &f, &o).unwrap().p
            }
            Err(_) => 0.0,
        }
    };
    let init = latin_hypercube(&law, 20, 4);
    let mut pts = init.points().to_vec();
    let mut vals = init.evaluate(q);
    let e0 = pf_of(&pts, &vals);
    let opts = RefineOptions::default();
    let mut stated = Vec::new();
    for _round in 0..5 {
        let prop = propose_runs(&law, &pts, &vals, threshold, fit, &opts).unwrap();
        assert_eq!(prop.points.len(), 2 * opts.new_runs);
        stated.push((prop.pf.p, prop.surrogate_error, prop.relative_error()));
        for x in prop.points.chunks_exact(2) {
            vals.push(q(x));
            pts.extend_from_slice(x);
        }
    }
    let last = propose_runs(&law, &pts, &vals, threshold, fit, &opts).unwrap();
    stated.push((last.pf.p, last.surrogate_error, last.relative_error()));
    eprintln!("refinement rounds (P_f, surrogate error, stated relative error): {stated:.3?}");
    // The stated error shrinks with the rounds and covers the true error at the end.
    assert!(
        stated[0].2 > 1.0 && last.surrogate_error < 0.05,
        "{stated:?}"
    );
    assert!((last.pf.p / exact - 1.0).abs() < 3.0 * last.relative_error());
    let eg = pf_of(&pts, &vals);
    // Same number of runs (40) placed by a space-filling design instead.
    let lhs = latin_hypercube(&law, 40, 4);
    let er = pf_of(lhs.points(), &lhs.evaluate(q));
    let rel = |p: f64| (p / exact - 1.0).abs();
    eprintln!(
        "refinement: exact {exact:.4e}; 20 LHS runs {e0:.4e} ({:.0} %); +20 goal-oriented {eg:.4e} ({:.1} %); 40 LHS {er:.4e} ({:.0} %)",
        100.0 * rel(e0),
        100.0 * rel(eg),
        100.0 * rel(er)
    );
    assert!(rel(eg) < 0.1 && rel(eg) < 0.5 * rel(er) && rel(eg) < 0.5 * rel(e0));
}
