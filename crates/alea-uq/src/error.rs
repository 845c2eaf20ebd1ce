//! Error type of the crate.
//!
//! Every variant names the object (law, design, surrogate) and the offending field, so a
//! message such as `truncated normal: std must be > 0, got -1` can be shown to a user as is.

use thiserror::Error;

/// Errors returned by constructors and fitting routines of `alea-uq`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum UqError {
    /// A parameter of a law, design or surrogate is out of its admissible range.
    #[error("{what}: {field} must be {requirement}, got {value}")]
    InvalidParameter {
        /// Object being built, e.g. `"truncated normal"`.
        what: &'static str,
        /// Offending field, e.g. `"std"`.
        field: &'static str,
        /// Requirement in words, e.g. `"> 0"`.
        requirement: &'static str,
        /// Value supplied.
        value: f64,
    },
    /// A structural problem (sizes, empty sets, non-SPD matrices...).
    #[error("{what}: {message}")]
    Invalid {
        /// Object being built.
        what: &'static str,
        /// Explanation.
        message: String,
    },
    /// Array lengths that must agree do not.
    #[error("{what}: {field} has length {got}, expected {expected}")]
    DimensionMismatch {
        /// Object or routine.
        what: &'static str,
        /// Offending argument.
        field: &'static str,
        /// Length expected.
        expected: usize,
        /// Length supplied.
        got: usize,
    },
    /// Reading or writing a file failed, or its content is malformed (the message names the
    /// line and column).
    #[error("{path}: {message}")]
    File {
        /// File path.
        path: String,
        /// What went wrong, e.g. `line 3, column "x2": "abc" is not a number`.
        message: String,
    },
    /// A least-squares or factorisation problem is (numerically) singular.
    #[error("{what}: matrix is singular or rank deficient (pivot {pivot} of {size})")]
    Singular {
        /// Routine that failed.
        what: &'static str,
        /// Index of the zero pivot.
        pivot: usize,
        /// Size of the system.
        size: usize,
    },
}

/// Shorthand result type.
pub type Result<T> = std::result::Result<T, UqError>;

/// Build an [`UqError::InvalidParameter`].
pub(crate) fn invalid(
    what: &'static str,
    field: &'static str,
    requirement: &'static str,
    value: f64,
) -> UqError {
    UqError::InvalidParameter {
        what,
        field,
        requirement,
        value,
    }
}

/// Check that two lengths agree.
pub(crate) fn check_len(
    what: &'static str,
    field: &'static str,
    expected: usize,
    got: usize,
) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(UqError::DimensionMismatch {
            what,
            field,
            expected,
            got,
        })
    }
}
