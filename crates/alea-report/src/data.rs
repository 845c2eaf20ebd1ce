//! What the report is made of: a plain data structure the study runner fills in.
//!
//! Everything here is serialisable (serde; a study does not save it: `alea report DIR` rebuilds
//! the report from the study's store). `write_report` validates it first: every number
//! must be finite (a NaN anywhere is an error naming its field), except the bounds `lo`/`hi`
//! of a parameter, which may be infinite (an untruncated law).

#[cfg(test)]
use std::path::Path;

use serde::{Deserialize, Serialize};

#[cfg(test)]
use super::ReportError;

/// Everything the report shows about one study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReportInput {
    /// Title of the page (the study's name).
    pub title: String,
    /// Path of the study file, shown as is.
    pub study_file: String,
    /// Units by quantity kind: `("length", "mm")`, `("stress", "MPa")`, ...
    pub units: Vec<(String, String)>,
    /// The surrogate method in words, e.g. "polynomial chaos, degree 2, regression on 9 runs".
    pub method: String,
    /// The random parameters, in the order of `RunInfo::params`.
    pub parameters: Vec<ParamInfo>,
    /// Every deterministic run of the study (converged or not).
    pub runs: Vec<RunInfo>,
    /// LATIN error indicator per iteration for a few runs: (label, history).
    pub residual_histories: Vec<(String, Vec<f64>)>,
    /// The quantities of interest, in the order of `RunInfo::qois`.
    pub qois: Vec<QoiReport>,
    /// Methods side by side on one QoI (thesis table 2.1), when the study asked for it.
    pub comparison: Option<Comparison>,
    /// Wall time per step: ("solves", s), ("surrogate", s), ("monte carlo", s) ...
    pub timings: Vec<(String, f64)>,
    /// Warnings shown prominently at the top of the report.
    pub notes: Vec<String>,
    /// The stochastic error estimate (thesis 3.2, 4.1-4.2), when the study has one.
    #[serde(default)]
    pub error: Option<ErrorReport>,
    /// The `[[reliability]]` analyses.
    #[serde(default)]
    pub reliability: Vec<ReliabilityReport>,
}

/// The stochastic error estimate of a study: per method, per entity of the main method, the
/// adaptive steps, and the error-density map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ErrorReport {
    /// The warning threshold of `i_geo` and `i_sto`.
    pub warn: f64,
    /// One row per method with a surrogate.
    pub methods: Vec<ErrorRow>,
    /// The method whose entities and map are shown.
    pub main: String,
    /// Entities of the main method.
    pub entities: Vec<EntityRow>,
    /// Adaptive methods' steps.
    pub adaptive: Vec<AdaptiveReport>,
    /// Density of the stochastic error over the first two parameters (others integrated), with
    /// the runs as points.
    pub map: Option<Surface>,
    /// The ParaView file of the mean error density per cell, when written.
    pub vtu: Option<String>,
}

/// The indicators of one method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ErrorRow {
    pub method: String,
    pub runs: usize,
    /// `e~` relative to the energy of the admissible stresses.
    pub relative: f64,
    pub i_geo: f64,
    pub i_sto: f64,
    /// The entity that carries most of `e~^2`, and its share.
    pub dominant: String,
    /// Probability of points where the interpolated interface fields are not admissible.
    pub violation: f64,
}

/// The indicators of one entity (substructure or interface).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EntityRow {
    pub entity: String,
    pub kind: String,
    pub relative: f64,
    pub i_geo: f64,
    pub i_sto: f64,
    /// Substructures: shares of the mean and standard-deviation parts (3.32) in `e^2`.
    pub mean_share: Option<f64>,
}

/// The steps of one adaptive method.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AdaptiveReport {
    pub method: String,
    /// Why it stopped.
    pub stop: String,
    /// The quantity whose statistics are listed per step.
    pub qoi: String,
    pub steps: Vec<StepRow>,
}

