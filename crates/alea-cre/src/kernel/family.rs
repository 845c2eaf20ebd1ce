//! What a cell family (2D: Tri3/Quad4/Tri6/Quad8 with their edges; 3D: Tet4/Tet10/Hex8 with
//! their faces) provides to the equilibrated-traction kernel beyond its side topology: the
//! side densities' polynomial spaces (values at the side nodes, side mass matrices, recovery of
//! a density from its projections) and the integrals on its sides (averaged FE traction
//! projections `b_bar`, prescribed-traction projections, interface densities).

use alea_fem::Model;
use alea_mesh::Mesh;

use super::loads::SideLoads;
use super::topology::SideTopology;
use super::vector::Frame;
use crate::CreError;
use crate::data::{SideForces, TractionField};

/// A cell family in dimension `D`: its side topology and side spaces.
pub(crate) trait CellFamily<const D: usize>: SideTopology<D> + Sized + Send {
    /// Per-slot vector values on one side (density values or projections at its nodes).
    type Values: AsRef<[[f64; D]]> + AsMut<[[f64; D]]> + Clone + Send + Sync;

    /// The side topology of `mesh` (errors for cells of another family).
    fn build(mesh: &Mesh) -> Result<Self, CreError>;

    /// Zero values on every side.
    fn zero_values(&self) -> Vec<Self::Values>;

    /// The thickness the residuals and forces are divided by (per unit thickness in 2D; 1 in
    /// 3D).
    fn thickness(model: &Model) -> f64;

    /// Side mass matrix `int_Gamma N_a N_b dS` (row-major, side nodes x side nodes).
    fn side_mass(&self, mesh: &Mesh, s: usize) -> Vec<f64>;

    /// Adds the prescribed tractions as data densities of their boundary sides and their
    /// projections `int_Gamma (P t) phi_a dS` to `loads.b_known`, integrated with the FE load
    /// vector's rule (so that the node systems are compatible to round-off).
    fn add_prescribed(
        &self,
        mesh: &Mesh,
        frames: &[Frame<D>],
        tractions: &[(String, TractionField)],
        loads: &mut SideLoads<Self::Values, D>,
    ) -> Result<(), CreError>;

    /// The averaged FE traction projections `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n
    /// phi_a dS` of every side (first-cell orientation).
    fn averaged_projections(&self, model: &Model, u: &[f64])
    -> Result<Vec<Self::Values>, CreError>;

    /// The densities of interface side `side` ([`super::split`]), per unit `thickness`.
    fn interface_densities(
        &self,
        mesh: &Mesh,
        side: &SideForces,
        thickness: f64,
        b_bar: &[Self::Values],
        frames: Option<&[Frame<D>]>,
    ) -> Result<Vec<(usize, Self::Values)>, CreError>;

    /// Adds to `values` the density of side `s` recovered from its projections `b` (`M F = b`,
    /// `mass` the side mass matrix).
    fn add_recovered(
        &self,
        mesh: &Mesh,
        s: usize,
        mass: &[f64],
        b: &Self::Values,
        values: &mut Self::Values,
    ) -> Result<(), CreError>;
}
