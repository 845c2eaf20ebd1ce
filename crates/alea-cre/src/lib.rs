//! Constitutive-relation-error (CRE) estimator (thesis chapter 3.1; placeholder doc, see below).

mod data;
mod domain;
pub mod eet;
mod error;
mod fe;
pub mod interface;
mod linalg;
pub mod poly;
mod result;
mod substructure;
pub mod topology;

pub use data::{LoadData, SideForces, TractionField, VectorField};
pub use domain::{CreOptions, DomainEstimate, estimate_domain, estimate_with_sides};
pub use error::CreError;
pub use interface::{InterfaceEstimate, interface_term};
pub use result::{CreResult, write_error_vtu};
pub use substructure::estimate_latin;
