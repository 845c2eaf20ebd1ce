//! Constitutive-relation-error (CRE) estimator (thesis chapter 3.1; placeholder doc, see below).

mod data;
mod domain;
pub mod eet;
mod error;
mod fe;
mod linalg;
pub mod poly;
pub mod topology;

pub use data::{LoadData, SideForces, TractionField, VectorField};
pub use domain::{CreOptions, DomainEstimate, estimate_domain, estimate_with_sides};
pub use error::CreError;
