//! Checked values of a model file: finite and positive numbers, vectors of the mesh's
//! dimension, numbers-or-expressions compiled against the model's variables, and where a
//! field lives, in words.

use toml::Spanned;

use crate::expr::Expr;
use crate::random_field::FieldDomain;
use crate::spec::{ModelFile, NumOrExpr};
use crate::{Source, StudyError};

/// Compiles a number-or-expression against `vars`.
pub(super) fn compile(
    src: &Source,
    v: &Spanned<NumOrExpr>,
    vars: &[&str],
    field: &str,
) -> Result<Expr, StudyError> {
    match v.get_ref() {
        NumOrExpr::Num(x) => {
            if !x.is_finite() {
                return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
            }
            Ok(Expr::constant(*x))
        }
        NumOrExpr::Expr(t) => Expr::parse(t, vars).map_err(|e| {
            let t = crate::expr::abbreviate(t);
            src.error(v.span(), field, format!("expression '{t}': {e}"))
        }),
    }
}

/// The value of `v`, which must be a finite number > 0.
pub(super) fn positive(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !(x.is_finite() && x > 0.0) {
        return Err(src.error(
            v.span(),
            field,
            format!("must be a finite number > 0, got {x}"),
        ));
    }
    Ok(x)
}

/// The value named by `v` among `choices` (`(name, value)`), else an error at `v` listing the
/// names: `must be "auto", "double" or "single", got "half"`.
pub(super) fn choice<T: Copy>(
    src: &Source,
    v: &Spanned<String>,
    field: &str,
    choices: &[(&str, T)],
) -> Result<T, StudyError> {
    let given = v.get_ref().as_str();
    if let Some((_, value)) = choices.iter().find(|(name, _)| *name == given) {
        return Ok(*value);
    }
    let names: Vec<String> = choices.iter().map(|(n, _)| format!("\"{n}\"")).collect();
    let listed = match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.join(""),
    };
    Err(src.error(
        v.span(),
        field,
        format!("must be {listed}, got \"{given}\""),
    ))
}

/// The value of `v`, which must be finite.
pub(super) fn finite(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !x.is_finite() {
        return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
    }
    Ok(x)
}

/// The `dim` finite components of `v`, padded with zeros to 3.
pub(super) fn vec3(
    src: &Source,
    v: &Spanned<Vec<f64>>,
    dim: usize,
    field: &str,
) -> Result<[f64; 3], StudyError> {
    let a = v.get_ref();
    if a.len() != dim || a.iter().any(|x| !x.is_finite()) {
        return Err(src.error(
            v.span(),
            field,
            format!("expected {dim} finite components, got {a:?}"),
        ));
    }
    let mut o = [0.0; 3];
    o[..dim].copy_from_slice(a);
    Ok(o)
}

/// Where a field lives, in words (for the errors of expressions that use it elsewhere).
pub(super) fn field_place(file: &ModelFile, domain: FieldDomain) -> String {
    match domain {
        FieldDomain::Interface(k) => format!("on interface '{}'", file.interface[k].name.get_ref()),
        FieldDomain::Substructure(k) => format!(
            "over the cells of substructure '{}'",
            file.substructure[k].name.get_ref()
        ),
    }
}
