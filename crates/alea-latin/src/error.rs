//! Errors of the LATIN crate.

/// What can go wrong when setting up or running the substructured solver.
#[derive(Debug, thiserror::Error)]
pub enum LatinError {
    /// Finite-element level error in a substructure.
    #[error("substructure '{sub}': {source}")]
    Fem {
        /// Substructure name.
        sub: String,
        /// Underlying error.
        #[source]
        source: alea_fem::FemError,
    },
    /// Mesh-level error (unknown group ...) in a substructure.
    #[error("substructure '{sub}': {source}")]
    Mesh {
        /// Substructure name.
        sub: String,
        /// Underlying error.
        #[source]
        source: alea_mesh::MeshError,
    },
    /// The two sides of an interface do not match node to node.
    #[error(
        "interface '{interface}': sides do not match node to node ({side1} nodes on side 1, {side2} on side 2); worst unmatched distance {worst:e} at ({:.6}, {:.6}, {:.6}), tolerance {tol:e}",
        at[0], at[1], at[2]
    )]
    Unmatched {
        /// Interface name.
        interface: String,
        /// Nodes on side 1.
        side1: usize,
        /// Nodes on side 2.
        side2: usize,
        /// Largest distance from a side-1 node to its nearest side-2 node.
        worst: f64,
        /// Where.
        at: [f64; 3],
        /// Matching tolerance.
        tol: f64,
    },
    /// An output file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The error.
        #[source]
        source: std::io::Error,
    },
    /// The two sides of an interface cannot be paired by the mortar method (no part of side 2
    /// faces side 1 within the search distance, unsupported facets, overlapping layers).
    #[error("interface '{interface}': {message}")]
    Pairing {
        /// Interface name.
        interface: String,
        /// What is wrong.
        message: String,
    },
    /// The two faces of a cyclic interface do not map onto each other under its rotation, or
    /// the interface is not one that cyclic symmetry applies to (module [`crate::cyclic`]).
    #[error("interface '{interface}': cyclic symmetry: {message}")]
    Cyclic {
        /// Interface name.
        interface: String,
        /// What is wrong.
        message: String,
    },
    /// The dense interface operators of the condensed linear stage (forced by
    /// `LinearStage::Condensed`) would not fit in a quarter of the available memory.
    #[error(
        "the condensed linear stage needs {:.1} MB for its dense interface operators (largest: substructure '{largest}', {unknowns} interface unknowns), more than a quarter of the {:.1} MB available; use the volume linear stage ([solver] linear_stage = \"volume\" or \"auto\")",
        bytes / 1e6, available / 1e6
    )]
    CondensedMemory {
        /// Bytes of the operators.
        bytes: f64,
        /// Bytes available.
        available: f64,
        /// The substructure with the most interface unknowns.
        largest: String,
        /// Its interface unknowns.
        unknowns: usize,
    },
    /// The set-up of a substructure owned by another rank failed, in a solver spread over
    /// ranks (module [`crate::ranks`]): every rank stops with the first failing rank's error.
    #[error("rank {rank}: {message}")]
    OtherRank {
        /// The rank whose set-up failed.
        rank: usize,
        /// Its error.
        message: String,
    },
    /// Inconsistent set-up or run input.
    #[error("{0}")]
    Invalid(String),
}