/// One adaptive step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StepRow {
    pub runs: usize,
    pub new_runs: usize,
    pub i_sto: f64,
    pub i_geo: f64,
    pub relative: f64,
    pub mean: f64,
    pub std: f64,
    /// `P(q > threshold)` for the quantity's first threshold, if any.
    pub failure: Option<f64>,
    /// Cumulative cost in the thesis's units (run 1, estimate 1.5).
    pub cost: f64,
}

/// One random parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParamInfo {
    pub name: String,
    /// The law in words, e.g. "truncated normal (240e3, 10e3) on [210e3, 270e3]".
    pub law: String,
    /// Lower bound of the support (may be -inf; JSON holds it as the string "-inf").
    #[serde(with = "bound")]
    pub lo: f64,
    /// Upper bound of the support (may be +inf; JSON holds it as the string "inf").
    #[serde(with = "bound")]
    pub hi: f64,
}

/// One deterministic run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunInfo {
    /// Parameter values, in the order of `ReportInput::parameters`.
    pub params: Vec<f64>,
    /// "converged", "not converged", "failed", ...
    pub status: String,
    /// LATIN iterations.
    pub iterations: usize,
    /// Wall time of the run in seconds.
    pub seconds: f64,
    /// QoI values in the order of `ReportInput::qois`; empty for a run that produced none.
    pub qois: Vec<f64>,
}

/// The distribution of one quantity of interest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QoiReport {
    pub name: String,
    pub unit: String,
    /// What it measures, in words (`resultant Fz on side 2 of interface 'I2'`).
    #[serde(default)]
    pub what: String,
    /// Monte Carlo samples on the surrogate (may be 250 000; plots subsample as needed).
    pub samples: Vec<f64>,
    pub mean: f64,
    pub std: f64,
    pub skewness: f64,
    /// (probability, value).
    pub quantiles: Vec<(f64, f64)>,
    /// (x, pdf) on a grid: the kernel density of the samples, or with atoms that of the other
    /// samples scaled by their share (it integrates to 1 minus the atoms' probabilities).
    pub kde: Vec<(f64, f64)>,
    /// Values the samples take exactly with a probability of at least 1 % (a contact that
    /// opens: many exact zeros), drawn as atoms (`alea_study::atoms`).
    #[serde(default)]
    pub atoms: Vec<Atom>,
    /// Failure probabilities for the user's thresholds.
    pub failure: Vec<FailureInfo>,
    /// The response surface over two parameters, when there is one to show.
    pub surface: Option<Surface>,
    /// The error budget of each statistic (empty when not estimated).
    #[serde(default)]
    pub budget: Vec<BudgetRow>,
    /// How the budget's parts were estimated (one sentence each).
    #[serde(default)]
    pub budget_basis: Vec<String>,
    /// Sobol' indices `(parameter, first order, total)` of the main method's surrogate
    /// (studies with random fields; empty otherwise).
    #[serde(default)]
    pub sobol: Vec<(String, f64, f64)>,
    /// How they were computed (one sentence).
    #[serde(default)]
    pub sobol_basis: String,
}

/// The error budget of one statistic (each part estimated, `None` when not): the study's own
/// row type, drawn as it is. What users read of it: [`BudgetRow::estimate`] and
/// [`BudgetRow::interval`] (the total interval).
pub use alea_study::budget::BudgetRow;

/// A probability atom of a quantity (value, probability, its sampling-only Wilson interval):
/// the study's own type.
pub use alea_study::atoms::Atom;

/// The statistic a budget row is of: the study's own type.
pub use alea_study::budget::Statistic;

/// The budget row of `statistic` in `rows`, if estimated.
pub fn budget_row(rows: &[BudgetRow], statistic: Statistic) -> Option<&BudgetRow> {
    rows.iter().find(|r| r.statistic == statistic)
}

/// The failure probability by one algorithm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReliabilityRow {
    pub algorithm: String,
    pub pf: f64,
    /// Confidence interval (sampling algorithms; FORM and SORM have none).
    pub interval: Option<(f64, f64)>,
    /// Evaluations of the surrogate.
    pub evaluations: usize,
}

