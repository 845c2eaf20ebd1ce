//! The equilibrated element tractions (EET) technique, phase 1, once for every cell family
//! (Ladeveze-Leguillon 1983; Ladeveze-Pelle 2004 ch. 2; thesis 3.1.1.4 b, (3.20)-(3.22)):
//! generic over the family's side topology ([`topology::SideTopology`]: edges in 2D, faces in
//! 3D) and side spaces ([`family::CellFamily`]); the 2D ([`crate::eet`]) and 3D
//! ([`crate::solid`]) estimators instantiate it (monomorphised: no dynamic dispatch).
//!
//! With `phi_i` the FE shape function of node `i`, `Q_E(i) = int_E sigma_h : eps(phi_i) -
//! int_E f phi_i` ([`residuals`]) and `b_(i,Gamma) = int_Gamma F_hat phi_i dS`, the
//! prolongation condition (3.21) and the element equilibrium (3.20) give for every node `i`
//! and every element `E` around it (3.22):
//!
//! `sum_{Gamma in dE, i in Gamma} eta_(E,Gamma) b_(i,Gamma) = Q_E(i)`,
//!
//! solved node by node and direction by direction in the node's constraint frame
//! ([`frames`], [`node_system`]) closest to the averaged FE tractions; interface forces of a
//! substructure become known densities ([`split`]); the densities are recovered side by side
//! from their projections ([`loads`], [`phase1`]).

pub mod family;
pub mod frames;
pub mod loads;
pub mod node_system;
pub mod phase1;
pub mod residuals;
pub mod split;
pub mod topology;
pub mod tractions;
pub mod vector;
