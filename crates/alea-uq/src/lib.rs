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
//!   probabilities and Sobol' indices.
//!
//! Determinism: every random routine takes a seed and splits its work in fixed chunks with their
//! own ChaCha8 stream, so results do not depend on the number of rayon threads.

pub mod basis;
pub mod design;
pub mod error;
pub mod joint;
pub mod kde;
pub mod law;
mod linalg;
pub mod quadrature;
pub mod rng;
pub mod samples;
pub mod sobol;
pub mod special;
pub mod stats;
pub mod surrogate;

pub use error::{Result, UqError};