/// One `[[reliability]]` analysis: the probability by each algorithm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReliabilityReport {
    pub quantity: String,
    pub threshold: f64,
    /// Label of the method whose surrogate was analysed.
    pub method: String,
    /// The probability by each algorithm.
    pub rows: Vec<ReliabilityRow>,
    /// Warnings (several design points) and failures of algorithms.
    pub notes: Vec<String>,
}

/// Probability of failure for one threshold, with its sampling-only confidence interval (the
/// total interval is that of the budget row [`failure_statistic`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FailureInfo {
    pub threshold: f64,
    pub probability: f64,
    /// Wilson interval from the draws alone (sampling only).
    pub ci_low: f64,
    pub ci_high: f64,
}

/// A QoI as a function of two parameters, on a regular grid, with the runs that built it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Surface {
    pub param_names: [String; 2],
    /// Grid abscissae (strictly increasing).
    pub x: Vec<f64>,
    /// Grid ordinates (strictly increasing).
    pub y: Vec<f64>,
    /// Row-major: `values[j * x.len() + i]` is the value at `(x[i], y[j])`.
    pub values: Vec<f64>,
    /// Collocation points `(p1, p2, qoi)`.
    pub points: Vec<[f64; 3]>,
}

/// Several surrogate methods on one QoI, side by side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    pub qoi: String,
    pub rows: Vec<ComparisonRow>,
}

/// One method of a comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComparisonRow {
    pub method: String,
    pub runs: usize,
    pub mean: f64,
    pub std: f64,
    /// (x, pdf) on a grid (of the continuous part when there are atoms, as
    /// [`QoiReport::kde`]).
    pub kde: Vec<(f64, f64)>,
    /// Probability atoms (as [`QoiReport::atoms`]).
    #[serde(default)]
    pub atoms: Vec<Atom>,
    /// The method's error budget of the quantity (empty when not estimated): each statistic
    /// with its own total interval.
    #[serde(default)]
    pub budget: Vec<BudgetRow>,
}

impl ReportInput {
    /// Saves the input as pretty JSON. Not an output of a study (the report is rebuilt from
    /// the study's store, `alea report DIR`); kept for the round-trip test.
    #[cfg(test)]
    pub fn save_json(&self, path: &Path) -> Result<(), ReportError> {
        let text = serde_json::to_string_pretty(self).map_err(|e| ReportError::Json {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        alea_mesh::atomic::write_bytes_atomic(path, text.as_bytes()).map_err(|source| {
            ReportError::Io {
                path: path.to_path_buf(),
                source,
            }
        })
    }

    /// Loads an input saved by [`ReportInput::save_json`] (`alea report` rebuilds from the
    /// study's store instead; kept for the round-trip test).
    #[cfg(test)]
    pub fn load_json(path: &Path) -> Result<Self, ReportError> {
        let text = std::fs::read_to_string(path).map_err(|source| ReportError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        serde_json::from_str(&text).map_err(|e| ReportError::Json {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }
}

/// A support bound in JSON: a number, or the strings "inf" / "-inf" (JSON has no infinity).
mod bound {
    use serde::{Deserialize, Deserializer, Serializer, de::Error};

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        if v.is_infinite() {
            s.serialize_str(if *v > 0.0 { "inf" } else { "-inf" })
        } else {
            s.serialize_f64(*v)
        }
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Bound {
        Number(f64),
        Text(String),
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        match Bound::deserialize(d)? {
            Bound::Number(v) => Ok(v),
            Bound::Text(t) => match t.as_str() {
                "inf" | "+inf" => Ok(f64::INFINITY),
                "-inf" => Ok(f64::NEG_INFINITY),
                other => Err(D::Error::custom(format!(
                    "expected a number, \"inf\" or \"-inf\", found \"{other}\""
                ))),
            },
        }
    }
}
