//! # alea-report: the study report - plots (PNG + SVG) and one self-contained HTML page
//!
//! The study pipeline (`alea-pipeline`) fills a [`ReportInput`] (plain data, serialisable as JSON) and calls
//! [`write_report`], which validates it (no NaN ever reaches a file), draws the plots with
//! `plotters` (text rendered with the bundled DejaVu Sans, so no system font library is needed)
//! and writes `report.html` with the SVG plots inlined, so the page stands alone.
//!
//! Files written into the output directory:
//! - `pdf_<qoi>.{png,svg}`: KDE of the PDF over a normalised histogram, mean and thresholds;
//! - `cdf_<qoi>.{png,svg}`: empirical CDF with the quantiles;
//! - `surface_<qoi>.{png,svg}`: response surface over two parameters (when given);
//! - `convergence.{png,svg}`: LATIN error indicator per iteration (when histories are given);
//! - `comparison.{png,svg}`: the PDFs of several methods (when a comparison is given);
//! - `error_map.{png,svg}`: the stochastic error density over two parameters (when given);
//! - `indicators.{png,svg}`: `i_sto` and `i_geo` against the runs of the adaptive methods
//!   (when given);
//! - `report.html`.
//!
//! `<qoi>` is the QoI name reduced to ASCII letters, digits, `-` and `_`.

mod data;
pub mod format;
mod html;
mod plots;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

// The whole input type family is public API for the study runner (and the tests).
#[allow(unused_imports)]
pub use data::{
    AdaptiveReport, Atom, BudgetRow, Comparison, ComparisonRow, EntityRow, ErrorReport, ErrorRow,
    FailureInfo, ParamInfo, QoiReport, ReliabilityReport, ReliabilityRow, ReportInput, RunInfo,
    Statistic, StepRow, Surface, budget_row,
};

/// What went wrong while writing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A number that must be finite is not (the field is named as `qois["work"].samples[17]`).
    #[error("report input: {field} is {value} (every value must be finite)")]
    NonFinite { field: String, value: f64 },
    /// An input that is inconsistent (lengths, order, range).
    #[error("report input: {field}: {reason}")]
    Invalid { field: String, reason: String },
    #[error("cannot write {path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("cannot draw the plot {plot}: {message}")]
    Plot { plot: String, message: String },
    #[error("report input JSON {path}: {message}")]
    Json { path: PathBuf, message: String },
}

/// The files a report consists of.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportFiles {
    /// `report.html`.
    pub html: PathBuf,
    /// Every plot, PNG and SVG, in the order written.
    pub plots: Vec<PathBuf>,
}

/// Validates `input`, then writes the plots and `report.html` into `dir` (created if needed).
pub fn write_report(dir: &Path, input: &ReportInput) -> Result<ReportFiles, ReportError> {
    validate(input)?;
    std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let figures = plots::draw_all(dir, input)?;
    let html_path = dir.join("report.html");
    let page = html::render(input, &figures);
    alea_mesh::atomic::write_bytes_atomic(&html_path, page.as_bytes()).map_err(|source| {
        ReportError::Io {
            path: html_path.clone(),
            source,
        }
    })?;
    let plots = figures
        .iter()
        .flat_map(|f| [f.png.clone(), f.svg_path.clone()])
        .collect();
    Ok(ReportFiles {
        html: html_path,
        plots,
    })
}

fn finite(field: impl FnOnce() -> String, value: f64) -> Result<(), ReportError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(ReportError::NonFinite {
            field: field(),
            value,
        })
    }
}

fn all_finite(field: &str, values: &[f64]) -> Result<(), ReportError> {
    for (k, &v) in values.iter().enumerate() {
        finite(|| format!("{field}[{k}]"), v)?;
    }
    Ok(())
}

fn invalid(field: impl Into<String>, reason: impl Into<String>) -> ReportError {
    ReportError::Invalid {
        field: field.into(),
        reason: reason.into(),
    }
}

fn probability(field: impl Fn() -> String, p: f64) -> Result<(), ReportError> {
    finite(&field, p)?;
    if !(0.0..=1.0).contains(&p) {
        return Err(invalid(
            field(),
            format!("{p} is not a probability in [0, 1]"),
        ));
    }
    Ok(())
}

