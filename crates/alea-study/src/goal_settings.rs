//! The `goal` of a goal-oriented adaptive method (issue 19): which quantity and statistic,
//! and the tolerance on its error budget; checked at load, before any run.

use crate::{Source, StudyError};

/// The goal of a goal-oriented adaptive method.
#[derive(Clone, Debug, PartialEq)]
pub struct Goal {
    /// Index of the quantity.
    pub quantity: usize,
    /// `Some(t)`: the statistic is `P(q > t)`; `None`: the mean and the standard deviation.
    pub threshold: Option<f64>,
    /// When the statistic's budget is small enough.
    pub tolerance: Tolerance,
    /// Where the threshold is written (file, line, field), for the check against the range of
    /// the quantity over the start design ([`Goal::check_threshold`]).
    pub threshold_at: Option<(std::path::PathBuf, usize, String)>,
}

impl Goal {
    /// The threshold checked against the range `[lo, hi]` of the goal quantity over the start
    /// design's runs: outside it, `P(q > t)` is 0 or 1 on every surrogate built on those runs
    /// (a multilinear interpolant stays within its runs' range) and no refinement toward the
    /// limit state can start - an input error at the threshold, once the range is known (the
    /// earliest point: the quantity's range is not known before any run).
    pub fn check_threshold(&self, lo: f64, hi: f64) -> Result<(), StudyError> {
        match (self.threshold, &self.threshold_at) {
            (Some(t), Some((file, line, field))) if !(lo < t && t < hi) => Err(StudyError::Input {
                file: file.clone(),
                line: *line,
                field: field.clone(),
                message: format!(
                    "the threshold {t} is outside the range [{lo:.6e}, {hi:.6e}] of the quantity \
                         over the start design's runs: P(q > {t}) would be {} on every \
                         surrogate, with no limit state to refine along",
                    if t >= hi { 0 } else { 1 }
                ),
            }),
            _ => Ok(()),
        }
    }
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
    let threshold_at = spec.threshold.as_ref().map(|t| {
        (
            src.path.clone(),
            src.line_of(t.span().start),
            f("threshold"),
        )
    });
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
        threshold_at,
    })
}
