//! From a parsed model file to solver inputs: mesh, substructure models with their
//! constraints and load cases, interfaces and LATIN options. Every semantic error names the
//! file, line and field.

//!
//! - [`parametric`]: the built model and how the parameters enter it;
//! - [`mesh`]: the mesh generators' parameters and dispatch (`mesh/generators.rs`), the split
//!   and the input hash;
//! - [`model`]: substructures, loads and LATIN options of a model file, assembled into the
//!   built model;
//! - [`interfaces`]: the interfaces of a model file;
//! - [`values`]: checked numbers, vectors and expressions of a model file;
//! - [`checks`]: consistency checks of the built interfaces.

mod checks;
mod interfaces;
mod mesh;
mod model;
mod parametric;
mod values;

pub use mesh::{build_mesh, input_files, input_hash};
pub use model::build_model;
pub(crate) use parametric::ProfileTable;
pub use parametric::{BuiltModel, InterfaceSite, Parametric};
