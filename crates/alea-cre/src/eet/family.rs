//! The 2D cell family of the EET kernel (`crate::kernel`): Tri3/Quad4/Tri6/Quad8 cells with
//! their edges ([`Topology`]) as sides; densities of the edge's degree (linear on 2-node
//! edges, quadratic on 3-node edges, per unit reference length on curved edges: see
//! [`super::phase1`]) stored as values at `[nodes[0], nodes[1], mid]`.

use alea_fem::Model;
use alea_mesh::Mesh;

use super::projections::{add_prescribed_tractions, averaged_projections};
use super::sides::{edge_mass, interface_densities};
use crate::CreError;
use crate::data::{SideForces, TractionField};
use crate::kernel::family::CellFamily;
use crate::kernel::loads::SideLoads;
use crate::kernel::topology::{Incidence, Side, SideTopology};
use crate::kernel::vector::{Frame, identity};
use crate::linalg::cholesky_solve;
use crate::topology::{Edge, Topology};

impl Side for Edge {
    fn cells(&self) -> &[(usize, usize)] {
        &self.cells
    }

    fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.all_nodes()
    }
}

impl SideTopology<2> for Topology {
    type Side = Edge;
    const SIDE: &'static str = "edge";

    fn sides(&self) -> &[Edge] {
        &self.edges
    }

    fn incidence(&self) -> Incidence<'_> {
        Incidence {
            cell_sides: &self.cell_edges,
            node_cells: &self.node_cells,
            node_sides: &self.node_edges,
        }
    }

    fn measure(&self, mesh: &Mesh, s: usize) -> f64 {
        self.geometry(mesh, s).1
    }

    /// A node with one free direction `t` gets the frame `(t, t^perp)`.
    fn complete_frame(free: [[f64; 2]; 2], nfree: usize) -> Frame<2> {
        match nfree {
            0 => (identity(), 0),
            1 => {
                let t = free[0];
                ([t, [-t[1], t[0]]], 1)
            }
            _ => (identity(), 2),
        }
    }
}

impl CellFamily<2> for Topology {
    type Values = [[f64; 2]; 3];

    fn build(mesh: &Mesh) -> Result<Self, CreError> {
        Topology::new(mesh)
    }

    fn zero_values(&self) -> Vec<[[f64; 2]; 3]> {
        vec![[[0.0; 2]; 3]; self.edges.len()]
    }

    fn thickness(model: &Model) -> f64 {
        model.analysis.thickness()
    }

    fn side_mass(&self, mesh: &Mesh, s: usize) -> Vec<f64> {
        let quadratic = self.edges[s].mid.is_some();
        let n = 2 + quadratic as usize;
        let m = edge_mass(quadratic, self.geometry(mesh, s).1);
        (0..n).flat_map(|i| (0..n).map(move |j| m[i][j])).collect()
    }

    fn add_prescribed(
        &self,
        mesh: &Mesh,
        frames: &[Frame<2>],
        tractions: &[(String, TractionField)],
        loads: &mut SideLoads<[[f64; 2]; 3], 2>,
    ) -> Result<(), CreError> {
        add_prescribed_tractions(mesh, self, frames, tractions, loads)
    }

    fn averaged_projections(
        &self,
        model: &Model,
        u: &[f64],
    ) -> Result<Vec<[[f64; 2]; 3]>, CreError> {
        averaged_projections(model, self, u)
    }

    fn interface_densities(
        &self,
        mesh: &Mesh,
        side: &SideForces,
        thickness: f64,
        b_bar: &[[[f64; 2]; 3]],
        frames: Option<&[Frame<2>]>,
    ) -> Result<Vec<(usize, [[f64; 2]; 3])>, CreError> {
        interface_densities(mesh, self, side, thickness, b_bar, frames)
    }

    /// `M F = b` on a 3-node edge; on a 2-node edge `F_a = (2 / L) (2 b_a - b_b)`.
    fn add_recovered(
        &self,
        mesh: &Mesh,
        s: usize,
        mass: &[f64],
        b: &[[f64; 2]; 3],
        values: &mut [[f64; 2]; 3],
    ) -> Result<(), CreError> {
        if self.edges[s].mid.is_some() {
            for c in 0..2 {
                let mut a = mass.to_vec();
                let mut x = vec![b[0][c], b[1][c], b[2][c]];
                if !cholesky_solve(&mut a, &mut x, 3) {
                    return Err(CreError::Invalid(format!("degenerate edge {s}")));
                }
                for k in 0..3 {
                    values[k][c] += x[k];
                }
            }
        } else {
            let len = self.geometry(mesh, s).1;
            for c in 0..2 {
                values[0][c] += 2.0 / len * (2.0 * b[0][c] - b[1][c]);
                values[1][c] += 2.0 / len * (2.0 * b[1][c] - b[0][c]);
            }
        }
        Ok(())
    }
}
