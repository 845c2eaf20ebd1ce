//! The sliding part of the error budget: what small sliding, the pairing of the initial
//! configuration kept throughout, changes in each statistic. With `[budget] large_sliding =
//! true` the study is also built with every small-sliding contact interface in large sliding
//! (`alea_latin::large_sliding`: the pairing and its normals re-found in the deformed
//! configuration of each run, the bodies still linear) and both are solved at the `2 d + 1`
//! design points of the mesh part ([`super::mesh::paired_check`]: the nominal point and, along
//! each parameter, its 5 % and 95 % quantiles); with `delta_i = q_small(xi_i) - q_large(xi_i)`,
//!
//! ```text
//! D = max_i |delta_i|,   S = max_i delta_i - min_i delta_i,
//! ```
//!
//! and the part is `D` for the mean and the quantiles, `S / 2` for the standard deviation and
//! `P(|q~ - t| <= D)` over the draws for `P(q > t)` (the propagation of the mesh part, module
//! [`super::mesh`], without Richardson's factor: the difference is the change itself, not one
//! term of a converging sequence).
//!
//! What it measures: the first-order effect of the deformed geometry on the contact (where the
//! points meet, and the normals' turn), which small sliding leaves out and which grows with
//! the displacements. It is the change toward the large-sliding model, not the error against a
//! large-deformation analysis (the bodies stay linear in both). Measured on the simple blade
//! root (`examples/blade-root-simple.toml`, header): T changes by +20 to +75 % between the two
//! models, both mesh-converged.

use toml::Spanned;

use crate::spec::BudgetSpec;
use crate::study::Study;
use crate::{Source, StudyError};

/// The study of `source` with every small-sliding contact interface in large sliding, without
/// `[budget]`, `[error]`, `[[reliability]]` and with a two-run Monte Carlo as its method (the
/// paired solves use its model only; the error estimate and adaptive methods refuse large
/// sliding). `None` without `large_sliding = true`.
///
/// # Errors
/// [`StudyError::Input`] at `budget` when it asks for no part, and at `budget.large_sliding`
/// when the study has no small-sliding contact interface or the patched study does not build.
pub fn sliding_study(
    source: &Source,
    budget: &Spanned<BudgetSpec>,
) -> Result<Option<Study>, StudyError> {
    let spec = budget.get_ref();
    let sliding = spec.large_sliding.as_ref().is_some_and(|f| *f.get_ref());
    if spec.refined_mesh.is_none() && !sliding {
        return Err(source.error(
            budget.span(),
            "budget",
            "[budget] asks for no part: give refined_mesh (the mesh part) and / or large_sliding = true (the sliding part)",
        ));
    }
    let Some(flag) = spec.large_sliding.as_ref().filter(|f| *f.get_ref()) else {
        return Ok(None);
    };
    let field = "budget.large_sliding";
    let fail = |why: String| source.error(flag.span(), field, why);
    let mut doc: toml::Table = toml::from_str(&source.text).map_err(|e| fail(e.to_string()))?;
    for key in ["budget", "error", "reliability"] {
        doc.remove(key);
    }
    let mut patched = 0;
    if let Some(toml::Value::Array(interfaces)) = doc.get_mut("interface") {
        for it in interfaces.iter_mut().filter_map(toml::Value::as_table_mut) {
            let contact = it.get("law").and_then(toml::Value::as_str) == Some("coulomb");
            let small = it
                .get("sliding")
                .and_then(toml::Value::as_str)
                .is_none_or(|s| s == "small");
            if contact && small {
                it.insert("sliding".into(), toml::Value::String("large".into()));
                patched += 1;
            }
        }
    }
    if patched == 0 {
        return Err(fail(
            "the study has no contact interface in small sliding (law = \"coulomb\" without sliding = \"large\"): there is no sliding part to estimate; leave out large_sliding".into(),
        ));
    }
    let mut method = toml::Table::new();
    method.insert("type".into(), toml::Value::String("monte_carlo".into()));
    method.insert("runs".into(), toml::Value::Integer(2));
    method.insert("label".into(), toml::Value::String("large sliding".into()));
    doc.insert(
        "method".into(),
        toml::Value::Array(vec![toml::Value::Table(method)]),
    );
    let text = toml::to_string(&doc).map_err(|e| fail(e.to_string()))?;
    let study = Study::from_source(Source {
        path: source.path.clone(),
        text,
    })
    .map_err(|e| fail(format!("the large-sliding study does not build: {e}")))?;
    Ok(Some(study))
}
