//! Validation runs (issue 40, item 1): runs of the solver at points drawn from the input law,
//! independent of every method's design, from which each statistic of a surrogate is corrected
//! and given an interval that includes the surrogate's error (`crate::budget::validation`).
//!
//! The points are the first `n` draws of one seeded sequence (the study's seed plus a fixed
//! offset, distinct from the analysis draws'); a goal loop's validation rounds
//! (`crate::goal_validation`) take longer prefixes of the same sequence, so their runs are shared.
//! They are run after every design and adaptive loop, stored and resumed like any run, and run
//! over MPI ranks by the same executor.
//!
//! Their number is `[budget] validation_runs` (0 switches them off), or by default a quarter of
//! the largest surrogate method's runs, at least [`AUTO_MIN`] and at most [`AUTO_MAX`]; none for a
//! study without random parameters or whose methods all run the model itself (Monte Carlo on the
//! model needs no surrogate correction). The analysis uses the longest prefix of the sequence
//! found among the study's runs (at most [`MAX_USED`]), so the goal rounds' runs count too.

use alea_uq::design;

use crate::method::{Method, MethodKind};
use crate::store::point_key;
use crate::study::Study;

/// Fewest validation runs of the automatic default (fewer give Student quantiles above 2.8).
pub const AUTO_MIN: usize = 5;

/// Most validation runs of the automatic default.
pub const AUTO_MAX: usize = 200;

/// Most validation runs the analysis looks for.
pub const MAX_USED: usize = 4096;

/// Offset of the validation draws' seed from the study's (distinct from the analysis draws').
const VALIDATION_SEED: u64 = 0x0005_eed0_fa11;

/// The first `n` validation points of `study`.
pub fn points(study: &Study, n: usize) -> Vec<Vec<f64>> {
    let d = study.params.names.len();
    if d == 0 || n == 0 {
        return Vec::new();
    }
    let draws = design::monte_carlo(
        study.params.joint.as_ref(),
        n,
        study.seed.wrapping_add(VALIDATION_SEED),
    );
    draws.points().chunks(d).map(<[f64]>::to_vec).collect()
}

/// The number of validation runs of `study` whose methods ended with `methods` (adaptive ones
/// with their final runs).
pub fn count(study: &Study, methods: &[Method]) -> usize {
    if study.params.names.is_empty() {
        return 0;
    }
    let surrogate_runs = methods
        .iter()
        .filter(|m| m.kind != MethodKind::MonteCarlo)
        .map(|m| m.points.len())
        .max();
    let Some(runs) = surrogate_runs else {
        return 0;
    };
    count_for(study, runs)
}

/// The number of validation runs of `study` for a surrogate of `runs` runs: `[budget]
/// validation_runs`, or a quarter of `runs` within [`AUTO_MIN`, `AUTO_MAX`].
pub fn count_for(study: &Study, runs: usize) -> usize {
    match study.validation_runs {
        Some(n) => n,
        None => (runs / 4).clamp(AUTO_MIN, AUTO_MAX),
    }
}

/// The validation points among the runs `has` (a run at the point, converged or not): the
/// longest prefix of the sequence, at most [`MAX_USED`].
pub fn found(study: &Study, has: &dyn Fn(&str) -> bool) -> Vec<Vec<f64>> {
    let mut all = points(study, MAX_USED);
    let n = all.iter().take_while(|p| has(&point_key(p))).count();
    all.truncate(n);
    all
}
