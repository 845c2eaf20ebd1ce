//! The standard EET technique in 3D (Tet4, Tet10, Hex8): the 2D construction of [`crate::eet`]
//! with faces in place of edges (Ladeveze-Leguillon 1983; Ladeveze-Pelle 2004 ch. 2; thesis
//! 3.1.1.4 b). Phase 1 is the same generic kernel (`crate::kernel`) on the faces.
//!
//! **Phase 1** ([`phase1`]): traction densities `F_hat` on the element faces, of the face's
//! FE degree (linear on Tri3 faces, bilinear on Quad4, quadratic on Tri6), such that every
//! element is in equilibrium with its body force and its face densities (3.20):
//! `int_dE eta_E F_hat . v dS + int_E f . v dV = 0` for the six rigid modes `v`. They are tied
//! to the FE stress by the prolongation condition (3.21)
//! `int_E (sigma_hat - sigma_h) grad phi_i dV = 0` for every node `i` and element `E`, which,
//! with `b_(i,Gamma) = int_Gamma F_hat phi_i dS`, becomes for each node `i` and each element `E`
//! around it (3.22):
//!
//! `sum_{Gamma face of E, i in Gamma} eta_(E,Gamma) b_(i,Gamma)
//!     = int_E sigma_h : grad phi_i dV - int_E f phi_i dV =: Q_E(i)`.
//!
//! These are small systems node by node (elements around the node x faces around it), solved
//! per direction with the minimisation of Ladeveze-Leguillon (closest to the averaged FE
//! traction projections). Element equilibrium follows: a rigid mode is a linear field
//! `v = sum_i v(x_i) phi_i`, so `int_dE eta F_hat . v = sum_i v(x_i) . Q_E(i) = int_E sigma_h :
//! eps(v) - int_E f . v = - int_E f . v`.
//!
//! **Phase 2** ([`phase2`]): on each element the Neumann problem `div sigma_hat + f = 0`,
//! `sigma_hat n = eta F_hat` (3.23), solved with a displacement field in the complete polynomial
//! space of degree `p + k` (default `k = 3`, [`crate::CreOptions::extra_degree`]) on the element
//! ([`poly`]), rigid modes removed; `sigma_hat = K eps(v)` and `theta_E^2 = ||sigma_hat -
//! sigma_h||^2_{K^-1,E}`.
//!
//! **Exactness.** With polynomial data and planar faces, every phase-1 integral is computed
//! exactly and the elements are in equilibrium to round-off (`tests/admissibility3d.rs`). A
//! warped Hex8 face (bilinear, non-planar) has an area element `|dx/dr x dx/ds|` that is not a
//! polynomial: the face mass matrices and loads are then quadratures, and the element balance
//! holds to their accuracy (1e-8 relative measured on a Hex8 mesh whose interior nodes were
//! moved randomly by 10 % of the cell size).
//!
//! **Substructures** ([`sides`]): the lumped interface forces of a LATIN linear stage are split
//! node by node between the interface faces around each node, as in 2D, and become known face
//! densities of phase 1.

mod family;
pub mod phase1;
pub mod phase2;
pub mod poly;
mod projections;
pub mod sides;
pub mod topology;
