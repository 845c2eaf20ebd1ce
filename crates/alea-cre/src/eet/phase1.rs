//! EET phase 1: traction densities on the element edges (thesis (3.20)-(3.22)): the
//! equilibrated-traction kernel `crate::kernel` instantiated for the 2D cell family (edges as
//! sides: `super::family`, edge integrals: `super::projections`).
//!
//! With `phi_i` the FE shape function of node `i` and `Q_E(i) = int_E sigma_h : eps(phi_i) -
//! int_E f phi_i` (a vector: one entry per direction), the prolongation condition (3.21) and the
//! element equilibrium (3.20) give, for every element `E` around node `i` ((3.22)):
//!
//! `sum_{Gamma in dE, i in Gamma} eta_E b_(i,Gamma) = Q_E(i)`,  `b_(i,Gamma) = int_Gamma F_hat phi_i dS`.
//!
//! Node by node this is a small system (one equation per element around the node, one unknown
//! per edge around it, per direction). Unknowns: interior edges, and boundary edges in the
//! directions constrained at all their nodes (the reaction is free there); on the other
//! boundary edges `b` is data: prescribed tractions, interface densities (see
//! [`interface_densities`]) or zero on free edges. The systems are singular (interior nodes) but
//! compatible when `u_h` is the FE solution for these loads: the node's equation sum is its FE
//! equilibrium. Among the solutions we take the one closest (Euclidean) to the projections of the
//! averaged FE tractions `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n phi_i`, the usual
//! minimisation of Ladeveze-Leguillon. A non-zero residual (incompatible data) is reported as
//! the compatibility defect. Directions are taken node by node in the frame of the node's
//! constraints (free directions, then constrained ones), so skew constraints are handled.
//!
//! For quadratic cells (T6/Q8) the same holds with every node of the mesh, vertex or mid-side
//! (the mid-side node's system has one unknown, determined by its FE equilibrium). On each edge
//! the density of degree `p` (1 or 2) is recovered from its `p + 1` projections through the
//! edge mass matrix: `F_a = (2 / L) (2 b_a - b_b)` on a 2-node edge. Everything is per unit
//! thickness.
//!
//! # Curved edges
//! A quadratic edge whose mid node is off the chord is the isoparametric curve `x(s)`,
//! `s in [0, 1]`, with length element `J(s) = |x'(s)|` and normal `n(s)`
//! ([`crate::topology::Edge::point`]); the FE shape functions restricted to it are the edge
//! shape functions `N_k(s)` of the reference parameter. The density is stored **per unit
//! reference length**: with `L` the chord length and `P(s) = sum_k N_k(s) F_k` the stored
//! quadratic polynomial ([`EdgeDensity::lin`]),
//!
//! `F_hat(x(s)) J(s) = L P(s)`, i.e. the traction `F_hat(x(s)) = (L / J(s)) P(s)`
//! ([`EdgeTractions::traction`]).
//!
//! Then `b_k = int_Gamma F_hat N_k dS = L int_0^1 P N_k ds = (M_L F)_k` with the same edge mass
//! matrix `M_L` as a straight edge of length `L`: the node systems (3.22), the recovery of `F`
//! from its projections and the interface densities are unchanged, and the projections hold
//! exactly. Because the isoparametric space reproduces the rigid modes exactly (`sum_i phi_i =
//! 1` and `sum_i phi_i (-y_i, x_i) = (-y, x)` on the curved cell), the prolongation condition
//! makes every cell's force **and moment** resultant of `F_hat` (plus the body force, with the
//! FE load rule) vanish to round-off, as on straight cells. On a straight edge `J = L` and the
//! representation is the usual one. A uniform stress `sigma_0` has the traction `sigma_0 n J /
//! L = sigma_0 (x'_y, -x'_x) / L`, linear in `s`: it is represented exactly. The targets
//! `b_bar` and the prescribed-traction projections are integrated on the curved edge
//! (`n(s)`, `J(s)`; for the latter the FE load vector's rule and facet geometry).

