//! Studies for alea: the TOML input schema ([`spec`]), building solver inputs from it
//! ([`build_model`]), and (next) the stochastic runner, store and analysis.
//!
//! Errors ([`StudyError`]) name the file, the line and the field of every bad input.

mod build;
mod error;
mod source;
pub mod spec;

pub use build::{BuiltModel, build_mesh, build_model};
pub use error::StudyError;
pub use source::Source;
