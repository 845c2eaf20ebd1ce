//! The stored data of finished runs, checked before it is used.
//!
//! A converged run's row is committed in the same transaction as its data (its displacement
//! fields, and with error estimation its error-estimate values: the `run_data` table of
//! `study.db`), so a kill cannot leave a row without them; data removed or cut afterwards (a
//! row deleted by hand, a damaged database page, or in a directory written when each run's data
//! was a file - `fields/run_<h>.bin`, `cre/run_<h>.bin` - a file removed or truncated) could,
//! and every output that reads it would then fail. [`usable_runs`] checks each converged run's
//! data when a study directory is opened (its size against the model's number of field values,
//! its study hash; `Store::damaged_files`, which reads sizes, not values): a run with damaged
//! data is left out of the stored runs, so that `alea run` computes it again (its row and data
//! are replaced on commit) and `alea report` counts it as missing; either way the run is named
//! in a note ("the run at (...) cannot be used: its field data has N values, expected M"). A
//! study is never blocked by one lost run.

use crate::store::{RunRecord, Store};
use crate::study::{Study, estimates_error};

/// Number of values of a run's field data ([`Study::field_values`]).
pub fn field_values(study: &Study) -> usize {
    study.field_values()
}

/// The runs of `records` whose stored data can be used; each converged run with damaged data
/// is left out and named to `note` (`compute`: it is computed again; else it is missing
/// from the outputs).
pub fn usable_runs(
    study: &Study,
    store: &Store,
    records: Vec<RunRecord>,
    compute: bool,
    note: &dyn Fn(&str),
) -> Vec<RunRecord> {
    let values = field_values(study);
    let estimate = estimates_error(study);
    let mut kept = Vec::with_capacity(records.len());
    for r in records {
        if !r.converged() {
            kept.push(r);
            continue;
        }
        match store.damaged_files(&r.params, values, estimate) {
            None => kept.push(r),
            Some(why) => note(&format!(
                "the run at {} cannot be used: {why}; {}",
                describe_point(study, &r.params),
                if compute {
                    "it is computed again"
                } else {
                    "it is counted as missing (`alea run` computes it again)"
                }
            )),
        }
    }
    kept
}

/// A run's point as `name = value, ...`.
pub fn describe_point(study: &Study, params: &[f64]) -> String {
    let pairs: Vec<String> = study
        .params
        .names
        .iter()
        .zip(params)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    format!("({})", pairs.join(", "))
}
