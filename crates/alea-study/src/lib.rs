//! Studies for alea: the TOML input schema ([`spec`]), building solver inputs from it
//! ([`build_model`]), and (next) the stochastic runner, store and analysis.
//!
//! Errors ([`StudyError`]) name the file, the line and the field of every bad input.

pub mod adaptive;
pub mod analysis;
pub mod atoms;
pub mod budget;
mod build;
mod cell_field;
pub mod cre;
pub mod cycle;
pub mod data_law;
#[cfg(feature = "mpi")]
pub mod distributed;
pub mod draw_range;
mod error;
mod error_settings;
pub mod estimate;
pub mod expr;
pub mod failure_region;
mod field_spec;
pub mod fields;
pub mod goal;
mod goal_settings;
pub mod goal_validation;
mod integrity;
mod law_keys;
pub mod limits;
pub mod lock;
pub mod method;
pub mod model_session;
pub mod output_settings;
pub mod paired_runs;
mod params;
pub mod points;
pub mod qoi;
pub mod random_field;
pub mod reliability;
pub mod reopen;
pub mod run_hash;
pub mod runner;
mod schedule;
pub mod sensitivity;
mod settings_check;
pub mod sliding_note;
pub mod solve;
pub mod solver_spec;
mod source;
mod sparse;
mod spatial;
pub mod spec;
mod step_spec;
pub mod steps;
pub mod store;
pub mod study;
pub mod study_runs;
pub mod target_validation;
pub mod temporaries;
#[cfg(test)]
mod test_rng;
pub mod validation_runs;

/// Sequential dense kernels of faer (results independent of the thread count); called by the
/// programs that run studies (the `alea` binary, the Python module).
pub use alea_latin::dense::use_sequential_dense_kernels;
pub use build::{BuiltModel, InterfaceSite, Parametric, build_mesh, build_model};
pub use error::StudyError;
pub use params::{ParamSpace, build_params};
pub use source::Source;
