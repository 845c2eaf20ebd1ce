//! Pieces shared by the alea-study benchmarks (included with `mod support;`).

use alea_study::store::RunRecord;

/// A converged run record of the given sizes for store timings: parameters `(index, 0.5)`,
/// `qois` values, an `iterations`-long history, `state` warm-start values.
pub fn synthetic_record(index: usize, iterations: usize, qois: usize, state: usize) -> RunRecord {
    RunRecord {
        params: vec![index as f64, 0.5],
        status: "converged".into(),
        iterations,
        residual: 1e-7,
        seconds: 0.01,
        qois: (1..=qois).map(|q| q as f64).collect(),
        history: vec![1e-3; iterations],
        state: vec![0.1; state],
        slide: None,
    }
}
