//! Linear-elastic finite elements for alea.
//!
//! Layers, from the bottom: [`quadrature`] and [`reference`] (shape functions on reference cells,
//! no mesh), [`kinematics`] (Jacobians, strain operator `B`), [`Material`] (Hooke's law), the
//! element kernel [`assembly::element_stiffness`] (`int B^T D B dV`) and global assembly into a
//! [`SymCsc`] on the free unknowns of a [`DofMap`] (constraints, including skew ones),
//! [`Loads`] (nodal, traction/pressure, body, centrifugal), the sparse [`Cholesky`] solver, and
//! [`post`] (stresses, nodal recovery, von Mises, reactions, energy). [`solve_elastic`] chains
//! them for a one-shot solve. [`locate`] finds the cell and reference coordinates of physical
//! points (2D), to evaluate one mesh's fields at another's points.
//!
//! Supported cells: T3, T6, Q4, Q8 (plane strain / plane stress with thickness), Tet4, Tet10,
//! Hex8.

pub mod assembly;
mod dofs;
mod error;
pub mod kinematics;
mod loads;
pub mod locate;
mod material;
mod model;
pub mod partition;
pub mod post;
mod problem;
pub mod quadrature;
mod simplicial;
mod single;
mod solver;
mod sparse;

pub use alea_mesh::reference;
pub use assembly::{Assembled, assemble_stiffness};
pub use dofs::{Constraints, DofMap};
pub use error::FemError;
pub use loads::Loads;
pub use locate::{Location, PointLocator};
pub use material::{Analysis, Material, von_mises};
pub use model::Model;
pub use problem::{ElasticSolution, Timings, solve_elastic};
pub use quadrature::Quadrature;
pub use solver::{Cholesky, FactorKind, Ordering, SolveScratch};
pub use sparse::SymCsc;
