//! The `[[step]]` tables of a model file (schema only; the checks and the plan are in module
//! `steps`).

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
