//! Studies for alea: the TOML input schema ([`spec`]), building solver inputs from it
//! ([`build_model`]), and (next) the stochastic runner, store and analysis.
//!
//! Errors ([`StudyError`]) name the file, the line and the field of every bad input.

pub mod analysis;
mod build;
mod error;
pub mod expr;
pub mod fields;
pub mod method;
mod params;
pub mod qoi;
pub mod runner;
mod source;
pub mod spec;
pub mod store;

pub use build::{BuiltModel, InterfaceSite, Parametric, build_mesh, build_model};
pub use error::StudyError;
pub use params::{ParamSpace, build_params};
pub use source::Source;
