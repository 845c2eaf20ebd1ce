//! The validation part of the error budget (issue 40, item 1): statistics corrected by runs of
//! the solver at points drawn from the input law independently of the design, with intervals
//! that include the surrogate's error.

use serde::{Deserialize, Serialize};

/// A statistic corrected by validation runs, and the half-width of its interval from the
/// surrogate's draws and the validation runs together (at the study's confidence level).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Corrected {
    /// The corrected statistic.
    pub value: f64,
    /// Half-width of its interval from the draws on the surrogate and the validation runs
    /// (sampling and surrogate error together; the mesh and sliding parts are added to it in
    /// the row's total).
    pub half_width: f64,
    /// Converged validation runs behind it.
    pub runs: usize,
}