fn pdf_curve(field: &str, kde: &[(f64, f64)]) -> Result<(), ReportError> {
    for (k, &(x, p)) in kde.iter().enumerate() {
        finite(|| format!("{field}[{k}].x"), x)?;
        finite(|| format!("{field}[{k}].pdf"), p)?;
        if p < 0.0 {
            return Err(invalid(
                format!("{field}[{k}].pdf"),
                format!("negative density {p}"),
            ));
        }
    }
    Ok(())
}

/// Checks atoms: finite values, probabilities with their intervals in `[0, 1]`.
fn atoms(field: &str, list: &[Atom]) -> Result<(), ReportError> {
    for (i, a) in list.iter().enumerate() {
        let f = |what: &str| format!("{field}[{i}].{what}");
        finite(|| f("value"), a.value)?;
        probability(|| f("probability"), a.probability)?;
        probability(|| f("ci_low"), a.ci_low)?;
        probability(|| f("ci_high"), a.ci_high)?;
    }
    Ok(())
}

/// Checks the values and parts of budget rows are finite (a part may be absent).
fn budget(field: &str, rows: &[BudgetRow]) -> Result<(), ReportError> {
    for (i, r) in rows.iter().enumerate() {
        let f = |what: &str| format!("{field}[{i}] \"{}\".{what}", r.statistic);
        finite(|| f("value"), r.value)?;
        finite(|| f("sampling"), r.sampling)?;
        finite(|| f("total"), r.total)?;
        let (lo, hi) = r.interval();
        finite(|| f("interval"), lo)?;
        finite(|| f("interval"), hi)?;
        for (name, part) in [
            ("mesh", r.mesh),
            ("surrogate", r.surrogate),
            ("sliding", r.sliding),
        ] {
            if let Some(v) = part {
                finite(|| f(name), v)?;
            }
        }
    }
    Ok(())
}

/// Checks a surface: finite values, strictly increasing grids of at least 2 values, matching
/// sizes.
fn validate_surface(field: &str, s: &Surface) -> Result<(), ReportError> {
    let f = |what: &str| format!("{field}.{what}");
    all_finite(&f("x"), &s.x)?;
    all_finite(&f("y"), &s.y)?;
    all_finite(&f("values"), &s.values)?;
    for (i, p) in s.points.iter().enumerate() {
        all_finite(&f(&format!("points[{i}]")), p)?;
    }
    for (axis, g) in [("x", &s.x), ("y", &s.y)] {
        if g.len() < 2 {
            return Err(invalid(
                f(axis),
                format!("{} grid values (at least 2 needed)", g.len()),
            ));
        }
        if g.windows(2).any(|w| w[1] <= w[0]) {
            return Err(invalid(f(axis), "grid values are not strictly increasing"));
        }
    }
    if s.values.len() != s.x.len() * s.y.len() {
        return Err(invalid(
            f("values"),
            format!(
                "{} values for a {} x {} grid",
                s.values.len(),
                s.x.len(),
                s.y.len()
            ),
        ));
    }
    Ok(())
}

