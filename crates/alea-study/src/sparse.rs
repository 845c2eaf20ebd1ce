//! Sparse polynomial chaos in a study (`type = "pc_sparse"`): once a method's runs are done,
//! hybrid LARS with the corrected leave-one-out error (`alea_uq::surrogate::lars`, Blatman &
//! Sudret 2011) selects, for each quantity of interest, terms of the total-degree candidate
//! basis from the converged runs' values; the method's basis is the **union** of the
//! selections (in the candidate basis's order), fitted by least squares. The surrogate is then
//! linear in the run data like every other one, so the statistics, the error budget, the mean
//! / std fields, the error estimate and the Sobol' indices use it unchanged; each quantity's
//! fit on the union is at least as rich as its own selection.
//!
//! The selection is a function of the runs' values only (LARS is deterministic), so `alea
//! report` rebuilds the same basis from the store. When LARS fails, or the union has as many
//! terms as there are converged runs (least squares would interpolate), the method is left
//! without a basis and its surrogate is reported unavailable.

use std::collections::{HashMap, HashSet};

use alea_uq::basis::PcBasis;
use alea_uq::surrogate::PcSurrogate;

use crate::method::{Method, MethodKind};
use crate::store::{RunRecord, point_key};
use crate::study::Study;

/// Selects the basis of every sparse-chaos method of `methods` from the runs in `by_key`
/// (missing or failed runs left out).
pub(crate) fn select_bases(
    study: &Study,
    methods: &mut [Method],
    by_key: &HashMap<String, RunRecord>,
) {
    for m in methods.iter_mut() {
        if let MethodKind::PcSparse { degree } = m.kind {
            m.sparse_basis = select(study, m, degree, by_key);
        }
    }
}

fn select(
    study: &Study,
    m: &Method,
    degree: usize,
    by_key: &HashMap<String, RunRecord>,
) -> Option<Vec<Vec<u16>>> {
    let used: Vec<&RunRecord> = m
        .points
        .iter()
        .filter_map(|p| by_key.get(&point_key(p)).filter(|r| r.converged()))
        .collect();
    let candidates = PcBasis::total_degree(&study.params.marginals, degree).ok()?;
    let flat: Vec<f64> = used.iter().flat_map(|r| r.params.iter().copied()).collect();
    let mut chosen: HashSet<Vec<u16>> = HashSet::new();
    for q in 0..study.qois.len() {
        let values: Vec<f64> = used.iter().map(|r| r.qois[q]).collect();
        let pc = PcSurrogate::lars(candidates.clone(), &flat, &values).ok()?;
        chosen.extend(pc.basis().indices().iter().map(|a| a.to_vec()));
    }
    let union: Vec<Vec<u16>> = candidates
        .indices()
        .iter()
        .filter(|a| chosen.contains(*a))
        .map(|a| a.to_vec())
        .collect();
    (union.len() < used.len()).then_some(union)
}
