//! What can go wrong while producing a study's outputs.

use std::path::PathBuf;

use alea_study::StudyError;

use alea_report::ReportError;

/// An error of running a study or writing its outputs. The wrapped errors keep their own
/// messages and sources (`transparent`), so a front end shows them exactly as it would the
/// inner error.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Loading, running or analysing the study (its [`StudyError::exit_code`] says which kind).
    #[error(transparent)]
    Study(#[from] StudyError),
    /// Writing the report.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// An output file cannot be written.
    #[error("writing {}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A directory without a study store.
    #[error("{}: no study store here (no study.db)", dir.display())]
    NoStore { dir: PathBuf },
    /// A study store cannot be read (not a study directory, or not an SQLite store).
    #[error("{}: {message}", path.display())]
    Store { path: PathBuf, message: String },
    /// A bug: a non-finite value reached `summary.json`.
    #[error("internal error: a non-finite value reached summary.json")]
    NonFinite,
    /// A bug: `summary.json` could not be serialised.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
}
