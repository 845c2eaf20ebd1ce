//! Random fields discretised by Karhunen-Loeve (KL) expansion.
//!
//! A second-order random field `g(x)` over a domain `D` (a contact line meshed by segments, or a
//! surface meshed by triangles) with mean `m` and covariance `k(x, y)` is expanded as
//!
//! ```text
//! g(x) = m + sum_k sqrt(lambda_k) phi_k(x) xi_k,   int_D k(x, y) phi_k(y) dy = lambda_k phi_k(x),
//! ```
//!
//! with `xi_k` independent standard normal variables for a Gaussian field and
//! `int_D phi_k phi_l = delta_kl`. Since `sum_k lambda_k = int_D k(x, x) dx = sigma^2 |D|`, the
//! series is truncated when the kept eigenvalues reach a stated fraction of `sigma^2 |D|`.
//!
//! * [`covariance`]: squared-exponential, exponential and Matern (nu = 3/2, 5/2) kernels with a
//!   variance and (anisotropic) correlation lengths;
//! * [`mesh`]: nodes and P1 cells, mass matrix;
//! * [`kl`]: the Galerkin discretisation `C v = lambda M v` (P1 basis) and realisations;
//! * [`transform`]: the Gaussian field and its lognormal and bounded transforms.
//!
//! ```
//! use alea_uq::field::*;
//! # fn main() -> alea_uq::Result<()> {
//! // mu(x) along a 10 mm flank: mean 0.3, std 0.05, correlation length 2 mm.
//! let mesh = FieldMesh::interval(0.0, 10.0, 100)?;
//! let cov = Covariance::new(KernelShape::Exponential, 0.05f64.powi(2), 2.0)?;
//! let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::VarianceFraction(0.9))?;
//! assert!(kl.captured_fraction() >= 0.9);
//! let mu = RandomField::new(0.3, 0.05, FieldTransform::Gaussian, kl)?;
//! let xi = vec![0.0; mu.num_variables()];
//! assert!(mu.at_nodes(&xi)?.iter().all(|v| (v - 0.3).abs() < 1e-15));
//! # Ok(())
//! # }
//! ```

pub mod covariance;
pub mod kl;
pub mod mesh;
pub mod transform;

pub use covariance::{Covariance, KernelShape};
pub use kl::{KernelIntegration, KlExpansion, Truncation};
pub use mesh::{FieldCells, FieldMesh};
pub use transform::{FieldTransform, RandomField, lognormal_gaussian_parameters};
