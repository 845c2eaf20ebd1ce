//! Errors of the mesh crate.

use std::path::PathBuf;

/// What can go wrong when building, reading or querying a mesh.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// A group name that the mesh does not have.
    #[error("unknown {kind} group '{name}' (the mesh has: {available})")]
    UnknownGroup {
        /// "cell", "facet" or "node".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// Comma-separated names the mesh does have.
        available: String,
    },
    /// A cell or facet refers to a node that does not exist.
    #[error("{what} refers to node {node}, but the mesh has {num_nodes} nodes")]
    NodeOutOfRange {
        /// Which cell or facet.
        what: String,
        /// The bad node index.
        node: usize,
        /// Number of nodes of the mesh.
        num_nodes: usize,
    },
    /// Bad generator or geometry input.
    #[error("invalid mesh input: {0}")]
    Invalid(String),
    /// A file could not be parsed: names the file, the line (1-based, 0 if unknown) and what was expected.
    #[error("{}:{line}: in section {section}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number (0 when the position is a byte offset in a binary block).
        line: usize,
        /// The section being read (e.g. "$Nodes").
        section: String,
        /// What was found and what was expected.
        message: String,
    },
    /// I/O failure on a file.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
}
