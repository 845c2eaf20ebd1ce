//! Laws fitted to measured data in study files (issue 24, item 3): a `[[parameter]]` with
//! `data = "file.csv"` (relative to the study file; one value per row, a header row naming the
//! columns, `column` choosing one when there are several) and
//!
//! - `law = "empirical"`: the empirical law of the values (piecewise-linear distribution
//!   function through the order statistics, `alea_uq::law::Empirical`);
//! - `law = "kde"`: the Gaussian kernel density estimate (Silverman's bandwidth, or
//!   `bandwidth = h` in the parameter's unit);
//! - `law = "fit"`: the maximum-likelihood fit with the smallest BIC among `families`
//!   (default `normal`, `lognormal`, `gamma`, `uniform`), described with its parameters and
//!   goodness of fit (Kolmogorov-Smirnov statistic and p-value, Anderson-Darling).
//!
//! The data file is read with the input-size guard of `alea_mesh::input`, and its bytes enter
//! the study hash ([`crate::build::input_hash`]): a changed data file makes a different study.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use alea_uq::fit::{Family, fit_best};
use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::law::{Empirical, KdeLaw, Marginal};

use crate::spec::ParameterSpec;
use crate::{Source, StudyError};

/// The laws that take `data`.
pub const DATA_LAWS: &[&str] = &["empirical", "kde", "fit"];

/// Refuses the keys of laws from data that parameter `i`'s law would ignore: `families` but
/// with `fit`, `bandwidth` but with `kde`, `column` without `data`.
pub fn check_data_keys(src: &Source, p: &ParameterSpec, i: usize) -> Result<(), StudyError> {
    let law = p.law.get_ref().as_str();
    let misplaced = |span: std::ops::Range<usize>, key: &str, used: &str| {
        Err(src.error(
            span,
            format!("parameter[{i}].{key}"),
            format!("'{key}' is used by {used} only; this parameter's law is '{law}'"),
        ))
    };
    if let Some(f) = &p.families
        && law != "fit"
    {
        return misplaced(f.span(), "families", "law = \"fit\"");
    }
    if let Some(b) = &p.bandwidth
        && law != "kde"
    {
        return misplaced(b.span(), "bandwidth", "law = \"kde\"");
    }
    if let Some(c) = &p.column
        && p.data.is_none()
    {
        return misplaced(c.span(), "column", "a law with data = \"...\"");
    }
    Ok(())
}

/// The data file of a parameter, relative to the study file.
pub fn data_path(src: &Source, data: &str) -> PathBuf {
    src.path.parent().unwrap_or(Path::new(".")).join(data)
}

/// The values of parameter `i`'s data file (its `column`), checked: finite numbers, at least 3.
pub fn read_values(src: &Source, p: &ParameterSpec, i: usize) -> Result<Vec<f64>, StudyError> {
    let field = format!("parameter[{i}].data");
    let Some(data) = &p.data else {
        return Err(src.error(
            p.law.span(),
            field,
            format!(
                "law '{}' needs data = \"file.csv\" (the measured values)",
                p.law.get_ref()
            ),
        ));
    };
    let path = data_path(src, data.get_ref());
    let bytes = alea_mesh::input::read_input(&path)
        .map_err(|e| src.error(data.span(), &field, format!("{}: {e}", path.display())))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        src.error(
            data.span(),
            &field,
            format!("{}: not UTF-8 text ({e})", path.display()),
        )
    })?;
    let at = |line: usize, msg: String| {
        src.error(
            data.span(),
            &field,
            format!("{}:{line}: {msg}", path.display()),
        )
    };
    let mut rows = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let split = |l: &str| -> Vec<String> { l.split(',').map(|c| c.trim().to_string()).collect() };
    let Some((first_no, first)) = rows.next() else {
        return Err(at(1, "no values".into()));
    };
    let cells = split(first);
    let header = cells.iter().any(|c| c.parse::<f64>().is_err());
    let col = match (&p.column, header) {
        (Some(name), true) => cells
            .iter()
            .position(|c| c == name.get_ref())
            .ok_or_else(|| {
                src.error(
                    name.span(),
                    format!("parameter[{i}].column"),
                    format!(
                        "{} has no column '{}'; its columns are {}",
                        path.display(),
                        name.get_ref(),
                        cells.join(", ")
                    ),
                )
            })?,
        (Some(name), false) => {
            return Err(src.error(
                name.span(),
                format!("parameter[{i}].column"),
                format!("{} has no header row to name columns", path.display()),
            ));
        }
        (None, _) if cells.len() == 1 => 0,
        (None, _) => {
            return Err(at(
                first_no + 1,
                format!("{} columns: name one with column = \"...\"", cells.len()),
            ));
        }
    };
    let mut values = Vec::new();
    let body: Box<dyn Iterator<Item = (usize, &str)>> = if header {
        Box::new(rows)
    } else {
        Box::new(std::iter::once((first_no, first)).chain(rows))
    };
    for (no, line) in body {
        let cells = split(line);
        let cell = cells
            .get(col)
            .ok_or_else(|| at(no + 1, format!("no column {} in this row", col + 1)))?;
        match cell.parse::<f64>() {
            Ok(v) if v.is_finite() => values.push(v),
            _ => return Err(at(no + 1, format!("'{cell}' is not a finite number"))),
        }
    }
    if values.len() < 3 {
        return Err(at(
            first_no + 1,
            format!("{} values; a law from data needs at least 3", values.len()),
        ));
    }
    Ok(values)
}