use std::sync::Arc;

use crate::CreError;
use crate::kernel::loads::SideData;
pub use crate::kernel::phase1::Phase1Input;
use crate::kernel::phase1::equilibrate;
pub use crate::kernel::tractions::SideTractions;

pub use super::sides::{EdgeLinear, NodeFrame, facet_projections, interface_densities};
use crate::topology::{EdgePoint, Topology};

/// Data part of an edge's density: a prescribed-traction field (index in the domain's load
/// data) and the projector applied to it (removes directions constrained along the edge).
pub type EdgeData = SideData<2>;

/// Density on one edge (first-cell orientation: the traction exerted on the edge's first cell).
#[derive(Clone, Debug, Default)]
pub struct EdgeDensity {
    /// Polynomial part: values at the edge's end nodes and mid node (the mid value is unused on
    /// a 2-node edge), interpolated with [`crate::topology::Edge::shape`].
    pub lin: [[f64; 2]; 3],
    /// Prescribed-traction part (possibly non-polynomial).
    pub data: Vec<EdgeData>,
}

/// Result of phase 1: the edge densities (the topology is shared with the estimator context
/// that built it).
pub type EdgeTractions = SideTractions<Arc<Topology>, EdgeDensity>;

impl EdgeTractions {
    /// Traction on edge `e`'s first cell at parameter `s in [0, 1]` (from `nodes[0]`), physical
    /// point `x` and first-cell outward normal `n` (on a curved edge: `x(s)` and `n(s)` of
    /// [`crate::topology::Edge::point`]; the polynomial part is then scaled by `L / J(s)`, see
    /// the module doc).
    pub fn traction(&self, e: usize, s: f64, x: [f64; 3], n: [f64; 2]) -> [f64; 2] {
        let edge = &self.topo.edges[e];
        let scale = if edge.curved {
            edge.chord() / edge.point(s).jac
        } else {
            1.0
        };
        self.traction_scaled(e, s, x, n, scale)
    }

    /// [`EdgeTractions::traction`] at the edge point `p` of parameter `s` (its `x`, `n` and
    /// `J`).
    pub fn traction_at(&self, e: usize, s: f64, p: &EdgePoint) -> [f64; 2] {
        let edge = &self.topo.edges[e];
        let scale = if edge.curved {
            edge.chord() / p.jac
        } else {
            1.0
        };
        self.traction_scaled(e, s, p.x, p.n, scale)
    }

    /// The polynomial density at `s` (values per unit chord length of the reference
    /// parametrisation: `t J / L`, see the module doc).
    pub fn polynomial(&self, e: usize, s: f64) -> [f64; 2] {
        let d = &self.density[e];
        let sh = self.topo.edges[e].shape(s);
        let mut t = [0.0; 2];
        for k in 0..3 {
            t[0] += sh[k] * d.lin[k][0];
            t[1] += sh[k] * d.lin[k][1];
        }
        t
    }

    fn traction_scaled(&self, e: usize, s: f64, x: [f64; 3], n: [f64; 2], scale: f64) -> [f64; 2] {
        let d = &self.density[e];
        let p = self.polynomial(e, s);
        let mut t = [scale * p[0], scale * p[1]];
        for ed in &d.data {
            let v = (self.fields[ed.field])(x, [n[0], n[1], 0.0]);
            let p = ed.projector;
            t[0] += p[0][0] * v[0] + p[0][1] * v[1];
            t[1] += p[1][0] * v[0] + p[1][1] * v[1];
        }
        t
    }
}

/// The 2D density of the kernel's parts.
pub(crate) fn edge_density(lin: [[f64; 2]; 3], data: Vec<EdgeData>) -> EdgeDensity {
    EdgeDensity { lin, data }
}

/// Runs phase 1 on one 2D domain.
pub fn phase1(inp: &Phase1Input) -> Result<EdgeTractions, CreError> {
    equilibrate::<Topology, _, _, 2>(inp, Arc::new, edge_density)
}
