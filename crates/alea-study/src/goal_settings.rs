//! The `goal` of a goal-oriented adaptive method (issue 19): which quantity and statistic,
//! and the tolerance on its error budget; checked at load, before any run.

use crate::{Source, StudyError};

/// The goal of a goal-oriented adaptive method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Goal {
    /// Index of the quantity.
    pub quantity: usize,
    /// `Some(t)`: the statistic is `P(q > t)`; `None`: the mean and the standard deviation.
    pub threshold: Option<f64>,
    /// When the statistic's budget is small enough.
    pub tolerance: Tolerance,
}

/// A tolerance on an error budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// In the statistic's unit.
    Absolute(f64),
    /// Relative to the statistic's value.
    Relative(f64),
}

impl Tolerance {
    /// True if a budget `total` on a statistic of value `value` is within the tolerance.
    pub fn holds(&self, total: f64, value: f64) -> bool {
        match *self {
            Tolerance::Absolute(t) => total <= t,
            Tolerance::Relative(r) => total <= r * value.abs(),
        }
    }
}

pub(crate) fn goal(
    src: &Source,
    g: &toml::Spanned<crate::spec::GoalSpec>,
    i: usize,
    quantities: &[String],
) -> Result<Goal, StudyError> {
    let f = |k: &str| format!("method[{i}].goal.{k}");
    let spec = g.get_ref();
    let name = spec.quantity.get_ref();
    let quantity = quantities.iter().position(|q| q == name).ok_or_else(|| {
        src.error(
            spec.quantity.span(),
            f("quantity"),
            format!(
                "unknown quantity '{name}'; the study's quantities are {}",
                quantities.join(", ")
            ),
        )
    })?;
    let threshold = match &spec.threshold {
        Some(t) if !t.get_ref().is_finite() => {
            return Err(src.error(t.span(), f("threshold"), "must be a finite number"));
        }
        t => t.as_ref().map(|t| *t.get_ref()),
    };
    let tolerance = match (&spec.tolerance, &spec.relative_tolerance) {
        (Some(t), None) => {
            let x = *t.get_ref();
            if !(x > 0.0 && x.is_finite()) {
                return Err(src.error(t.span(), f("tolerance"), format!("must be > 0, got {x}")));
            }
            if threshold.is_some() && x >= 1.0 {
                return Err(src.error(
                    t.span(),
                    f("tolerance"),
                    format!("a tolerance on a probability must be below 1, got {x}"),
                ));
            }
            Tolerance::Absolute(x)
        }
        (None, Some(r)) => {
            let x = *r.get_ref();
            if !(x > 0.0 && x < 1.0) {
                return Err(src.error(
                    r.span(),
                    f("relative_tolerance"),
                    format!("must be in (0, 1), got {x}"),
                ));
            }
            Tolerance::Relative(x)
        }
        (Some(_), Some(r)) => {
            return Err(src.error(
                r.span(),
                f("relative_tolerance"),
                "give tolerance or relative_tolerance, not both",
            ));
        }
        (None, None) => {
            return Err(src.error(
                g.span(),
                format!("method[{i}].goal"),
                "needs tolerance (absolute) or relative_tolerance",
            ));
        }
    };
    Ok(Goal {
        quantity,
        threshold,
        tolerance,
    })
}
