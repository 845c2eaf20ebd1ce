//! The `[[step]]` tables and the `[cycle]` table of a model file (schema only; the checks and
//! the plan are in modules `steps` and `cycle`).

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

/// `[[step]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    /// Name (default `step-K`, `K` from 1); names the step in messages and output files.
    #[serde(default)]
    pub name: Option<Spanned<String>>,
    /// Factor of each named load in this step.
    #[serde(default)]
    pub load: BTreeMap<String, Spanned<f64>>,
    /// New values of imposed displacements.
    #[serde(default)]
    pub constraint: Vec<StepConstraintSpec>,
}

/// `[[step]] constraint = [...]`: new values for an existing constraint.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepConstraintSpec {
    /// Substructure name.
    pub substructure: Spanned<String>,
    /// The group of one of its constraints.
    pub group: Spanned<String>,
    /// New `x` value.
    #[serde(default)]
    pub x: Option<Spanned<f64>>,
    /// New `y` value.
    #[serde(default)]
    pub y: Option<Spanned<f64>>,
    /// New `z` value.
    #[serde(default)]
    pub z: Option<Spanned<f64>>,
    /// New normal value.
    #[serde(default)]
    pub normal: Option<Spanned<f64>>,
}

/// `[cycle]`: the last `[[step]]`s of the history, repeated as a load cycle (module `cycle`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CycleSpec {
    /// Names of the steps of the cycle: the last steps of the history, in their order.
    pub steps: Spanned<Vec<Spanned<String>>>,
    /// Number of cycles run (with `until`: at most this many, default 20).
    #[serde(default)]
    pub repeat: Option<Spanned<i64>>,
    /// Shakedown tolerance: cycles are repeated until the slip amplitude changes by less than
    /// this from one cycle to the next (relative to its largest value).
    #[serde(default)]
    pub until: Option<Spanned<f64>>,
}
