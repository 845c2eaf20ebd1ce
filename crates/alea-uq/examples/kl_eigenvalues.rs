//! Galerkin Karhunen-Loeve of a covariance kernel on a uniform mesh of `[-a, a]`, printed as JSON
//! (`eigenvalues`, `modes` at the nodes, `seconds`) for `scripts/kl_vs_openturns.py`.
//!
//! ```text
//! cargo run -p alea-uq --release --example kl_eigenvalues -- [a L cells modes kernel integration]
//! ```
//!
//! Defaults: `a = 1`, `L = 1`, 100 cells, 20 modes, kernel `exponential` (also
//! `squared-exponential`, `matern32`, `matern52`), integration `quadrature` (or `nodal`, the
//! kernel interpolated at the nodes as in OpenTURNS's `KarhunenLoeveP1Algorithm`); unit variance.

use alea_uq::field::{
    Covariance, FieldMesh, KernelIntegration, KernelShape, KlExpansion, Truncation,
};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or_else(|| default.to_string());
    let a: f64 = arg(0, "1").parse()?;
    let len: f64 = arg(1, "1").parse()?;
    let cells: usize = arg(2, "100").parse()?;
    let modes: usize = arg(3, "20").parse()?;
    let shape = match arg(4, "exponential").as_str() {
        "exponential" => KernelShape::Exponential,
        "squared-exponential" => KernelShape::SquaredExponential,
        "matern32" => KernelShape::Matern32,
        "matern52" => KernelShape::Matern52,
        other => return Err(format!("unknown kernel {other}").into()),
    };
    let integration = match arg(5, "quadrature").as_str() {
        "quadrature" => KernelIntegration::Quadrature,
        "nodal" => KernelIntegration::NodalInterpolation,
        other => return Err(format!("unknown integration {other}").into()),
    };
    let start = Instant::now();
    let mesh = FieldMesh::interval(-a, a, cells)?;
    let cov = Covariance::new(shape, 1.0, len)?;
    let kl = KlExpansion::galerkin_with(&mesh, &cov, Truncation::Modes(modes), integration)?;
    let seconds = start.elapsed().as_secs_f64();
    let out = serde_json::json!({
        "eigenvalues": kl.eigenvalues(),
        "modes": (0..kl.num_modes()).map(|k| kl.mode(k).to_vec()).collect::<Vec<_>>(),
        "seconds": seconds,
    });
    println!("{out}");
    Ok(())
}