/// The law of parameter `i` from its data (`law` one of [`DATA_LAWS`]) and its description.
pub fn data_law(
    src: &Source,
    p: &ParameterSpec,
    i: usize,
) -> Result<(Arc<dyn Marginal>, String), StudyError> {
    let values = read_values(src, p, i)?;
    let file = p
        .data
        .as_ref()
        .map(|d| d.get_ref().clone())
        .unwrap_or_default();
    let what = match &p.column {
        Some(c) => format!("{} values of {file} (column {})", values.len(), c.get_ref()),
        None => format!("{} values of {file}", values.len()),
    };
    let bad = |field: &str, e: alea_uq::UqError| {
        src.error(
            p.law.span(),
            format!("parameter[{i}].{field}"),
            e.to_string(),
        )
    };
    match p.law.get_ref().as_str() {
        "empirical" => {
            let law = Empirical::new(&values).map_err(|e| bad("data", e))?;
            Ok((Arc::new(law), format!("empirical law of the {what}")))
        }
        "kde" => {
            let bw = match &p.bandwidth {
                Some(h) if !(*h.get_ref() > 0.0 && h.get_ref().is_finite()) => {
                    return Err(src.error(
                        h.span(),
                        format!("parameter[{i}].bandwidth"),
                        format!("must be > 0, got {}", h.get_ref()),
                    ));
                }
                Some(h) => Bandwidth::Fixed(*h.get_ref()),
                None => Bandwidth::Silverman,
            };
            let kde = Kde::new(&values, bw).map_err(|e| bad("data", e))?;
            let h = kde.bandwidth();
            Ok((
                Arc::new(KdeLaw::new(kde)),
                format!("Gaussian kernel density (bandwidth {h:.4e}) of the {what}"),
            ))
        }
        _ => {
            let families = match &p.families {
                None => vec![Family::Normal, Family::LogNormal, Family::Gamma, Family::Uniform],
                Some(list) => list
                    .get_ref()
                    .iter()
                    .map(|f| match f.as_str() {
                        "normal" => Ok(Family::Normal),
                        "lognormal" => Ok(Family::LogNormal),
                        "gamma" => Ok(Family::Gamma),
                        "uniform" => Ok(Family::Uniform),
                        other => Err(src.error(
                            list.span(),
                            format!("parameter[{i}].families"),
                            format!(
                                "unknown family '{other}'; expected normal, lognormal, gamma or uniform"
                            ),
                        )),
                    })
                    .collect::<Result<Vec<_>, _>>()?,
            };
            if families.is_empty() {
                return Err(src.error(
                    p.law.span(),
                    format!("parameter[{i}].families"),
                    "is empty",
                ));
            }
            let fits = fit_best(&values, &families).map_err(|e| bad("data", e))?;
            let best = &fits[0];
            let params = best
                .parameters
                .iter()
                .map(|(n, v)| format!("{n} {v:.6e}"))
                .collect::<Vec<_>>()
                .join(", ");
            let family = match best.family {
                Family::Normal => "normal",
                Family::LogNormal => "lognormal",
                Family::Gamma => "gamma",
                Family::Uniform => "uniform",
                Family::Beta { .. } => "beta",
            };
            Ok((
                best.law.clone(),
                format!(
                    "{family} fitted by maximum likelihood to the {what} ({params}): the smallest BIC of {} families; Kolmogorov-Smirnov D {:.4} (p = {:.3}), Anderson-Darling {:.3}",
                    families.len(),
                    best.ks,
                    best.ks_pvalue,
                    best.anderson_darling
                ),
            ))
        }
    }
}

/// The bytes of every data file of the study's parameters (for the study hash).
pub fn data_bytes(src: &Source, params: &[ParameterSpec]) -> Result<Vec<Vec<u8>>, StudyError> {
    params
        .iter()
        .enumerate()
        .filter_map(|(i, p)| p.data.as_ref().map(|d| (i, d)))
        .map(|(i, d)| {
            let path = data_path(src, d.get_ref());
            alea_mesh::input::read_input(&path).map_err(|e| {
                src.error(
                    d.span(),
                    format!("parameter[{i}].data"),
                    format!("{}: {e}", path.display()),
                )
            })
        })
        .collect()
}
