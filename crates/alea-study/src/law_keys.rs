//! The keys of a `[[parameter]]` that its law uses, and the refusal of the others (issue 42,
//! item 5): a key the law would ignore is a value the user believes in - `lo` / `hi` on a
//! `normal` law would leave the normal untruncated, `std` on a `uniform` law would change
//! nothing. Every law takes `name`, `law` and `unit`, and only the keys of [`LAW_KEYS`].

use std::ops::Range;

use toml::Spanned;

use crate::spec::ParameterSpec;
use crate::{Source, StudyError};

/// Each law of a `[[parameter]]` and the keys it uses (besides `name`, `law` and `unit`).
pub const LAW_KEYS: &[(&str, &[&str])] = &[
    ("uniform", &["lo", "hi"]),
    ("normal", &["mean", "std"]),
    ("truncated_normal", &["mean", "std", "lo", "hi"]),
    ("lognormal", &["mean", "std"]),
    ("beta", &["alpha", "beta", "lo", "hi"]),
    ("triangular", &["lo", "mode", "hi"]),
    ("empirical", &["data", "column"]),
    ("kde", &["data", "column", "bandwidth"]),
    ("fit", &["data", "column", "families"]),
];

/// The keys of `law`, `None` for a law not in [`LAW_KEYS`].
pub fn keys_of(law: &str) -> Option<&'static [&'static str]> {
    LAW_KEYS
        .iter()
        .find(|(name, _)| *name == law)
        .map(|(_, keys)| *keys)
}

/// The law-dependent keys given in `p` with their spans, in the order of the file.
fn given_keys(p: &ParameterSpec) -> Vec<(&'static str, Range<usize>)> {
    fn at<T>(key: &'static str, v: &Option<Spanned<T>>) -> Option<(&'static str, Range<usize>)> {
        v.as_ref().map(|s| (key, s.span()))
    }
    let mut keys: Vec<_> = [
        at("mean", &p.mean),
        at("std", &p.std),
        at("lo", &p.lo),
        at("hi", &p.hi),
        at("mode", &p.mode),
        at("alpha", &p.alpha),
        at("beta", &p.beta),
        at("data", &p.data),
        at("column", &p.column),
        at("bandwidth", &p.bandwidth),
        at("families", &p.families),
    ]
    .into_iter()
    .flatten()
    .collect();
    keys.sort_by_key(|(_, span)| span.start);
    keys
}

/// What to write instead of `key` on `law`, when another law is what the user meant.
fn hint(law: &str, key: &str) -> &'static str {
    match (law, key) {
        ("normal", "lo" | "hi") => {
            "; a normal law bounded by lo and hi is law = \"truncated_normal\" (mean and std of the parent normal, lo, hi)"
        }
        ("uniform", "mean" | "std") => {
            "; a uniform law is given by its bounds lo and hi only (a law with a mean and a std is \"normal\", \"truncated_normal\" or \"lognormal\")"
        }
        ("lognormal", "lo" | "hi") => "; a lognormal law is not bounded",
        _ => "",
    }
}

/// Refuses the first key of parameter `i` that its law does not use (in the order of the
/// file), naming the key's line and field and the law's keys. A law not in [`LAW_KEYS`] is
/// left to the caller (its error names the known laws).
///
/// # Errors
/// [`StudyError::Input`] at `parameter[i].<key>`.
pub fn check(src: &Source, p: &ParameterSpec, i: usize) -> Result<(), StudyError> {
    let law = p.law.get_ref().as_str();
    let Some(used) = keys_of(law) else {
        return Ok(());
    };
    match given_keys(p).into_iter().find(|(k, _)| !used.contains(k)) {
        None => Ok(()),
        Some((key, span)) => Err(src.error(
            span,
            format!("parameter[{i}].{key}"),
            format!(
                "law '{law}' does not use '{key}' (it takes {}){}",
                used.join(", "),
                hint(law, key)
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_law_of_the_parameter_code_has_its_keys() {
        for law in [
            "uniform",
            "normal",
            "truncated_normal",
            "lognormal",
            "beta",
            "triangular",
        ]
        .iter()
        .chain(crate::data_law::DATA_LAWS)
        {
            assert!(keys_of(law).is_some(), "{law}");
        }
        assert_eq!(keys_of("gaussian"), None);
    }
}
