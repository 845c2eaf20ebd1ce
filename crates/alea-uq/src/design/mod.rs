//! Designs of experiments: the points where a model is run.
//!
//! A [`Design`] is a row-major `n x dim` array of points. Random designs are generated in the unit
//! cube and mapped to the physical space by the isoprobabilistic map of a [`JointLaw`]
//! (`x = T^-1(u)`), so they respect dependent laws too.
//!
//! * [`monte_carlo`]: i.i.d. draws (seeded, identical for any number of threads);
//! * [`latin_hypercube`] / [`latin_hypercube_maximin`]: one point per stratum and direction;
//! * [`sobol`]: Sobol' sequence (Joe-Kuo direction numbers, up to 40 dimensions), optionally
//!   scrambled by a random linear matrix scramble and digital shift (Matousek);
//! * [`tensor_grid`], [`corners_and_centre`]: deterministic designs on a box;
//! * [`pc_collocation`]: roots of the next-degree orthogonal polynomial (thesis 2.3, Sudret),
//!   a subset of their tensor grid chosen greedily D-optimal ([`d_optimal_subset`]);
//! * [`information`]: rank and condition number of the information matrix `Psi^T Psi / n` of a
//!   basis on a design - whether a least-squares surrogate is determined by it.

mod grid;
mod information;
mod lhs;
mod mc;
mod pc_points;
mod sobol_seq;

pub use grid::{corners_and_centre, tensor_grid};
pub use information::{Information, information};
pub use lhs::{latin_hypercube, latin_hypercube_maximin};
pub use mc::monte_carlo;
pub use pc_points::{d_optimal_subset, pc_collocation};
pub use sobol_seq::{SOBOL_MAX_DIM, SobolSequence, sobol};

use crate::joint::JointLaw;

/// Points of a design, row-major `len x dim`.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    dim: usize,
    points: Vec<f64>,
}

impl Design {
    /// Wrap raw points.
    ///
    /// # Errors
    /// If `points.len()` is not a multiple of `dim` or `dim == 0`.
    pub fn new(dim: usize, points: Vec<f64>) -> crate::Result<Self> {
        if dim == 0 || !points.len().is_multiple_of(dim) {
            return Err(crate::UqError::Invalid {
                what: "design",
                message: format!(
                    "{} values do not form points of dimension {dim}",
                    points.len()
                ),
            });
        }
        Ok(Self { dim, points })
    }
    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len() / self.dim
    }
    /// `true` if there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
    /// Point `i`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dim..(i + 1) * self.dim]
    }
    /// All points, row-major.
    pub fn points(&self) -> &[f64] {
        &self.points
    }
    /// Iterate over points.
    pub fn iter(&self) -> impl Iterator<Item = &[f64]> {
        self.points.chunks_exact(self.dim)
    }
    /// Map unit-cube points through `law.unit_to_x`.
    pub fn map_from_unit(&self, law: &dyn JointLaw) -> Design {
        let mut out = vec![0.0; self.points.len()];
        for (u, x) in self
            .points
            .chunks_exact(self.dim)
            .zip(out.chunks_exact_mut(self.dim))
        {
            law.unit_to_x(u, x);
        }
        Design {
            dim: self.dim,
            points: out,
        }
    }
    /// Evaluate a model at every point (in parallel, order preserved).
    pub fn evaluate(&self, f: impl Fn(&[f64]) -> f64 + Sync) -> Vec<f64> {
        use rayon::prelude::*;
        self.points.par_chunks_exact(self.dim).map(&f).collect()
    }
}
