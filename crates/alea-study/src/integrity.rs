//! The stored files of finished runs, checked before they are used.
//!
//! A converged run's row is committed after its files (`fields/run_<h>.bin`, and with error
//! estimation `cre/run_<h>.bin`), so a kill cannot leave a row without them; a file removed or
//! truncated afterwards (by hand, a full disk, a copy of the directory that was cut short)
//! could, and every output that reads it would then fail. [`usable_runs`] checks each
//! converged run's files when a study directory is opened (sizes against the model's number of
//! field values, headers against the study hash; `Store::damaged_files`): a run with a damaged
//! file is left out of the stored runs, so that `alea run` computes it again (its row is
//! replaced on commit) and `alea report` counts it as missing; either way the run is named in a
//! note. A study is never blocked by one lost file.

use crate::store::{RunRecord, Store};
use crate::study::{Study, estimates_error};

/// Number of values of a run's field file ([`Study::field_values`]).
pub fn field_values(study: &Study) -> usize {
    study.field_values()
}

/// The runs of `records` whose stored files can be used; each converged run with a damaged
/// file is left out and named to `note` (`compute`: it is computed again; else it is missing
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
