//! The `[error]` table of a study file, read and checked when the study is loaded (before any
//! run: a bad setting found after the runs would cost them, since fixing the file changes the
//! study's hash) and again by the estimate.

use crate::spec::ErrorSpec;
use crate::{Source, StudyError};

/// Settings of the `[error]` table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorSettings {
    /// Warn when `i_geo` or `i_sto` exceeds this.
    pub warn: f64,
    /// Cells per parameter of the regular integration partition (global surrogates).
    pub cells_per_dim: usize,
    /// Gauss points per parameter per cell.
    pub points_per_cell: usize,
    /// Grid points per parameter of the density maps.
    pub map_points: usize,
}

/// Reads and checks the `[error]` table `spec` of a study with `d` parameters (defaults when
/// absent).
///
/// # Errors
/// [`StudyError::Input`] naming the bad field.
pub fn read(src: &Source, spec: Option<&ErrorSpec>, d: usize) -> Result<ErrorSettings, StudyError> {
    let e = spec.cloned().unwrap_or_default();
    let warn = match &e.warn {
        Some(v) => {
            let x = *v.get_ref();
            if !(x > 0.0 && x.is_finite()) {
                return Err(src.error(v.span(), "error.warn", format!("must be > 0, got {x}")));
            }
            x
        }
        None => 0.1,
    };
    let default_cells = match d {
        0..=2 => 16,
        3 => 8,
        4 => 4,
        _ => 2,
    };
    let cells_per_dim = match &e.cells_per_dim {
        Some(v) => *v.get_ref(),
        None => default_cells,
    };
    let points_per_cell = match &e.points_per_cell {
        Some(v) => *v.get_ref(),
        None => 4,
    };
    for (value, v, field) in [
        (cells_per_dim, &e.cells_per_dim, "error.cells_per_dim"),
        (points_per_cell, &e.points_per_cell, "error.points_per_cell"),
    ] {
        if value == 0 {
            return Err(src.error(
                v.as_ref().map_or(0..0, |v| v.span()),
                field,
                "must be at least 1",
            ));
        }
    }
    let total = (cells_per_dim as f64 * points_per_cell as f64).powi(d as i32);
    if total > alea_estimate::rule::MAX_POINTS as f64 {
        // Named at the field that was given (the larger one when both were).
        let (v, field) = match (&e.cells_per_dim, &e.points_per_cell) {
            (Some(c), Some(p)) if *p.get_ref() > *c.get_ref() => (Some(p), "error.points_per_cell"),
            (Some(c), _) => (Some(c), "error.cells_per_dim"),
            (None, Some(p)) => (Some(p), "error.points_per_cell"),
            (None, None) => (None, "error.cells_per_dim"),
        };
        return Err(src.error(
            v.map_or(0..0, |v| v.span()),
            field,
            format!(
                "{cells_per_dim} cells x {points_per_cell} points per parameter in {d} parameters = {total:.0} integration points (need 1 to {})",
                alea_estimate::rule::MAX_POINTS
            ),
        ));
    }
    let map_points = match &e.map_points {
        Some(v) => {
            let x = *v.get_ref();
            if !(2..=1000).contains(&x) {
                return Err(src.error(
                    v.span(),
                    "error.map_points",
                    format!("must be in 2..=1000, got {x}"),
                ));
            }
            x
        }
        None => 80,
    };
    Ok(ErrorSettings {
        warn,
        cells_per_dim,
        points_per_cell,
        map_points,
    })
}
