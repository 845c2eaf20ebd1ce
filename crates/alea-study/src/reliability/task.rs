//! The `[[reliability]]` tables of a study file, checked at load (before any run): the
//! quantity, the threshold, the method whose surrogate is the limit state, the algorithms.

use crate::method::{Method, MethodKind};
use crate::qoi::Qoi;
use crate::spec::ReliabilitySpec;
use crate::{ParamSpace, Source, StudyError};

/// The algorithms of a `[[reliability]]` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algorithm {
    /// First-order reliability method.
    Form,
    /// Second order (Breitung, Tvedt).
    Sorm,
    /// Importance sampling around the design point.
    Importance,
    /// Subset simulation.
    Subset,
}

/// A checked `[[reliability]]` table.
#[derive(Clone, Debug, PartialEq)]
pub struct ReliabilityTask {
    /// Index of the quantity.
    pub quantity: usize,
    /// Threshold.
    pub threshold: f64,
    /// Index of the method whose surrogate is the limit state.
    pub method: usize,
    /// Algorithms to run.
    pub algorithms: Vec<Algorithm>,
    /// Target coefficient of variation of importance sampling.
    pub target_cov: f64,
    /// Importance-sampling runs of the solver at the surrogate's design point (0: none).
    pub solver_runs: usize,
}

/// Fewest solver runs of a confirmation (below, its interval means little).
pub const MIN_SOLVER_RUNS: i64 = 10;
/// Most solver runs of a confirmation.
pub const MAX_SOLVER_RUNS: i64 = 100_000;

/// Checks the `[[reliability]]` tables of a study file (at load, before any run).
///
/// # Errors
/// [`StudyError::Input`] naming the table and field: an unknown quantity, method or algorithm,
/// a method without surrogate, a study without random parameters, a target outside (0, 1).
pub fn build_reliability(
    src: &Source,
    specs: &[ReliabilitySpec],
    qois: &[Qoi],
    methods: &[Method],
    params: &ParamSpace,
) -> Result<Vec<ReliabilityTask>, StudyError> {
    let mut out = Vec::new();
    for (i, r) in specs.iter().enumerate() {
        let f = |k: &str| format!("reliability[{i}].{k}");
        if params.names.is_empty() {
            return Err(src.error(
                r.quantity.span(),
                f("quantity"),
                "a reliability analysis needs random parameters ([[parameter]])",
            ));
        }
        let name = r.quantity.get_ref();
        let quantity = qois.iter().position(|q| &q.name == name).ok_or_else(|| {
            src.error(
                r.quantity.span(),
                f("quantity"),
                format!(
                    "unknown quantity '{name}'; the study's quantities are {}",
                    qois.iter()
                        .map(|q| q.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
        let threshold = *r.threshold.get_ref();
        if !threshold.is_finite() {
            return Err(src.error(r.threshold.span(), f("threshold"), "must be finite"));
        }
        let with_surrogate = |m: &Method| m.kind != MethodKind::MonteCarlo;
        let method = match &r.method {
            Some(label) => {
                let m = methods
                    .iter()
                    .position(|m| &m.label == label.get_ref())
                    .ok_or_else(|| {
                        src.error(
                            label.span(),
                            f("method"),
                            format!(
                                "no method is labelled '{}'; the labels are {}",
                                label.get_ref(),
                                methods
                                    .iter()
                                    .map(|m| format!("'{}'", m.label))
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        )
                    })?;
                if !with_surrogate(&methods[m]) {
                    return Err(src.error(
                        label.span(),
                        f("method"),
                        "Monte Carlo on the model has no surrogate to analyse",
                    ));
                }
                m
            }
            None => methods.iter().position(with_surrogate).ok_or_else(|| {
                src.error(
                    r.quantity.span(),
                    f("method"),
                    "no method of the study has a surrogate",
                )
            })?,
        };
        let algorithms = match &r.algorithms {
            None => vec![
                Algorithm::Form,
                Algorithm::Sorm,
                Algorithm::Importance,
                Algorithm::Subset,
            ],
            Some(list) => {
                let mut a = Vec::new();
                for name in list.get_ref() {
                    a.push(match name.as_str() {
                        "form" => Algorithm::Form,
                        "sorm" => Algorithm::Sorm,
                        "importance" => Algorithm::Importance,
                        "subset" => Algorithm::Subset,
                        other => {
                            return Err(src.error(
                                list.span(),
                                f("algorithms"),
                                format!("unknown algorithm '{other}'; expected form, sorm, importance or subset"),
                            ));
                        }
                    });
                }
                if a.is_empty() {
                    return Err(src.error(list.span(), f("algorithms"), "is empty"));
                }
                a
            }
        };
        let target_cov = match &r.target_cov {
            Some(v) if !(*v.get_ref() > 0.0 && *v.get_ref() < 1.0) => {
                return Err(src.error(
                    v.span(),
                    f("target_cov"),
                    format!("must be in (0, 1), got {}", v.get_ref()),
                ));
            }
            Some(v) => *v.get_ref(),
            None => 0.05,
        };
        let solver_runs = match &r.solver_runs {
            Some(v)
                if *v.get_ref() != 0
                    && !(MIN_SOLVER_RUNS..=MAX_SOLVER_RUNS).contains(v.get_ref()) =>
            {
                return Err(src.error(
                    v.span(),
                    f("solver_runs"),
                    format!(
                        "must be 0 (none) or between {MIN_SOLVER_RUNS} and {MAX_SOLVER_RUNS} (each is a solve), got {}",
                        v.get_ref()
                    ),
                ));
            }
            Some(v) => *v.get_ref() as usize,
            None => 0,
        };
        out.push(ReliabilityTask {
            quantity,
            threshold,
            method,
            algorithms,
            target_cov,
            solver_runs,
        });
    }
    Ok(out)
}
