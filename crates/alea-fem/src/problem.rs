//! One-shot linear-elastic solve: assemble `T^T K T u_free = T^T (f - K u_p)`, factorise,
//! solve, expand, recover reactions. Timings of each phase are returned for benchmarks.

use std::time::Instant;

use crate::{
    Cholesky, Constraints, DofMap, FemError, Loads, Model, Ordering, assemble_stiffness,
    post::internal_forces,
};

/// Wall-clock seconds of each phase of a solve.
#[derive(Clone, Copy, Debug, Default)]
pub struct Timings {
    /// Element matrices + scatter.
    pub assembly: f64,
    /// Ordering + symbolic factorisation.
    pub symbolic: f64,
    /// Numeric factorisation.
    pub numeric: f64,
    /// Triangular solves.
    pub solve: f64,
}

/// The result of a linear-elastic solve.
#[derive(Clone, Debug)]
pub struct ElasticSolution {
    /// Node-major displacements (`num_nodes * dim`).
    pub u: Vec<f64>,
    /// Node-major reaction forces `K u - f_ext` (non-zero only where constrained, up to
    /// round-off).
    pub reactions: Vec<f64>,
    /// Number of free unknowns.
    pub num_free: usize,
    /// Entries of the Cholesky factor.
    pub nnz_factor: usize,
    /// Phase timings.
    pub timings: Timings,
}

/// Solves `model` with `constraints` and `loads`.
pub fn solve_elastic(
    model: &Model,
    constraints: &Constraints,
    loads: &Loads,
    ordering: Ordering,
) -> Result<ElasticSolution, FemError> {
    let mut timings = Timings::default();
    let t0 = Instant::now();
    let dofs = DofMap::for_mesh(&model.mesh, constraints)?;
    let asm = assemble_stiffness(model, &dofs)?;
    timings.assembly = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let mut chol = Cholesky::new(&asm.k, ordering, Some(&dofs.node_of_dof()))?;
    timings.symbolic = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    chol.factorize(&asm.k)?;
    timings.numeric = t0.elapsed().as_secs_f64();
    let mut rhs = dofs.reduce(&loads.f);
    for (r, p) in rhs.iter_mut().zip(&asm.f_prescribed) {
        *r += p;
    }
    let t0 = Instant::now();
    chol.solve_in_place(&mut rhs);
    timings.solve = t0.elapsed().as_secs_f64();
    let u = dofs.expand(&rhs);
    if let Some(i) = u.iter().position(|v| !v.is_finite()) {
        return Err(FemError::Solver(format!(
            "non-finite displacement at node {} component {}",
            i / model.mesh.dim,
            i % model.mesh.dim
        )));
    }
    let mut reactions = internal_forces(model, &u)?;
    for (r, f) in reactions.iter_mut().zip(&loads.f) {
        *r -= f;
    }
    Ok(ElasticSolution {
        u,
        reactions,
        num_free: dofs.num_free(),
        nnz_factor: chol.nnz_factor(),
        timings,
    })
}
