//! Errors of studies: every input error names the file, the line and the field.

use std::path::PathBuf;

/// What can go wrong with a study or model file, or while running it.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// A value in an input file is missing, malformed or invalid.
    #[error("{}:{line}: {field}: {message}", file.display())]
    Input {
        /// The file.
        file: PathBuf,
        /// 1-based line (0 if unknown).
        line: usize,
        /// Dotted path of the field (e.g. `substructure[1].young`).
        field: String,
        /// What is wrong and what was expected.
        message: String,
    },
    /// File system error.
    #[error("{}: {source}", path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The error.
        #[source]
        source: std::io::Error,
    },
    /// Mesh error.
    #[error(transparent)]
    Mesh(#[from] alea_mesh::MeshError),
    /// Finite-element error.
    #[error(transparent)]
    Fem(#[from] alea_fem::FemError),
    /// Solver error.
    #[error(transparent)]
    Latin(#[from] alea_latin::LatinError),
    /// Anything else, described.
    #[error("{0}")]
    Other(String),
}

impl StudyError {
    /// Process exit code for this kind of error: 2 for input errors, 3 for I/O, 4 for
    /// computation failures.
    pub fn exit_code(&self) -> i32 {
        match self {
            StudyError::Input { .. } => 2,
            StudyError::Io { .. } => 3,
            _ => 4,
        }
    }
}
