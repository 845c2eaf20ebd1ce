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
    /// Deterministic error-estimator error (admissible stresses of a run).
    #[error(transparent)]
    Cre(#[from] alea_cre::CreError),
    /// Stochastic error-estimate error (Gram matrices, rules, criteria).
    #[error(transparent)]
    Estimate(#[from] alea_estimate::EstimateError),
    /// Stochastic toolkit error (laws, designs, surrogates, the stochastic mesh).
    #[error(transparent)]
    Uq(#[from] alea_uq::UqError),
    /// A command-line argument or study directory that cannot be used as asked.
    #[error("{0}")]
    Usage(String),
    /// Another process holds the study directory's lock.
    #[error(
        "{} is in use by {holder}; wait for it to finish, stop it, or use another --dir",
        dir.display()
    )]
    Busy {
        /// The study directory.
        dir: PathBuf,
        /// Who holds it (pid, host, start time, command).
        holder: String,
    },
    /// A size that cannot be handled (memory, run count, threads): the estimate is in the
    /// message.
    #[error("{0}")]
    TooLarge(String),
    /// The computation ran but gave no usable result (no run converged, no method produced
    /// statistics).
    #[error("{0}")]
    Failed(String),
    /// Anything else, described.
    #[error("{0}")]
    Other(String),
}

impl StudyError {
    /// Process exit code for this kind of error (the table is in `docs/study-file.md`): 2 for
    /// input errors (including sizes beyond the limits), 3 for file-system errors, 4 for
    /// computation failures, 5 for a study directory in use by another process.
    pub fn exit_code(&self) -> i32 {
        match self {
            StudyError::Input { .. } | StudyError::Usage(_) | StudyError::TooLarge(_) => 2,
            StudyError::Io { .. } => 3,
            StudyError::Mesh(alea_mesh::MeshError::Io { .. })
            | StudyError::Latin(alea_latin::LatinError::Io { .. })
            | StudyError::Latin(alea_latin::LatinError::Mesh {
                source: alea_mesh::MeshError::Io { .. },
                ..
            }) => 3,
            StudyError::Busy { .. } => 5,
            _ => 4,
        }
    }
}
