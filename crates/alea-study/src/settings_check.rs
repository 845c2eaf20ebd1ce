//! Settings that a study file may give but that would be ignored, refused at load with
//! `file:line: field` (a value that is silently ignored is a value the user believes in):
//!
//! - `[joint]`: `correlation` only with `type = "gaussian_copula"` or `"student"`, `theta`
//!   only with the Archimedean copulas, `nu` only with `"student"`, `density` only with
//!   `type = "density"`;
//! - `[[method]]`: each key only for the types (and designs, criteria) that read it - `degree`
//!   for the polynomial methods, `design` where a design can be chosen, `runs` for the random
//!   and collocation designs, `points_per_dim` for grids, projection rules and piecewise-linear
//!   meshes, `criterion`, `target`, `max_runs` and `goal` for `adaptive`, `fraction` with the
//!   improved criterion and `depth` with the maximum-error criterion only;
//! - names written into file names (substructures: their ParaView parts; interfaces: their
//!   CSV files) must stay distinct once made safe for a file name (ASCII letters, digits, `-`,
//!   `_`; anything else becomes `_`): `é` and `è` would both be written to `_`.

use std::ops::Range;

use alea_mesh::atomic::safe_file_name;
use toml::Spanned;

use crate::spec::{MethodSpec, ModelFile};
use crate::{Source, StudyError};

/// Runs every check of this module.
///
/// # Errors
/// [`StudyError::Input`] at the first setting that would be ignored or name that collides.
pub fn check(src: &Source, file: &ModelFile) -> Result<(), StudyError> {
    check_joint(src, file)?;
    check_ranks_per_run(src, file)?;
    for (i, m) in file.method.iter().enumerate() {
        check_method(src, i, m)?;
    }
    check_file_names(src, file)
}

fn check_joint(src: &Source, file: &ModelFile) -> Result<(), StudyError> {
    let Some(j) = &file.joint else { return Ok(()) };
    let kind = j.kind.get_ref().as_str();
    if let Some(c) = &j.correlation
        && kind != "gaussian_copula"
        && kind != "student"
    {
        return Err(src.error(
            c.span(),
            "joint.correlation",
            format!(
                "a correlation matrix is used by type = \"gaussian_copula\" or \"student\" only; this joint law is '{kind}' (remove it, or change the type)"
            ),
        ));
    }
    if let Some(t) = &j.theta
        && !["clayton", "gumbel", "frank"].contains(&kind)
    {
        return Err(src.error(
            t.span(),
            "joint.theta",
            format!(
                "theta is used by the clayton, gumbel and frank copulas only; this joint law is '{kind}'"
            ),
        ));
    }
    if let Some(n) = &j.nu
        && kind != "student"
    {
        return Err(src.error(
            n.span(),
            "joint.nu",
            format!("nu is used by type = \"student\" only; this joint law is '{kind}'"),
        ));
    }
    if let Some(d) = &j.density
        && kind != "density"
    {
        return Err(src.error(
            d.span(),
            "joint.density",
            format!(
                "a density is used by type = \"density\" only; this joint law is '{kind}' (remove it, or change the type)"
            ),
        ));
    }
    Ok(())
}

/// The design a method runs on, as `build_methods` chooses it.
/// Most MPI ranks one run may be spread over.
pub const MAX_RANKS_PER_RUN: i64 = 4096;

/// `[solver] ranks_per_run` in 1 - [`MAX_RANKS_PER_RUN`]; the number of ranks of a job must
/// then be a multiple of it (checked when the job starts, `crate::distributed`).
fn check_ranks_per_run(src: &Source, file: &ModelFile) -> Result<(), StudyError> {
    let Some(r) = &file.solver.ranks_per_run else {
        return Ok(());
    };
    let v = *r.get_ref();
    if !(1..=MAX_RANKS_PER_RUN).contains(&v) {
        return Err(src.error(
            r.span(),
            "solver.ranks_per_run",
            format!(
                "must be between 1 and {MAX_RANKS_PER_RUN} (MPI ranks solving one run together, each owning some substructures), got {v}"
            ),
        ));
    }
    Ok(())
}

fn design_of(m: &MethodSpec) -> Option<String> {
    let given = m.design.as_ref().map(|d| d.get_ref().clone());
    match m.kind.get_ref().as_str() {
        "pc_regression" => Some(given.unwrap_or_else(|| "pc_collocation".into())),
        "pc_sparse" => Some(given.unwrap_or_else(|| "lhs".into())),
        "polynomial" => Some(given.unwrap_or_else(|| "grid".into())),
        "monte_carlo" => Some(given.unwrap_or_else(|| "monte_carlo".into())),
        _ => given,
    }
}

