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
    /// A method's surrogate that cannot be built on its runs.
    #[error(transparent)]
    Surrogate(#[from] SurrogateError),
    /// The study database failed (a file-system failure is [`StudyError::Io`]).
    #[error("study database in {}: {error}", dir.display())]
    Database {
        /// The study directory.
        dir: PathBuf,
        /// The database error.
        error: rusqlite::Error,
    },
    /// A stored field or error-estimate file that is truncated or corrupt.
    #[error("{} is truncated or corrupt", path.display())]
    Corrupt {
        /// The file.
        path: PathBuf,
    },
    /// A stored file written by another study (another study hash).
    #[error(
        "{} belongs to another study (hash {hash}, this study {study}); run again with --restart",
        path.display()
    )]
    ForeignFile {
        /// The file.
        path: PathBuf,
        /// The hash in the file.
        hash: String,
        /// This study's hash.
        study: String,
    },
    /// A run's stored data in the study database that cannot be used: missing, damaged, or
    /// written by another study (`why` says which).
    #[error("study database in {}: the {what} of the run at {params:?} {why}", dir.display())]
    RunData {
        /// The study directory.
        dir: PathBuf,
        /// The run's parameters.
        params: Vec<f64>,
        /// `field data` or `error-estimate data`.
        what: &'static str,
        /// What is wrong with it (`is missing`, `belongs to another study ...`, ...).
        why: String,
    },
    /// A run's stored field data with another number of values than the model has.
    #[error("field data of the run at {params:?} has {found} values, expected {expected}")]
    FieldSize {
        /// The run's parameters.
        params: Vec<f64>,
        /// Values in the file.
        found: usize,
        /// Values of the model.
        expected: usize,
    },
    /// A run without a stored error estimate.
    #[error(
        "the run at {params:?} has no stored error estimate{}",
        if *restart_hint {
            " (a study run before error estimation was enabled: run it again with --restart)"
        } else {
            ""
        }
    )]
    NoEstimate {
        /// The run's parameters.
        params: Vec<f64>,
        /// Whether the message says how to recover (run again with `--restart`).
        restart_hint: bool,
    },
    /// A run's stored error estimate that does not decode.
    #[error("the stored error estimate of the run at {params:?} is damaged")]
    DamagedEstimate {
        /// The run's parameters.
        params: Vec<f64>,
    },
    /// A stored error estimate of another model (other substructures).
    #[error(
        "a stored error estimate does not match the model{}",
        if *restart_hint { " (run the study with --restart)" } else { "" }
    )]
    StaleEstimate {
        /// Whether the message says how to recover (run again with `--restart`).
        restart_hint: bool,
    },
    /// A stored error estimate of another mesh of a substructure.
    #[error("substructure '{sub}': stored error estimate of another mesh")]
    EstimateMesh {
        /// The substructure.
        sub: String,
    },
    /// A stored displacement field shorter than the model.
    #[error("a stored displacement field is shorter than the model")]
    ShortField,
    /// A run's field values, as loaded for the field statistics, of the wrong length.
    #[error("run {run} has {found} field values, expected {expected}")]
    RunFieldSize {
        /// The run (index among the method's runs).
        run: usize,
        /// Values loaded.
        found: usize,
        /// Values expected.
        expected: usize,
    },
    /// Field statistics asked of Monte Carlo on the model (no surrogate to sample).
    #[error("Monte Carlo on the model has no surrogate for fields")]
    MonteCarloFields,
    /// Field statistics without parameters or without Monte Carlo draws.
    #[error("no Monte Carlo draws for the field statistics")]
    NoFieldDraws,
    /// The error estimator of a substructure cannot be set up.
    ///
    /// The estimator error is in the message, so it is a field and not the error's `source`
    /// (the command line prints the source chain after the message).
    #[error("substructure '{sub}': {error}")]
    SubEstimator {
        /// The substructure.
        sub: String,
        /// The estimator error.
        error: alea_cre::CreError,
    },
    /// The error estimator of the assembly cannot be set up (the error is in the message).
    #[error("error estimator set-up: {0}")]
    EstimatorSetup(alea_cre::CreError),
    /// The error estimate of one run failed (the error is in the message).
    #[error("error estimate of the run at {theta:?}: {error}")]
    RunEstimate {
        /// The run's parameters.
        theta: Vec<f64>,
        /// The estimator error.
        error: alea_cre::CreError,
    },
    /// A method's integration rule of the error estimate cannot be built (the error is in the
    /// message).
    #[error("method '{method}': {error}")]
    MethodRule {
        /// The method's label.
        method: String,
        /// The rule error.
        error: alea_estimate::EstimateError,
    },
    /// The facets of an interface side cannot be found (the error is in the message).
    #[error("interface '{interface}', substructure '{sub}': {error}")]
    InterfaceFacets {
        /// The interface.
        interface: String,
        /// The substructure.
        sub: String,
        /// The mesh error (boxed: it would make every `StudyError` larger).
        error: Box<alea_mesh::MeshError>,
    },
    /// A quantity of interest at a point that is not on its interface.
    #[error("quantity '{qoi}': its point is not on interface '{interface}'")]
    QoiOffInterface {
        /// The quantity.
        qoi: String,
        /// The interface.
        interface: String,
    },
    /// A converged run with a quantity of interest that is not finite.
    #[error("a quantity of interest is not finite at {theta:?}")]
    NonFiniteQoi {
        /// The run's parameters.
        theta: Vec<f64>,
    },
    /// The user asked to stop ([`crate::runner::Progress::stop_requested`]): the runs that
    /// finished are committed to the store and the next invocation resumes from them.
    #[error(
        "interrupted: the finished runs are in the study directory and a new run resumes from them"
    )]
    Interrupted,
    /// A lock held by a thread that panicked.
    #[error("{0} lock poisoned")]
    Poisoned(&'static str),
    /// A failure of the distributed (MPI) execution: set-up, a rank, the messages.
    #[error("{0}")]
    Mpi(String),
    /// An invariant of alea that does not hold (a bug: please report it with the input).
    #[error("{0}")]
    Internal(String),
}

