//! Substructured LATIN solver for assemblies with frictional contact interfaces.
//!
//! An [`Assembly`] holds linear-elastic [`Substructure`]s (each an `alea_fem::Model` with its
//! constraints and load cases) and [`InterfaceSpec`]s joining facet groups of two of them, with
//! a pointwise [`InterfaceLaw`] ([`Perfect`] or [`CoulombContact`] with a friction field
//! `mu(x)` and an initial-gap / shape-defect field `g0(x)`). Sides are paired node to node
//! when they match and by a dual mortar method otherwise ([`mortar`]: meshes made
//! independently, curved bodies on flat ones, sides of different extent). [`LatinSolver`]
//! factorises each substructure operator once and runs the LATIN iteration (thesis chapter
//! 2.1; conventions and closed-form local stage in [`law`]) for any number of parameter points,
//! each started from the interface state its caller gives (multiresolution, thesis 5.1.3: a
//! study starts each run from its nearest finished ones). A [`RunResult`] carries the
//! displacement of every substructure, the interface fields of both stages, the contact status
//! per point, the residual history and the quantities of interest.
//!
//! Load histories ([`steps`]): a sequence of load steps, each warm-started from the previous
//! one's interface state, with the Coulomb law applied incrementally. Fretting quantities over
//! a load cycle of such steps (slip amplitude, frictional work, stick zone, Ruiz F1 / F2, SWT):
//! [`fretting`].
//!
//! Cyclic symmetry (zero harmonic): a perfect interface joining a sector's two faces through
//! the sector's rotation, `u(B) = R u(A)`, `F_B = -R F_A` ([`cyclic`]).
//!
//! This crate knows nothing about probability.

mod anderson;
mod assembly;
mod coarse;
pub mod contact;
pub mod cyclic;
pub mod dense;
mod equilibrium;
mod error;
pub mod fretting;
pub mod interface;
pub mod large_sliding;
pub mod law;
pub mod mortar;
pub mod output;
pub mod ranks;
pub mod reactions;
mod result;
mod rotation;
pub mod samples;
pub mod sides;
pub mod sliding;
mod solver;
pub use solver::split;
mod state;
pub mod steps;

pub use assembly::{
    Assembly, DirectionScale, InterfaceSpec, PointField, Sliding, Substructure, constant,
};
pub use equilibrium::SubEquilibrium;
pub use error::LatinError;
pub use interface::{InterfacePairing, Pairing, PairingKind, SideProjection};
pub use law::{CoulombContact, InterfaceLaw, LocalSolution, Perfect, PointData, PointStatus};
pub use ranks::{RankExchange, ThreadExchange};
pub use result::{InterfaceResult, RunResult, RunStatus, RunTimings};
pub use rotation::Cyclic;
pub use solver::{
    DEFAULT_ACCELERATION, FactorPrecision, LatinOptions, LatinSolver, LinearStage,
    LinearStageSummary, RunInput, SINGLE_MIN_ENTRIES, SearchDirection, Subdomains,
};
pub use state::LocalState;