/// Checks every number is finite and the shapes agree, naming the field at fault.
pub fn validate(input: &ReportInput) -> Result<(), ReportError> {
    let np = input.parameters.len();
    for (k, p) in input.parameters.iter().enumerate() {
        let f = |what: &str| format!("parameters[{k}] \"{}\".{what}", p.name);
        if p.lo.is_nan() {
            return Err(ReportError::NonFinite {
                field: f("lo"),
                value: p.lo,
            });
        }
        if p.hi.is_nan() {
            return Err(ReportError::NonFinite {
                field: f("hi"),
                value: p.hi,
            });
        }
        if p.lo > p.hi {
            return Err(invalid(
                f("lo"),
                format!("lower bound {} above upper bound {}", p.lo, p.hi),
            ));
        }
    }
    let nq = input.qois.len();
    for (r, run) in input.runs.iter().enumerate() {
        all_finite(&format!("runs[{r}].params"), &run.params)?;
        all_finite(&format!("runs[{r}].qois"), &run.qois)?;
        finite(|| format!("runs[{r}].seconds"), run.seconds)?;
        if run.params.len() != np {
            return Err(invalid(
                format!("runs[{r}].params"),
                format!("{} values for {np} parameters", run.params.len()),
            ));
        }
        if !run.qois.is_empty() && run.qois.len() != nq {
            return Err(invalid(
                format!("runs[{r}].qois"),
                format!(
                    "{} values for {nq} quantities of interest (give all or none)",
                    run.qois.len()
                ),
            ));
        }
    }
    for (label, history) in &input.residual_histories {
        all_finite(&format!("residual_histories[\"{label}\"]"), history)?;
    }
    for (k, q) in input.qois.iter().enumerate() {
        let f = |what: &str| format!("qois[{k}] \"{}\".{what}", q.name);
        all_finite(&f("samples"), &q.samples)?;
        finite(|| f("mean"), q.mean)?;
        finite(|| f("std"), q.std)?;
        finite(|| f("skewness"), q.skewness)?;
        if q.std < 0.0 {
            return Err(invalid(
                f("std"),
                format!("negative standard deviation {}", q.std),
            ));
        }
        for (i, &(p, v)) in q.quantiles.iter().enumerate() {
            probability(|| f(&format!("quantiles[{i}].probability")), p)?;
            finite(|| f(&format!("quantiles[{i}].value")), v)?;
        }
        pdf_curve(&f("kde"), &q.kde)?;
        atoms(&f("atoms"), &q.atoms)?;
        budget(&f("budget"), &q.budget)?;
        for (i, (_, first, total)) in q.sobol.iter().enumerate() {
            finite(|| f(&format!("sobol[{i}].first")), *first)?;
            finite(|| f(&format!("sobol[{i}].total")), *total)?;
        }
        for (i, fl) in q.failure.iter().enumerate() {
            finite(|| f(&format!("failure[{i}].threshold")), fl.threshold)?;
            probability(|| f(&format!("failure[{i}].probability")), fl.probability)?;
            probability(|| f(&format!("failure[{i}].ci_low")), fl.ci_low)?;
            probability(|| f(&format!("failure[{i}].ci_high")), fl.ci_high)?;
            if fl.ci_low > fl.ci_high {
                return Err(invalid(
                    f(&format!("failure[{i}]")),
                    format!(
                        "confidence interval [{}, {}] is reversed",
                        fl.ci_low, fl.ci_high
                    ),
                ));
            }
        }
        if let Some(s) = &q.surface {
            validate_surface(&f("surface"), s)?;
        }
    }
    if let Some(e) = &input.error {
        finite(|| "error.warn".into(), e.warn)?;
        for (k, r) in e.methods.iter().enumerate() {
            let f = |what: &str| format!("error.methods[{k}] \"{}\".{what}", r.method);
            finite(|| f("relative"), r.relative)?;
            finite(|| f("i_geo"), r.i_geo)?;
            finite(|| f("i_sto"), r.i_sto)?;
            probability(|| f("violation"), r.violation)?;
        }
        for (k, r) in e.entities.iter().enumerate() {
            let f = |what: &str| format!("error.entities[{k}] \"{}\".{what}", r.entity);
            finite(|| f("relative"), r.relative)?;
            finite(|| f("i_geo"), r.i_geo)?;
            finite(|| f("i_sto"), r.i_sto)?;
            if let Some(m) = r.mean_share {
                finite(|| f("mean_share"), m)?;
            }
        }
        for (a, ad) in e.adaptive.iter().enumerate() {
            for (k, s) in ad.steps.iter().enumerate() {
                let f = |what: &str| format!("error.adaptive[{a}].steps[{k}].{what}");
                for (name, v) in [
                    ("i_sto", s.i_sto),
                    ("i_geo", s.i_geo),
                    ("relative", s.relative),
                    ("mean", s.mean),
                    ("std", s.std),
                    ("cost", s.cost),
                ] {
                    finite(|| f(name), v)?;
                }
                if let Some(p) = s.failure {
                    probability(|| f("failure"), p)?;
                }
            }
        }
        if let Some(s) = &e.map {
            validate_surface("error.map", s)?;
        }
    }
    if let Some(c) = &input.comparison {
        for (k, row) in c.rows.iter().enumerate() {
            let f = |what: &str| format!("comparison.rows[{k}] \"{}\".{what}", row.method);
            finite(|| f("mean"), row.mean)?;
            finite(|| f("std"), row.std)?;
            pdf_curve(&f("kde"), &row.kde)?;
            atoms(&f("atoms"), &row.atoms)?;
            budget(&f("budget"), &row.budget)?;
        }
    }
    for (label, t) in &input.timings {
        finite(|| format!("timings[\"{label}\"]"), *t)?;
    }
    Ok(())
}