impl StudyError {
    /// Process exit code for this kind of error (the table is in `docs/study-file.md`): 2 for
    /// input errors (including sizes beyond the limits), 3 for file-system and store errors (a
    /// corrupt `study.db`, damaged or foreign stored run data), 4 for
    /// computation failures, 5 for a study directory in use by another process.
    pub fn exit_code(&self) -> i32 {
        match self {
            StudyError::Input { .. } | StudyError::Usage(_) | StudyError::TooLarge(_) => 2,
            // The store: its database or a stored file that cannot be used.
            StudyError::Io { .. }
            | StudyError::Database { .. }
            | StudyError::Corrupt { .. }
            | StudyError::RunData { .. }
            | StudyError::ForeignFile { .. } => 3,
            StudyError::Mesh(alea_mesh::MeshError::Io { .. })
            | StudyError::Latin(alea_latin::LatinError::Io { .. })
            | StudyError::Latin(alea_latin::LatinError::Mesh {
                source: alea_mesh::MeshError::Io { .. },
                ..
            }) => 3,
            StudyError::Busy { .. } => 5,
            // The shell's code of a process stopped by SIGINT (128 + 2).
            StudyError::Interrupted => 130,
            _ => 4,
        }
    }
}

/// Why a method's surrogate cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum SurrogateError {
    /// The fit failed (basis, regression, projection, grid).
    #[error(transparent)]
    Uq(#[from] alea_uq::UqError),
    /// The method has no surrogate on these runs (the reason).
    #[error("{0}")]
    Unavailable(&'static str),
}

/// The message, for callers that keep a method's failure as text.
impl From<SurrogateError> for String {
    fn from(e: SurrogateError) -> String {
        e.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The typed variants print the texts their `Other(String)` predecessors printed, and
    /// keep their exit code (4, a computation failure).
    #[test]
    fn typed_variants_keep_the_former_messages_and_exit_code() {
        let cases = [
            (
                StudyError::NoEstimate {
                    params: vec![1.0, 0.5],
                    restart_hint: true,
                },
                "the run at [1.0, 0.5] has no stored error estimate (a study run before error \
                 estimation was enabled: run it again with --restart)",
            ),
            (
                StudyError::NoEstimate {
                    params: vec![2.0],
                    restart_hint: false,
                },
                "the run at [2.0] has no stored error estimate",
            ),
            (
                StudyError::StaleEstimate { restart_hint: true },
                "a stored error estimate does not match the model (run the study with --restart)",
            ),
            (
                StudyError::StaleEstimate {
                    restart_hint: false,
                },
                "a stored error estimate does not match the model",
            ),
            (
                StudyError::FieldSize {
                    params: vec![0.25],
                    found: 3,
                    expected: 4,
                },
                "field data of the run at [0.25] has 3 values, expected 4",
            ),
            (StudyError::Poisoned("run list"), "run list lock poisoned"),
            (
                StudyError::Surrogate(SurrogateError::Unavailable("Monte Carlo has no surrogate")),
                "Monte Carlo has no surrogate",
            ),
        ];
        for (e, text) in cases {
            assert_eq!(e.to_string(), text);
            assert_eq!(e.exit_code(), 4);
        }
        // Errors of the store are file-system errors (3), like a failing disk.
        let foreign = StudyError::ForeignFile {
            path: "d/f.bin".into(),
            hash: "abc".into(),
            study: "def".into(),
        };
        assert_eq!(
            foreign.to_string(),
            "d/f.bin belongs to another study (hash abc, this study def); run again with --restart"
        );
        assert_eq!(foreign.exit_code(), 3);
        assert_eq!(StudyError::Corrupt { path: "f".into() }.exit_code(), 3);
        let data = StudyError::RunData {
            dir: "d".into(),
            params: vec![0.5],
            what: "field data",
            why: "is missing".into(),
        };
        assert_eq!(
            data.to_string(),
            "study database in d: the field data of the run at [0.5] is missing"
        );
        assert_eq!(data.exit_code(), 3);
        let db = StudyError::Database {
            dir: "d".into(),
            error: rusqlite::Error::InvalidQuery,
        };
        assert_eq!(db.exit_code(), 3);
    }
}