fn check_method(src: &Source, i: usize, m: &MethodSpec) -> Result<(), StudyError> {
    let kind = m.kind.get_ref().as_str();
    let known = [
        "pc_regression",
        "pc_sparse",
        "pc_projection",
        "polynomial",
        "piecewise_linear",
        "adaptive",
        "monte_carlo",
    ];
    if !known.contains(&kind) {
        // The type itself is reported by `build_methods`.
        return Ok(());
    }
    let design = design_of(m);
    let adaptive = kind == "adaptive";
    let max_error = m
        .criterion
        .as_ref()
        .is_some_and(|c| c.get_ref() == "max_error");
    let grid = design.as_deref() == Some("grid");
    let counted = matches!(
        design.as_deref(),
        Some("lhs" | "monte_carlo" | "sobol" | "pc_collocation")
    );
    let why_not = |key: &str| -> Option<String> {
        let of_type = format!("a {kind} method");
        let d = design.as_deref().unwrap_or("none");
        match key {
            "degree"
                if !matches!(
                    kind,
                    "pc_regression" | "pc_sparse" | "pc_projection" | "polynomial"
                ) =>
            {
                Some(format!("{of_type} has no polynomial degree"))
            }
            "design" if kind == "pc_projection" => Some(format!(
                "{of_type} runs on its Gauss rule (set its size with points_per_dim)"
            )),
            "runs" if !counted => Some(format!(
                "the number of runs of {of_type} on design '{d}' is set by {}",
                match kind {
                    "pc_projection" | "piecewise_linear" => "points_per_dim",
                    "adaptive" => "max_runs",
                    _ if grid => "points_per_dim",
                    _ => "the design",
                }
            )),
            "points_per_dim"
                if !(grid || matches!(kind, "pc_projection" | "piecewise_linear")) =>
            {
                Some(format!(
                    "points_per_dim sets a grid; {of_type} on design '{d}' has none (its size is runs)"
                ))
            }
            "criterion" | "target" | "max_runs" | "fraction" | "depth" if !adaptive => Some(
                format!("{of_type} is not adaptive ({key} is a setting of type = \"adaptive\")"),
            ),
            "fraction" if max_error => Some(
                "fraction is a setting of the improved criterion; this method uses criterion = \"max_error\" (its setting is depth)".into(),
            ),
            "depth" if !max_error => Some(
                "depth is a setting of criterion = \"max_error\"; this method uses the improved criterion (its setting is fraction)".into(),
            ),
            _ => None,
        }
    };
    let given: [(&str, Option<Range<usize>>); 8] = [
        ("degree", m.degree.as_ref().map(Spanned::span)),
        ("design", m.design.as_ref().map(Spanned::span)),
        ("runs", m.runs.as_ref().map(Spanned::span)),
        (
            "points_per_dim",
            m.points_per_dim.as_ref().map(Spanned::span),
        ),
        ("criterion", m.criterion.as_ref().map(Spanned::span)),
        ("target", m.target.as_ref().map(Spanned::span)),
        ("max_runs", m.max_runs.as_ref().map(Spanned::span)),
        ("fraction", m.fraction.as_ref().map(Spanned::span)),
    ];
    let depth = [("depth", m.depth.as_ref().map(Spanned::span))];
    for (key, span) in given.into_iter().chain(depth) {
        if let (Some(span), Some(why)) = (span, why_not(key)) {
            return Err(src.error(
                span,
                format!("method[{i}].{key}"),
                format!("not used: {why}; remove it"),
            ));
        }
    }
    Ok(())
}

/// Names that become file names must stay distinct once made safe.
fn check_file_names(src: &Source, file: &ModelFile) -> Result<(), StudyError> {
    let subs = file.substructure.iter().map(|s| &s.name);
    distinct_file_names(src, "substructure", subs)?;
    let interfaces = file.interface.iter().map(|s| &s.name);
    distinct_file_names(src, "interface", interfaces)
}

fn distinct_file_names<'a>(
    src: &Source,
    table: &str,
    names: impl Iterator<Item = &'a Spanned<String>>,
) -> Result<(), StudyError> {
    let mut seen: Vec<(String, &str)> = Vec::new();
    for (i, n) in names.enumerate() {
        let name = n.get_ref().as_str();
        let safe = safe_file_name(name);
        if let Some((_, other)) = seen.iter().find(|(s, o)| *s == safe && *o != name) {
            return Err(src.error(
                n.span(),
                format!("{table}[{i}].name"),
                format!(
                    "'{name}' and '{other}' would be written to the same file name '{safe}' (file names keep ASCII letters, digits, '-' and '_' only); rename one"
                ),
            ));
        }
        seen.push((safe, name));
    }
    Ok(())
}
