//! Meshes for alea.
//!
//! The main type is [`Mesh`]: node coordinates, cells of mixed [`CellType`]s, and named groups
//! of cells, facets ([`Facet`]) and nodes. Groups are how the rest of alea refers to
//! substructures, loads, constraints and interfaces.
//!
//! - [`generate`]: structured rectangles and boxes, the multi-block mapped quad generator
//!   ([`generate::multiblock`], Coons patches with curved edges), ready-made shapes (plate with a
//!   hole, annular sector, dovetail root in a disk sector) and extrusion of quad meshes to hexes.
//! - [`Mesh::extract`] splits a mesh into substructures (sub-meshes of cell groups with a node
//!   map); [`Mesh::append`] joins meshes without merging nodes.
//! - [`read_msh`]: Gmsh `.msh` 4.1 reader (ASCII and binary, physical groups become groups).
//! - [`input::read_input`]: input files are read only if they are regular files of bounded size.
//! - [`VtuWriter`] / [`write_vtm`]: ParaView output with point and cell fields.
//! - [`atomic::write_atomic`]: every output file is written to a temporary and renamed.
//! - [`Mesh::cell_measure`], [`Mesh::cell_min_jacobian`]: geometric checks (areas, volumes,
//!   orientation).
//! - [`Mesh::refined`]: uniform refinement (every cell and grouped facet split into `2^dim`
//!   children, curved quadratic edges kept), for mesh-convergence checks.
//! - [`reference`]: shape functions of the reference cells, shared with the finite elements.
//! - [`vec3`]: dot and cross products of 3-vectors, shared by the crates above.

pub mod atomic;
mod cell;
mod error;
mod extract;
pub mod generate;
mod geometry;
pub mod gmsh;
pub mod input;
mod mesh;
pub mod reference;
mod refine;
pub mod vec3;
pub mod vtu;

pub use cell::CellType;
pub use error::MeshError;
pub use gmsh::read_msh;
pub use mesh::{BoundaryFacet, Facet, Mesh};
pub use vtu::{VtuEncoding, VtuWriter, write_pvd, write_vtm};
