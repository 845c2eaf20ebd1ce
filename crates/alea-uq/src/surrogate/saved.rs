//! Saving and loading a fitted chaos surrogate with its run data, as JSON (`serde_json`, exact
//! round trip of every `f64`): the one-dimensional recurrences and multi-indices of the basis,
//! the linear map `A` (`P x K`, so that coefficients are `A q`), the regression diagnostics
//! (leverages, design matrix, trace term), and the runs' points (`K x d`) and values
//! (`K x m`, any number of values per run: scalars or whole fields). Loading checks every
//! size and value and names the file and field of the first problem.

use super::pc::{PcMethod, PcSurrogate};
use crate::basis::{MultiIndexSet, OrthoPoly, PcBasis};
use crate::error::{Result, UqError};
use serde::{Deserialize, Serialize};
use std::path::Path;

const FORMAT: &str = "alea-uq PC surrogate v1";

/// Run data stored with a surrogate.
#[derive(Debug, Clone, PartialEq)]
pub struct RunData {
    /// Run points, row-major `K x dim`.
    pub points: Vec<f64>,
    /// Run values, row-major `K x values_per_run`.
    pub values: Vec<f64>,
    /// Values per run (1 for a scalar quantity of interest).
    pub values_per_run: usize,
}

#[derive(Serialize, Deserialize)]
struct SavedPc {
    format: String,
    polys: Vec<OrthoPoly>,
    indices: Vec<Vec<u16>>,
    method: PcMethod,
    runs: usize,
    map: Vec<f64>,
    hat_diag: Option<Vec<f64>>,
    design_matrix: Option<Vec<f64>>,
    condition: f64,
    trace_inv_gram: Option<f64>,
    points: Vec<f64>,
    values: Vec<f64>,
    values_per_run: usize,
}

fn err(path: &Path, message: String) -> UqError {
    UqError::File {
        path: path.display().to_string(),
        message,
    }
}

impl PcSurrogate {
    /// Save the surrogate and its runs (`points`: `K x dim`, `values`: `K x values_per_run`).
    ///
    /// # Errors
    /// If the sizes disagree with the surrogate, a value is not finite, or the file cannot be
    /// written.
    pub fn save_json(&self, path: impl AsRef<Path>, runs: &RunData) -> Result<()> {
        let path = path.as_ref();
        let d = self.basis.dim();
        let (k, m) = (self.k, runs.values_per_run);
        if runs.points.len() != k * d || m == 0 || runs.values.len() != k * m {
            return Err(err(
                path,
                format!(
                    "run data of {} coordinates and {} values do not match {k} runs of dimension {d} with {m} values each",
                    runs.points.len(),
                    runs.values.len()
                ),
            ));
        }
        if let Some(v) = runs
            .points
            .iter()
            .chain(&runs.values)
            .find(|v| !v.is_finite())
        {
            return Err(err(
                path,
                format!("run data contain the non-finite value {v}"),
            ));
        }
        let saved = SavedPc {
            format: FORMAT.into(),
            polys: self.basis.polys().to_vec(),
            indices: self.basis.indices().iter().map(|a| a.to_vec()).collect(),
            method: self.method,
            runs: k,
            map: self.a.clone(),
            hat_diag: self.hat_diag.clone(),
            design_matrix: self.psi.clone(),
            condition: self.cond,
            trace_inv_gram: self
                .trace_inv_gram
                .is_finite()
                .then_some(self.trace_inv_gram),
            points: runs.points.clone(),
            values: runs.values.clone(),
            values_per_run: m,
        };
        let text = serde_json::to_string(&saved).map_err(|e| err(path, e.to_string()))?;
        std::fs::write(path, text).map_err(|e| err(path, e.to_string()))
    }

    /// Load a surrogate and its runs saved by [`PcSurrogate::save_json`].
    ///
    /// # Errors
    /// If the file cannot be read, is not a saved chaos surrogate, or its sizes or values are
    /// inconsistent.
    pub fn load_json(path: impl AsRef<Path>) -> Result<(Self, RunData)> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| err(path, e.to_string()))?;
        let s: SavedPc = serde_json::from_str(&text).map_err(|e| err(path, e.to_string()))?;
        if s.format != FORMAT {
            return Err(err(
                path,
                format!("format {:?}, expected {FORMAT:?}", s.format),
            ));
        }
        for p in &s.polys {
            p.check().map_err(|e| err(path, e.to_string()))?;
        }
        let d = s.polys.len();
        let set =
            MultiIndexSet::from_indices(d, &s.indices).map_err(|e| err(path, e.to_string()))?;
        let basis = PcBasis::from_parts(s.polys, set).map_err(|e| err(path, e.to_string()))?;
        let (p, k, m) = (basis.len(), s.runs, s.values_per_run);
        let check = |field: &str, got: usize, expected: usize| -> Result<()> {
            if got == expected {
                Ok(())
            } else {
                Err(err(
                    path,
                    format!("field {field:?} has {got} entries, expected {expected}"),
                ))
            }
        };
        check("map", s.map.len(), p * k)?;
        check("points", s.points.len(), k * d)?;
        if m == 0 {
            return Err(err(path, "field \"values_per_run\" must be >= 1".into()));
        }
        check("values", s.values.len(), k * m)?;
        if let Some(h) = &s.hat_diag {
            check("hat_diag", h.len(), k)?;
        }
        if let Some(x) = &s.design_matrix {
            check("design_matrix", x.len(), k * p)?;
        }
        if s.method == PcMethod::Regression && (s.hat_diag.is_none() || s.design_matrix.is_none()) {
            return Err(err(
                path,
                "a regression surrogate needs hat_diag and design_matrix".into(),
            ));
        }
        let all = s.map.iter().chain(&s.points).chain(&s.values);
        if let Some(v) = all.into_iter().find(|v| !v.is_finite()) {
            return Err(err(path, format!("non-finite value {v}")));
        }
        Ok((
            Self {
                basis,
                a: s.map,
                k,
                hat_diag: s.hat_diag,
                psi: s.design_matrix,
                cond: s.condition,
                method: s.method,
                trace_inv_gram: s.trace_inv_gram.unwrap_or(f64::NAN),
            },
            RunData {
                points: s.points,
                values: s.values,
                values_per_run: m,
            },
        ))
    }
}
