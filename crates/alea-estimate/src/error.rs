//! Errors of the estimator.

/// What can go wrong when building or evaluating a stochastic estimate.
#[derive(Debug, thiserror::Error)]
pub enum EstimateError {
    /// Inconsistent or non-finite input (lengths, counts, factors).
    #[error("stochastic estimate: {0}")]
    Invalid(String),
    /// A size beyond what the estimator accepts (with the estimate in the message).
    #[error("stochastic estimate: {0}")]
    TooLarge(String),
    /// An error of the stochastic toolkit (laws, meshes, rules).
    #[error("stochastic estimate: {0}")]
    Uq(#[from] alea_uq::UqError),
}
