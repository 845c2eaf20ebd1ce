//! `[[reliability]]` tables against exact failure probabilities (issue 19): a plate in uniaxial
//! tension (plane stress, nu = 0) whose tip displacement is exactly `u = f(P) s L / E`, with
//! `E ~ U(150e3, 250e3)` MPa, `P ~ N(1, 0.1^2)` and the traction scaled by `f(P)`:
//! - `f(P) = P`: one failure mode, `P(u > t) = int_a^b (1 - Phi((t E / (s L) - 1) / 0.1)) dE /
//!   (b - a)` (quadrature);
//! - `f(P) = (P - 1)^2`: two symmetric modes `P - 1 = +-(t E / (s L))^(1/2)`, each half of the
//!   probability: FORM sees one, and the analysis must say so.
//!
//! The surrogate is a degree-4 chaos on 40 runs (its own error on `u` is below 1e-4 relative),
//! so the algorithms are held to the exact value within their own intervals (importance
//! sampling, subset simulation) or their approximation (SORM within 10 %: measured 7.8 %, the limit state bends beyond second
//! order through the uniform law of `E`; FORM within 25 %).

use alea_study::Source;
use alea_study::reliability::analyse_reliability;
use alea_study::runner::{NoProgress, Study, run_study};

fn study(factor: &str, threshold: f64) -> Study {
    let text = format!(
        r#"
[study]
title = "plate reliability"
seed = 3

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [100.0, 20.0]
cells = [4, 1]

[analysis]
type = "plane_stress"

[[parameter]]
name = "E"
law = "uniform"
lo = 150e3
hi = 250e3

[[parameter]]
name = "P"
law = "normal"
mean = 1.0
std = 0.1

[[substructure]]
name = "plate"
young = "E"
poisson = 0.0
constraint = [ {{ group = "xmin", x = 0.0 }}, {{ group = "ymin", y = 0.0 }} ]
load = [ {{ group = "xmax", traction = [200.0, 0.0], factor = "{factor}" }} ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [100.0, 20.0]
component = 0
unit = "mm"

[[method]]
type = "pc_regression"
degree = 4
design = "lhs"
runs = 40

[[reliability]]
quantity = "tip"
threshold = {threshold:e}
target_cov = 0.05
"#
    );
    Study::from_source(Source::from_text("reliability.toml", &text)).unwrap()
}

fn norm_cdf(x: f64) -> f64 {
    alea_uq::special::norm_cdf(x)
}

/// Exact `P(u > t)` for `u = f(P) s L / E` by quadrature over `E`.
fn exact(t: f64, two_modes: bool) -> f64 {
    let (a, b, sl) = (150e3, 250e3, 200.0 * 100.0);
    let n = 20_000;
    (0..n)
        .map(|i| {
            let e = a + (b - a) * (i as f64 + 0.5) / n as f64;
            let c = t * e / sl;
            if two_modes {
                let r = c.sqrt() / 0.1;
                2.0 * norm_cdf(-r)
            } else {
                1.0 - norm_cdf((c - 1.0) / 0.1)
            }
        })
        .sum::<f64>()
        / n as f64
}

fn analyse(s: &Study, name: &str) -> alea_study::reliability::ReliabilityResult {
    let dir = std::env::temp_dir().join(format!("alea-rel-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(s, &dir, false, &NoProgress).unwrap();
    let out = analyse_reliability(s, &s.reliability, &runs.methods, &runs.records, 0.95);
    let _ = std::fs::remove_dir_all(&dir);
    out.into_iter().next().unwrap()
}

#[test]
fn one_failure_mode_matches_the_exact_probability() {
    let t = 0.13;
    let r = analyse(&study("P", t), "one");
    let p = exact(t, false);
    assert!(r.errors.is_empty(), "{:?}", r.errors);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    let form = &r.design_points[0];
    assert!((form.pf / p - 1.0).abs() < 0.25, "FORM {} vs {p}", form.pf);
    let sorm = r.sorm.as_ref().unwrap();
    assert!(
        (sorm.pf_breitung / p - 1.0).abs() < 0.10,
        "SORM {} vs {p}",
        sorm.pf_breitung
    );
    for (name, e) in [("IS", r.importance.as_ref()), ("subset", r.subset.as_ref())] {
        let e = e.unwrap();
        let half = 0.5 * (e.upper - e.lower);
        assert!(
            (e.pf - p).abs() <= half + 0.01 * p,
            "{name} {} [{}, {}] vs {p}",
            e.pf,
            e.lower,
            e.upper
        );
    }
    // Importance sampling stops at its target: a coefficient of variation of 5 % on a
    // probability near 0.08 needs a few thousand draws around the design point, not 16 384.
    let is = r.importance.as_ref().unwrap();
    assert!(is.cov.unwrap() <= 0.05, "{:?}", is);
    assert!(is.evaluations <= 8_192, "{} evaluations", is.evaluations);
}

#[test]
fn two_failure_modes_are_both_found_and_reported() {
    let t = 0.004;
    let r = analyse(&study("(P - 1) * (P - 1)", t), "two");
    let p = exact(t, true);
    assert_eq!(r.design_points.len(), 2, "{:?}", r.design_points);
    assert!(
        r.warnings.iter().any(|w| w.contains("2 design points")),
        "{:?}",
        r.warnings
    );
    // One design point holds half of the probability; subset simulation sees both.
    let form = &r.design_points[0];
    assert!(form.pf < 0.7 * p, "FORM {} vs {p}", form.pf);
    let sub = r.subset.as_ref().unwrap();
    assert!(
        (sub.pf - p).abs() <= 0.5 * (sub.upper - sub.lower) + 0.01 * p,
        "subset {} [{}, {}] vs {p}",
        sub.pf,
        sub.lower,
        sub.upper
    );
}

/// `solver_runs`: importance sampling with runs of the solver itself, centred at the design
/// point of a deliberately poor surrogate (a degree-1 chaos on 8 runs: `u = P s L / E` is
/// convex in `E`, which a plane misses in the tail). The solver's estimate is unbiased whatever
/// the centre: the exact probability lies within its interval, while the surrogate's own
/// importance sampling is off by more than its interval.
#[test]
fn solver_runs_confirm_the_probability_that_a_poor_surrogate_misses() {
    let t = 0.13;
    let text = study("P", t)
        .source
        .text
        .replace(
            "degree = 4\ndesign = \"lhs\"\nruns = 40",
            "degree = 1\ndesign = \"lhs\"\nruns = 8",
        )
        .replace("target_cov = 0.05", "target_cov = 0.05\nsolver_runs = 400");
    let s = Study::from_source(Source::from_text("reliability.toml", &text)).unwrap();
    assert_eq!(s.reliability[0].solver_runs, 400);
    let r = analyse(&s, "solver");
    let p = exact(t, false);
    let c = r.solver.as_ref().expect("a solver confirmation");
    let is = r.importance.as_ref().unwrap();
    eprintln!(
        "exact {p:.5e}; solver IS {:.5e} [{:.5e}, {:.5e}] CoV {:?} ({} runs); surrogate IS {:.5e} [{:.5e}, {:.5e}]",
        c.pf, c.lower, c.upper, c.cov, c.runs, is.pf, is.lower, is.upper
    );
    assert_eq!((c.runs, c.failed), (400, 0));
    assert!(
        c.lower <= p && p <= c.upper,
        "solver IS {} [{}, {}] vs exact {p}",
        c.pf,
        c.lower,
        c.upper
    );
    assert!(c.cov.unwrap() < 0.15, "CoV {:?}", c.cov);
    assert!(
        p < is.lower || p > is.upper,
        "the degree-1 surrogate's IS {} [{}, {}] covers the exact {p}: the test shows nothing",
        is.pf,
        is.lower,
        is.upper
    );
}

/// A confirmation of fewer than 10 runs is refused at its line.
#[test]
fn too_few_solver_runs_are_refused_at_load() {
    let text = study("P", 0.13)
        .source
        .text
        .replace("target_cov = 0.05", "target_cov = 0.05\nsolver_runs = 5");
    let e = Study::from_source(Source::from_text("reliability.toml", &text)).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("reliability.toml:"), "{msg}");
    assert!(msg.contains("reliability[0].solver_runs"), "{msg}");
    assert!(msg.contains("between 10 and 100000"), "{msg}");
}
