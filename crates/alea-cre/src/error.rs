//! Errors of the estimator.

/// What can go wrong when estimating the error.
#[derive(Debug, thiserror::Error)]
pub enum CreError {
    /// Mesh-level problem (unknown group, ...).
    #[error(transparent)]
    Mesh(#[from] alea_mesh::MeshError),
    /// FE-level problem (material, constraints, Jacobian).
    #[error(transparent)]
    Fem(#[from] alea_fem::FemError),
    /// A cell type the estimator does not handle.
    #[error("cell {cell}: the EET estimator handles Tri3, Quad4, Tri6 and Quad8 cells, not {kind}")]
    UnsupportedCell {
        /// Cell index.
        cell: usize,
        /// Cell type name.
        kind: String,
    },
    /// Inconsistent input (lengths, indices, non-finite data).
    #[error("invalid input: {0}")]
    Invalid(String),
    /// A local (element) problem could not be solved.
    #[error("element {cell}: local Neumann problem is singular or not positive definite")]
    LocalSolve {
        /// Cell index.
        cell: usize,
    },
}
