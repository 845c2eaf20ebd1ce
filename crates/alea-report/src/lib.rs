//! # alea-report: a study's outputs, shared by the `alea` command line and the Python package
//!
//! Two layers, one way:
//!
//! * [`report`]: pure drawing. A validated [`report::ReportInput`] (plain data, JSON) becomes
//!   plots in PNG and SVG (plotters, bundled DejaVu font) and one self-contained `report.html`.
//!   It knows nothing of studies.
//! * [`study`]: the orchestration over `alea-study` that both front ends call. [`study::run`]
//!   runs a study file into a study directory (the runs, resumable; surrogates and Monte Carlo
//!   statistics; the stochastic error estimates; `summary.json`, `samples.csv`, mean / std
//!   fields, the report); [`study::rebuild`] rebuilds every output from the store alone
//!   (`alea report DIR`, Python's `alea.report(dir)`); [`study::run_runs`] with
//!   [`study::analyse`] (the statistics and reliability results that [`study::write_outputs`]
//!   writes) and [`study::stored_runs`] give the results without writing outputs (Python's
//!   `alea.run` and `alea.open_store`).
//!
//! What a study prints goes through a [`Console`] (the CLI prints to stdout / stderr, Python
//! stays silent); errors are typed ([`Error`]), the front ends map them to exit codes or
//! exceptions.

mod console;
mod error;
pub mod report;
pub mod study;

pub use console::{Console, Silent};
pub use error::Error;
