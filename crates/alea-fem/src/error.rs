//! Errors of the FE crate.

/// What can go wrong when setting up or solving a linear-elastic problem.
#[derive(Debug, thiserror::Error)]
pub enum FemError {
    /// Mesh-level problem (unknown group, ...).
    #[error(transparent)]
    Mesh(#[from] alea_mesh::MeshError),
    /// Bad material data.
    #[error("invalid material: {0}")]
    InvalidMaterial(String),
    /// A cell with no material assigned, or another set-up inconsistency.
    #[error("invalid problem set-up: {0}")]
    Setup(String),
    /// A cell whose Jacobian is not positive at a quadrature point.
    #[error(
        "cell {cell} ({kind}) has a non-positive Jacobian {det:e} (inverted or degenerate element)"
    )]
    BadJacobian {
        /// Cell index.
        cell: usize,
        /// Cell type name.
        kind: String,
        /// The determinant found.
        det: f64,
    },
    /// Constraints that cannot hold together at a node.
    #[error("conflicting constraints at node {node}: {detail}")]
    ConflictingConstraints {
        /// Node index.
        node: usize,
        /// What conflicts.
        detail: String,
    },
    /// The stiffness matrix is not positive definite (usually an unconstrained rigid-body mode).
    #[error(
        "stiffness matrix is not positive definite: is the structure constrained against rigid-body motion?"
    )]
    NotPositiveDefinite,
    /// The sparse solver failed.
    #[error("sparse solver: {0}")]
    Solver(String),
}
