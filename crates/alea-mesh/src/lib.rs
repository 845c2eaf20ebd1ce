//! Meshes for alea.
//!
//! The main type is [`Mesh`]: node coordinates, cells of mixed [`CellType`]s, and named groups
//! of cells, facets ([`Facet`]) and nodes. Groups are how the rest of alea refers to
//! substructures, loads, constraints and interfaces. [`generate`] builds structured and
//! multi-block meshes.

mod cell;
mod error;
mod extract;
pub mod generate;
mod geometry;
pub mod gmsh;
mod mesh;
pub mod vtu;

pub use cell::CellType;
pub use error::MeshError;
pub use gmsh::read_msh;
pub use mesh::{BoundaryFacet, Facet, Mesh};
pub use vtu::{VtuEncoding, VtuWriter, write_vtm};
