//! Polynomial chaos of the Ishigami function (a = 7, b = 0.1, x ~ U(-pi, pi)^3).
//!
//! Builds a degree-`p` total-degree Legendre chaos by least squares on a Latin hypercube
//! (thesis (1.29): s = (Psi^T Psi)^-1 Psi^T S), then prints the mean, variance, first-order
//! Sobol' indices and the leave-one-out error next to the exact values.
//!
//! Run: `cargo run -p alea-uq --release --example ishigami_pc`

use alea_uq::basis::PcBasis;
use alea_uq::design::latin_hypercube;
use alea_uq::joint::Independent;
use alea_uq::law::{Marginal, Uniform};
use alea_uq::samples::Ishigami;
use alea_uq::surrogate::{PcExpansion, PcSurrogate};
use std::f64::consts::PI;
use std::sync::Arc;

/// Fit the chaos of degree `degree` on `points` LHS points; returns the expansion and LOO error.
pub fn run(degree: usize, points: usize, seed: u64) -> alea_uq::Result<(PcExpansion, f64)> {
    // 1. Law of the inputs.
    let marginals: Vec<Arc<dyn Marginal>> = (0..3)
        .map(|_| Ok(Arc::new(Uniform::new(-PI, PI)?) as Arc<dyn Marginal>))
        .collect::<alea_uq::Result<_>>()?;
    let law = Independent::new(marginals.clone())?;
    // 2. Design and model runs.
    let design = latin_hypercube(&law, points, seed);
    let ishigami = Ishigami::default();
    let values = design.evaluate(|x| ishigami.eval(x));
    // 3. Surrogate (linear in the run values) and its statistics.
    let basis = PcBasis::total_degree(&marginals, degree)?;
    let pc = PcSurrogate::regression(basis, design.points())?;
    for w in pc.warnings() {
        eprintln!("warning: {w}");
    }
    Ok((pc.expansion(&values)?, pc.loo_error(&values)?))
}

#[allow(dead_code)]
fn main() -> alea_uq::Result<()> {
    let ish = Ishigami::default();
    let (e, loo) = run(10, 1000, 1)?;
    let s = e.sobol_first();
    let exact = ish.sobol_first();
    println!("terms      {}", e.coefficients().len());
    println!("mean       {:.5}  (exact {:.5})", e.mean(), ish.mean());
    println!(
        "variance   {:.5}  (exact {:.5})",
        e.variance(),
        ish.variance()
    );
    for i in 0..3 {
        println!("S{}         {:.5}  (exact {:.5})", i + 1, s[i], exact[i]);
    }
    println!("LOO error  {loo:.2e}");
    Ok(())
}
