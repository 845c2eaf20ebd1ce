//! Constitutive-relation-error (CRE) estimator for linear-elastic substructures and frictional
//! contact interfaces (thesis chapter 3.1, SEED-NOTES section 4). Deterministic only (the
//! stochastic estimator of 3.2 builds on it).
//!
//! # The estimate
//! With an admissible pair (`u_hat` kinematically admissible, `sigma_hat` statically
//! admissible), the CRE (3.16) `e^2 = 1/2 ||sigma_hat - K eps(u_hat)||^2_{K^-1}` satisfies the
//! Prager-Synge identity (3.19) `||u_ex - u_hat||^2_K + ||sigma_ex - sigma_hat||^2_{K^-1} =
//! 2 e^2`, so `theta = sqrt(2) e` bounds the energy-norm error `||u_ex - u_h||_K =
//! (int (sigma_ex - sigma_h) : eps(u_ex - u_h))^(1/2)`. We take `u_hat = u_h` and build
//! `sigma_hat` by the standard EET technique ([`eet`] in 2D, [`solid`] in 3D, phase 1 one
//! kernel generic over the cell family: `kernel`): phase 1
//! (3.20)-(3.22) equilibrated edge (2D) or face (3D) tractions from the prolongation condition,
//! node by node; phase 2 (3.23) element-by-element Neumann problems solved with degree `p + 3`
//! polynomials. Element contributions
//! `theta_E^2 = ||sigma_hat - sigma_h||^2_{K^-1,E}`, `theta^2 = sum_E theta_E^2`.
//!
//! With contact (3.26): `e^2 = 1/2 sum_s ||sigma_hat^s - K eps(u_hat^s)||^2 + int_Ic [b(-w_hat,
//! F_hat) + w_hat . F_hat] dS`, hence here `theta^2 = sum_s theta_s^2 + 2 sum_I term_I`.
//! Substructure fields ([`estimate_latin`], [`LatinEstimator`]): each substructure is isolated and loaded by the
//! interface forces its last linear-stage solution is in equilibrium with (lumped interface
//! mass: nodal forces `m_i F_i`, reproduced exactly by the interface edge densities), then EET.
//! Interface fields ([`interface`]): `w_hat` = jump (gap included) of local stage `n - 1`,
//! `F_hat` = force of local stage `n` (3.1.3.2 b), strictly admissible (3.27); de Saxce
//! bipotential; indicator functions checked with a tolerance and reported, never infinite.
//! Relative error: `theta / ||u_h||_K`.
//!
//! # What is guaranteed
//! `theta >= ||u_ex - u_h||_K` holds **if** (i) `u_h` is kinematically admissible (the
//! prescribed displacements are those of the exact problem and the FE space represents them:
//! homogeneous or piecewise-linear data), (ii) the FE solution is in equilibrium with the loads
//! given to the estimator as functions ([`LoadData`]: same body force and tractions as the
//! nodal load vectors) - reported as [`DomainEstimate::compatibility_defect`], (iii) the
//! phase-2 local problems are solved exactly and the data integrals are exact. (iii) never holds
//! exactly: the degree `p + 3` displacement solution of a Neumann problem has slightly *less*
//! energy than the exact local solution (corner singularities of the local problems make this
//! convergence slow; on a distorted 6 x 5 mesh `tests/admissibility.rs` measures
//! `theta(p+3) / theta(p+5)` = 0.97 (T3, Q4), 0.95 (T6), 0.86 (Q8)), and non-polynomial loads
//! are integrated by quadrature ([`DomainEstimate::balance_defect`]). So `theta` is a *nearly*
//! guaranteed bound; the measured efficiency indices (manufactured solutions: 1.17-1.27 Q4,
//! 2.27-2.76 T3, 1.07-1.57 Q8, 2.14-2.64 T6; in 3D 1.16-1.40 Hex8, 2.85-4.02 Tet4, 2.33-2.92
//! Tet10, `tests/manufactured3d.rs`) leave a margin, smallest for Q8 and Hex8, where raising
//! [`CreOptions::extra_degree`] is advisable when a strict bound matters. In 3D
//! `theta(p+3) / theta(p+4)` = 0.98 (Hex8), 0.98 (Tet4), 0.97 (Tet10) on a distorted 3 x 3 x 3
//! mesh (`tests/admissibility3d.rs`); warped Hex8 faces make the face integrals quadratures
//! (see [`solid`]). Curved (isoparametric) Tri6/Quad8 edges keep (i)-(iii) as they are on
//! straight cells: phase 1 and the phase-2 loads and stiffness are exact there
//! ([`eet::phase2`] "Curved cells"), only `eps_h` (rational) and non-polynomial data are
//! quadratures; measured on Lame's thick cylinder meshed with arcs, data `sigma_ex n_h` so that
//! `u_ex` solves the meshed problem (`tests/curved.rs`): efficiency 1.08 (Q8), 2.30-2.51 (T6) on
//! 4 meshes, `theta` converging at the error's rate; `theta(p+3) / theta(p+5)` = 0.999 (Q8),
//! 0.95 (T6), 0.94 (Q8 with every mid node moved off its chord by up to 5 %, efficiency
//! 1.25-1.58). On curved cells phase 2 costs about twice a straight cell's (richer rules).
//! For an assembly, the bound additionally needs a **converged LATIN** solution: the
//! substructure stresses are in equilibrium with the linear-stage forces `F_n` while the
//! interface term uses the local-stage `(W_hat_(n-1), F_hat_n)`; only at convergence are these
//! the same interface fields, and only then is (3.26) the CRE of one admissible solution. The
//! interface term is `>= 0` for any strictly admissible pair (always, up to round-off); it
//! vanishes wherever the point's status (open/stick/slip, slip direction) is the same at stages
//! `n - 1` and `n`, so it is not a measure of the LATIN convergence error by itself.
//!
//! # Multiresolution
//! A study estimates every run of one assembly: [`LatinEstimator`] (per substructure a
//! [`DomainEstimator`]) computes once everything that does not depend on the run - topology,
//! constraint frames, the phase-1 node systems with their least-change operators, per-cell-type
//! shape tables, the Cholesky factor of every phase-2 local matrix `K0` (reference materials,
//! `K = alpha K0` for a Young's factor `alpha`), `Z = L^-1 int eps(phi)^T D0 B` and the FE
//! energy outside the local space on `2 nn - 3` deformation coordinates, the moments of an
//! [`AffineBody`] force - and a run costs what depends on its displacements, interface forces,
//! loads and Young's factors ([`estimator`], [`eet::phase1_cache`], [`eet::phase2_cache`]). The
//! result is the direct path's ([`estimate_latin_direct`], every matrix rebuilt) to round-off
//! (`tests/context.rs`). Measured (`BENCHMARKS.md`): 8-11x faster per run than the direct path,
//! 0.3-0.5x a warm-started accelerated LATIN solve on the simple blade root and the four-part
//! dovetail (the thesis: 1.5x); the context holds ~5.1 KB per Q4 cell (57 MB for the 23k-dof
//! dovetail, 3.0 KB of it the Cholesky factors) and takes 1.5x the direct path's time to build,
//! so [`estimate_latin`] (one run: builds a context) is that much slower than the direct path.
//! 3D substructures keep the direct path.
//!
//! # Scope
//! 2D (plane strain / plane stress): Tri3, Quad4, Tri6 and Quad8 cells; quadratic cells may
//! have curved (isoparametric) edges: phase-1 densities per unit reference length on the
//! curved edge, phase-2 local problems on the curved cell with rules exact for their
//! polynomial integrands ([`eet::phase1`] and [`eet::phase2`] "Curved ..."; `tests/curved.rs`).
//! 3D: Tet4, Tet10 (straight edges) and Hex8 (faces may be warped). Curved Tet10 edges are
//! rejected with [`CreError::Invalid`], other cells with [`CreError::UnsupportedCell`];
//! constraints along axes or skew (`fix_normal`) - a boundary edge carries a reaction only in a
//! direction constrained at all its nodes, so a sliding constraint along a curved boundary (the
//! nodal normals differ along each edge) is not equilibrated:
//! [`DomainEstimate::compatibility_defect`] reports it (0.4-0.5 measured on an arc, Q4 and Q8
//! alike); isotropic materials (one per cell). The
//! interface term is dimension-free (tangent line or plane). Missing: curved 3D edges, the
//! "improved" technique (3.1.1.4 b). Cost in 3D: one dense local problem of `3 n_s - 6`
//! unknowns per cell (99 for Tet4/Hex8 at `p + 3`, 162 for Tet10), about three times a
//! deterministic LATIN solve on the 3D benchmark (`BENCHMARKS.md`).

mod contribution;
mod data;
mod domain;
pub mod eet;
mod error;
pub mod estimator;
mod fe;
mod fe_samples;
pub mod interface;
mod kernel;
mod legendre;
mod linalg;
pub mod poly;
mod result;
mod samples;
pub mod solid;
mod substructure;
pub mod topology;

pub use contribution::ElementContribution;
pub use data::{
    AffineBody, FaceProjections, FacetProjections, LoadData, SideForces, TractionField, VectorField,
};
pub use domain::{Admissible, CreOptions, DomainEstimate, estimate_domain, estimate_with_sides};
pub use error::CreError;
pub use estimator::DomainEstimator;
pub use fe_samples::FeEnergySampler;
pub use interface::{InterfaceEstimate, interface_term};
pub use result::{CreResult, write_error_vtu};
pub use samples::EnergySampler;
pub use substructure::{LatinEstimator, estimate_latin, estimate_latin_direct};
