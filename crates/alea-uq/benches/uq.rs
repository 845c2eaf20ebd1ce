//! Benchmarks of alea-uq (plain `main`, no harness): run with
//!
//! ```text
//! CARGO_TARGET_DIR=/work/target-uq cargo bench -p alea-uq --bench uq
//! ```
//!
//! 1. Degree-4 PC by regression on 200 LHS points of Ishigami, with mean, variance and
//!    first-order Sobol' indices (reference: OpenTURNS 2.1 ms on this machine).
//! 2. 10^6 Monte Carlo evaluations of a 2D piecewise-bilinear surrogate on 10^4 cells.
//! 3. 10^6 draws of a truncated normal and of a 3-D Gaussian copula (OpenTURNS reference from
//!    `scripts/ot_compare.py`: 71 ms and 586 ms on this machine).
//! 4. Gaussian KDE on 250 000 samples evaluated at 512 points (Silverman and ISJ bandwidths).
//!
//! Each case reports the median (and min) of repeated runs, with 1 and 2 rayon threads.

use alea_uq::basis::PcBasis;
use alea_uq::design::latin_hypercube;
use alea_uq::joint::{GaussianCopula, Independent};
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::law::{LogNormal, Marginal, TruncatedNormal, Uniform};
use alea_uq::samples::Ishigami;
use alea_uq::stats::{Summary, sample_model};
use alea_uq::surrogate::{PcSurrogate, StochasticMesh};
use std::f64::consts::PI;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

#[path = "../../../benches/support/timing.rs"]
mod timing;
use timing::{cpu_seconds, with_threads};

/// Median wall time, minimum wall time and mean process CPU time of `reps` runs (the CPU
/// time is read once around the whole loop: schedstat is only updated at scheduler events).
fn time(reps: usize, mut f: impl FnMut()) -> (f64, f64, f64) {
    f(); // warm-up
    let mut wall = Vec::with_capacity(reps);
    std::thread::yield_now();
    let c0 = cpu_seconds();
    for _ in 0..reps {
        let s = Instant::now();
        f();
        wall.push(s.elapsed().as_secs_f64());
    }
    std::thread::yield_now();
    let cpu = (cpu_seconds() - c0) / reps as f64;
    wall.sort_by(f64::total_cmp);
    (wall[reps / 2], wall[0], cpu)
}

fn fmt(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.1} us", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

fn main() {
    let ish = Ishigami::default();
    let m: Vec<Arc<dyn Marginal>> = (0..3)
        .map(|_| Arc::new(Uniform::new(-PI, PI).unwrap()) as Arc<dyn Marginal>)
        .collect();
    let law3 = Independent::new(m.clone()).unwrap();
    let law2 = Independent::new(vec![
        Arc::new(Uniform::new(0.0, 1.0).unwrap()) as Arc<dyn Marginal>,
        Arc::new(Uniform::new(0.0, 1.0).unwrap()),
    ])
    .unwrap();
    let mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 1.0], &[100, 100]).unwrap();
    let values: Vec<f64> = (0..mesh.num_runs())
        .map(|k| {
            let x = mesh.run_point(k);
            (3.0 * x[0]).sin() * x[1] + x[0] * x[0]
        })
        .collect();
    let kde_data = sample_model(&law3, 250_000, 1, |x| ish.eval(x));
    let kde_pts: Vec<f64> = (0..512).map(|i| -10.0 + 28.0 * i as f64 / 511.0).collect();

    let tn: Arc<dyn Marginal> = Arc::new(TruncatedNormal::new(1.0, 0.2, 0.5, 1.5).unwrap());
    let law_tn = Independent::new(vec![tn.clone()]).unwrap();
    let copula = GaussianCopula::new(
        vec![
            tn.clone(),
            Arc::new(LogNormal::new(0.0, 0.25).unwrap()),
            Arc::new(Uniform::new(0.0, 1.0).unwrap()),
        ],
        vec![1.0, 0.5, 0.0, 0.5, 1.0, 0.3, 0.0, 0.3, 1.0],
    )
    .unwrap();
    println!("| case | threads | wall median | wall min | CPU mean (all threads) |");
    println!("|---|---|---|---|---|");
    for threads in [1, 2] {
        with_threads(threads, || {
            // 1. PC regression.
            let mut seed = 0;
            let (med, min, cpu) = time(2000, || {
                seed += 1;
                let basis = PcBasis::total_degree(&m, 4).unwrap();
                let design = latin_hypercube(&law3, 200, seed);
                let y: Vec<f64> = design.iter().map(|x| ish.eval(x)).collect();
                let pc = PcSurrogate::regression(basis, design.points()).unwrap();
                let e = pc.expansion(&y).unwrap();
                black_box((e.mean(), e.variance(), e.sobol_first()));
            });
            println!(
                "| PC degree 4, regression on 200 LHS points of Ishigami + mean, variance, S_i (35 terms) | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            // 2. MC on the piecewise-bilinear surrogate.
            assert_eq!(mesh.num_leaves(), 10_000);
            let (med, min, cpu) = time(10, || {
                let q = sample_model(&law2, 1_000_000, 7, |x| mesh.interpolate(x, &values));
                black_box(Summary::of(&q).mean);
            });
            println!(
                "| 10^6 MC evaluations of a 2D piecewise-bilinear surrogate, 10^4 cells (+ mean/std) | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            let (med, min, cpu) = time(10, || {
                let q = sample_model(&law2, 1_000_000, 7, |x| x[0] + x[1]);
                black_box(Summary::of(&q).mean);
            });
            println!(
                "| (same, sampling only: 10^6 draws of U(0,1)^2 through the joint law) | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            // Sampling a truncated normal and a 3-D Gaussian copula (OpenTURNS reference in
            // BENCHMARKS.md, measured by scripts/ot_compare.py).
            let (med, min, cpu) = time(10, || {
                black_box(sample_model(&law_tn, 1_000_000, 3, |x| x[0]));
            });
            println!(
                "| 10^6 draws of TN(1, 0.2, [0.5, 1.5]) | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            let (med, min, cpu) = time(10, || {
                black_box(sample_model(&copula, 1_000_000, 3, |x| x[0] + x[1] + x[2]));
            });
            println!(
                "| 10^6 draws of a 3-D Gaussian copula (TN, lognormal, uniform) | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            // 3. KDE.
            let (med, min, cpu) = time(10, || {
                let k = Kde::new(&kde_data, Bandwidth::Silverman).unwrap();
                black_box(k.eval_binned(&kde_pts));
            });
            println!(
                "| KDE 250 000 samples at 512 points, Silverman, binned evaluation | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            let (med, min, cpu) = time(5, || {
                let k = Kde::new(&kde_data, Bandwidth::Silverman).unwrap();
                black_box(k.eval(&kde_pts));
            });
            println!(
                "| KDE 250 000 samples at 512 points, Silverman, exact evaluation | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
            let (med, min, cpu) = time(5, || {
                let k = Kde::new(&kde_data, Bandwidth::Isj).unwrap();
                black_box(k.eval_binned(&kde_pts));
            });
            println!(
                "| KDE 250 000 samples at 512 points, ISJ bandwidth, binned evaluation | {threads} | {} | {} | {} |",
                fmt(med),
                fmt(min),
                fmt(cpu)
            );
        });
    }
}
