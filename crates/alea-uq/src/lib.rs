//! # alea-uq: a stochastic toolkit
//!
//! Laws, designs, linear surrogates and statistics for non-intrusive uncertainty quantification.
//! The crate knows nothing about finite elements: a model is any function of the parameters, and
//! a surrogate sees only arrays of run values.
//!
//! Main types:
//! * [`law::Marginal`] and [`joint::JointLaw`]: one-dimensional laws and joint laws (independent,
//!   Gaussian copula, user density on a box) with their isoprobabilistic maps;
//! * [`design::Design`]: points where the model is run (Monte Carlo, LHS, Sobol', grids, PC
//!   collocation);
//! * [`surrogate::LinearSurrogate`]: every surrogate is **linear in the run data**,
//!   `q(xi) = sum_k w_k(xi) q_k` (thesis (1.22)), so the same weights interpolate scalars and
//!   whole fields. Implemented by [`surrogate::PcSurrogate`] (polynomial chaos by regression or
//!   projection), [`surrogate::MonomialSurface`] and [`surrogate::StochasticMesh`] (piecewise
//!   multilinear on an adaptive mesh with hanging nodes);
//! * [`stats`], [`kde::Kde`], [`sobol`]: Monte Carlo statistics, kernel density estimates, failure
//!   probabilities and Sobol' indices;
//! * [`reliability::LimitState`]: rare events on a model or surrogate (FORM, SORM, importance
//!   and subset sampling, goal-oriented refinement); [`validation`]: Q2, K-fold; [`fit`],
//!   [`copula`], [`io`]: laws from data, more copulas, CSV;
//! * [`field`]: random fields on a P1 mesh (covariance models, Galerkin Karhunen-Loeve
//!   expansion truncated at a variance fraction, lognormal and bounded transforms).
//!
//! ```
//! use alea_uq::{basis::PcBasis, design::latin_hypercube, joint::Independent, law::*};
//! use alea_uq::surrogate::{LinearSurrogate, PcSurrogate, StochasticMesh};
//! use std::sync::Arc;
//!
//! # fn main() -> alea_uq::Result<()> {
//! let m: Vec<Arc<dyn Marginal>> = vec![
//!     Arc::new(TruncatedNormal::new(1.0, 0.2, 0.5, 1.5)?),
//!     Arc::new(Uniform::new(0.0, 1.0)?),
//! ];
//! let law = Independent::new(m.clone())?;
//! let model = |x: &[f64]| x[0] * x[0] + x[1];
//!
//! // Polynomial chaos by regression: the weights do not depend on the values.
//! let design = latin_hypercube(&law, 30, 7);
//! let runs = design.evaluate(model);
//! let pc = PcSurrogate::regression(PcBasis::total_degree(&m, 2)?, design.points())?;
//! assert!((pc.eval(&[1.1, 0.3], &runs) - model(&[1.1, 0.3])).abs() < 1e-10);
//! let mean = pc.expansion(&runs)?.mean();
//! assert!((mean - (law.marginals()[0].std().powi(2) + 1.0 + 0.5)).abs() < 1e-10);
//!
//! // Piecewise bilinear on a stochastic mesh: refine, run the new points, interpolate.
//! let mut mesh = StochasticMesh::new(&[0.5, 0.0], &[1.5, 1.0], &[2, 2])?;
//! let mut q: Vec<f64> = (0..mesh.num_runs()).map(|k| model(mesh.run_point(k))).collect();
//! let cell = mesh.locate(&[0.6, 0.1]).unwrap();
//! for run in mesh.refine(&[cell])? {
//!     q.push(model(&run.point));
//! }
//! let mut w = Vec::new();
//! mesh.weights(&[0.6, 0.1], &mut w); // (run, weight) pairs
//! assert!((w.iter().map(|(k, wk)| wk * q[*k]).sum::<f64>() - mesh.eval(&[0.6, 0.1], &q)).abs() < 1e-14);
//! # Ok(())
//! # }
//! ```
//!
//! Determinism: every random routine takes a seed and splits its work in fixed chunks with their
//! own ChaCha8 stream, so results do not depend on the number of rayon threads.

pub mod basis;
pub mod bytes;
pub mod copula;
pub mod design;
pub mod eigen;
pub mod error;
pub mod field;
pub mod fit;
pub mod io;
pub mod joint;
pub mod kde;
pub mod law;
mod linalg;
pub mod quadrature;
pub mod reliability;
pub mod rng;
pub mod samples;
pub mod sobol;
pub mod special;
pub mod stats;
pub mod surrogate;
pub mod validation;

pub use error::{Result, UqError};
