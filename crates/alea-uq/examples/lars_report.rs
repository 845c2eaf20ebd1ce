//! Sparse chaos of the Ishigami function by hybrid LARS at candidate degrees 8 to 14: number of
//! terms kept, the reported (corrected leave-one-out) error and the true error `1 - Q2` on an
//! independent test set.
//!
//! ```text
//! cargo run -p alea-uq --release --example lars_report [design.csv test.csv]
//! ```
//!
//! Without arguments: 200 LHS points (seed 1) and 10^5 Monte Carlo test points (seed 2). With
//! two CSV files (columns x1,x2,x3, e.g. written by `scripts/ot_compare.py`), the design and
//! test points are read from them, so that another library can be compared on the same points.

use alea_uq::basis::PcBasis;
use alea_uq::design::{Design, latin_hypercube, monte_carlo};
use alea_uq::joint::Independent;
use alea_uq::law::{Marginal, Uniform};
use alea_uq::samples::Ishigami;
use alea_uq::surrogate::{LarsOptions, PcSurrogate};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::Arc;
use std::time::Instant;

fn main() -> alea_uq::Result<()> {
    let ish = Ishigami::default();
    let m: Vec<Arc<dyn Marginal>> = (0..3)
        .map(|_| Ok(Arc::new(Uniform::new(-PI, PI)?) as Arc<dyn Marginal>))
        .collect::<alea_uq::Result<_>>()?;
    let law = Independent::new(m.clone())?;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (design, test) = if args.len() == 2 {
        (Design::from_csv(&args[0])?.0, Design::from_csv(&args[1])?.0)
    } else {
        (latin_hypercube(&law, 200, 1), monte_carlo(&law, 100_000, 2))
    };
    let y = design.evaluate(|x| ish.eval(x));
    let yt = test.evaluate(|x| ish.eval(x));
    let mt = yt.iter().sum::<f64>() / yt.len() as f64;
    let vt: f64 = yt.iter().map(|v| (v - mt).powi(2)).sum();
    println!("degree,terms,corrected_loo,held_out,fit_ms");
    for degree in 8..=14 {
        let t0 = Instant::now();
        let basis = PcBasis::total_degree(&m, degree)?;
        let (pc, rep) =
            PcSurrogate::lars_with(basis, design.points(), &y, &LarsOptions::default())?;
        let e = pc.expansion(&y)?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let pts: Vec<&[f64]> = test.iter().collect();
        let sq: f64 = pts
            .par_iter()
            .zip(&yt)
            .map(|(x, v)| (v - e.eval(x)).powi(2))
            .sum();
        println!(
            "{degree},{},{:.4e},{:.4e},{ms:.1}",
            rep.terms,
            rep.corrected_loo,
            sq / vt
        );
    }
    Ok(())
}
