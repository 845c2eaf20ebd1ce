//! Bases of the stochastic space: orthonormal polynomials of one variable ([`OrthoPoly`]),
//! multi-index sets ([`MultiIndexSet`]) and their tensor products ([`PcBasis`]).

mod multi_index;
mod orthopoly;
mod pc_basis;

pub use multi_index::MultiIndexSet;
pub use orthopoly::{OrthoPoly, PolyKind};
pub use pc_basis::PcBasis;
