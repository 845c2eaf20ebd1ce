//! EET phase 1 in 3D: traction densities on the element faces (thesis (3.20)-(3.22), with faces
//! in place of edges): the equilibrated-traction kernel `crate::kernel` instantiated for the
//! 3D cell family (faces as sides: `super::family`, face integrals: `super::projections`).
//!
//! With `phi_i` the FE shape function of node `i` and `Q_E(i) = int_E sigma_h : eps(phi_i) -
//! int_E f phi_i` (a vector: one entry per direction), the prolongation condition (3.21) and the
//! element equilibrium (3.20) give, for every element `E` around node `i` ((3.22)):
//!
//! `sum_{Gamma face of E, i in Gamma} eta_(E,Gamma) b_(i,Gamma) = Q_E(i)`,
//! `b_(i,Gamma) = int_Gamma F_hat phi_i dS`.
//!
//! Node by node this is a small system per direction: one equation per element around the
//! node, one unknown per face around it (interior faces; boundary faces in the directions
//! constrained at all their nodes, where the reaction is free). On the other boundary faces
//! `b` is data: prescribed tractions (integrated with the rule of `alea_fem::Loads::traction`, so
//! that the node systems are compatible to round-off), interface densities
//! ([`super::sides::interface_densities`]) or zero on free faces. Among the solutions we take
//! the one closest to the projections of the averaged FE tractions
//! `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n phi_i`, in the norm
//! `sum_Gamma (b - b_bar)^2 / |Gamma|` (Ladeveze-Leguillon's minimisation, weighted by the face
//! areas as the 2D code weights by edge lengths). The systems are singular (interior nodes:
//! every column holds `+1` and `-1`) but compatible when `u_h` is the FE solution for these
//! loads; a non-zero residual is reported as the compatibility defect. Directions are taken
//! node by node in the frame of the node's constraints (free directions first), so skew
//! constraints are handled.
//!
//! For Tet10 the same holds for every node, vertex or mid-edge (a mid-edge node's system has
//! the elements and faces around its edge). On each face the density of the face's degree
//! (linear on Tri3, bilinear on Quad4, quadratic on Tri6) is recovered from its projections
//! through the face mass matrix: `M F = b`, `M_ab = int_Gamma N_a N_b dS`.

use crate::CreError;
use crate::kernel::loads::SideData;
pub use crate::kernel::phase1::Phase1Input;
use crate::kernel::phase1::equilibrate;
pub use crate::kernel::tractions::SideTractions;

pub use super::sides::NodeFrame3;
use super::topology::FaceTopology;

/// Data part of a face's density: a prescribed-traction field (index in the domain's load
/// data) and the projector applied to it (removes directions constrained on the whole face).
pub type FaceData = SideData<3>;

/// Density on one face (first-cell orientation: the traction exerted on the face's first cell).
#[derive(Clone, Debug, Default)]
pub struct FaceDensity {
    /// Polynomial part: values at the face's nodes, interpolated with the face's shape functions.
    pub values: Vec<[f64; 3]>,
    /// Prescribed-traction part (possibly non-polynomial).
    pub data: Vec<FaceData>,
}

/// Result of phase 1 in 3D: the face densities.
pub type FaceTractions = SideTractions<FaceTopology, FaceDensity>;

impl FaceTractions {
    /// Traction on face `f`'s first cell at a face point with face shape values `shape`,
    /// physical point `x` and first-cell outward normal `n`.
    pub fn traction(&self, f: usize, shape: &[f64], x: [f64; 3], n: [f64; 3]) -> [f64; 3] {
        let d = &self.density[f];
        let mut t = [0.0; 3];
        for (a, v) in d.values.iter().enumerate() {
            for c in 0..3 {
                t[c] += shape[a] * v[c];
            }
        }
        for fd in &d.data {
            let v = (self.fields[fd.field])(x, n);
            let p = fd.projector;
            for c in 0..3 {
                t[c] += p[c][0] * v[0] + p[c][1] * v[1] + p[c][2] * v[2];
            }
        }
        t
    }
}

/// Runs phase 1 on one 3D domain.
pub fn phase1(inp: &Phase1Input) -> Result<FaceTractions, CreError> {
    equilibrate::<FaceTopology, _, _, 3>(
        inp,
        |topo| topo,
        |values, data| FaceDensity { values, data },
    )
}
